/* PNG encoding through libpng into an open util/outfile output or a write callback: the one
 * place that drives libpng's writer, its longjmp error handling and its messages. Every PNG
 * Sylva writes goes through it: the RGB and RGBA pictures of texture/png.c, the 16-bit factor
 * maps of terrain/write.c and the textures io/ embeds in a .glb (in memory). */
#ifndef SYL_UTIL_PNGOUT_H
#define SYL_UTIL_PNGOUT_H
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "util/outfile.h"

typedef struct PngOutText {
    const char *key, *text;
} PngOutText;

typedef struct PngOutImage {
    int width, height;
    int channels; /* 1 grey, 3 RGB, 4 RGBA */
    int depth;    /* bits per sample: 8, or 16 (host-order uint16_t samples) */
    int level;    /* zlib compression level, 0-9 */
    bool unfiltered; /* rows as they are (PNG filter None), not libpng's best filter per row */
    const PngOutText *text;
    int ntext;
    /* Row y: a pointer to width * channels samples; scratch has room for one row, for a
     * source that converts rather than points into its own pixels. */
    const void *(*row)(void *ctx, int y, void *scratch);
    void *ctx;
} PngOutImage;

/* Encode img into o: SYL_OK, SYL_ELIMIT (out of memory) or SYL_EIO, reported to sink. */
int pngout_encode(const OutFile *o, const PngOutImage *img, const SylSink *sink);
/* Encode img through write(ctx, bytes, n) (into memory): the same bytes as into a file;
 * SYL_OK, SYL_ELIMIT or SYL_EIO, reported to sink (NULL: silently) as about `name`. */
int pngout_encode_to(void (*write)(void *ctx, const void *data, size_t n), void *ctx, const char *name,
                     const PngOutImage *img, const SylSink *sink);

#endif
