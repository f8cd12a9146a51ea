/* The mesh formats by extension (io/formats.def): what each holds, and the writers that go
 * by the output's name. */
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "sylva/lod.h"
#include "sylva/mesh.h"
#include "sylva/wind.h"
#include "util/diag.h"

/* a scene's parts in a .glb: one node each, under the mesh's name */
static int glb_parts(const SylMesh *m, SylMesh *const *parts, int n, const char *path, const SylSink *sink) {
    return syl_mesh_write_glb_parts(parts, n, m->name[0] ? m->name : "scene", path, sink);
}

typedef struct Format {
    SylMeshFormat f;
    int (*write)(const SylMesh *m, const char *path, const SylSink *sink);
    int (*write_parts)(const SylMesh *m, SylMesh *const *parts, int n, const char *path, const SylSink *sink);
} Format;

static const Format formats[] = {
#define FORMAT(ext, name, can, write, parts) {{ext, name, can}, write, parts},
#include "io/formats.def"
#undef FORMAT
};
enum { NFORMATS = sizeof formats / sizeof *formats };

static const Format *format_of(const char *path, const SylSink *sink) {
    const char *dot = strrchr(path, '.');
    for (int i = 0; dot && !strchr(dot, '/') && i < NFORMATS; i++)
        if (!strcasecmp(dot, formats[i].f.ext)) return &formats[i];
    if (sink) { /* "name it *.glb, *.obj or *.ply" */
        char names[256];
        size_t k = 0;
        for (int i = 0; i < NFORMATS && k < sizeof names; i++)
            k += (size_t)snprintf(names + k, sizeof names - k, "%s*%s", i == 0 ? "" : i == NFORMATS - 1 ? " or " : ", ",
                                  formats[i].f.ext);
        sink_error(sink, "cannot tell the format of '%s': name it %s", path, names);
    }
    return NULL;
}

const SylMeshFormat *syl_mesh_format(const char *path, const SylSink *sink) {
    const Format *f = format_of(path, sink);
    return f ? &f->f : NULL;
}

int syl_mesh_write(const SylMesh *m, const char *path, const SylSink *sink) {
    const Format *f = format_of(path, sink);
    return f ? f->write(m, path, sink) : SYL_EUSAGE;
}

int syl_mesh_write_parts(const SylMesh *m, SylMesh *const *parts, int n, const char *path, const SylSink *sink) {
    const Format *f = format_of(path, sink);
    if (!f) return SYL_EUSAGE;
    return n > 0 && f->write_parts ? f->write_parts(m, parts, n, path, sink) : f->write(m, path, sink);
}

int syl_mesh_write_output(const SylMeshOutput *o, const char *path, const SylSink *sink) {
    const Format *f = format_of(path, sink);
    if (!f) return SYL_EUSAGE;
    int wants = (o->lods ? SYL_FORMAT_LEVELS : 0) | (o->wind ? SYL_FORMAT_WIND : 0) |
                (o->instanced ? SYL_FORMAT_INSTANCES : 0);
    if (wants & ~f->f.can) {
        if (sink)
            sink_error(sink, "a %s file cannot hold %s: '%s'", f->f.name,
                    wants & ~f->f.can & SYL_FORMAT_LEVELS ? "levels of detail"
                    : wants & ~f->f.can & SYL_FORMAT_WIND ? "a skinned mesh"
                                                          : "instanced leaves",
                    path);
        return SYL_EUSAGE;
    }
    if (o->lods) return syl_wind_write_glb_lods(o->lods, o->wind ? o->skeleton : NULL, o->wind, path, sink);
    if (o->wind) return syl_wind_write_glb(o->mesh, o->sets, o->instanced ? o->nsets : 0, o->skeleton, o->wind, path, sink);
    if (o->instanced) return syl_mesh_write_glb_instanced(o->mesh, o->sets, o->nsets, path, sink);
    return syl_mesh_write_parts(o->mesh, o->parts, o->nparts, path, sink);
}
