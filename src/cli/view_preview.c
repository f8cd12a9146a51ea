/* sylva view's preview: while a slider is dragged and right after a save, the page first
 * draws a lighter picture of the new build, then the .glb of `sylva mesh` once it is there
 * (docs/view.md, "Speed"). The preview is three-sided tubes with every leaf one instanced
 * card — or, for a skeleton too big to mesh quickly, just its segments coloured by order. */
#include <stdlib.h>
#include <string.h>

#include "cli/view.h"

/* Beyond this many skeleton nodes a preview is the segments (a lines draw), not a mesh:
 * meshing, writing, parsing and drawing tens of thousands of tubes takes seconds in software
 * WebGL, while a line each is drawn in a fraction of it. */
enum { PREVIEW_MESH_NODES = 20000 };

void view_preview_mesh_options(SylMeshOptions *mo) {
    mo->sides = 3, mo->min_sides = 3;
    /* blades and cards as one card placed per leaf: a few triangles, however many leaves */
    if (mo->leaves != SYL_LEAVES_INSTANCED && mo->leaves != SYL_LEAVES_INSTANCED_CARDS)
        mo->leaves = SYL_LEAVES_INSTANCED_CARDS;
    mo->vertex_nodes = 0;
}

bool view_preview_as_lines(const SylSkeleton *sk) { return sk->nnodes > PREVIEW_MESH_NODES; }

/* Into one block sized once (a million-module plant has hundreds of thousands of segments:
 * written a few bytes at a time through a FILE, they took a third of a second). */
int view_preview_lines(const SylSkeleton *sk, char **buf, size_t *len) {
    size_t n = 0;
    for (size_t i = 0; i < sk->nnodes; i++) n += sk->nodes[i].kind == SYL_KIND_INTERNODE && sk->nodes[i].parent >= 0;
    char *b = malloc(n * 25 + 1);
    if (!b) return SYL_ELIMIT;
    float *seg = (float *)b; /* 6 floats a segment, then a byte of branch order a segment */
    uint8_t *order = (uint8_t *)b + n * 24;
    for (size_t i = 0, k = 0; i < sk->nnodes; i++) {
        const SylNode *d = &sk->nodes[i];
        if (d->kind != SYL_KIND_INTERNODE || d->parent < 0) continue;
        memcpy(seg + 6 * k, sk->nodes[d->parent].pos, 3 * sizeof(float));
        memcpy(seg + 6 * k + 3, d->pos, 3 * sizeof(float));
        order[k++] = d->order > 255 ? 255 : (uint8_t)d->order;
    }
    *buf = b, *len = n * 25;
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
