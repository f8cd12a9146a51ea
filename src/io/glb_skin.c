/* A skinned plant in a .glb (docs/mesh.md#wind): each vertex's joint (its stem's, or its
 * nearest jointed ancestor's, weight 1) and the shader attributes _BRANCH_LEVEL, _PHASE and
 * _STIFFNESS; the joint nodes (translations from their parent joint, no rest rotation), the
 * inverse bind matrices, and the wind animation of their rotations. glb.c places them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/glb.h"
#include "sylva/stream.h"

static bool wide_joints(const SylWind *w) { return w->njoints > 256; }

/* Point p's weights on joint j (the joint of its stem, or of its nearest jointed ancestor):
 * j's, from the parent joint's to j's by smoothstep(t), 3t^2 - 2t^3, where t grows from 0 to
 * 1 from blend_start to blend_start + blend_length along the stem's first direction from its
 * base, or past the blend's end by the distance to the base (so a twig far out on a stem that
 * bends back is not blended). As bytes summing to 255, the larger first. */
static void blend_weights(const SylWind *w, int32_t j, const float *p, int joint[2], uint8_t weight[2]) {
    joint[0] = j, joint[1] = 0, weight[0] = 255, weight[1] = 0;
    const SylWindJoint *jt = &w->joints[j];
    if (jt->parent < 0 || !(jt->blend_length > 0)) return;
    const SylWindStem *st = &w->stems[jt->stem];
    double s = 0, d2 = 0;
    for (int c = 0; c < 3; c++) {
        double x = (double)p[c] - st->base[c];
        s += x * st->dir[c], d2 += x * x;
    }
    double a = jt->blend_start, l = jt->blend_length, x = fmax(s, sqrt(d2) - (a + l));
    double t = fmin(1, fmax(0, (x - a) / l));
    long own = lround(255 * t * t * (3 - 2 * t));
    if (own == 0) joint[0] = jt->parent; /* all the parent's */
    else if (own < 255) joint[1] = jt->parent;
    if (own > 0 && own < 255) weight[0] = (uint8_t)own, weight[1] = (uint8_t)(255 - own);
    if (weight[1] > weight[0]) {
        int k = joint[0];
        uint8_t x8 = weight[0];
        joint[0] = joint[1], joint[1] = k, weight[0] = weight[1], weight[1] = x8;
    }
}

/* The joint of node nd's stem, or of its nearest jointed ancestor. */
static int joint_of_node(const SylSkeleton *s, const SylWind *w, int32_t nd) {
    int32_t j = w->stems[syl_wind_stem_of(s, w, nd)].joint;
    return j >= 0 ? j : 0;
}

/* The joint of vertex v's stem, or of its nearest jointed ancestor. */
static int joint_of(const GlbPart *p, size_t v) {
    const SylWind *w = p->wind;
    int32_t j = w->stems[syl_wind_stem_of(p->skel, w, p->mesh->node ? p->mesh->node[v] : -1)].joint;
    return j >= 0 ? j : 0;
}

/* The joint an instance follows: of the two of the blend at its place, the heavier. */
static int joint_of_instance(const GlbPart *p, const SylInstances *set, size_t i) {
    int j[2];
    uint8_t wt[2];
    blend_weights(p->wind, joint_of_node(p->skel, p->wind, set->node ? set->node[i] : -1), set->t + 3 * i, j, wt);
    return j[0];
}

void syl_wind_skin(const SylMesh *m, const SylSkeleton *s, const SylWind *w, int32_t *joints, uint8_t *weights) {
    for (size_t v = 0; v < m->nverts; v++) {
        int j[2];
        blend_weights(w, joint_of_node(s, w, m->node ? m->node[v] : -1), m->pos + 3 * v, j, weights + 2 * v);
        joints[2 * v] = j[0], joints[2 * v + 1] = j[1];
    }
}

bool glb_skin_split(const GlbPart *p, SylInstances **out, int **joint, int *n) {
    const SylWind *w = p->wind;
    *out = NULL, *joint = NULL, *n = 0;
    int *of = NULL, *count = calloc((size_t)w->njoints, sizeof *count), total = 0;
    size_t most = 1;
    for (int s = 0; s < p->nsets; s++) most = p->sets[s].count > most ? p->sets[s].count : most;
    if (!count || !(of = malloc(most * sizeof *of))) goto oom;
    for (int pass = 0; pass < 2; pass++) /* count the sets, then fill them */
        for (int s = 0, k = 0; s < p->nsets; s++) {
            const SylInstances *set = &p->sets[s];
            for (int j = 0; j < w->njoints; j++) count[j] = 0;
            for (size_t i = 0; i < set->count; i++) count[of[i] = joint_of_instance(p, set, i)]++;
            for (int j = 0; j < w->njoints; j++) {
                if (!count[j]) continue;
                if (!pass) {
                    total++;
                    continue;
                }
                SylInstances *o = &(*out)[k];
                (*joint)[k++] = j;
                snprintf(o->name, sizeof o->name, "%.40s_stem%d", set->name, w->joints[j].stem);
                o->proto = set->proto; /* borrowed: glb_skin_split_free leaves it */
                o->t = malloc(3 * sizeof *o->t * (size_t)count[j]);
                o->r = malloc(4 * sizeof *o->r * (size_t)count[j]);
                o->s = malloc(3 * sizeof *o->s * (size_t)count[j]);
                if (!o->t || !o->r || !o->s) goto oom;
                const float *b = w->stems[w->joints[j].stem].base;
                for (size_t i = 0; i < set->count; i++) {
                    if (of[i] != j) continue;
                    size_t c = o->count++;
                    for (int a = 0; a < 3; a++) o->t[3 * c + a] = set->t[3 * i + a] - b[a];
                    memcpy(o->r + 4 * c, set->r + 4 * i, 4 * sizeof *o->r);
                    memcpy(o->s + 3 * c, set->s + 3 * i, 3 * sizeof *o->s);
                }
            }
            if (!pass && s == p->nsets - 1 && total) {
                *out = calloc((size_t)total, sizeof **out);
                *joint = malloc((size_t)total * sizeof **joint);
                *n = total;
                if (!*out || !*joint) goto oom;
            }
        }
    free(count), free(of);
    return true;
oom:
    free(count), free(of);
    glb_skin_split_free(*out, *n);
    free(*joint);
    *out = NULL, *joint = NULL, *n = 0;
    return false;
}

void glb_skin_split_free(SylInstances *sets, int n) {
    for (int i = 0; sets && i < n; i++) free(sets[i].t), free(sets[i].r), free(sets[i].s);
    free(sets);
}

void glb_skin_vertices(const GlbPart *p, IoBuf *bin, View *views, int *nviews, bool strided) {
    const SylMesh *m = p->mesh;
    const SylWind *w = p->wind;
    size_t nv = m->nverts, at = bin->len;
    bool wide = wide_joints(w);
    uint8_t *wt = malloc(4 * nv + 4);
    if (!wt) {
        bin->failed = true;
        return;
    }
    for (size_t v = 0; v < nv; v++) { /* JOINTS_0: two joints, then two unused (weight 0) */
        int j[2];
        blend_weights(w, joint_of(p, v), m->pos + 3 * v, j, wt + 4 * v);
        wt[4 * v + 2] = wt[4 * v + 3] = 0;
        uint8_t shorts[8] = {(uint8_t)j[0], (uint8_t)(j[0] >> 8), (uint8_t)j[1], (uint8_t)(j[1] >> 8)};
        uint8_t bytes[4] = {(uint8_t)j[0], (uint8_t)j[1]};
        if (wide) io_put(bin, shorts, 8);
        else io_put(bin, bytes, 4);
    }
    views[(*nviews)++] = (View){at, bin->len - at, ARRAY_BUFFER, strided ? (wide ? 8 : 4) : 0};
    at = bin->len; /* WEIGHTS_0: normalized bytes summing to 255, 1 exactly */
    io_put(bin, wt, 4 * nv);
    free(wt);
    views[(*nviews)++] = (View){at, bin->len - at, ARRAY_BUFFER, strided ? 4 : 0};
    for (int a = 0; a < 3; a++) { /* _BRANCH_LEVEL, _PHASE, _STIFFNESS of the vertex's own stem */
        at = bin->len;
        for (size_t v = 0; v < nv; v++) {
            const SylWindStem *st = &w->stems[syl_wind_stem_of(p->skel, w, m->node ? m->node[v] : -1)];
            float x = a == 0 ? (float)st->order : a == 1 ? st->phase : st->stiffness;
            glb_words(bin, &x, 1);
        }
        views[(*nviews)++] = (View){at, bin->len - at, ARRAY_BUFFER, strided ? 4 : 0};
    }
}

void glb_skin_animation(const SylWind *w, IoBuf *bin, View *views, int *nviews) {
    size_t at = bin->len;
    for (int j = 0; j < w->njoints; j++) { /* inverse bind matrices: the joint's base, undone */
        const float *b = w->stems[w->joints[j].stem].base;
        float ibm[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -b[0], -b[1], -b[2], 1};
        glb_words(bin, ibm, 16);
    }
    views[(*nviews)++] = (View){at, bin->len - at, 0, 0};
    at = bin->len;
    for (int k = 0; k < w->nkeys; k++) {
        float t = k == w->nkeys - 1 ? w->seconds : w->seconds * (float)k / (float)(w->nkeys - 1);
        glb_words(bin, &t, 1);
    }
    views[(*nviews)++] = (View){at, bin->len - at, 0, 0};
    at = bin->len;
    glb_words(bin, w->rot, 4 * (size_t)w->njoints * (size_t)w->nkeys);
    views[(*nviews)++] = (View){at, bin->len - at, 0, 0};
}

/* The mesh's five vertex accessors (views view..view+4) over vertices lo .. lo + nv - 1. */
void glb_skin_vertex_accessors(IoBuf *js, const GlbPart *p, int view, size_t lo, size_t nv) {
    const SylWind *w = p->wind;
    const size_t size[5] = {wide_joints(w) ? 8 : 4, 4, 4, 4, 4}; /* an element's bytes */
    const int type[5] = {wide_joints(w) ? UNSIGNED_SHORT : UNSIGNED_BYTE, UNSIGNED_BYTE, FLOAT, FLOAT, FLOAT};
    for (int a = 0; a < 5; a++) {
        io_printf(js, ",{\"bufferView\":%d,", view + a);
        if (lo) io_printf(js, "\"byteOffset\":%zu,", lo * size[a]);
        io_printf(js, "\"componentType\":%d,%s\"count\":%zu,\"type\":\"%s\"}", type[a],
                  a == 1 ? "\"normalized\":true," : "", nv, a < 2 ? "VEC4" : "SCALAR");
    }
}

/* From view anim on: the inverse bind matrices, the key times and each joint's rotations. */
void glb_skin_anim_accessors(IoBuf *js, const SylWind *w, int anim) {
    io_printf(js, ",{\"bufferView\":%d,\"componentType\":%d,\"count\":%d,\"type\":\"MAT4\"}", anim, FLOAT, w->njoints);
    io_printf(js, ",{\"bufferView\":%d,\"componentType\":%d,\"count\":%d,\"type\":\"SCALAR\",\"min\":[0],\"max\":[%.9g]}",
              anim + 1, FLOAT, w->nkeys, (double)w->seconds);
    for (int j = 0; j < w->njoints; j++)
        io_printf(js, ",{\"bufferView\":%d,\"byteOffset\":%zu,\"componentType\":%d,\"count\":%d,\"type\":\"VEC4\"}",
                  anim + 2, (size_t)j * (size_t)w->nkeys * 16, FLOAT, w->nkeys);
}

/* The vertex attributes' part of a primitive; acc: the first of the five. */
void glb_skin_attributes(IoBuf *js, int acc) {
    io_printf(js, ",\"JOINTS_0\":%d,\"WEIGHTS_0\":%d,\"_BRANCH_LEVEL\":%d,\"_PHASE\":%d,\"_STIFFNESS\":%d", acc,
              acc + 1, acc + 2, acc + 3, acc + 4);
}

/* The root joints, as children of the skinned node: ,N,.. */
void glb_skin_roots(IoBuf *js, const SylWind *w, int first_node, bool comma) {
    for (int j = 0; j < w->njoints; j++)
        if (w->joints[j].parent < 0) io_printf(js, "%s%d", comma ? "," : "", first_node + j), comma = true;
}

/* The joint nodes, numbered from first_node: ,{..},{..}. With prefix, a copy of them named
 * PREFIX_stemA (a level's anchors for its leaves), without their extras; extra: more
 * children of joint j, extra[start[j]] .. extra[start[j + 1] - 1] (start may be NULL). */
void glb_skin_nodes(IoBuf *js, const SylWind *w, int first_node, const char *prefix, const int *start, const int *extra) {
    int *child = malloc(((size_t)w->njoints + 1) * sizeof *child), *next = malloc(((size_t)w->njoints + 1) * sizeof *next);
    if (!child || !next) {
        js->failed = true;
        free(child), free(next);
        return;
    }
    for (int j = 0; j < w->njoints; j++) child[j] = next[j] = -1;
    for (int j = w->njoints - 1; j >= 0; j--) /* children in joint order */
        if (w->joints[j].parent >= 0) next[j] = child[w->joints[j].parent], child[w->joints[j].parent] = j;
    for (int j = 0; j < w->njoints; j++) {
        const SylWindJoint *jt = &w->joints[j];
        const float *b = w->stems[jt->stem].base, *pb = jt->parent >= 0 ? w->stems[w->joints[jt->parent].stem].base : NULL;
        char name[96];
        snprintf(name, sizeof name, "%.80s%sstem%d", prefix ? prefix : "", prefix ? "_" : "", jt->stem);
        io_printf(js, ",{\"name\":");
        io_json_string(js, name);
        io_printf(js, ",\"translation\":[%.9g,%.9g,%.9g]", (double)(b[0] - (pb ? pb[0] : 0)),
                  (double)(b[1] - (pb ? pb[1] : 0)), (double)(b[2] - (pb ? pb[2] : 0)));
        bool more = start && start[j + 1] > start[j];
        if (child[j] >= 0 || more) {
            io_printf(js, ",\"children\":[");
            bool first = true;
            for (int c = child[j]; c >= 0; c = next[c], first = false) io_printf(js, "%s%d", first ? "" : ",", first_node + c);
            for (int e = more ? start[j] : 0; more && e < start[j + 1]; e++, first = false)
                io_printf(js, "%s%d", first ? "" : ",", extra[e]);
            io_put(js, "]", 1);
        }
        if (prefix) {
            io_put(js, "}", 1);
            continue;
        }
        io_printf(js, ",\"extras\":{\"sylva_wind\":{\"amplitude\":%.6g,\"frequency\":%.6g", (double)jt->amplitude,
                  (double)jt->frequency);
        if (jt->blend_length > 0) {
            const float *d = w->stems[jt->stem].dir;
            io_printf(js, ",\"blend\":[%.9g,%.9g],\"direction\":[%.9g,%.9g,%.9g]", (double)jt->blend_start,
                      (double)jt->blend_length, (double)d[0], (double)d[1], (double)d[2]);
        }
        io_put(js, "}}}", 3);
    }
    free(child);
    free(next);
}

/* "skins" and "animations"; anim_acc: the inverse bind matrices' accessor. The copies of
 * the joints from nodes copies[0], .. copies[ncopies - 1] turn with them (the same samplers). */
void glb_skin_json(IoBuf *js, const SylWind *w, int first_node, int anim_acc, const int *copies, int ncopies) {
    io_printf(js, ",\"skins\":[{\"inverseBindMatrices\":%d,\"joints\":[", anim_acc);
    for (int j = 0; j < w->njoints; j++) io_printf(js, "%s%d", j ? "," : "", first_node + j);
    io_printf(js, "]}],\"animations\":[{\"name\":\"wind\",\"samplers\":[");
    for (int j = 0; j < w->njoints; j++)
        io_printf(js, "%s{\"input\":%d,\"output\":%d,\"interpolation\":\"LINEAR\"}", j ? "," : "", anim_acc + 1, anim_acc + 2 + j);
    io_printf(js, "],\"channels\":[");
    for (int c = -1; c < ncopies; c++)
        for (int j = 0; j < w->njoints; j++)
            io_printf(js, "%s{\"sampler\":%d,\"target\":{\"node\":%d,\"path\":\"rotation\"}}", j || c >= 0 ? "," : "",
                      j, (c < 0 ? first_node : copies[c]) + j);
    io_printf(js, "]}]");
}

static int write_wind(const SylMesh *m, const SylInstances *sets, int n, const SylSkeleton *s, const SylWind *w,
                      const char *path, FILE *stream, SylTextureCache *tc, const SylSink *sink) {
    if (!m->node) {
        sink_error(sink, "the mesh has no vertex nodes to skin (SylMeshOptions.vertex_nodes)");
        return SYL_EUSAGE;
    }
    const char *name = m->name[0] ? m->name : "plant";
    GlbPart part = {.mesh = m, .sets = sets, .nsets = n > 0 ? n : 0, .name = name, .wind = w, .skel = s};
    GlbScene sc = {.part = &part, .nparts = 1, .scene_name = name, .stream = stream, .textures = tc};
    return glb_write(&sc, path, sink);
}

int syl_wind_write_glb(const SylMesh *m, const SylInstances *sets, int n, const SylSkeleton *s, const SylWind *w,
                       const char *path, const SylSink *sink) {
    return write_wind(m, sets, n, s, w, path, NULL, NULL, sink);
}

int syl_wind_write_glb_stream(const SylMesh *m, const SylInstances *sets, int n, const SylSkeleton *s,
                              const SylWind *w, FILE *out, const SylSink *sink) {
    return write_wind(m, sets, n, s, w, "(stream)", out, NULL, sink);
}

int syl_wind_write_glb_cached(const SylMesh *m, const SylInstances *sets, int n, const SylSkeleton *s,
                              const SylWind *w, SylTextureCache *tc, FILE *out, const SylSink *sink) {
    return write_wind(m, sets, n, s, w, "(stream)", out, tc, sink);
}
