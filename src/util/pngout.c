/* PNG encoding through libpng (util/pngout.h). */
#include "util/pngout.h"
#include "util/diag.h"

#include <png.h>
#include <stdbool.h>
#include <stdlib.h>

#include "sylva/sylva.h"

typedef struct PngErr {
    const SylSink *sink;
    const OutFile *o; /* NULL: written through write */
    const char *name;
    void (*write)(void *ctx, const void *data, size_t n);
    void *ctx;
} PngErr;

static void on_error(png_structp png, png_const_charp msg) {
    PngErr *e = png_get_error_ptr(png);
    /* A failed write ("Write Error") is reported with its reason by outfile_close. */
    if (e->sink && !(e->o && e->o->err)) sink_error(e->sink, "cannot write '%s': %s", e->name, msg);
    png_longjmp(png, 1);
}

static void on_write(png_structp png, png_bytep data, png_size_t n) {
    PngErr *e = png_get_io_ptr(png);
    e->write(e->ctx, data, n);
}
static void on_flush(png_structp png) { (void)png; }

static void on_warning(png_structp png, png_const_charp msg) {
    (void)png;
    (void)msg;
}

static int encode(PngErr *e, const PngOutImage *img) {
    const SylSink *sink = e->sink;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, e, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    void *scratch = malloc((size_t)img->width * (size_t)img->channels * (size_t)(img->depth / 8));
    if (!info || !scratch) {
        png_destroy_write_struct(&png, &info);
        free(scratch);
        sink_error(sink, "out of memory writing '%s'", e->name);
        return SYL_ELIMIT;
    }
    volatile bool ok = false;
    if (!setjmp(png_jmpbuf(png))) {
        if (e->o) png_init_io(png, e->o->f);
        else png_set_write_fn(png, e, on_write, on_flush);
        int type = img->channels == 1 ? PNG_COLOR_TYPE_GRAY : img->channels == 4 ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB;
        png_set_IHDR(png, info, (png_uint_32)img->width, (png_uint_32)img->height, img->depth, type,
                     PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        if (img->ntext > 0) {
            png_text text[8];
            int n = img->ntext < 8 ? img->ntext : 8;
            for (int i = 0; i < n; i++)
                text[i] = (png_text){.compression = PNG_TEXT_COMPRESSION_NONE,
                                     .key = (char *)img->text[i].key,
                                     .text = (char *)img->text[i].text};
            png_set_text(png, info, text, n);
        }
        png_set_compression_level(png, img->level);
        if (img->unfiltered) png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
        png_write_info(png, info);
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
        if (img->depth == 16) png_set_swap(png); /* samples are host-order uint16_t; PNG is big-endian */
#endif
        for (int y = 0; y < img->height; y++) png_write_row(png, (png_const_bytep)img->row(img->ctx, y, scratch));
        png_write_end(png, info);
        ok = true;
    }
    png_destroy_write_struct(&png, &info);
    free(scratch);
    return ok ? SYL_OK : SYL_EIO;
}

int pngout_encode(const OutFile *o, const PngOutImage *img, const SylSink *sink) {
    PngErr e = {.sink = sink, .o = o, .name = o->path};
    return encode(&e, img);
}

int pngout_encode_to(void (*write)(void *ctx, const void *data, size_t n), void *ctx, const char *name,
                     const PngOutImage *img, const SylSink *sink) {
    PngErr e = {.sink = sink, .name = name, .write = write, .ctx = ctx};
    return encode(&e, img);
}
