/* PNG output of RGB and RGBA pictures, encoded by util/pngout and written through util/outfile. */
#include <stdint.h>

#include "sylva/texture.h"
#include "util/outfile.h"
#include "util/pngout.h"

typedef struct Rows {
    const uint8_t *px;
    int width, channels;
} Rows;

static const void *pixel_row(void *ctx, int y, void *scratch) {
    (void)scratch;
    const Rows *r = ctx;
    return r->px + (size_t)y * (size_t)r->width * (size_t)r->channels;
}

static int write_png(const char *path, const uint8_t *px, int width, int height, int channels, FILE *diag) {
    if (width <= 0 || height <= 0) {
        if (diag) fprintf(diag, "sylva: error: cannot write '%s': empty picture\n", path);
        return SYL_EUSAGE;
    }
    OutFile o; /* "-" is standard output */
    if (!outfile_open(&o, path, NULL, diag)) return SYL_EIO;
    Rows src = {px, width, channels};
    /* level 1: fast, pictures are big and noisy */
    PngOutImage img = {.width = width, .height = height, .channels = channels, .depth = 8, .level = 1,
                       .row = pixel_row, .ctx = &src};
    int status = pngout_encode(&o, &img, diag);
    if (!outfile_close(&o, status == SYL_OK, diag) && !status) status = SYL_EIO;
    return status;
}

int syl_write_png(const char *path, const uint8_t *rgb, int width, int height, FILE *diag) {
    return write_png(path, rgb, width, height, 3, diag);
}

int syl_write_png_rgba(const char *path, const uint8_t *rgba, int width, int height, FILE *diag) {
    return write_png(path, rgba, width, height, 4, diag);
}
