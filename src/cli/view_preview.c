/* sylva view's preview: while a slider is dragged and right after a save, the page first
 * draws a lighter picture of the new build, then the .glb of `sylva mesh` once it is there
 * (docs/view.md, "Speed"). The preview is three-sided tubes with every leaf one instanced
 * card — or, for a skeleton too big to mesh quickly, just its segments coloured by order. */
#include <stdlib.h>
#include <string.h>

#include "cli/view.h"

/* Beyond this many skeleton nodes and leaves a preview is the segments (a lines draw), not a
 * mesh: meshing, writing, parsing and drawing tens of thousands of tubes takes seconds in
 * software WebGL, while a line each is drawn in a fraction of it. Leaves count as nodes: the
 * Weber-Penn aspen's 6,229 nodes and 22,026 instanced cards took SwiftShader 0.53 s a frame
 * (0.15 s without the cards), its segments 16 ms. */
enum { PREVIEW_MESH_NODES = 20000 };

void view_preview_mesh_options(SylMeshOptions *mo) {
    mo->sides = 3, mo->min_sides = 3;
    /* blades and cards as one card placed per leaf: a few triangles, however many leaves */
    if (mo->leaves != SYL_LEAVES_INSTANCED && mo->leaves != SYL_LEAVES_INSTANCED_CARDS)
        mo->leaves = SYL_LEAVES_INSTANCED_CARDS;
    mo->vertex_nodes = 0;
}

bool view_preview_as_lines(const SylSkeleton *sk) { return sk->nnodes + sk->norgans > PREVIEW_MESH_NODES; }

/* Does segment a (from, to) go on straight from line k (it starts where k ends, onward, in its
 * direction)? web/scene.js's joinStraight's test, in the same double arithmetic in the same
 * order (the file is built without contracting to fused multiply-adds): the same lines. */
static bool goes_on(const float *k, const float *a) {
    if (a[0] != k[3] || a[1] != k[4] || a[2] != k[5]) return false;
    double ux = (double)k[3] - k[0], uy = (double)k[4] - k[1], uz = (double)k[5] - k[2];
    double vx = (double)a[3] - k[3], vy = (double)a[4] - k[4], vz = (double)a[5] - k[5];
    double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
    /* parallel within float noise (sin² of the angle below 1e-8), and onward, not back */
    return ux * vx + uy * vy + uz * vz > 0 &&
           cx * cx + cy * cy + cz * cz <= 1e-8 * (ux * ux + uy * uy + uz * uz) * (vx * vx + vy * vy + vz * vz);
}

/* Into one block sized once (a million-module plant has hundreds of thousands of segments:
 * written a few bytes at a time through a FILE, they took a third of a second). Joined, a
 * straight run is one line: a quarter of the bytes for an L-system's F → FF, and the page
 * draws them as they come. */
int view_preview_lines(const SylSkeleton *sk, bool join, char **buf, size_t *len) {
    size_t n = 0;
    for (size_t i = 0; i < sk->nnodes; i++) n += sk->nodes[i].kind == SYL_KIND_INTERNODE && sk->nodes[i].parent >= 0;
    char *b = malloc(n * 25 + 1);
    if (!b) return SYL_ELIMIT;
    float *seg = (float *)b; /* 6 floats a line, then a byte of branch order a line */
    uint8_t *order = (uint8_t *)b + n * 24;
    size_t k = 0;
    for (size_t i = 0; i < sk->nnodes; i++) {
        const SylNode *d = &sk->nodes[i];
        if (d->kind != SYL_KIND_INTERNODE || d->parent < 0) continue;
        uint8_t o = d->order > 255 ? 255 : (uint8_t)d->order;
        float s[6];
        memcpy(s, sk->nodes[d->parent].pos, 3 * sizeof(float));
        memcpy(s + 3, d->pos, 3 * sizeof(float));
        if (join && k > 0 && order[k - 1] == o && goes_on(seg + 6 * (k - 1), s)) {
            memcpy(seg + 6 * (k - 1) + 3, s + 3, 3 * sizeof(float));
            continue;
        }
        memcpy(seg + 6 * k, s, sizeof s);
        order[k++] = o;
    }
    memmove(b + k * 24, order, k); /* the orders right after the lines kept */
    *buf = b, *len = k * 25;
    return SYL_OK;
}

void view_tab_saw(View *v, const ViewRequest *rq) {
    if (!rq->tab) return;
    pthread_mutex_lock(&v->gen_lock);
    int k = 0; /* its slot, else the one seen longest ago */
    for (int i = 0; i < VIEW_TABS; i++) {
        if (v->tabs[i].tab == rq->tab) {
            k = i;
            break;
        }
        if (v->tabs[i].seen < v->tabs[k].seen) k = i;
    }
    if (v->tabs[k].tab != rq->tab) v->tabs[k].tab = rq->tab, v->tabs[k].seq = rq->seq;
    if (rq->seq > v->tabs[k].seq) v->tabs[k].seq = rq->seq;
    v->tabs[k].seen = cli_now();
    pthread_mutex_unlock(&v->gen_lock);
}

bool view_tab_moved_on(View *v, const ViewRequest *rq) {
    bool moved = false;
    if (!rq->tab) return false;
    pthread_mutex_lock(&v->gen_lock);
    for (int i = 0; i < VIEW_TABS; i++)
        if (v->tabs[i].tab == rq->tab) moved = v->tabs[i].seq > rq->seq;
    pthread_mutex_unlock(&v->gen_lock);
    return moved;
}
