/* The PLY writer (binary little endian). */

/* Vertices with position, normal and UV (s, t with t up the
 * picture, as Blender and MeshLab read it), faces with three indices and a material index.
 * Materials are described in comments: "comment material INDEX NAME R G B". */
#include <stdlib.h>
#include <string.h>

#include "io/io_internal.h"

static void put_f32(uint8_t *p, float x) {
    uint32_t u;
    memcpy(&u, &x, 4);
    p[0] = (uint8_t)u, p[1] = (uint8_t)(u >> 8), p[2] = (uint8_t)(u >> 16), p[3] = (uint8_t)(u >> 24);
}

static void put_u32(uint8_t *p, uint32_t u) {
    p[0] = (uint8_t)u, p[1] = (uint8_t)(u >> 8), p[2] = (uint8_t)(u >> 16), p[3] = (uint8_t)(u >> 24);
}

int syl_mesh_write_ply(const SylMesh *m, const char *path, const SylSink *sink) {
    OutFile fo;
    if (!io_open(&fo, path, sink)) return SYL_EIO;
    FILE *f = fo.f;
    char name[sizeof m->name];
    io_line_text(name, sizeof name, m->name, false);
    fprintf(f, "ply\nformat binary_little_endian 1.0\ncomment Sylva %s: %s\n", SYLVA_VERSION, name);
    for (int g = 0; g < m->ngroups; g++) {
        int k = m->groups[g].material;
        char name[32];
        io_material_name(m, k, name, sizeof name);
        const float *c = m->materials[k].rgb;
        fprintf(f, "comment material %d %s %.4f %.4f %.4f\n", k, name, c[0], c[1], c[2]);
    }
    fprintf(f,
            "element vertex %zu\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\n"
            "property float s\nproperty float t\n"
            "element face %zu\n"
            "property list uchar uint vertex_indices\n"
            "property uchar material_index\n"
            "end_header\n",
            m->nverts, m->nidx / 3);
    enum { VSIZE = 32, FSIZE = 14, CHUNK = 4096 };
    uint8_t *buf = malloc(CHUNK * VSIZE);
    if (!buf) {
        sink_error(sink, "out of memory writing '%s'", path);
        return io_close(&fo, SYL_ELIMIT, sink);
    }
    for (size_t i = 0; i < m->nverts;) {
        size_t n = m->nverts - i < CHUNK ? m->nverts - i : CHUNK;
        for (size_t k = 0; k < n; k++, i++) {
            uint8_t *p = buf + k * VSIZE;
            for (int c = 0; c < 3; c++) put_f32(p + 4 * c, m->pos[3 * i + c]);
            for (int c = 0; c < 3; c++) put_f32(p + 12 + 4 * c, m->nrm[3 * i + c]);
            put_f32(p + 24, m->uv[2 * i]);
            put_f32(p + 28, 1.0f - m->uv[2 * i + 1]);
        }
        fwrite(buf, VSIZE, n, f);
    }
    for (int g = 0; g < m->ngroups; g++) {
        const uint32_t *ix = m->idx + m->groups[g].first;
        size_t ntri = m->groups[g].count / 3;
        for (size_t t = 0; t < ntri;) {
            size_t n = ntri - t < CHUNK ? ntri - t : CHUNK;
            for (size_t k = 0; k < n; k++, t++) {
                uint8_t *p = buf + k * FSIZE;
                p[0] = 3;
                for (int c = 0; c < 3; c++) put_u32(p + 1 + 4 * c, ix[3 * t + (size_t)c]);
                p[13] = m->groups[g].material;
            }
            fwrite(buf, FSIZE, n, f);
        }
    }
    free(buf);
    return io_close(&fo, SYL_OK, sink); /* fwrite's failures are caught there */
}
