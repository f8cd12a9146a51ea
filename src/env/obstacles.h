/* Obstacles: triangle meshes (read from OBJ files) in an Embree scene, asked whether a
 * straight segment is free — a bud never grows into a wall, and a marker behind a wall is
 * not seen — and how high the terrain is under a point. */
#ifndef SYL_ENV_OBSTACLES_H
#define SYL_ENV_OBSTACLES_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/sylva.h"

#include "util/lazy_embree.h"

typedef struct Obstacles {
    RTCScene scene;  /* NULL until committed with triangles */
    float *v;        /* 3 per vertex, with room for Embree's 16-byte reads */
    size_t nv, vcap;
    uint32_t *tri;
    size_t nt, tcap;
    float lo[3], hi[3]; /* bounds */
} Obstacles;

/* Read an OBJ file and add its triangles scaled by scale and moved by offset.
 * SYL_OK, SYL_EIO or SYL_EMODEL (reported as file:line: error). */
int obstacles_add_obj(Obstacles *o, const char *path, const float offset[3], float scale, const SylSink *sink);
bool obstacles_add(Obstacles *o, const float *v, size_t nv, const uint32_t *tri, size_t nt);
/* Build the Embree scene (after the last add). */
int obstacles_commit(Obstacles *o, RTCDevice dev, const SylSink *sink);
void obstacles_free(Obstacles *o);

static inline bool obstacles_any(const Obstacles *o) { return o->scene != NULL; }
/* Does the segment a-b (extended by margin beyond b) cross an obstacle? */
bool obstacles_blocked(const Obstacles *o, const float a[3], const float b[3], float margin);
/* How far from org along the unit dir the first obstacle surface is (either side of it);
 * far when none is nearer. */
float obstacles_distance(const Obstacles *o, const float org[3], const float dir[3], float far);
/* Is p inside the closed surfaces (odd crossings of a ray from p, counted by parity)? A
 * mesh that is not closed gives an answer, but not a meaningful one. */
bool obstacles_inside(const Obstacles *o, const float p[3]);
/* The height of the highest obstacle surface under (x, z), looking down from y; false if none. */
bool obstacles_height(const Obstacles *o, float x, float z, float y, float *out);

#endif
