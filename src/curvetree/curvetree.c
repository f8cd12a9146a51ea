/* syl_curvetree: the Blender plug-in's tree from a `curvetree` block (docs/curvetree.md): its
 * trunk curve and envelope read, the budget charged, the tree built; syl_curvetree_validate:
 * the block's check for `sylva check`. */
#include <errno.h>
#include <png.h>
#include <stdlib.h>
#include <string.h>

#include "skeleton/store.h"
#include "curvetree/curvetree.h"
#include "env/obstacles.h"
#include "sylva/trees.h"
#include "util/budget.h"

int syl_curvetree_validate(const SylProgram *p, FILE *diag) {
    return syl_program_kind(p) == SYL_MODEL_CURVETREE ? ct_params_check(p, diag) : 0;
}

typedef struct Envelope {
    Obstacles obs;
    RTCDevice dev;
} Envelope;

/* The inside test of a closed mesh: a ray's crossings counted by parity (env/obstacles.c),
 * right for any closed mesh, convex or not; a point outside its bounds is outside without a
 * ray (a fifth of the tree's time). */
static bool inside(void *user, const double p[3]) {
    const Obstacles *o = &((Envelope *)user)->obs;
    float q[3] = {(float)p[0], (float)p[1], (float)p[2]};
    for (int j = 0; j < 3; j++)
        if (!(q[j] >= o->lo[j] && q[j] <= o->hi[j])) return false;
    return obstacles_inside(o, q);
}

static int load_envelope(const SylProgram *p, const SylDirective *d, Envelope *e, FILE *diag) {
    char *path = NULL;
    const char *name = d->args[0].text;
    int st = syl_program_file(p, name, &path); /* beside the program's file unless absolute */
    if (st == SYL_ELIMIT) return st;
    if (st && diag) fprintf(diag, "sylva: error: cannot read '%s': %s\n", name, syl_file_refused);
    static const float zero[3] = {0, 0, 0};
    if (!st) st = obstacles_add_obj(&e->obs, path, zero, 1.0f, diag);
    free(path);
    if (!st && e->obs.nt == 0) st = SYL_EMODEL;
    if (!st) {
        e->dev = rtcNewDevice("threads=1");
        st = e->dev ? obstacles_commit(&e->obs, e->dev, diag) : SYL_ELIMIT;
    }
    if (st && diag)
        syl_directive_error(p, diag, d, &d->args[0], "cannot use the envelope \"%s\" (a closed mesh in an .obj file)",
                            name);
    return st;
}

/* The leaf texture's height / width (its PNG header, through libpng). */
static void png_failed(png_structp png, png_const_charp msg) {
    (void)msg;
    png_longjmp(png, 1);
}
static int leaf_aspect(const SylProgram *p, const SylDirective *d, double *aspect, FILE *diag) {
    char *path = NULL;
    const char *name = d->args[0].text;
    int st = syl_program_file(p, name, &path);
    if (st == SYL_ELIMIT) return st;
    if (st) {
        syl_directive_error(p, diag, d, &d->args[0], "cannot read '%s': %s", name, syl_file_refused);
        return SYL_EIO;
    }
    FILE *f = fopen(path, "rb");
    free(path);
    if (!f) {
        syl_directive_error(p, diag, d, &d->args[0], "cannot read the leaf texture '%s': %s", name, strerror(errno));
        return SYL_EIO;
    }
    unsigned char sig[8];
    png_uint_32 w = 0, h = 0;
    png_structp png = NULL;
    png_infop info = NULL;
    bool ok = fread(sig, 1, 8, f) == 8 && !png_sig_cmp(sig, 0, 8) &&
              (png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, png_failed, NULL)) != NULL &&
              (info = png_create_info_struct(png)) != NULL;
    if (ok && !setjmp(png_jmpbuf(png))) {
        png_init_io(png, f);
        png_set_sig_bytes(png, 8);
        png_read_info(png, info);
        w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    }
    if (png) png_destroy_read_struct(&png, info ? &info : NULL, NULL);
    fclose(f);
    if (!(w > 0 && h > 0)) {
        syl_directive_error(p, diag, d, &d->args[0], "the leaf texture '%s' is not a readable PNG image", name);
        return SYL_EMODEL;
    }
    *aspect = (double)h / w;
    return SYL_OK;
}

int syl_curvetree(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out) {
    static const SylTreeOptions none = {0};
    if (!opt) opt = &none;
    FILE *diag = opt->diag;
    *out = NULL;
    if (syl_program_kind(p) != SYL_MODEL_CURVETREE) {
        if (diag)
            fprintf(diag, "sylva: error: '%s' is a %s, not a curvetree block\n", syl_program_name(p),
                    syl_model_kind_name(syl_program_kind(p)));
        return SYL_EUSAGE;
    }
    CtParams P;
    if (ct_params_read(p, &P, diag)) return SYL_EMODEL;
    double aspect = P.leafAspect;
    if (P.texture_at) {
        int st = leaf_aspect(p, P.texture_at, &aspect, diag);
        if (st) return st;
    }
    CtCurve trunk;
    int st = ct_curve_of_directive(p, P.trunk_at, true, &trunk, diag);
    if (st) return st;
    Envelope env = {0};
    st = load_envelope(p, P.envelope_at, &env, diag);
    uint64_t nodes = 0, leaves = 0, bytes = 0;
    Budget own, *mem = budget_use(&own, opt->max_memory, opt->budget);
    if (!st) {
        ct_bounds(&P, &trunk, &nodes, &leaves);
        bytes = nodes * sizeof(SylNode) + leaves * sizeof(SylOrgan);
        if (!budget_charge(mem, bytes)) {
            if (diag)
                fprintf(diag,
                        "sylva: error: '%s' may need %llu nodes and %llu leaves (%llu MB), more than --max-memory "
                        "allows (%llu MB%s); lower branch1Density, branch2Density or leavesDensity\n",
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
        st = ct_build(&P, &trunk, inside, &env, aspect, seed, sk);
        if (st && diag) fprintf(diag, "sylva: error: '%s': out of memory for the skeleton\n", syl_program_name(p));
    }
    obstacles_free(&env.obs);
    if (env.dev) rtcReleaseDevice(env.dev);
    ct_curve_free(&trunk);
    if (st) {
        syl_skeleton_free(sk);
        return st;
    }
    *out = sk;
    return SYL_OK;
}
