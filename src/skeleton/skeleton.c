/* Skeleton storage, bounds and export. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>

#include "sylva/skeleton.h"
#include "skeleton/store.h"
#include "util/array.h"
#include "util/budget.h"
#include "util/json.h"
#include "util/numcache.h"
#include "util/numtext.h"
#include "util/pages.h"

const char *const syl_kind_names[SYL_KIND_COUNT] = {"root", "internode", "leaf", "flower",
                                                   "needle", "sphere", "bud", "disc"};

/* A default palette: what the renderer draws when a model sets no colours. Index 0 is bark,
 * 1 leaf, 2 flower, then plain colours for models that count with ' ; , */
static const SylMaterial palette[] = {
    {.rgb = {0.40f, 0.28f, 0.18f}, .kind = SYL_MATERIAL_BARK},   {.rgb = {0.22f, 0.50f, 0.14f}, .kind = SYL_MATERIAL_LEAF},
    {.rgb = {0.92f, 0.55f, 0.70f}, .kind = SYL_MATERIAL_FLOWER}, {.rgb = {0.85f, 0.75f, 0.25f}, .kind = SYL_MATERIAL_PLAIN},
    {.rgb = {0.30f, 0.45f, 0.80f}, .kind = SYL_MATERIAL_PLAIN},  {.rgb = {0.80f, 0.30f, 0.25f}, .kind = SYL_MATERIAL_PLAIN},
    {.rgb = {0.55f, 0.70f, 0.30f}, .kind = SYL_MATERIAL_LEAF},   {.rgb = {0.95f, 0.95f, 0.90f}, .kind = SYL_MATERIAL_FLOWER},
};

/* The skeleton and its store, one allocation. */
typedef struct Whole {
    SylSkeleton s;
    struct SylSkeletonStore store;
} Whole;

SylSkeleton *syl_skeleton_new(const char *name) {
    Whole *w = calloc(1, sizeof *w);
    if (!w) return NULL;
    SylSkeleton *s = &w->s;
    s->store = &w->store;
    snprintf(s->name, sizeof s->name, "%s", name ? name : "plant");
    int np = (int)(sizeof palette / sizeof *palette);
    for (int i = 0; i < 256; i++) s->materials[i] = palette[i % np];
    s->nmaterials = 1;
    return s;
}

static bool in_block(const SylSkeleton *s, const void *p) {
    const char *b = s->store->block;
    return b && p && (const char *)p >= b && (const char *)p < b + s->store->block_bytes;
}

/* An array in the block, about to grow, moved out to malloc's first (the block is freed whole). */
static bool own(SylSkeleton *s, void *arrp, size_t n, size_t elem) {
    void **arr = arrp;
    if (!in_block(s, *arr)) return true;
    void *p = malloc(n ? n * elem : 1);
    if (!p) return false;
    memcpy(p, *arr, n * elem);
    *arr = p;
    return true;
}

void skeleton_adopt_block(SylSkeleton *s, void *block, size_t bytes) {
    pages_free(s->store->block, s->store->block_bytes);
    s->store->block = block, s->store->block_bytes = bytes;
}

void syl_skeleton_free(SylSkeleton *s) {
    if (!s) return;
    if (s->store) budget_release(s->store->budget, s->store->charged);
    if (!in_block(s, s->nodes)) free(s->nodes);
    if (!in_block(s, s->organs)) free(s->organs);
    pages_free(s->store->block, s->store->block_bytes);
    free(s->polys);
    free(s->poly_verts);
    free(s->parts);
    syl_images_release(s->images);
    free(s);
}

int syl_skeleton_add_part(SylSkeleton *s, const char *name, int obstacle) {
    /* grown by doubling: one more each time was quadratic (10,000 plants copied 4 GB under ASan) */
    if (s->nparts >= INT32_MAX || !array_reserve(&s->parts, &s->store->part_cap, (size_t)s->nparts + 1, sizeof *s->parts))
        return -1;
    SylSkeletonPart *p = s->parts + s->nparts;
    *p = (SylSkeletonPart){.first_node = s->nnodes, .obstacle = obstacle};
    /* unique: Beech, Beech_2, Beech_3. The k-th part of a name is guessed from how many have it
     * already (one pass), then checked; a scene of 10,000 plants of one model stays linear per
     * part, not a search of every suffix in turn */
    size_t n = strlen(name);
    int same = 0;
    for (int i = 0; i < s->nparts; i++) {
        const char *q = s->parts[i].name;
        if (!strncmp(q, name, n) && (q[n] == 0 || (q[n] == '_' && q[n + 1] >= '0' && q[n + 1] <= '9'))) same++;
    }
    int k = same + 1;
    if (k == 1) snprintf(p->name, sizeof p->name, "%s", name);
    else snprintf(p->name, sizeof p->name, "%.50s_%d", name, k);
    for (int again = 1; again;) {
        again = 0;
        for (int i = 0; i < s->nparts && !again; i++)
            if (!strcmp(s->parts[i].name, p->name)) again = 1;
        if (again) snprintf(p->name, sizeof p->name, "%.50s_%d", name, ++k);
    }
    return s->nparts++;
}

void skeleton_charge(SylSkeleton *s, SylBudget *b, uint64_t bytes) {
    s->store->budget = b;
    s->store->charged = bytes;
}

/* Room reserved at once (a generator that knows its counts): on huge pages when large
 * (util/pages.h), so that filling it costs a fault per 2 MB, not per 4 KB. */
static bool reserve(void *arrp, size_t *cap, size_t used, size_t n, size_t elem) {
    void **arr = arrp;
    if (n <= *cap) return true;
    if (n > PTRDIFF_MAX / elem || n * elem < PAGES_OWNED_KEPT) return array_reserve(arrp, cap, n, elem);
    void *p = pages_owned(n * elem, PAGES_OWNED_KEPT);
    if (!p) return false;
    if (used) memcpy(p, *arr, used * elem);
    free(*arr);
    *arr = p, *cap = n;
    return true;
}

bool skeleton_reserve_nodes(SylSkeleton *s, size_t n) {
    if (n > s->store->node_cap && !own(s, &s->nodes, s->nnodes, sizeof *s->nodes)) return false;
    return reserve(&s->nodes, &s->store->node_cap, s->nnodes, n, sizeof *s->nodes);
}

bool skeleton_reserve_organs(SylSkeleton *s, size_t n) {
    if (n > s->store->organ_cap && !own(s, &s->organs, s->norgans, sizeof *s->organs)) return false;
    return reserve(&s->organs, &s->store->organ_cap, s->norgans, n, sizeof *s->organs);
}

void skeleton_adopt_organs(SylSkeleton *s, SylOrgan *organs, size_t n, size_t cap) {
    if (!in_block(s, s->organs)) free(s->organs);
    s->organs = organs, s->norgans = n, s->store->organ_cap = cap;
}

static void note_material(SylSkeleton *s, uint8_t m) {
    if (m >= s->nmaterials) s->nmaterials = m + 1;
}

int32_t syl_skeleton_add_node(SylSkeleton *s, const SylNode *n) {
    if (s->nnodes >= s->store->node_cap && !own(s, &s->nodes, s->nnodes, sizeof *n)) return -1;
    if (s->nnodes >= INT32_MAX || !array_reserve(&s->nodes, &s->store->node_cap, s->nnodes + 1, sizeof *n)) return -1;
    s->nodes[s->nnodes] = *n;
    /* round: callers built their nodes before lobes sat in the padding, which they leave unset;
     * a model lobes its nodes after adding them (weber writes them itself) */
    s->nodes[s->nnodes].lobes = 0, s->nodes[s->nnodes].lobe_depth = 0;
    note_material(s, n->material);
    return (int32_t)s->nnodes++;
}

int32_t syl_skeleton_add_organ(SylSkeleton *s, const SylOrgan *o) {
    if (s->norgans >= s->store->organ_cap && !own(s, &s->organs, s->norgans, sizeof *o)) return -1;
    if (s->norgans >= INT32_MAX || !array_reserve(&s->organs, &s->store->organ_cap, s->norgans + 1, sizeof *o))
        return -1;
    SylOrgan *d = &s->organs[s->norgans];
    *d = *o;
    /* the two bytes between material and module are padding the caller's struct leaves unset:
     * zeroed, so that one seed gives one skeleton to the byte (memcmp, checkpoints) */
    memset(&d->material + 1, 0, offsetof(SylOrgan, module) - offsetof(SylOrgan, material) - 1);
    note_material(s, o->material);
    return (int32_t)s->norgans++;
}

int32_t syl_skeleton_add_polygon(SylSkeleton *s, const float (*verts)[3], uint32_t n, int32_t node,
                                 uint8_t material, uint32_t module) {
    /* SylPolygon.first is 32-bit: every vertex index must fit */
    if (s->npolys >= INT32_MAX || s->nverts + n > UINT32_MAX ||
        !array_reserve(&s->polys, &s->store->poly_cap, s->npolys + 1, sizeof *s->polys) ||
        !array_reserve(&s->poly_verts, &s->store->vert_cap, s->nverts + n, sizeof *s->poly_verts))
        return -1; /* all the room first: a failure leaves no orphan vertices */
    for (uint32_t i = 0; i < n; i++) memcpy(s->poly_verts[s->nverts++], verts[i], sizeof *verts);
    SylPolygon *p = &s->polys[s->npolys];
    p->first = (uint32_t)(s->nverts - n);
    p->count = n;
    p->node = node;
    p->material = material;
    p->module = module;
    note_material(s, material);
    return (int32_t)s->npolys++;
}

static void extend(float lo[3], float hi[3], const float p[3], float r) {
    for (int k = 0; k < 3; k++) {
        if (p[k] - r < lo[k]) lo[k] = p[k] - r;
        if (p[k] + r > hi[k]) hi[k] = p[k] + r;
    }
}

void syl_skeleton_bounds(const SylSkeleton *s, float lo[3], float hi[3]) {
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (size_t i = 0; i < s->nnodes; i++) extend(lo, hi, s->nodes[i].pos, s->nodes[i].radius);
    for (size_t i = 0; i < s->norgans; i++) extend(lo, hi, s->organs[i].pos, s->organs[i].size);
    for (size_t i = 0; i < s->nverts; i++) extend(lo, hi, s->poly_verts[i], 0);
    if (lo[0] > hi[0])
        for (int k = 0; k < 3; k++) lo[k] = hi[k] = 0;
}

/* Rows written without printf, through a buffer: numtext writes "%.6g" and "%d"'s very text
 * (docs/mesh.md#number-text), five times as fast. */
enum { ROWS_SIZE = 1 << 18, ROW_MAX = 1024, TAIL_MAX = 96 };

/* The end of a JSON row as text, kept while the values it is made of repeat (a leaf's size,
 * kind and material; a node's order, axis, kind and material along its stem). */
typedef struct Tail {
    uint64_t key;
    bool ok;
    size_t len;
    char text[TAIL_MAX];
} Tail;

typedef struct Rows {
    FILE *out;
    char *p, buf[ROWS_SIZE + ROW_MAX];
    NumCache sizes; /* radii and sizes repeat (a species' leaves share one); positions do not */
    /* JSON's `,"kind":"NAME","material":` for each kind, made once a write from syl_kind_names:
     * one fixed 48-byte copy a row instead of strlen and a call to memcpy */
    struct {
        char text[48];
        size_t len;
    } kind[SYL_KIND_COUNT];
    /* the row's id as text, counted up in place: ids go 0, 1, 2, ... */
    char id[32];
    size_t id_len;
    /* `,"parent":P,"x":` of the last organ row: a node's organs follow each other */
    int parent;
    size_t parent_len;
    char parent_text[48];
    Tail tail;
} Rows;

static Rows *rows_new(FILE *out) {
    Rows *r = malloc(sizeof *r);
    if (!r) return NULL;
    r->out = out, r->p = r->buf;
    numcache_init(&r->sizes, "0", 1);
    for (int k = 0; k < SYL_KIND_COUNT; k++) {
        int n = snprintf(r->kind[k].text, sizeof r->kind[k].text, ",\"kind\":\"%s\",\"material\":", syl_kind_names[k]);
        r->kind[k].len = n > 0 && (size_t)n < sizeof r->kind[k].text ? (size_t)n : 0;
    }
    memset(r->id, 0, sizeof r->id);
    r->parent_len = 0;
    r->tail.ok = false;
    return r;
}

/* The id counter set to v. */
static void rows_id_set(Rows *r, size_t v) { r->id_len = (size_t)(numtext_int(r->id, (long long)v) - r->id); }

/* The id written, then counted up by one for the next row. */
static void rows_id(Rows *r) {
    memcpy(r->p, r->id, 24); /* at most 20 digits */
    r->p += r->id_len;
    size_t i = r->id_len;
    while (i > 0 && r->id[i - 1] == '9') r->id[--i] = '0';
    if (i > 0) r->id[i - 1]++;
    else memmove(r->id + 1, r->id, r->id_len++), r->id[0] = '1'; /* 99 -> 100 */
}

static void rows_text(Rows *r, const char *s) {
    size_t n = strlen(s);
    memcpy(r->p, s, n);
    r->p += n;
}
static void rows_int(Rows *r, long long v) { r->p = numtext_int(r->p, v); }
static void rows_g(Rows *r, float x) { r->p = numtext_g6(r->p, x); }
static char *text_g(char *p, float x, int prec) { return numtext_g(p, x, prec); }
static void rows_size(Rows *r, float x) { r->p = numcache_put(&r->sizes, r->p, x, 6, text_g); }
static void rows_kind(Rows *r, uint8_t kind) {
    memcpy(r->p, r->kind[kind].text, sizeof r->kind[kind].text);
    r->p += r->kind[kind].len;
}
/* The tail for key: its kept text when key is the last one's; otherwise the text just written
 * from start (the row so far) to r->p is kept for the next row. */
static bool rows_tail_hit(Rows *r, uint64_t key) {
    if (!r->tail.ok || r->tail.key != key) return false;
    memcpy(r->p, r->tail.text, TAIL_MAX);
    r->p += r->tail.len;
    return true;
}
static void rows_tail_keep(Rows *r, uint64_t key, const char *start) {
    size_t n = (size_t)(r->p - start);
    r->tail.ok = n <= TAIL_MAX;
    if (r->tail.ok) memcpy(r->tail.text, start, n), r->tail.len = n, r->tail.key = key;
}
static void rows_end(Rows *r) { /* after each row: at most ROW_MAX bytes were added */
    if (r->p - r->buf >= ROWS_SIZE) {
        /* a whole ROWS_SIZE: a stream whose buffer is empty and divides it writes it straight
         * through, where a longer piece is first copied into the stream's buffer */
        fwrite(r->buf, 1, ROWS_SIZE, r->out);
        size_t rest = (size_t)(r->p - r->buf) - ROWS_SIZE;
        memcpy(r->buf, r->buf + ROWS_SIZE, rest);
        r->p = r->buf + rest;
    }
}
static void rows_flush(Rows *r) { fwrite(r->buf, 1, (size_t)(r->p - r->buf), r->out), r->p = r->buf; }

/* id,parent,x,y,z,size,order,kind */
static void csv_row(Rows *r, size_t id, int parent, const float pos[3], float size, unsigned order, uint8_t kind) {
    rows_int(r, (long long)id), *r->p++ = ',';
    rows_int(r, parent);
    for (int k = 0; k < 3; k++) *r->p++ = ',', rows_g(r, pos[k]);
    *r->p++ = ',', rows_size(r, size), *r->p++ = ',';
    rows_int(r, order), *r->p++ = ',';
    rows_text(r, syl_kind_names[kind]);
    *r->p++ = '\n';
    rows_end(r);
}

int syl_skeleton_write_csv(const SylSkeleton *s, FILE *out) {
    Rows *r = rows_new(out);
    if (!r) return SYL_ELIMIT;
    rows_text(r, "id,parent,x,y,z,radius,order,kind\n");
    for (size_t i = 0; i < s->nnodes; i++) {
        const SylNode *n = &s->nodes[i];
        csv_row(r, i, n->parent, n->pos, n->radius, n->order, n->kind);
    }
    for (size_t i = 0; i < s->norgans; i++) {
        const SylOrgan *o = &s->organs[i];
        unsigned order = o->node >= 0 ? s->nodes[o->node].order : 0;
        csv_row(r, s->nnodes + i, o->node, o->pos, o->size / 2, order, o->kind);
    }
    rows_flush(r);
    free(r);
    return ferror(out) ? SYL_EIO : SYL_OK;
}

static void put_rows(void *ctx, const void *p, size_t n) {
    Rows *r = ctx;
    memcpy(r->p, p, n);
    r->p += n;
}

/* a row's start: `\n{"id":ID` after a comma but for the first */
static void rows_row(Rows *r, size_t i) {
    if (i) memcpy(r->p, ",\n{\"id\":", 8), r->p += 8;
    else memcpy(r->p, "\n{\"id\":", 7), r->p += 7;
    rows_id(r);
}

/* X,"y":Y,"z":Z */
static void json_xyz(Rows *r, const float pos[3]) {
    rows_g(r, pos[0]);
    memcpy(r->p, ",\"y\":", 5), r->p += 5;
    rows_g(r, pos[1]);
    memcpy(r->p, ",\"z\":", 5), r->p += 5;
    rows_g(r, pos[2]);
}

int syl_skeleton_write_json(const SylSkeleton *s, FILE *out) {
    Rows *r = rows_new(out);
    if (!r) return SYL_ELIMIT;
    /* the head in the rows' buffer: the stream's own stays empty (see rows_end) */
    rows_text(r, "{\"name\":");
    json_string(s->name, put_rows, r); /* any string: syl_skeleton_new takes one; 64 bytes < ROW_MAX / 6 */
    rows_text(r, ",\"nodes\":[");
    rows_id_set(r, 0);
    for (size_t i = 0; i < s->nnodes; i++) {
        const SylNode *n = &s->nodes[i];
        rows_row(r, i);
        memcpy(r->p, ",\"parent\":", 10), r->p += 10;
        rows_int(r, n->parent);
        memcpy(r->p, ",\"x\":", 5), r->p += 5;
        json_xyz(r, n->pos);
        memcpy(r->p, ",\"radius\":", 10), r->p += 10;
        rows_size(r, n->radius);
        uint64_t key = (uint64_t)(uint32_t)n->axis | (uint64_t)n->order << 32 | (uint64_t)n->kind << 48 |
                       (uint64_t)n->material << 56;
        if (!rows_tail_hit(r, key)) {
            char *start = r->p;
            rows_text(r, ",\"order\":"), rows_int(r, n->order);
            rows_text(r, ",\"axis\":"), rows_int(r, n->axis);
            rows_kind(r, n->kind), rows_int(r, n->material);
            *r->p++ = '}';
            rows_tail_keep(r, key, start);
        }
        rows_end(r);
    }
    rows_text(r, "\n],\"organs\":[");
    r->tail.ok = false;
    rows_id_set(r, s->nnodes);
    for (size_t i = 0; i < s->norgans; i++) {
        const SylOrgan *o = &s->organs[i];
        rows_row(r, i);
        if (!r->parent_len || o->node != r->parent) {
            char *e = r->parent_text;
            memcpy(e, ",\"parent\":", 10), e += 10;
            e = numtext_int(e, o->node);
            memcpy(e, ",\"x\":", 5), e += 5;
            r->parent = o->node, r->parent_len = (size_t)(e - r->parent_text);
        }
        memcpy(r->p, r->parent_text, 32);
        r->p += r->parent_len;
        json_xyz(r, o->pos);
        uint32_t bits;
        memcpy(&bits, &o->size, 4);
        uint64_t key = bits | (uint64_t)o->kind << 32 | (uint64_t)o->material << 40;
        if (!rows_tail_hit(r, key)) {
            char *start = r->p;
            rows_text(r, ",\"size\":"), rows_size(r, o->size);
            rows_kind(r, o->kind), rows_int(r, o->material);
            *r->p++ = '}';
            rows_tail_keep(r, key, start);
        }
        rows_end(r);
    }
    rows_text(r, "\n],\"polygons\":");
    rows_int(r, (long long)s->npolys);
    rows_text(r, "}\n");
    rows_flush(r);
    free(r);
    return ferror(out) ? SYL_EIO : SYL_OK;
}
