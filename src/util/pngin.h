/* PNG decoding from memory through libpng (its simplified reader): the image files a model
 * names as textures, checked when read and decoded for the renderer. */
#ifndef SYL_UTIL_PNGIN_H
#define SYL_UTIL_PNGIN_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The largest side of a texture image Sylva reads (docs/language.md#21-textures-bark-and-leaf-images). */
enum { PNGIN_MAX_SIDE = 8192 };

/* Decode len bytes of a PNG into RGBA, rows top to bottom (malloc'd into *rgba when rgba is
 * not NULL; NULL: only checked). False, with why (a phrase: "not a PNG file", libpng's
 * reason), when it is not a whole, readable PNG of at most PNGIN_MAX_SIDE a side. *alpha: the
 * file has an alpha channel or a transparent colour. */
bool pngin_decode(const uint8_t *data, size_t len, int *w, int *h, bool *alpha, uint8_t **rgba, char *why,
                  size_t size);

#endif
