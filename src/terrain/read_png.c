/* The PNG DEM reader: a greyscale PNG of 8 or 16 bits (with or without alpha: alpha 0 is no
 * data), grey 0 at the lowest height and white at the highest, the first row the north. */
#include <png.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

#include "terrain/terrain.h"
#include "util/budget.h"

typedef struct Mem {
    const uint8_t *p;
    size_t len, at;
    const char *path;
    const SylSink *sink;
    bool reported;
} Mem;

static void mem_read(png_structp png, png_bytep out, png_size_t n) {
    Mem *m = png_get_io_ptr(png);
    if (n > m->len - m->at) png_error(png, "the file ends early (truncated)");
    memcpy(out, m->p + m->at, n);
    m->at += n;
}

static void on_error(png_structp png, png_const_charp msg) {
    Mem *m = png_get_error_ptr(png);
    if (!m->reported) diag_say(NULL, m->sink, DIAG_ERROR, m->path, "a malformed PNG: %s", msg);
    m->reported = true;
    png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg) {
    (void)png;
    (void)msg;
}

/* Whether every chunk's length fits in the file: libpng allocates a text chunk's stated length
 * before it reads it, so a damaged length in a small file would ask for gigabytes. */
static bool chunks_fit(const uint8_t *d, size_t len) {
    for (size_t at = 8; at + 8 <= len;) {
        size_t n = (size_t)d[at] << 24 | (size_t)d[at + 1] << 16 | (size_t)d[at + 2] << 8 | d[at + 3];
        if (n > len - at - 8 || len - at - 8 - n < 4) return false; /* data and CRC */
        if (!memcmp(d + at + 4, "IEND", 4)) return true;
        at += 12 + n;
    }
    return true; /* a file cut between chunks: libpng says so */
}

int terrain_read_png(const char *path, const uint8_t *data, size_t len, const SylTerrainOptions *o,
                     Terrain **out) {
    *out = NULL;
    const SylSink *sink = opt_sink(o);
    const double lo = o->height_lo, hi = lo == 0 && o->height_hi == 0 ? 1 : o->height_hi;
    const double cell = o->cell > 0 ? o->cell : 1;
    if (len < 8 || png_sig_cmp(data, 0, 8)) {
        diag_say(NULL, sink, DIAG_ERROR, path, "not a PNG file (its first bytes are not PNG's signature)");
        return SYL_EMODEL;
    }
    if (!chunks_fit(data, len)) {
        diag_say(NULL, sink, DIAG_ERROR, path, "a malformed PNG: the file ends early (truncated)");
        return SYL_EMODEL;
    }
    Mem m = {data, len, 0, path, sink, false};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &m, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        diag_say(NULL, sink, DIAG_ERROR, path, "out of memory");
        return SYL_ELIMIT;
    }
    Terrain *volatile t = NULL;
    png_bytep volatile row = NULL;
    volatile int st = SYL_EMODEL;
    if (setjmp(png_jmpbuf(png))) goto done;
    png_set_read_fn(png, &m, mem_read);
    /* Our own limits, checked before any row is allocated (libpng's default is 1,000,000). */
    png_set_user_limits(png, TERRAIN_MAX_SIDE, TERRAIN_MAX_SIDE);
    png_read_info(png, info);
    png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    int depth = png_get_bit_depth(png, info), type = png_get_color_type(png, info);
    if (type != PNG_COLOR_TYPE_GRAY && type != PNG_COLOR_TYPE_GRAY_ALPHA) {
        diag_say(NULL, sink, DIAG_ERROR, path, "a %s PNG: a DEM is a greyscale PNG (8 or 16 bits), one height a pixel",
                    type == PNG_COLOR_TYPE_PALETTE ? "palette" : "colour");
        goto done;
    }
    if (depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (depth == 16) png_set_swap(png); /* little-endian machine: rows as uint16_t */
    if (png_get_interlace_type(png, info) != PNG_INTERLACE_NONE) {
        diag_say(NULL, sink, DIAG_ERROR, path, "an interlaced PNG: write the DEM without interlacing");
        goto done;
    }
    png_read_update_info(png, info);
    Terrain *tt;
    st = terrain_new((int)w, (int)h, o->budget, o->max_memory, path, sink, &tt);
    if (st) {
        m.reported = true;
        goto done;
    }
    t = tt;
    st = SYL_EMODEL;
    t->cell = cell;
    size_t rowbytes = png_get_rowbytes(png, info);
    row = malloc(rowbytes);
    if (!row) {
        diag_say(NULL, sink, DIAG_ERROR, path, "out of memory");
        st = SYL_ELIMIT;
        goto done;
    }
    int channels = type == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : 1, wide = depth == 16;
    double top = wide ? 65535.0 : 255.0;
    for (png_uint_32 k = 0; k < h; k++) {
        png_read_row(png, row, NULL);
        for (png_uint_32 i = 0; i < w; i++) {
            size_t c = (size_t)k * w + i;
            unsigned grey, alpha = 1;
            if (wide) {
                const uint16_t *r = (const uint16_t *)row;
                grey = r[i * channels];
                if (channels == 2) alpha = r[i * 2 + 1];
            } else {
                grey = row[i * channels];
                if (channels == 2) alpha = row[i * 2 + 1];
            }
            t->height[c] = (float)(lo + (hi - lo) * grey / top);
            t->valid[c] = alpha != 0;
        }
    }
    if (!terrain_fill_unknown(t)) {
        diag_say(NULL, sink, DIAG_ERROR, path, "every pixel is transparent: no height is known");
        goto done;
    }
    st = SYL_OK;
done:
    png_destroy_read_struct(&png, &info, NULL);
    free(row);
    if (st == SYL_OK) *out = t;
    else syl_terrain_free(t);
    return st;
}
