/* syl_curvetree_build: the Blender plug-in's tree from a `curvetree` block (docs/curvetree.md): its
 * trunk curve and envelope read, the budget charged, the tree built; syl_curvetree_validate:
 * the block's check for `sylva check`. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "skeleton/store.h"
#include "curvetree/curvetree.h"
#include "env/obstacles.h"
#include "env/parity.h"
#include "lang/textures.h"
#include "sylva/trees.h"
#include "util/budget.h"
#include "lang/program.h"

int syl_curvetree_validate(const SylProgram *p, FILE *diag) {
    return syl_program_kind(p) == SYL_MODEL_CURVETREE ? ct_params_check(p, diag) : 0;
}

typedef struct Envelope {
    Obstacles obs; /* the mesh as read */
    ParityGrid grid;
} Envelope;

/* The inside test of a closed mesh: a ray's crossings counted by parity (env/parity.c),
 * right for any closed mesh, convex or not; a point outside its bounds is outside without a
 * ray (a fifth of the tree's time). The ray has one direction, so a grid of the triangles'
 * shadows along it finds its crossings: no Embree scene, whose loading and start-up were
 * two thirds of a 100-branch tree's time (docs/curvetree.md). */
static bool inside(void *user, const double p[3]) {
    const Envelope *e = user;
    float q[3] = {(float)p[0], (float)p[1], (float)p[2]};
    for (int j = 0; j < 3; j++)
        if (!(q[j] >= e->obs.lo[j] && q[j] <= e->obs.hi[j])) return false;
    return parity_inside(&e->grid, q);
}

static int load_envelope(const SylProgram *p, const SylDirective *d, Envelope *e, FILE *diag) {
    char *path = NULL;
    const char *name = d->args[0].text;
    int st = syl_program_file(p, name, &path); /* beside the program's file unless absolute */
    if (st == SYL_ELIMIT) return st;
    if (st) program_say(p, diag, DIAG_ERROR, NULL, "cannot read '%s': %s", name, syl_file_refused);
    static const float zero[3] = {0, 0, 0};
    if (!st) st = obstacles_add_obj(&e->obs, path, zero, 1.0f, diag_sink(&(SylSink){0}, diag, program_sink(p)));
    free(path);
    if (!st && e->obs.nt == 0) st = SYL_EMODEL;
    if (!st && !parity_build(&e->grid, e->obs.v, e->obs.nv, e->obs.tri, e->obs.nt)) st = SYL_ELIMIT;
    if (st && diag)
        syl_directive_report_error(p, diag, d, &d->args[0], "cannot use the envelope \"%s\" (a closed mesh in an .obj file)",
                                   name);
    return st;
}

int syl_curvetree_build(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out) {
    static const SylTreeOptions none = {0};
    if (!opt) opt = &none;
    FILE *diag = opt->diag;
    *out = NULL;
    if (syl_program_kind(p) != SYL_MODEL_CURVETREE) {
        program_say(p, diag, DIAG_ERROR, NULL, "'%s' is a %s, not a curvetree block", syl_program_name(p),
                    syl_model_kind_name(syl_program_kind(p)));
        return SYL_EUSAGE;
    }
    CtParams P;
    if (ct_params_read(p, &P, diag)) return SYL_EMODEL;
    SylTextureSpec tex;
    int terr = lang_textures(p, &tex, diag);
    if (terr) return terr;
    double aspect = P.leafAspect;
    if (tex.nleaf) { /* the first leaf image's height / width */
        const SylImage *g = &tex.images->img[tex.leaf[0] - 1];
        aspect = (double)g->height / g->width;
    }
    CtCurve trunk;
    int st = ct_curve_of_directive(p, P.trunk_at, true, &trunk, diag);
    if (st) {
        lang_textures_free(&tex);
        return st;
    }
    Envelope env = {0};
    st = load_envelope(p, P.envelope_at, &env, diag);
    uint64_t nodes = 0, leaves = 0, bytes = 0;
    Budget own, *mem = budget_use(&own, opt->max_memory, opt->budget);
    if (!st) {
        ct_bounds(&P, &trunk, &nodes, &leaves);
        bytes = nodes * sizeof(SylNode) + leaves * sizeof(SylOrgan);
        if (!budget_charge(mem, bytes)) {
            program_say(p, diag, DIAG_ERROR, NULL, "'%s' may need %llu nodes and %llu leaves (%llu MB), more than --max-memory "
                        "allows (%llu MB%s); lower branch1Density, branch2Density or leavesDensity",
                        syl_program_name(p), (unsigned long long)nodes, (unsigned long long)leaves,
                        (unsigned long long)(bytes >> 20), (unsigned long long)budget_limit_mb(mem),
                        mem == &own ? "" : " in all");
            st = SYL_ELIMIT;
        }
    }
    SylSkeleton *sk = NULL;
    if (!st && !(sk = syl_skeleton_new(syl_program_name(p)))) st = SYL_ELIMIT, budget_release(mem, bytes);
    if (!st) {
        if (mem != &own) skeleton_charge(sk, mem, bytes);
        else budget_release(mem, bytes);
        uint64_t seed = opt->use_seed ? opt->seed : (uint64_t)P.seed;
        seed += opt->seed_offset; /* a scene's n-th plant of a row: a tree of its own */
        st = ct_build(&P, &trunk, inside, &env, aspect, seed, sk, opt->cancel);
        if (!st) st = syl_skeleton_apply_textures(sk, &tex, seed);
        if (st && st != SYL_ECANCELED) /* stopped: nothing said */
            program_say(p, diag, DIAG_ERROR, NULL, "'%s': out of memory for the skeleton", syl_program_name(p));
    }
    lang_textures_free(&tex);
    parity_free(&env.grid);
    obstacles_free(&env.obs);
    ct_curve_free(&trunk);
    if (st) {
        syl_skeleton_free(sk);
        return st;
    }
    *out = sk;
    return SYL_OK;
}
