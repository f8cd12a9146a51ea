/* syl_weber_build: a Weber–Penn tree from a `weber` block. The tree is made depth first on one
 * thread (Arbaro's order: its error diffusion runs through the whole tree), every stem drawing
 * from random streams keyed by its place in the tree, so the same block and seed give the
 * same skeleton whatever -j says. docs/weberpenn.md describes the model. */
#include <stdlib.h>
#include <string.h>

#include "lang/textures.h"
#include "skeleton/store.h"
#include "sylva/trees.h"
#include "util/budget.h"
#include "util/pages.h"
#include "weber/internal.h"
#include "lang/program.h"

int syl_weber_validate(const SylProgram *p, FILE *diag) { return weber_params_check(p, diag); }

/* The scratch freed; the arena's pages that hold sk's nodes and organs (taken last) go to sk. */
static void free_gen(WeberGen *g, SylSkeleton *sk) {
    budget_release(g->budget, g->charged);
    weber_free(g, g->stems, g->stems_cap * sizeof *g->stems);
    weber_free(g, g->pts, g->pts_cap * sizeof *g->pts);
    if (!arena_holds(&g->arena, g->lvs)) free(g->lvs);
    weber_free(g, g->node_dist, g->node_dist_cap * sizeof *g->node_dist);
    weber_free(g, g->leafy, g->leafy_cap * sizeof *g->leafy);
    weber_free(g, g->leafy_f, g->leafy_f_cap * sizeof *g->leafy_f);
    const void *from = !sk ? NULL : arena_holds(&g->arena, sk->nodes) ? (const void *)sk->nodes
                                  : arena_holds(&g->arena, sk->organs) ? (const void *)sk->organs : NULL;
    size_t bytes;
    void *block = from ? arena_detach(&g->arena, from, &bytes) : NULL;
    if (block) skeleton_adopt_block(sk, block, bytes);
    arena_free(&g->arena);
}

/* The trunks: 0Branches of them, aimed by 0DownAngle and 0Rotate, spread by 0BranchDist. */
static void make_trunks(WeberGen *g, JRand *j0, JRand *j1) {
    const WeberParams *w = &g->w;
    Rng r = weber_rng(g, 0, WRNG_KIDS);
    double rot = 0;
    for (int i = 0; i < (int)w->Branches[0] && !g->failed; i++) {
        bool java = i == 0 && j0; /* the draws Arbaro makes for its first trunk */
        double u[5];
        for (int k = 0; k < 5; k++) u[k] = java ? jrand_double(j0) : rng_unit(&r);
        WStem t = {0};
        t.level = 0;
        t.parent = t.from = -1;
        t.key = weber_key(1, 0, (uint64_t)i);
        t.u_length = java ? u[4] : -1;
        t.u_lcm = java ? jrand_double(j1) : -1;
        frame_identity(&t.start);
        double a;
        if (w->Rotate[0] >= 0) { /* as children turn (children.c) */
            rot = fmod(rot + w->Rotate[0] + w->RotateV[0] * (2 * u[0] - 1) + 360, 360);
            a = rot;
        } else {
            rot = fabs(rot) != 1 ? -1 : -rot;
            a = rot * (180 + w->Rotate[0] + w->RotateV[0] * (2 * u[0] - 1));
        }
        frame_rotxz(&t.start, w->DownAngle[0] + w->DownAngleV[0] * (2 * u[1] - 1), a);
        double angle = 360 * (2 * u[2] - 1) * M_PI / 180, dist = w->BranchDist[0] * (2 * u[3] - 1);
        t.start.t[0] = dist * sin(angle);
        t.start.t[1] = dist * cos(angle);
        weber_make_stem(g, t);
    }
}

/* The stems the parameters make (clones too), as many as Branches allows at each level, each
 * split doubling or more what follows it: SegSplits 2 on 40 segments is 3^39 clones, 0BaseSplits
 * a number of trunks. Their bytes (the stem, each segment's frame while it is traced, its axis
 * points and skeleton nodes) are compared with the budget before any stem is made. Also their
 * segments, and the last level's (whose frames are kept for the leaves). */
typedef struct Estimate {
    double stems, bytes, segs, last_stems, last_segs;
} Estimate;

static Estimate estimate_stems(const WeberGen *g) {
    const WeberParams *w = &g->w;
    double parents = 1;
    Estimate e = {0};
    for (int lv = 0; lv < g->levels; lv++) {
        int l = weber_lv(lv);
        double res = w->CurveRes[l];
        parents *= w->Branches[l];
        double pieces = parents * pow(1 + w->SegSplits[l], res - 1);
        if (lv == 0 && w->BaseSplits > 0) pieces *= (1 + w->BaseSplits) / (1 + w->SegSplits[l]);
        e.stems += pieces;
        e.segs += pieces * res;
        e.last_stems = pieces;
        e.last_segs = pieces * res;
        e.bytes += pieces * (sizeof(WStem) + res * (sizeof(WSeg) + sizeof(WPoint) + sizeof(SylNode)));
    }
    return e;
}

/* The arena, sized from the estimate (an upper bound, about), and the arrays in it sized so
 * at once, in the order they fill: none is grown by doubling (which left a copy behind) or
 * moved out to pages of its own (each rounded up to 2 MB), so the oak's scratch reaches three
 * 2 MB pages where it reached six. The arena's pages exist once written: what the estimate
 * has too much costs address space. Past ARENA_MOST, the arrays grow as they come. */
enum { ARENA_MOST = 256 << 20 };
static void presize(WeberGen *g, const Estimate *e) {
    double leafy = g->leaves != 0 ? e->last_segs : 0, leafy_stems = g->leaves != 0 ? e->last_stems : 0;
    double pts = e->segs + e->stems; /* a point per segment and one more per stem, about */
    double sized = e->stems * sizeof(WStem) + pts * sizeof(WPoint) + leafy_stems * sizeof(int) + leafy * sizeof(Frame);
    /* and what weber_write_nodes takes: a distance per node, four words per stem, sorted */
    double later = (pts + 2 * e->stems) * sizeof(float) + e->stems * 64 + (4 << 10) + (64 << 10);
    /* and the skeleton's nodes and leaves, last (they go to the skeleton with the pages they
     * reach: the poplar's scratch, nodes and leaves fill one 2 MB page where they filled three) */
    later += (pts + 2 * e->stems) * sizeof(SylNode) + 64 +
             leafy_stems * (fabs((double)g->leaves) * g->w.LeafQuality + 1) * sizeof(SylOrgan) + 64;
    if (!(sized + later <= ARENA_MOST)) sized = 0; /* (the first arrays still packed in it) */
    if (!arena_fix(&g->arena, (size_t)(sized + later < (4 << 20) ? 4 << 20 : sized + later)) || !sized) return;
    if (e->stems >= 1) weber_grow(g, (void **)&g->stems, &g->stems_cap, (size_t)e->stems, sizeof *g->stems);
    if (pts >= 1) weber_grow(g, (void **)&g->pts, &g->pts_cap, (size_t)pts, sizeof *g->pts);
    if (leafy_stems >= 1) weber_grow(g, (void **)&g->leafy, &g->leafy_cap, (size_t)leafy_stems, sizeof *g->leafy);
    if (leafy >= 1) weber_grow(g, (void **)&g->leafy_f, &g->leafy_f_cap, (size_t)leafy, sizeof *g->leafy_f);
}

static int load_envelope(const SylProgram *p, const WeberParams *w, WeberEnvelope *e, FILE *diag) {
    char *path = NULL;
    int st = syl_program_file(p, w->envelope, &path); /* beside the program's file unless absolute */
    if (st == SYL_ELIMIT) return st;
    if (st) program_say(p, diag, DIAG_ERROR, NULL, "cannot read '%s': %s", w->envelope, syl_file_refused);
    static const float zero[3] = {0, 0, 0};
    if (!st) st = obstacles_add_obj(&e->obs, path, zero, 1.0f, diag_sink(&(SylSink){0}, diag, program_sink(p)));
    free(path);
    if (!st && e->obs.nt == 0) st = SYL_EMODEL;
    if (!st) {
        e->dev = rtcNewDevice(NULL);
        st = e->dev ? obstacles_commit(&e->obs, e->dev, diag_sink(&(SylSink){0}, diag, program_sink(p))) : SYL_ELIMIT;
    }
    if (st && diag)
        syl_directive_report_error(p, diag, w->envelope_at, &w->envelope_at->args[0],
                                   "cannot use the envelope \"%s\" (a closed mesh in an .obj file)", w->envelope);
    return st;
}

int syl_weber_build(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out) {
    FILE *diag = opt ? opt->diag : NULL;
    *out = NULL;
    if (syl_program_kind(p) != SYL_MODEL_WEBER) return SYL_EUSAGE;
    WeberGen *g = calloc(1, sizeof *g);
    if (!g) return SYL_ELIMIT;
    if (weber_params_read(p, &g->w, diag)) {
        free(g);
        return SYL_EMODEL;
    }
    const WeberParams *w = &g->w;
    Budget local;
    g->budget = budget_use(&local, opt ? opt->max_memory : 0, opt ? opt->budget : NULL);
    g->levels = (int)w->Levels;
    g->leaves = (int)w->Leaves;
    if (opt && opt->levels > 0 && opt->levels < g->levels) g->levels = opt->levels, g->leaves = 0;
    g->seed = opt && opt->use_seed ? opt->seed : w->seed;
    g->cancel = opt ? opt->cancel : NULL;
    if (opt) g->seed += opt->seed_offset; /* a scene's n-th plant of a row: a tree of its own */
    g->leaf_len = w->LeafScale / sqrt(w->LeafQuality);
    g->leaf_width = w->LeafScale * w->LeafScaleX / sqrt(w->LeafQuality);
    WeberEnvelope env = {0};
    if (w->envelope) {
        int est = load_envelope(p, w, &env, diag);
        if (est) {
            obstacles_free(&env.obs);
            if (env.dev) rtcReleaseDevice(env.dev);
            free(g);
            return est;
        }
        g->envelope = &env;
    }
    Estimate est = estimate_stems(g);
    double bytes = est.bytes, stems = est.stems;
    uint64_t used = atomic_load(&g->budget->used);
    if (!(bytes < (double)(g->budget->limit - (used < g->budget->limit ? used : g->budget->limit)))) {
        program_say(p, diag, DIAG_ERROR, NULL, "'%s': the tree would have about %.3g stems (%.0f MB), more than --max-memory "
                    "allows (%llu MB in all); raise the limit with --max-memory, or lower SegSplits, 0BaseSplits "
                    "or Branches",
                    syl_program_name(p), stems, bytes / (1 << 20), (unsigned long long)budget_limit_mb(g->budget));
        obstacles_free(&env.obs);
        if (env.dev) rtcReleaseDevice(env.dev);
        free(g);
        return SYL_ELIMIT;
    }
    presize(g, &est);
    JRand j0, j1;
    bool java = w->convention == WEBER_ARBARO;
    double u;
    if (java) {
        jrand_tree((int64_t)g->seed, &j0, &j1);
        u = jrand_double(&j0);
    } else {
        Rng tree = weber_rng(g, 0, WRNG_SELF);
        u = rng_unit(&tree);
    }
    g->scale_tree = w->Scale + w->ScaleV * (2 * u - 1);
    make_trunks(g, java ? &j0 : NULL, &j1);
    /* the last array presized, whose estimate is the loosest: what it did not use goes to
     * what weber_write_nodes takes next (the oak's scratch then reaches two 2 MB pages) */
    weber_trim(g, g->leafy_f, &g->leafy_f_cap, g->nleafy_f, sizeof *g->leafy_f);
    size_t leaves = weber_count_leaves(g), most = g->npts + g->nstems, ns = g->nstems;
    /* what comes after (weber_write_nodes, weber_place_leaves): node distances, the nodes,
     * then the attachments' scratch or the leaves in its place */
    size_t scratch = (ns + 64) * 40 /* (write.c: per stem two 16-byte Attach and two words) */, lvs = (leaves + 1) * sizeof(SylOrgan);
    if (!g->failed) weber_pack(g, (most + 256) * sizeof(float) + (most + 1) * sizeof(SylNode) + 128 + (scratch > lvs ? scratch : lvs));
    int st = SYL_OK;
    SylSkeleton *sk = NULL;
    if (g->failed) st = SYL_ELIMIT;
    if (!st && weber_stop(g)) st = SYL_ECANCELED;
    if (!st && !(sk = syl_skeleton_new(syl_program_name(p)))) st = SYL_ELIMIT;
    if (!st) st = weber_write_nodes(g, sk);
    if (!st && g->leaves && weber_stop(g)) st = SYL_ECANCELED;
    if (!st) weber_place_leaves(g, leaves);
    if (!st && g->failed) st = SYL_ELIMIT;
    if (g->cancelled) st = SYL_ECANCELED; /* nothing said */
    if (!st) weber_write_leaves(g, sk);
    if (!st) {
        uint64_t bytes = (uint64_t)sk->store->node_cap * sizeof *sk->nodes + (uint64_t)sk->store->organ_cap * sizeof *sk->organs;
        if (budget_charge(g->budget == &local ? NULL : g->budget, bytes)) {
            if (g->budget != &local) skeleton_charge(sk, g->budget, bytes);
        } else {
            st = SYL_ELIMIT;
        }
    }
    if (st == SYL_ELIMIT)
        program_say(p, diag, DIAG_ERROR, NULL, "'%s': the tree needs more memory than --max-memory allows (%llu MB)",
                syl_program_name(p), (unsigned long long)budget_limit_mb(g->budget));
    if (!st) st = lang_textures_apply(p, sk, g->seed, diag);
    free_gen(g, sk);
    free(g);
    obstacles_free(&env.obs);
    if (env.dev) rtcReleaseDevice(env.dev);
    if (st) {
        syl_skeleton_free(sk);
        return st;
    }
    *out = sk;
    return SYL_OK;
}
