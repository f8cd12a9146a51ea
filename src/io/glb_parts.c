/* The parts of a glTF binary writer (glb.c, and any other writer of .glb: a forest's):
 * little-endian words, padding, accessor
 * bounds, the buffer views and the container. */
#include <math.h>
#include <stdio.h>

#include "io/glb.h"

float glb_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

void glb_u32(IoBuf *b, uint32_t u) {
    uint8_t p[4] = {(uint8_t)u, (uint8_t)(u >> 8), (uint8_t)(u >> 16), (uint8_t)(u >> 24)};
    io_put(b, p, 4);
}

/* Little-endian 32-bit words (floats or integers), whatever the host. */
void glb_words(IoBuf *b, const void *x, size_t n) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    if (n >= 1 << 16) io_ref(b, x, 4 * n); /* a mesh's arrays: written from where they are */
    else io_put(b, x, 4 * n);
#else
    const uint32_t *w = x;
    for (size_t i = 0; i < n; i++) glb_u32(b, w[i]);
#endif
}

void glb_pad(IoBuf *b, uint8_t with) {
    while (b->len % 4 && !b->failed) io_put(b, &with, 1); /* a failed buffer no longer grows */
}

/* "min":[..],"max":[..] of n vectors of k floats. */
void glb_min_max(IoBuf *j, const float *x, size_t n, int k) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < k; c++) {
            float v = x[k * i + (size_t)c];
            if (v < lo[c]) lo[c] = v;
            if (v > hi[c]) hi[c] = v;
        }
    for (int w = 0; w < 2; w++) {
        io_printf(j, ",\"%s\":[", w ? "max" : "min");
        for (int c = 0; c < k; c++) io_printf(j, "%s%.17g", c ? "," : "", (double)(w ? hi[c] : lo[c]));
        io_put(j, "]", 1);
    }
}

/* The GLB container: header, JSON chunk and (with geometry) BIN chunk, through a temporary
 * file. SYL_OK, SYL_ELIMIT or SYL_EIO, reported. */
int glb_container(const char *path, const IoBuf *js, const IoBuf *bin, bool geometry, const SylSink *sink) {
    return glb_container_to(path, NULL, js, bin, geometry, sink);
}

int glb_container_to(const char *path, FILE *stream, const IoBuf *js, const IoBuf *bin, bool geometry, const SylSink *sink) {
    int status = SYL_OK;
    if (js->failed || bin->failed) {
        sink_error(sink, "out of memory writing '%s'", path);
        status = SYL_ELIMIT;
    } else if (12 + 8 + js->len + (geometry ? 8 + bin->len : 0) > UINT32_MAX) {
        sink_error(sink, "'%s' would be larger than 4 GiB, the limit of .glb", path);
        status = SYL_ELIMIT;
    }
    OutFile fo = {.f = stream};
    if (!status && !stream && !io_open(&fo, path, sink)) status = SYL_EIO;
    if (!status) {
        IoBuf head = {0};
        size_t total = 12 + 8 + js->len + (geometry ? 8 + bin->len : 0);
        glb_u32(&head, GLB_MAGIC);
        glb_u32(&head, 2);
        glb_u32(&head, (uint32_t)total);
        glb_u32(&head, (uint32_t)js->len);
        glb_u32(&head, GLB_JSON);
        fwrite(head.data, 1, head.len, fo.f);
        fwrite(js->data, 1, js->len, fo.f);
        if (geometry) {
            head.len = 0;
            glb_u32(&head, (uint32_t)bin->len);
            glb_u32(&head, GLB_BIN);
            fwrite(head.data, 1, head.len, fo.f);
            io_write(bin, fo.f);
        }
        if (head.failed && sink) sink_error(sink, "out of memory writing '%s'", path);
        if (head.failed) status = SYL_ELIMIT;
        io_free(&head);
        if (!stream) status = io_close(&fo, status, sink); /* also catches the fwrite failures above */
        else if (!status && (fflush(stream) || ferror(stream))) {
            sink_error(sink, "cannot write '%s'", path);
            status = SYL_EIO;
        }
    }
    return status;
}

void glb_buffer_views(IoBuf *js, const View *views, int n, size_t bin_len) {
    io_printf(js, ",\"bufferViews\":[");
    for (int v = 0; v < n; v++) {
        io_printf(js, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu", v ? "," : "", views[v].offset,
                  views[v].length);
        if (views[v].stride) io_printf(js, ",\"byteStride\":%d", views[v].stride);
        if (views[v].target) io_printf(js, ",\"target\":%d", views[v].target);
        io_put(js, "}", 1);
    }
    io_printf(js, "],\"buffers\":[{\"byteLength\":%zu}]", bin_len);
}
