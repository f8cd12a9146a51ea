/* PNG output through libpng, written through util/outfile. */
#include <errno.h>
#include <png.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sylva/texture.h"
#include "util/outfile.h"

typedef struct PngErr {
    FILE *diag;
    const OutFile *o;
} PngErr;

static void png_error_fn(png_structp png, png_const_charp msg) {
    PngErr *e = png_get_error_ptr(png);
    /* A failed write ("Write Error") is reported with its reason by outfile_close. */
    if (e->diag && !e->o->err) fprintf(e->diag, "sylva: error: cannot write '%s': %s\n", e->o->path, msg);
    png_longjmp(png, 1);
}

static void png_warning_fn(png_structp png, png_const_charp msg) {
    (void)png;
    (void)msg;
}

/* Encode into an open file: SYL_OK, SYL_ELIMIT (out of memory) or SYL_EIO, reported. */
static int encode(const OutFile *o, const uint8_t *rgb, int width, int height, int channels, FILE *diag) {
    PngErr err = {diag, o};
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &err, png_error_fn, png_warning_fn);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        if (diag) fprintf(diag, "sylva: error: out of memory writing '%s'\n", o->path);
        return SYL_ELIMIT;
    }
    volatile bool ok = false;
    if (!setjmp(png_jmpbuf(png))) {
        png_init_io(png, o->f);
        png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, channels == 4 ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_set_compression_level(png, 1); /* fast: pictures are big, and noisy */
        png_write_info(png, info);
        for (int y = 0; y < height; y++) png_write_row(png, (png_const_bytep)(rgb + (size_t)y * (size_t)width * (size_t)channels));
        png_write_end(png, info);
        ok = true;
    }
    png_destroy_write_struct(&png, &info);
    return ok ? SYL_OK : SYL_EIO;
}

static int write_png(const char *path, const uint8_t *rgb, int width, int height, int channels, FILE *diag) {
    if (width <= 0 || height <= 0) {
        if (diag) fprintf(diag, "sylva: error: cannot write '%s': empty picture\n", path);
        return SYL_EUSAGE;
    }
    OutFile o; /* "-" is standard output */
    if (!outfile_open(&o, path, NULL, diag)) return SYL_EIO;
    int status = encode(&o, rgb, width, height, channels, diag);
    if (!outfile_close(&o, status == SYL_OK, diag) && !status) status = SYL_EIO;
    return status;
}

int syl_write_png(const char *path, const uint8_t *rgb, int width, int height, FILE *diag) {
    return write_png(path, rgb, width, height, 3, diag);
}

int syl_write_png_rgba(const char *path, const uint8_t *rgba, int width, int height, FILE *diag) {
    return write_png(path, rgba, width, height, 4, diag);
}
