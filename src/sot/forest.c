/* The forest's life and its yearly cycle: see forest.h. Light and registration are in
 * forest_light.c, shoot growth in forest_grow.c. */
#include "sot/forest.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sot/allocate.h"
#include "sot/forest_internal.h"
#include "sot/shed.h"
#include "lang/program.h"

double forest_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

int forest_init(Forest *f, int threads, FILE *diag, SylGrowStats *stats) {
    memset(f, 0, sizeof *f);
    f->threads = threads;
    f->diag = diag;
    f->stats = stats;
    f->max_metamers = 20000000;
    f->max_buds = 100000000;
    budget_init(&f->own, 0);
    f->mem = &f->own;
    return env_init(&f->env, threads, diag_sink(&(SylSink){0}, diag, NULL));
}

void forest_limits(Forest *f, const SylGrowOptions *opt) {
    if (opt->max_metamers) f->max_metamers = opt->max_metamers;
    if (opt->max_buds) f->max_buds = opt->max_buds;
    f->max_modules = opt->max_modules;
    f->max_work = opt->max_work;
    f->mem = budget_use(&f->own, opt->max_memory, opt->budget);
    f->cancel = opt->cancel;
}

int forest_said(Forest *f, int st, int year) {
    if (st != SYL_ELIMIT || f->reported) return st;
    f->reported = true;
    if (!f->diag) return st;
    char when[32] = "";
    if (year > 0) snprintf(when, sizeof when, " in year %d", year);
    if (atomic_load(&f->mem->refused))
        diag_say(f->diag, f->sink, DIAG_ERROR, NULL, "growing would need more than %llu MB of memory%s; raise the limit with "
                         "--max-memory", (unsigned long long)budget_limit_mb(f->mem), when);
    else diag_say(f->diag, f->sink, DIAG_ERROR, NULL, "out of memory%s", when);
    return st;
}

void forest_free(Forest *f) {
    for (int i = 0; i < f->ntrees; i++) tree_free(&f->trees[i]);
    for (int i = 0; i < f->nrules; i++) shoot_rule_free(f->rules[i].rule);
    free(f->rules);
    budget_release(f->mem, f->charged);
    free(f->trees);
    free(f->cand);
    free(f->sb);
    free(f->sr);
    free(f->sb_cand);
    free(f->occ);
    env_free(&f->env);
    memset(f, 0, sizeof *f);
}

/* The shoot rule `name` of grow model `from`, built once for all its trees. */
static ShootRule *shared_rule(Forest *f, const SylProgram *from, const char *name) {
    for (int i = 0; i < f->nrules; i++)
        if (f->rules[i].from == from && !strcmp(f->rules[i].name, name)) return f->rules[i].rule;
    if (f->nrules == f->rules_cap) {
        int cap = f->rules_cap ? 2 * f->rules_cap : 4;
        ForestRule *r = realloc(f->rules, (size_t)cap * sizeof *r);
        if (!r) return NULL;
        f->rules = r;
        f->rules_cap = cap;
    }
    ShootRule *rule = shoot_rule_new(from, name);
    if (!rule) return NULL;
    shoot_rule_limits(rule, f->max_modules, f->max_work, f->mem);
    shoot_rule_derive_with(rule, f->shoot_derive);
    f->rules[f->nrules++] = (ForestRule){.from = from, .name = name, .rule = rule};
    return rule;
}

int forest_add_tree(Forest *f, const GrowParams *P, const float base[3], int years) {
    if (f->ntrees == f->trees_cap) {
        int cap = f->trees_cap ? 2 * f->trees_cap : 4;
        Tree *t = realloc(f->trees, (size_t)cap * sizeof *t);
        if (!t) return SYL_ELIMIT;
        f->trees = t;
        f->trees_cap = cap;
    }
    GrowParams q = *P;
    q.years = years;
    ShootRule *rule = NULL;
    if (q.rule[0] && q.from && !(rule = shared_rule(f, q.from, q.rule))) return SYL_ELIMIT;
    q.from = NULL; /* the tree takes the forest's rule */
    Tree *t = &f->trees[f->ntrees];
    if (!tree_init(t, &q, f->ntrees, base, 0)) return SYL_ELIMIT;
    t->rule = rule;
    t->rule_shared = true;
    f->ntrees++;
    /* charged from the tree's start: its first node and bud */
    t->mem = f->mem;
    t->charged = (uint64_t)t->cap * sizeof *t->nodes + (uint64_t)t->bcap * sizeof *t->buds;
    if (!budget_charge(t->mem, t->charged)) {
        t->charged = 0;
        return SYL_ELIMIT;
    }
    if (years > f->years) f->years = years;
    return SYL_OK;
}

int forest_add_static(Forest *f, const float pos[3]) {
    return env_add_static(&f->env, pos) ? SYL_OK : SYL_ELIMIT;
}

int forest_setup(Forest *f, float ground, const float sun[3], bool sun_set) {
    Env *e = &f->env;
    e->ground = ground;
    const GrowParams *shadow = NULL, *sky = NULL, *space = NULL;
    for (int i = 0; i < f->ntrees; i++) {
        Tree *t = &f->trees[i];
        /* trees that grow fewer years start later: all end together */
        t->start_year = f->years - t->P.years;
        t->nodes[0].born = (uint16_t)t->start_year;
        t->buds[0].born = (uint16_t)t->start_year;
        if (sun_set) memcpy(t->P.sun, sun, sizeof t->P.sun);
        if (t->P.light == LIGHT_SHADOW && !shadow) shadow = &t->P;
        if (t->P.light == LIGHT_SKY && !sky) sky = &t->P;
        if (t->P.space != SPACEM_OFF && !space) space = &t->P;
    }
    const GrowParams *first = f->ntrees ? &f->trees[0].P : NULL;
    memcpy(e->sun, sun_set || !first ? sun : first->sun, sizeof e->sun);
    if (shadow) {
        ShadowParams sp = {.voxel = shadow->voxel, .full = shadow->full, .a = shadow->shadow_a, .b = shadow->shadow_b,
                           .depth = shadow->depth};
        memcpy(sp.sun, e->sun, sizeof sp.sun);
        shadow_init(&e->shadow, &sp, ground);
        e->shadow.mem = f->mem;
        e->shadow_on = true;
    } else if (f->lsys_shadow) { /* only for ?E light: no tree reads it */
        ShadowParams sp = probe_shadow_params(f->lsys_shadow_voxel, e->sun);
        shadow_init(&e->shadow, &sp, ground);
        e->shadow.mem = f->mem;
        e->shadow_on = true;
    }
    e->sky_on = sky != NULL;
    if (space) {
        f->space_any = true;
        f->space_variant = space->space == SPACEM_GLOBAL ? SPACE_GLOBAL : SPACE_PER_BUD;
        e->occupancy = space->occupancy * space->internode;
        if (f->space_variant == SPACE_GLOBAL) {
            float reach = 0, il3 = space->internode * space->internode * space->internode;
            for (int i = 0; i < f->ntrees; i++)
                if (f->trees[i].P.perception * f->trees[i].P.internode > reach)
                    reach = f->trees[i].P.perception * f->trees[i].P.internode;
            markers_init(&e->cloud, reach, space->density / il3, e->occupancy, ground, space->seed ^ 0x3a7c3u);
            e->cloud.mem = f->mem;
            e->cloud_on = true;
        }
    }
    return SYL_OK;
}

bool forest_too_many(Forest *f, int year) {
    uint64_t n = 0, buds = 0;
    for (int i = 0; i < f->ntrees; i++) n += f->trees[i].n - 1, buds += f->trees[i].nb;
    if (n <= f->max_metamers && buds <= f->max_buds) return false;
    f->reported = true;
    if (n > f->max_metamers)
        diag_say(f->diag, f->sink, DIAG_ERROR, NULL, "more than %llu metamers in year %d (the --max-metamers limit)",
                (unsigned long long)f->max_metamers, year);
    else diag_say(f->diag, f->sink, DIAG_ERROR, NULL, "more than %llu buds in year %d (the --max-buds limit)",
                (unsigned long long)f->max_buds, year);
    return true;
}

static int shed_all(Forest *f) {
    for (int i = 0; i < f->ntrees; i++) {
        Tree *t = &f->trees[i];
        if (!(t->P.shed_threshold > 0) && !(t->P.bare_trunk > 0)) continue;
        bool shadow = t->P.light == LIGHT_SHADOW; /* shed_mark looks each node up itself */
        if (!shadow) forest_node_light(f, t);
        size_t marked = shed_mark(t, shadow ? &f->env.shadow : NULL);
        if (marked == (size_t)-1) return SYL_ELIMIT;
        if (!marked) continue;
        int st = forest_drop_dead(f, t, marked);
        if (st) return st;
    }
    return SYL_OK;
}

int forest_run(Forest *f, void (*progress)(void *, double), void *user) {
    SylGrowStats *s = f->stats;
    size_t *before = malloc((size_t)(f->ntrees ? f->ntrees : 1) * sizeof *before);
    int st = before ? forest_register_statics(f) : SYL_ELIMIT;
    for (int year = 1; year <= f->years && !st; year++) {
        if (syl_cancelled(f->cancel)) { /* the caller frees the forest, as after any error */
            st = SYL_ECANCELED;
            break;
        }
        double th = forest_now();
        if (f->year_start) st = f->year_start(f->year_user, year);
        double t0 = forest_now();
        if (s) s->other_s += t0 - th;
        for (int i = 0; i < f->ntrees; i++) before[i] = f->trees[i].n;
        if (!st) st = forest_light(f, year);
        double t1 = forest_now();
        if (!st) st = forest_space_light(f, year);
        double t2 = forest_now();
        for (int i = 0; i < f->ntrees && !st; i++) {
            Tree *t = &f->trees[i];
            if (t->start_year >= year) continue;
            alloc_demand(t, year);
            if (!alloc_resources(t, year)) st = SYL_ELIMIT;
            alloc_shoots(t, year);
        }
        double t3 = forest_now();
        if (!st) st = forest_grow(f, year);
        double t4 = forest_now();
        if (!st) st = forest_register(f, before);
        double t5 = forest_now();
        if (!st) st = shed_all(f);
        double t6 = forest_now();
        if (!st) st = forest_occupancy(f);
        double t7 = forest_now();
        if (s) {
            s->light_s += (t1 - t0) + (t5 - t4);
            s->space_s += (t2 - t1) + (t7 - t6);
            s->alloc_s += t3 - t2;
            s->growth_s += t4 - t3;
            s->shed_s += t6 - t5;
        }
        if (!st && forest_too_many(f, year)) st = SYL_ELIMIT;
        st = forest_said(f, st, year);
        if (progress) progress(user, (double)year / f->years);
    }
    free(before);
    if (s) {
        s->years = f->years;
        s->plants += f->ntrees;
        for (int i = 0; i < f->ntrees; i++) {
            const Tree *t = &f->trees[i];
            s->metamers += t->n - 1;
            s->grown += t->grown;
            s->shed_branches += t->shed_branches;
            s->shed_metamers += t->shed_metamers;
            for (size_t b = 0; b < t->nb; b++) s->buds += t->buds[b].alive;
        }
    }
    return st;
}
