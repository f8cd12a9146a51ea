/* PNG output of RGB pictures, encoded by util/pngout and written through util/outfile. */
#include <stdint.h>

#include "sylva/texture.h"
#include "util/outfile.h"
#include "util/pngout.h"

typedef struct Rgb {
    const uint8_t *px;
    int width;
} Rgb;

static const void *rgb_row(void *ctx, int y, void *scratch) {
    (void)scratch;
    const Rgb *r = ctx;
    return r->px + (size_t)y * (size_t)r->width * 3;
}

int syl_write_png(const char *path, const uint8_t *rgb, int width, int height, FILE *diag) {
    if (width <= 0 || height <= 0) {
        if (diag) fprintf(diag, "sylva: error: cannot write '%s': empty picture\n", path);
        return SYL_EUSAGE;
    }
    OutFile o; /* "-" is standard output */
    if (!outfile_open(&o, path, NULL, diag)) return SYL_EIO;
    Rgb src = {rgb, width};
    /* level 1: fast, pictures are big and noisy */
    PngOutImage img = {.width = width, .height = height, .channels = 3, .depth = 8, .level = 1, .row = rgb_row,
                       .ctx = &src};
    int status = pngout_encode(&o, &img, diag);
    if (!outfile_close(&o, status == SYL_OK, diag) && !status) status = SYL_EIO;
    return status;
}
