/* A plant's leaf surface and trunk jitter, carried into the scene's skeleton (surface.h). */
#include "scene/surface.h"

#include <math.h>
#include <string.h>

static bool has_leaves(const SylSkeleton *sk, size_t first_organ) {
    for (size_t k = first_organ; k < sk->norgans; k++)
        if (sk->organs[k].kind == SYL_KIND_LEAF) return true;
    return false;
}

static bool same_leaf(const SylSkeleton *a, const SylSkeleton *b) {
    return a->leaf_tris == b->leaf_tris && a->leaf_outline == b->leaf_outline &&
           (a->leaf_tris == 0 || a->leaf_width == b->leaf_width);
}

void scene_surface_carry(SceneSurface *S, SylSkeleton *sk, const SylSkeleton *own, size_t first_node,
                         size_t first_organ, const char *name, const SylProgram *p, int line, int col, FILE *diag) {
    static const SylSkeleton blade = {0}; /* a grown tree's: Sylva's blade, no jitter */
    const SylSkeleton *s = own ? own : &blade;
    if (has_leaves(sk, first_organ)) {
        if (!S->leaves_by) {
            S->leaves_by = name;
            sk->leaf_tris = s->leaf_tris, sk->leaf_width = s->leaf_width, sk->leaf_outline = s->leaf_outline;
        } else if (!same_leaf(sk, s) && !S->leaves_warned) {
            S->leaves_warned = true;
            program_warning(p, diag, line, col,
                            "'%s' has other leaves than '%s': one mesh draws one leaf shape, %s's", name,
                            S->leaves_by, S->leaves_by);
        }
    }
    float j = isfinite(s->trunk_jitter) && s->trunk_jitter > 0 ? s->trunk_jitter : 0;
    if (j == 0) { /* the mesher jitters every trunk of a skeleton with a jitter: not this one */
        for (size_t k = first_node; k < sk->nnodes; k++)
            if (sk->nodes[k].order == 0) sk->nodes[k].flags |= SYL_NODE_NO_JITTER;
    } else if (!S->jitter_by) {
        S->jitter_by = name;
        sk->trunk_jitter = j;
    } else if (sk->trunk_jitter != j && !S->jitter_warned) {
        S->jitter_warned = true;
        program_warning(p, diag, line, col,
                        "'%s' has another trunk jitter (0ScaleV) than '%s': one mesh draws one, %s's", name,
                        S->jitter_by, S->jitter_by);
    }
}
