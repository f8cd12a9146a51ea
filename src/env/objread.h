/* A small Wavefront OBJ reader for obstacles: vertices (`v x y z`) and faces (`f a b c ...`,
 * indices as i, i/t, i//n or i/t/n, negative ones counting back), polygons split into
 * fans. Everything else (normals, texture coordinates, groups, materials) is skipped.
 * A malformed line is reported as `file:line: error: message`. */
#ifndef SYL_ENV_OBJREAD_H
#define SYL_ENV_OBJREAD_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/sylva.h"

typedef struct ObjMesh {
    float *v;       /* 3 per vertex */
    size_t nv;
    uint32_t *tri;  /* 3 per triangle */
    size_t nt;
} ObjMesh;

/* SYL_OK, SYL_EIO (cannot read) or SYL_EMODEL (malformed, or no faces). */
int obj_read(const char *path, ObjMesh *out, const SylSink *sink);
/* The same on text in memory (path names it in messages). */
int obj_parse(const char *path, const char *text, size_t len, ObjMesh *out, const SylSink *sink);
void obj_free(ObjMesh *m);

#endif
