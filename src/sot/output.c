/* Tree to skeleton: see output.h. */
#include "sot/output.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sot/geometry.h"
#include "sot/shed.h"

int32_t skeleton_next_axis(const SylSkeleton *sk) {
    int32_t next = 0;
    for (size_t i = 0; i < sk->nnodes; i++)
        if (sk->nodes[i].axis >= next) next = sk->nodes[i].axis + 1;
    return next;
}

/* An organ's frame: H along it, its face U turned up as far as H allows. */
static void organ_frame(const vec3 h, const vec3 fallback_u, SylOrgan *o) {
    vec3 u = {0, 1, 0}, l;
    glm_vec3_muladds((float *)h, -h[1], u);
    if (!sot_normalize(u)) glm_vec3_copy((float *)fallback_u, u);
    glm_vec3_cross(u, (float *)h, l);
    sot_normalize(l);
    memcpy(o->h, h, sizeof o->h);
    memcpy(o->l, l, sizeof o->l);
    glm_vec3_cross((float *)h, l, u);
    memcpy(o->u, u, sizeof o->u);
}

static int add_organs(Tree *t, int year, SylSkeleton *sk, size_t first, const uint8_t *has_child, uint64_t *count) {
    const GrowParams *P = &t->P;
    for (int s = 0; s < P->norgans; s++) {
        const OrganSpec *os = &P->organs[s];
        for (size_t i = 1; i < t->n; i++) {
            const Node *nd = &t->nodes[i];
            if (year - (int)nd->born >= os->age) continue;
            if (os->place == ORGAN_TIPS && has_child[i]) continue;
            Rng r = rng_stream(P->seed, (uint64_t)s, 0x06a, i);
            vec3 h, l, u;
            glm_vec3_copy((float *)nd->h, h);
            glm_vec3_copy((float *)nd->l, l);
            glm_vec3_cross(h, l, u);
            for (int k = 0; k < os->count; k++) {
                if (os->chance < 1 && rng_unit(&r) >= os->chance) continue;
                SylOrgan o = {.size = os->size, .node = (int32_t)(first + i), .kind = os->kind,
                              .material = os->kind == SYL_KIND_FLOWER ? SYL_MATERIAL_FLOWER : SYL_MATERIAL_LEAF,
                              .module = (uint32_t)i};
                memcpy(o.pos, nd->pos, sizeof o.pos);
                float az = ((float)nd->rank * P->divergence + (float)k * 360.0f / (float)os->count + 90.0f) * SOT_DEG;
                float a = (os->place == ORGAN_TIPS && os->count == 1 ? 0 : os->angle) * SOT_DEG;
                vec3 d;
                for (int j = 0; j < 3; j++)
                    d[j] = cosf(a) * h[j] + sinf(a) * (cosf(az) * l[j] + sinf(az) * u[j]);
                sot_normalize(d);
                organ_frame(d, u, &o);
                if (syl_skeleton_add_organ(sk, &o) < 0) return SYL_ELIMIT;
                (*count)++;
            }
        }
    }
    return SYL_OK;
}

/* What the shoot rule hung on the tree, less what is older than `keep` years. */
static int add_rule_parts(Tree *t, int year, SylSkeleton *sk, size_t first, int32_t axis, uint64_t *count) {
    int keep = t->P.rule_keep;
    for (size_t i = 0; i < t->norgans; i++) {
        const TreeOrgan *g = &t->organs[i];
        if (keep > 0 && year - (int)g->born >= keep) continue;
        SylOrgan o = {.size = g->size, .node = (int32_t)(first + (size_t)g->node), .kind = g->kind,
                      .material = g->material, .module = (uint32_t)g->node};
        memcpy(o.pos, g->pos, sizeof o.pos);
        memcpy(o.h, g->h, sizeof o.h);
        memcpy(o.l, g->l, sizeof o.l);
        glm_vec3_cross(o.h, o.l, o.u);
        if (syl_skeleton_add_organ(sk, &o) < 0) return SYL_ELIMIT;
        (*count)++;
    }
    int32_t *at = malloc((t->ntwigs ? t->ntwigs : 1) * sizeof *at); /* each twig's end, in sk */
    if (!at) return SYL_ELIMIT;
    int st = SYL_OK;
    for (size_t i = 0; i < t->ntwigs && !st; i++) {
        const TreeTwig *w = &t->twigs[i];
        at[i] = -1;
        if (keep > 0 && year - (int)w->born >= keep) continue;
        const Node *nd = &t->nodes[w->node];
        SylNode n = {.radius = w->radius, .order = (uint16_t)(nd->order + 1), .kind = SYL_KIND_INTERNODE,
                     .material = w->material, .module = (uint32_t)w->node};
        n.parent = w->parent >= 0 ? at[w->parent] : (int32_t)(first + (size_t)w->node);
        n.axis = w->parent >= 0 && n.parent >= 0 ? sk->nodes[n.parent].axis : axis++;
        memcpy(n.h, w->h, sizeof n.h);
        memcpy(n.l, w->l, sizeof n.l);
        glm_vec3_cross(n.h, n.l, n.u);
        if (w->detached || n.parent < 0) { /* it starts away from the shoot: a root of its own */
            SylNode r = n;
            memcpy(r.pos, w->from, sizeof r.pos);
            r.parent = -1;
            r.kind = SYL_KIND_ROOT;
            int32_t k = syl_skeleton_add_node(sk, &r);
            if (k < 0) st = SYL_ELIMIT;
            n.parent = k;
        }
        memcpy(n.pos, w->to, sizeof n.pos);
        if (!st && (at[i] = syl_skeleton_add_node(sk, &n)) < 0) st = SYL_ELIMIT;
    }
    free(at);
    if (t->rule) {
        bool set[256];
        float rgb[256][3];
        shoot_rule_colours(t->rule, set, rgb);
        for (int m = 0; m < 256; m++)
            if (set[m]) {
                memcpy(sk->materials[m].rgb, rgb[m], sizeof rgb[m]);
                if (m >= sk->nmaterials) sk->nmaterials = m + 1;
            }
    }
    return st;
}

int tree_to_skeleton(Tree *t, int year, SylSkeleton *sk, int32_t axis_base, uint64_t *organs) {
    if (!pipe_areas(t)) return SYL_ELIMIT;
    const double *A = t->acc;
    uint8_t *has_child = (uint8_t *)t->acc2; /* the areas are read from acc; acc2 is free */
    memset(has_child, 0, t->n);
    for (size_t i = 1; i < t->n; i++) has_child[t->nodes[i].parent] = 1;
    size_t first = sk->nnodes;
    for (size_t i = 0; i < t->n; i++) {
        const Node *nd = &t->nodes[i];
        SylNode out;
        memset(&out, 0, sizeof out);
        memcpy(out.pos, nd->pos, sizeof out.pos);
        memcpy(out.h, nd->h, sizeof out.h);
        memcpy(out.l, nd->l, sizeof out.l);
        glm_vec3_cross((float *)nd->h, (float *)nd->l, out.u);
        double area = A[i];
        if (i == 0 && nd->main >= 0) area = A[nd->main];
        out.radius = pipe_radius(&t->P, area);
        out.parent = nd->parent >= 0 ? (int32_t)(first + (size_t)nd->parent) : -1;
        out.axis = axis_base + nd->axis;
        out.order = nd->order;
        out.kind = i == 0 ? SYL_KIND_ROOT : SYL_KIND_INTERNODE;
        out.material = SYL_MATERIAL_BARK;
        out.module = (uint32_t)i;
        if (syl_skeleton_add_node(sk, &out) < 0) return SYL_ELIMIT;
    }
    int st = add_organs(t, year, sk, first, has_child, organs);
    return st ? st : add_rule_parts(t, year, sk, first, axis_base + t->axes, organs);
}
