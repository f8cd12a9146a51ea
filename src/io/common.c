/* What the mesh writers share: files, buffers, numbers, names, PNG in memory (util/pngout.c's
 * encoder). The format of an extension is io/formats.c's. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "io/io_internal.h"
#include "sylva/texture.h"
#include "util/json.h"
#include "util/numtext.h"
#include "util/pngout.h"

bool io_open(OutFile *o, const char *path, const SylSink *sink) { return outfile_open(o, path, NULL, sink); }

int io_close(OutFile *o, int status, const SylSink *sink) {
    /* A write error is reported by outfile_close; other failures by whoever set status. */
    if (!outfile_close(o, status == SYL_OK, sink) && !status) status = SYL_EIO;
    return status;
}

/* Room for n more own bytes (cap doubled until it holds own + n); false when out of memory
 * (b failed). */
static bool room(IoBuf *b, size_t n) {
    if (b->failed) return false;
    size_t own = b->len - b->ref_bytes;
    if (own + n <= b->cap) return true;
    if (n > SIZE_MAX / 4 - b->len) { /* doubling would overflow */
        b->failed = true;
        return false;
    }
    size_t c = b->cap ? b->cap : 4096;
    while (c < own + n) c *= 2;
    uint8_t *d = realloc(b->data, c);
    if (!d) {
        b->failed = true;
        return false;
    }
    b->data = d;
    b->cap = c;
    return true;
}

void io_put(IoBuf *b, const void *p, size_t n) {
    if (!room(b, n)) return;
    memcpy(b->data + (b->len - b->ref_bytes), p, n);
    b->len += n;
}

uint8_t *io_room(IoBuf *b, size_t n) {
    if (!room(b, n)) return NULL;
    uint8_t *p = b->data + (b->len - b->ref_bytes);
    b->len += n;
    return p;
}

void io_reserve(IoBuf *b, size_t n) {
    size_t own = b->len - b->ref_bytes;
    if (b->failed || own + n <= b->cap || n > SIZE_MAX / 4 - b->len) return;
    uint8_t *d = realloc(b->data, own + n);
    if (d) b->data = d, b->cap = own + n; /* else it grows as it goes, or fails then */
}

void io_ref(IoBuf *b, const void *p, size_t n) {
    if (b->failed || !n) return;
    if (n > SIZE_MAX / 4 - b->len) {
        b->failed = true;
        return;
    }
    if (b->nrefs == b->ref_cap) {
        size_t c = b->ref_cap ? 2 * b->ref_cap : 16;
        IoRef *r = realloc(b->refs, c * sizeof *r);
        if (!r) {
            b->failed = true;
            return;
        }
        b->refs = r, b->ref_cap = c;
    }
    b->refs[b->nrefs++] = (IoRef){b->len - b->ref_bytes, p, n};
    b->len += n, b->ref_bytes += n;
}

void io_write(const IoBuf *b, FILE *f) {
    size_t own = 0;
    for (size_t i = 0; i < b->nrefs; i++) {
        if (b->refs[i].at > own) fwrite(b->data + own, 1, b->refs[i].at - own, f);
        fwrite(b->refs[i].p, 1, b->refs[i].n, f);
        own = b->refs[i].at;
    }
    if (b->len - b->ref_bytes > own) fwrite(b->data + own, 1, b->len - b->ref_bytes - own, f);
}

void io_printf(IoBuf *b, const char *fmt, ...) {
    char small[256];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    if (n < 0) {
        b->failed = true;
        return;
    }
    if ((size_t)n < sizeof small) {
        io_put(b, small, (size_t)n);
        return;
    }
    char *big = malloc((size_t)n + 1);
    if (!big) {
        b->failed = true;
        return;
    }
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    io_put(b, big, (size_t)n);
    free(big);
}

static void put_buf(void *b, const void *p, size_t n) { io_put(b, p, n); }

void io_json_string(IoBuf *b, const char *s) { json_string(s, put_buf, b); }

void io_line_text(char *dst, size_t n, const char *s, bool no_spaces) {
    size_t i = 0;
    for (; s[i] && i + 1 < n; i++) {
        unsigned char c = (unsigned char)s[i];
        dst[i] = c < 0x20 || c == 0x7f || (no_spaces && c == ' ') ? '_' : (char)c;
    }
    if (n) dst[i] = 0;
}

void io_free(IoBuf *b) {
    free(b->data);
    free(b->refs);
    *b = (IoBuf){0};
}

static const double pow10[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
static const double tenths[] = {1, 1e-1, 1e-2, 1e-3, 1e-4}; /* 1.0 / pow10[k]: the same doubles */

/* Exact, and without a division (docs/mesh.md#number-text): x * 10^dec is exact in a double
 * (a float's 24 bits times 5^dec < 2^21), so v is the correctly rounded value; it stays below
 * 2^32 (under 10^sig, or x itself under 1e9), and its whole part is x's own. */
char *io_float(char *p, float xf, int sig) {
    double x = isfinite(xf) ? xf : 0;
    if (x == 0) {
        *p++ = '0';
        return p;
    }
    if (x < 0) *p++ = '-', x = -x;
    if (x >= 1e9 || x < 1e-4) return numtext_g(p, x, sig);
    int e = 0; /* digits before the point, minus one */
    while (e < 9 && x >= pow10[e + 1]) e++;
    while (e > -4 && x < (e >= 0 ? pow10[e] : tenths[-e])) e--;
    int dec = sig - 1 - e;
    if (dec < 0) dec = 0;
    if (dec > 9) dec = 9;
    double y = x * pow10[dec];
    uint32_t v = (uint32_t)y, scale = (uint32_t)pow10[dec];
    if (y - (double)v >= 0.5) v++; /* half away from zero, as llround */
    uint32_t ip = (uint32_t)x, fp = v - ip * scale;
    if (fp >= scale) ip++, fp -= scale; /* 1.9999999 -> 2 */
#ifdef NUMTEXT_WORDS
    if (ip < 100000000 && dec <= 8) { /* each part built in a register, stored once (8 bytes) */
        uint64_t w = numtext_word8(ip);
        int lead = ip ? __builtin_ctzll(w ^ 0x3030303030303030ull) / 8 : 7;
        w >>= 8 * lead;
        memcpy(p, &w, 8);
        p += 8 - lead;
        if (fp) {
            uint64_t f = numtext_word8(fp) >> (8 * (8 - dec)); /* dec digits, zeros after the point kept */
            *p = '.';
            memcpy(p + 1, &f, 8);
            p += 1 + numtext_significant(f, dec);
        }
        return p;
    }
#endif
    int n = numtext_ndigits(ip);
    numtext_digits(p + n, ip, n);
    p += n;
    if (fp) {
        *p = '.';
        numtext_digits(p + 1 + dec, fp, dec);
        int last = dec;
        while (p[last] == '0') last--; /* fp > 0: stops at a digit */
        p += 1 + last;
    }
    return p;
}

const SylImage *io_image(const SylMesh *m, int material) {
    const SylMaterial *mt = &m->materials[material];
    if (mt->kind == SYL_MATERIAL_LEAF && m->leaves == SYL_LEAVES_CLUSTERS) return NULL; /* clusters: their own card */
    return mt->kind <= SYL_MATERIAL_FLOWER ? syl_material_image(m->images, mt) : NULL;
}

static const char *image_base(const SylImage *g) {
    const char *slash = strrchr(g->name, '/');
    return slash ? slash + 1 : g->name;
}

void io_image_file(const SylMesh *m, int k, const char *prefix, char *buf, size_t n) {
    const char *base = image_base(&m->images->img[k]);
    bool twice = false;
    for (int i = 0; i < k && !twice; i++) twice = !strcmp(image_base(&m->images->img[i]), base);
    char safe[sizeof m->images->img[0].name];
    io_line_text(safe, sizeof safe, base, false);
    if (twice) snprintf(buf, n, "%s_tex%d_%s", prefix, k, safe);
    else snprintf(buf, n, "%s_tex_%s", prefix, safe);
}

const char *io_texture_kind(const SylMesh *m, int material) {
    return syl_texture_name(m->materials[material].kind);
}

void io_material_name(const SylMesh *m, int material, char *buf, size_t n) {
    const char *kind = io_texture_kind(m, material);
    snprintf(buf, n, "%s%d", kind ? kind : "plain", material);
}

/* ---- PNG into memory (util/pngout, the one encoder) ---- */

static void png_mem_write(void *ctx, const void *data, size_t n) { io_put(ctx, data, n); }

typedef struct PngRows {
    const uint8_t *px;
    size_t stride;
} PngRows;

static const void *png_row(void *ctx, int y, void *scratch) {
    (void)scratch;
    const PngRows *r = ctx;
    return r->px + (size_t)y * r->stride;
}

static bool png_encode(IoBuf *b, const uint8_t *px, int w, int h, int channels) {
    PngRows rows = {px, (size_t)w * (size_t)channels};
    /* level 2, fast: the textures are small beside the mesh */
    PngOutImage img = {.width = w, .height = h, .channels = channels, .depth = 8, .level = 2, .row = png_row, .ctx = &rows};
    return pngout_encode_to(png_mem_write, b, "(texture)", &img, NULL) == SYL_OK && !b->failed;
}

bool io_png(IoBuf *b, const uint8_t *rgb, int size) { return png_encode(b, rgb, size, size, 3); }
bool io_png_rgba(IoBuf *b, const uint8_t *rgba, int w, int h) { return png_encode(b, rgba, w, h, 4); }
