/* The skeleton writer: every stem (and every clone) an axis of its own with order = level,
 * its nodes the points of its axis plus one wherever a child or a clone grows out (so that
 * each child starts from a node of its parent, where it really sits); leaves as organs.
 * Tree coordinates (z up) become Sylva's (Y up): (x, y, z) -> (x, z, -y). */
#include <stdlib.h>
#include <string.h>

#include "skeleton/store.h"
#include "util/leafoutline.h"
#include "util/pages.h"
#include "weber/internal.h"

typedef struct Attach {
    int host, stem;
    double at; /* distance along the host */
} Attach;

/* Sort the attachments by host, then distance, then stem: a counting sort by host (stable:
 * they come in stem order), then each host's few by distance, nearly in order already (a
 * stem's children come along it), by insertion. qsort's merge sort took more time and
 * memory. */
static bool sort_by_host(WeberGen *g, Attach *att, size_t na, size_t ns) {
    Attach *out = weber_take(g, (na ? na : 1) * sizeof *out);
    uint32_t *start = weber_take(g, (ns + 1) * sizeof *start);
    if (!start || !out) {
        weber_drop(g, start, (ns + 1) * sizeof *start);
        weber_drop(g, out, (na ? na : 1) * sizeof *out);
        return false;
    }
    memset(start, 0, (ns + 1) * sizeof *start);
    for (size_t i = 0; i < na; i++) start[att[i].host + 1]++;
    for (size_t h = 0; h < ns; h++) start[h + 1] += start[h];
    for (size_t i = 0; i < na; i++) out[start[att[i].host]++] = att[i]; /* start[h]: now host h's end */
    for (size_t h = 0, lo = 0; h < ns; lo = start[h++])
        for (size_t i = lo + 1; i < start[h]; i++) {
            Attach a = out[i];
            size_t k = i;
            for (; k > lo && out[k - 1].at > a.at; k--) out[k] = out[k - 1];
            out[k] = a;
        }
    memcpy(att, out, na * sizeof *att);
    weber_drop(g, start, (ns + 1) * sizeof *start);
    weber_drop(g, out, (na ? na : 1) * sizeof *out);
    return true;
}

static void to_sylva(float out[3], const float in[3]) {
    out[0] = in[0], out[1] = in[2], out[2] = -in[1];
}

typedef struct Writer {
    SylSkeleton *sk;
    float *dist;     /* each node's distance along its stem */
    bool failed;
    uint8_t lobes;       /* the trunk's cross-section (Lobes, LobeDepth) */
    uint16_t lobe_depth;
} Writer;

static int32_t put(Writer *wr, const WStem *st, int id, const float pos[3], const float z[3], const float x[3],
                   float r, float dist, int32_t parent, uint8_t kind) {
    SylNode nd = {0};
    to_sylva(nd.pos, pos);
    to_sylva(nd.h, z);
    to_sylva(nd.l, x);
    nd.u[0] = nd.h[1] * nd.l[2] - nd.h[2] * nd.l[1];
    nd.u[1] = nd.h[2] * nd.l[0] - nd.h[0] * nd.l[2];
    nd.u[2] = nd.h[0] * nd.l[1] - nd.h[1] * nd.l[0];
    nd.radius = r;
    nd.parent = parent;
    nd.axis = id;
    nd.order = (uint16_t)st->level; /* (a level: 0 to 3) */
    nd.kind = kind;
    nd.material = SYL_MATERIAL_BARK;
    nd.module = (uint32_t)id;
    if (st->level == 0) nd.lobes = wr->lobes, nd.lobe_depth = wr->lobe_depth; /* Arbaro lobes the trunk only */
    if (wr->sk->nnodes >= wr->sk->store->node_cap) return wr->failed = true, -1; /* (sized in advance) */
    int32_t k = (int32_t)wr->sk->nnodes;
    wr->sk->nodes[wr->sk->nnodes++] = nd;
    wr->dist[k] = dist;
    return k;
}

int weber_write_nodes(WeberGen *g, SylSkeleton *sk) {
    size_t ns = g->nstems, na = 0;
    /* every node at once: a root per trunk, the points, and at most one per attachment (a
     * stem that is not a trunk): npts + ns. In the arena's huge pages, past the scratch
     * (weber_keep), not the kept threshold's (util/pages.h): a tree's skeleton is short-lived
     * (meshed, or appended to a scene's and freed), and the poplar's 0.3 MB of nodes cost
     * 1.4 ms of 4 KB page faults. The attachments' scratch comes after them, and goes before
     * the leaves are made there (pages already written: the willow's tree reaches 18 2 MB
     * pages, not 19). */
    size_t most = g->npts + ns;
    if (!weber_grow(g, (void **)&g->node_dist, &g->node_dist_cap, most ? most : 1, sizeof *g->node_dist) ||
        !(sk->nodes = weber_keep(g, most * sizeof *sk->nodes)))
        return SYL_ELIMIT;
    sk->store->node_cap = most;
    Attach *att = weber_take(g, (ns ? ns : 1) * sizeof *att);
    int32_t *attach_node = weber_take(g, (ns ? ns : 1) * sizeof *attach_node);
    Writer wr = {.sk = sk};
    if (g->w.Lobes > 0 && g->w.LobeDepth > 0) {
        wr.lobes = (uint8_t)(g->w.Lobes < 255 ? g->w.Lobes : 255);
        wr.lobe_depth = (uint16_t)(g->w.LobeDepth < 6.5535 ? g->w.LobeDepth * 1e4 + 0.5 : 65535);
    }
    if (!att || !attach_node) {
        weber_drop(g, attach_node, (ns ? ns : 1) * sizeof *attach_node);
        weber_drop(g, att, (ns ? ns : 1) * sizeof *att);
        return SYL_ELIMIT;
    }
    for (size_t j = 0; j < ns; j++) {
        const WStem *s = &g->stems[j];
        attach_node[j] = -1;
        if (s->from < 0) continue;
        att[na++] = (Attach){s->from, (int)j, s->clone ? s->first_seg * g->stems[s->from].seglen : s->offset};
    }
    if (!sort_by_host(g, att, na, ns)) {
        weber_drop(g, attach_node, (ns ? ns : 1) * sizeof *attach_node);
        weber_drop(g, att, (ns ? ns : 1) * sizeof *att);
        return SYL_ELIMIT;
    }
    wr.dist = g->node_dist;
    size_t a = 0;
    for (size_t i = 0; i < ns && !wr.failed; i++) {
        WStem *st = &g->stems[i];
        st->node_first = (uint32_t)sk->nnodes;
        float base[3], z0[3], x0[3];
        for (int k = 0; k < 3; k++)
            base[k] = (float)st->start.t[k], z0[k] = (float)st->start.z[k], x0[k] = (float)st->start.x[k];
        float prev_d = (float)(st->first_seg * st->seglen);
        const float *prev = base;
        int32_t last;
        if (st->from < 0)
            last = put(&wr, st, (int)i, base, z0, x0, (float)weber_radius(g, st, 0), 0, -1, SYL_KIND_ROOT);
        else
            last = attach_node[i];
        while (a < na && att[a].host < (int)i) a++;
        for (uint32_t q = 0; q < st->pt_count && !wr.failed; q++) {
            const WPoint *p = &g->pts[st->pt_first + q];
            float tol = 1e-6f * (float)st->length;
            for (; a < na && att[a].host == (int)i && att[a].at < p->dist - tol; a++) {
                float t = p->dist > prev_d ? (float)((att[a].at - prev_d) / (p->dist - prev_d)) : 0, pos[3];
                if (t < 0) t = 0;
                for (int k = 0; k < 3; k++) pos[k] = prev[k] + (p->pos[k] - prev[k]) * t;
                last = put(&wr, st, (int)i, pos, p->z, p->x, (float)weber_radius(g, st, att[a].at), (float)att[a].at,
                           last, SYL_KIND_INTERNODE);
                attach_node[att[a].stem] = last;
            }
            last = put(&wr, st, (int)i, p->pos, p->z, p->x, p->r, p->dist, last, SYL_KIND_INTERNODE);
            for (; a < na && att[a].host == (int)i && att[a].at <= p->dist + tol; a++) attach_node[att[a].stem] = last;
            prev = p->pos, prev_d = p->dist;
        }
        for (; a < na && att[a].host == (int)i; a++) attach_node[att[a].stem] = last;
        st->node_count = (uint32_t)(sk->nnodes - st->node_first);
    }
    /* Arbaro's 0ScaleV: jitter of the trunk's surface (the paper's varies its radius, radius.c) */
    if (g->w.convention == WEBER_ARBARO) sk->materials[SYL_MATERIAL_BARK].trunk_jitter = (float)g->w.Scale0V;
    weber_drop(g, attach_node, (ns ? ns : 1) * sizeof *attach_node);
    weber_drop(g, att, (ns ? ns : 1) * sizeof *att);
    return wr.failed ? SYL_ELIMIT : SYL_OK;
}

int32_t weber_leaf_node(const WeberGen *g, int id, float dist) {
    const WStem *st = &g->stems[id];
    if (!st->node_count) return -1;
    const float *d = g->node_dist + st->node_first;
    size_t lo = 0, hi = st->node_count; /* the last node at or below the leaf */
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (d[mid] <= dist) lo = mid; else hi = mid;
    }
    return (int32_t)(st->node_first + lo);
}

void weber_write_leaves(WeberGen *g, SylSkeleton *sk) {
    if (g->nlvs) { /* the leaves are the organs, in order already */
        skeleton_adopt_organs(sk, g->lvs, g->nlvs, g->lvs_cap);
        g->lvs = NULL;
        if (sk->nmaterials < SYL_MATERIAL_LEAF + 1) sk->nmaterials = SYL_MATERIAL_LEAF + 1;
        /* the leaves' surface: LeafShape's outline (util/leafoutline.h), LeafScaleX wide */
        SylMaterial *m = &sk->materials[SYL_MATERIAL_LEAF];
        m->leaf_tris = (uint16_t)g->w.leaf_tris;
        m->leaf_width = (float)g->w.LeafScaleX;
        m->leaf_outline = g->w.leaf_kind == WEBER_LEAF_SQUARE ? LEAF_OUTLINE_SQUARE
                           : g->w.leaf_kind == WEBER_LEAF_PALM ? LEAF_OUTLINE_PALM
                                                               : LEAF_OUTLINE_OVAL;
    }
}
