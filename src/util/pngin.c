/* PNG decoding from memory (util/pngin.h). */
#include "util/pngin.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool pngin_decode(const uint8_t *data, size_t len, int *w, int *h, bool *alpha, uint8_t **rgba, char *why,
                  size_t size) {
    if (rgba) *rgba = NULL;
    if (len < 8 || png_sig_cmp(data, 0, 8)) {
        snprintf(why, size, "not a PNG file (its first bytes are not PNG's signature)");
        return false;
    }
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&im, data, len)) {
        snprintf(why, size, "not a readable PNG: %s", im.message);
        return false;
    }
    if (im.width < 1 || im.height < 1 || im.width > PNGIN_MAX_SIDE || im.height > PNGIN_MAX_SIDE) {
        snprintf(why, size, "%ux%u pixels: a texture is at most %d pixels a side", im.width, im.height,
                 PNGIN_MAX_SIDE);
        png_image_free(&im);
        return false;
    }
    *w = (int)im.width, *h = (int)im.height;
    *alpha = (im.format & PNG_FORMAT_FLAG_ALPHA) != 0;
    im.format = PNG_FORMAT_RGBA;
    uint8_t *px = malloc(PNG_IMAGE_SIZE(im));
    if (!px) {
        snprintf(why, size, "out of memory");
        png_image_free(&im);
        return false;
    }
    /* decoded whole even when only checked: a truncated or corrupt file is refused here */
    if (!png_image_finish_read(&im, NULL, px, 0, NULL)) {
        snprintf(why, size, "not a readable PNG: %s", im.message);
        free(px);
        return false;
    }
    if (rgba) *rgba = px;
    else free(px);
    return true;
}
