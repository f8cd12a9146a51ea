/* SylPicture (sylva.h): the pictures the library draws and hands over. */
#include <stdlib.h>

#include "sylva/sylva.h"

void syl_picture_free(SylPicture *p) {
    if (!p) return;
    free(p->rgb);
    *p = (SylPicture){0};
}
