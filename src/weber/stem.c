/* One stem: its length and radius, its segments (curvature, attraction, splits), the points
 * of its axis, then its clones, children and leaves, depth first. */
#include <stdlib.h>
#include <string.h>

#include "util/pages.h"
#include "weber/internal.h"

void weber_free(WeberGen *g, void *arr, size_t bytes) {
    if (!arena_holds(&g->arena, arr)) pages_free(arr, bytes);
}

void *weber_take(WeberGen *g, size_t bytes) {
    void *p = g->arena.fixed ? arena_take(&g->arena, bytes) : NULL;
    return p ? p : malloc(bytes ? bytes : 1);
}

void *weber_keep(WeberGen *g, size_t bytes) {
    void *p = g->arena.fixed ? arena_take(&g->arena, bytes) : NULL;
    return p ? p : pages_owned(bytes, PAGES_OWNED_SCRATCH);
}

void weber_drop(WeberGen *g, void *p, size_t bytes) {
    if (arena_holds(&g->arena, p)) arena_pop(&g->arena, p, bytes);
    else free(p);
}

/* The generator's own arrays: first packed in the arena, then, past it, from 64 KB mapped in
 * 2 MB pages (util/pages.h), which grow by moving their pages, not copying them (page faults
 * were a fifth of the time). */
bool weber_grow(WeberGen *g, void **arr, size_t *cap, size_t need, size_t size) {
    if (need <= *cap) return true;
    size_t nc = *cap ? *cap : need > 256 ? need : 256; /* a first size asked for exactly: kept */
    while (nc < need) nc *= 2;
    bool arena = g->arena.fixed && (!*arr || arena_holds(&g->arena, *arr));
    /* past the size where huge pages pay (util/pages.h), a whole 2 MB page at once: one fault
     * instead of one per 4 KB, and later growth moves pages instead of copying them */
    if (!arena && nc * size >= PAGES_OWNED_SCRATCH && nc * size < PAGES_HUGE) nc = PAGES_HUGE / size;
    if (!budget_resize(g->budget, (uint64_t)*cap * size, (uint64_t)nc * size)) return g->failed = true, false;
    void *p = arena ? arena_resize(&g->arena, *arr, *cap * size, nc * size) : NULL;
    if (!p && arena) { /* the arena is full: out of it for good, as above */
        size_t nh = nc * size >= PAGES_OWNED_SCRATCH && nc * size < PAGES_HUGE ? PAGES_HUGE / size : nc;
        if (nh != nc && !budget_resize(g->budget, (uint64_t)nc * size, (uint64_t)nh * size)) {
            budget_resize(g->budget, (uint64_t)nc * size, (uint64_t)*cap * size);
            return g->failed = true, false;
        }
        nc = nh;
        if ((p = pages_grow(NULL, 0, 0, nc * size)) && *cap) memcpy(p, *arr, *cap * size);
    } else if (!p) {
        p = pages_grow(*arr, *cap * size, *cap * size, nc * size);
    }
    if (!p) {
        budget_resize(g->budget, (uint64_t)nc * size, (uint64_t)*cap * size);
        return g->failed = true, false;
    }
    g->charged += (uint64_t)(nc - *cap) * size;
    *arr = p;
    *cap = nc;
    return true;
}

void weber_trim(WeberGen *g, void *arr, size_t *cap, size_t n, size_t size) {
    if (n >= *cap || !arena_holds(&g->arena, arr)) return;
    size_t used = g->arena.used;
    arena_trim(&g->arena, arr, *cap * size, n * size);
    if (g->arena.used == used) return; /* not the last: kept whole */
    budget_resize(g->budget, (uint64_t)*cap * size, (uint64_t)n * size);
    g->charged -= (uint64_t)(*cap - n) * size;
    *cap = n;
}

/* The turn at the start of segment seg (none at the first: the down and rotation angles
 * stay as given). */
static void new_direction(WeberGen *g, WStem *st, Frame *trf, int seg, Rng *r) {
    if (seg == 0) return;
    const WeberParams *w = &g->w;
    int lv = weber_lv(st->level);
    double res = w->CurveRes[lv], delta;
    if (w->CurveBack[lv] == 0) delta = w->Curve[lv] / res;
    else if (seg < ((int)res + 1) / 2) delta = w->Curve[lv] * 2 / res;
    else delta = w->CurveBack[lv] * 2 / res;
    delta += st->split_corr;
    frame_rot_local(trf, 1, 0, 0, delta);
    if (w->CurveV[lv] > 0) { /* a random bend about an axis in the segment's xy plane */
        double d = weber_var(r, w->CurveV[lv]) / res;
        double rho = (180 + weber_var(r, 180)) * (M_PI / 180);
        frame_rot_local(trf, cos(rho), sin(rho), 0, d);
    }
    if (w->AttractionUp != 0 && st->level >= 2) {
        double zz = trf->z[2] > 1 ? 1 : trf->z[2] < -1 ? -1 : trf->z[2];
        double decl = acos(zz);
        if (w->convention == WEBER_PAPER) { /* the paper's form, with the orientation term */
            double yz = trf->y[2] > 1 ? 1 : trf->y[2] < -1 ? -1 : trf->y[2];
            double up = w->AttractionUp * decl * cos(acos(yz)) / res;
            frame_rot_local(trf, 1, 0, 0, up * 180 / M_PI);
        } else { /* Arbaro's: about the horizontal axis across the stem */
            double up = w->AttractionUp * fabs(decl * sin(decl)) / res;
            double axis[3] = {-trf->z[1], trf->z[0], 0};
            frame_rot_global(trf, axis, -up * 180 / M_PI);
        }
    }
}

/* A stem traced: its segments, and its clones, each traced when it splits off (Arbaro's
 * order, which the error diffusion of splits follows); points and children come after. */
typedef struct Traced Traced;
typedef struct SapPlaces SapPlaces;
typedef struct Pending {
    Traced *c;
    size_t n, cap;
} Pending;
struct Traced {
    WStem st;
    WSeg *segs;
    Pending pend;
    const SapPlaces *places; /* SaplingLaw, a trunk and its clones: the trunk's children's places */
    int flat;                /* its number among them (the owner of its places) */
};
/* SaplingLaw: the trunk's places for children (shares of its length) and the stem (trunk or
 * clone, by number) each is on: Sapling puts one child at each, where its forks pass. */
struct SapPlaces {
    double *t;
    int *owner;
    size_t n;
};

/* Frees the clones, releasing what they were charged. */
static void free_pending(WeberGen *g, Pending *p) {
    for (size_t i = 0; i < p->n; i++) {
        free(p->c[i].segs);
        budget_release(g->budget, (uint64_t)p->c[i].st.nseg * sizeof(WSeg));
        free_pending(g, &p->c[i].pend);
    }
    free(p->c);
    budget_release(g->budget, (uint64_t)p->cap * sizeof *p->c);
    *p = (Pending){0};
}

/* test: traced only to find the first segment that leaves the envelope (check: found as
 * well while the stem and its clones are made: weber_make_stem's first try) */
static int trace_in(WeberGen *g, WStem *st, int s0, Frame trf, bool test, bool check, WSeg *segs, Pending *pend) {
    Rng r = weber_rng(g, st->key, WRNG_SHAPE); /* the same stream for a test and the real stem */
    if (s0 == 0) st->split_last = false;
    for (int s = s0; s < st->nseg; s++) {
        new_direction(g, st, &trf, s, &r);
        if (segs) segs[s].f = trf, segs[s].sps = st->sps;
        frame_move(&trf, weber_step(g, st, &trf));
        if (check && !weber_inside(g, trf.t)) return s;
        if (s >= st->nseg - 1) continue;
        int n = g->w.SaplingLaw ? weber_sapling_splits(g, st, s, &r) : weber_split_count(g, st, s);
        st->split_last = n > 0;
        if (n < 1) continue;
        double s_angle = 360.0 / (n + 1);
        for (int i = 0; i < n; i++) {
            WStem c = *st;
            c.clone = true;
            c.key = weber_key(st->key, 2 + (uint64_t)s, (uint64_t)i);
            c.first_seg = s + 1;
            c.rot = st->rot + 180;
            c.start = weber_split(g, &c, &r, trf, s_angle * (1 + i), s, n, test);
            if (g->w.SaplingLaw) weber_sapling_fork(g, st, &c, &trf);
            if (test) {
                int bad = trace_in(g, &c, s + 1, c.start, true, true, NULL, NULL);
                if (bad >= 0) return bad;
                continue;
            }
            if (pend->n == pend->cap) {
                size_t nc = pend->cap ? 2 * pend->cap : 4;
                if (!budget_resize(g->budget, (uint64_t)pend->cap * sizeof *pend->c, (uint64_t)nc * sizeof *pend->c))
                    return g->failed = true, -1;
                Traced *q = realloc(pend->c, nc * sizeof *q);
                if (!q) {
                    budget_resize(g->budget, (uint64_t)nc * sizeof *pend->c, (uint64_t)pend->cap * sizeof *pend->c);
                    return g->failed = true, -1;
                }
                pend->c = q, pend->cap = nc;
            }
            Traced *t = &pend->c[pend->n];
            t->pend = (Pending){0};
            t->places = NULL;
            if (!budget_charge(g->budget, (uint64_t)c.nseg * sizeof *t->segs)) return g->failed = true, -1;
            t->segs = malloc((size_t)c.nseg * sizeof *t->segs);
            if (!t->segs) {
                budget_release(g->budget, (uint64_t)c.nseg * sizeof *t->segs);
                return g->failed = true, -1;
            }
            t->st = c; /* nseg: what free_pending releases */
            pend->n++;
            int bad = trace_in(g, &c, s + 1, c.start, false, check, t->segs, &t->pend);
            if (g->failed) return -1;
            t->st = c;
            if (bad >= 0) return bad;
        }
        Frame t2 = weber_split(g, st, &r, trf, 0, s, n, test);
        if (g->w.convention == WEBER_PAPER) trf = t2; /* Arbaro's original stem keeps its heading */
    }
    return -1;
}

int weber_trace(WeberGen *g, WStem *st, int s0, Frame trf, bool test, WSeg *segs) {
    return trace_in(g, st, s0, trf, test, test, segs, NULL);
}

static bool put_point(WeberGen *g, const WStem *st, const Frame *f, const double p[3], double dist) {
    if (!weber_grow(g, (void **)&g->pts, &g->pts_cap, g->npts + 1, sizeof *g->pts)) return false;
    WPoint *q = &g->pts[g->npts++];
    for (int i = 0; i < 3; i++) q->pos[i] = (float)p[i], q->z[i] = (float)f->z[i], q->x[i] = (float)f->x[i];
    q->dist = (float)dist;
    q->r = (float)weber_radius(g, st, dist);
    return true;
}

/* The axis points of segment s: its end, and sub-sections where the radius profile or a
 * helix needs them (Arbaro's counts: 10 for flare, rounded ends and helices, 20 for beads). */
static bool put_segment(WeberGen *g, const WStem *st, int s, const Frame *f) {
    const WeberParams *w = &g->w;
    int lv = weber_lv(st->level);
    double len = st->seglen, base = s * len, taper = w->Taper[lv], p[3];
    double k = len > 0 ? weber_step(g, st, f) / len : 1; /* taperCrown: a shorter step, the same share */
#define AT(d) (p[0] = f->t[0] + f->z[0] * (d) * k, p[1] = f->t[1] + f->z[1] * (d) * k, p[2] = f->t[2] + f->z[2] * (d) * k, p)
    if (s == st->first_seg && !put_point(g, st, f, AT(len * 1e-3), base + len * 1e-3)) return false;
    if (w->CurveV[lv] < 0) { /* a helix: one turn per segment */
        double a = fabs(w->CurveV[lv]) * M_PI / 180, c = cos(a);
        double hr = sqrt(1.0 / (c * c) - 1) * len / M_PI / 2.0;
        for (int i = 1; i <= 10; i++) {
            double lx = hr * cos(2 * M_PI * i / 10) - hr, ly = hr * sin(2 * M_PI * i / 10), lz = i * len / 10;
            for (int k = 0; k < 3; k++) p[k] = f->t[k] + f->x[k] * lx + f->y[k] * ly + f->z[k] * lz;
            if (!put_point(g, st, f, p, base + lz)) return false;
        }
        return true;
    }
    if (taper > 1 && taper <= 2 && s == st->nseg - 1) { /* rounded end: shorter steps to the tip */
        for (int i = 1; i < 10; i++)
            if (!put_point(g, st, f, AT(len - len / pow(2, i)), base + len - len / pow(2, i))) return false;
    } else if (taper > 2) {
        for (int i = 1; i < 20; i++)
            if (!put_point(g, st, f, AT(i * len / 20), base + i * len / 20)) return false;
    } else if (st->level == 0 && w->Flare != 0 && s == 0) { /* flare: shorter steps to the base */
        for (int i = 9; i >= 1; i--)
            if (!put_point(g, st, f, AT(len / pow(2, i)), base + len / pow(2, i))) return false;
    }
    return put_point(g, st, f, AT(len), base + len);
#undef AT
}

static bool add_stem(WeberGen *g, const WStem *st, int *id) {
    if (!weber_grow(g, (void **)&g->stems, &g->stems_cap, g->nstems + 1, sizeof *g->stems)) return false;
    *id = (int)g->nstems;
    g->stems[g->nstems++] = *st;
    return true;
}

/* Points, clones, children and leaves of a traced stem already in the list. */
static void run_stem(WeberGen *g, int id, Traced *t) {
    WStem *st = &t->st;
    g->stems[id].pt_first = (uint32_t)g->npts;
    for (int s = st->first_seg; s < st->nseg && !g->failed; s++) put_segment(g, st, s, &t->segs[s].f);
    g->stems[id].pt_count = (uint32_t)(g->npts - g->stems[id].pt_first);
    for (size_t i = 0; i < t->pend.n && !g->failed; i++) {
        int cid;
        t->pend.c[i].st.from = id;
        if (add_stem(g, &t->pend.c[i].st, &cid)) run_stem(g, cid, &t->pend.c[i]);
    }
    if (st->level < g->levels - 1) {
        Rng kids = weber_rng(g, st->key, WRNG_KIDS);
        if (g->w.SaplingLaw && st->level > 0) {
            weber_sapling_children(g, id, st, t->segs, &kids);
        } else if (g->w.SaplingLaw) {
            for (size_t i = 0; t->places && i < t->places->n && !g->failed; i++)
                if (t->places->owner[i] == t->flat) weber_sapling_child(g, id, st, t->segs, t->places->t[i] * st->nseg, (int)i, &kids);
        } else {
            for (int s = st->first_seg; s < st->nseg && !g->failed; s++) weber_children(g, id, st, s, t->segs, &kids);
        }
        if (g->w.SaplingLaw && !g->failed) weber_tip_child(g, id, st, t->segs, &kids);
    } else if (g->leaves != 0) {
        weber_defer_leaves(g, id, st, t->segs);
    }
}

/* The counts of children and leaves per segment, and the most length of a child. */
static void prepare_children(WeberGen *g, WStem *st, Rng *self) {
    const WeberParams *w = &g->w;
    int cl = weber_lv(st->level + 1);
    st->lcm = w->Length[cl] + (st->u_lcm >= 0 ? w->LengthV[cl] * (2 * st->u_lcm - 1) : weber_var(self, w->LengthV[cl]));
    double most = w->Branches[cl], n;
    if (w->SaplingLaw && st->level > 0) { /* by its length against its level's longest; placed by weber_sapling_children */
        st->sap_n = most * (0.1 + 0.9 * st->length / weber_sapling_most(g, st));
        st->sps = 0;
    } else if (w->SaplingLaw) { /* the trunk: at Sapling's places (trunk_places) */
        st->sps = 0;
    } else if (st->level == 0) {
        st->sps = most / st->nseg / (1 - w->BaseSize);
    } else {
        const WStem *p = &g->stems[st->parent];
        if (st->level == 1) n = (int)(most * (0.2 + 0.8 * st->length / p->length / p->lcm));
        else n = (int)(most * (1.0 - 0.5 * st->offset / p->length));
        st->sps = n / st->nseg;
    }
    st->rot = 0;
    st->lps = st->level == g->levels - 1 ? weber_leaves_per_stem(g, st) / st->nseg : 0;
}

/* SaplingLaw: the segments of a stem and its clones, and the even places its children take
 * along each of them: Sapling shares a stem's children among all those segments. */
static int pending_segments(const Pending *p) {
    int n = 0;
    for (size_t i = 0; i < p->n; i++) n += p->c[i].st.nseg - p->c[i].st.first_seg + pending_segments(&p->c[i].pend);
    return n;
}
static void set_main(Pending *p, int main) {
    for (size_t i = 0; i < p->n; i++) p->c[i].st.sap_main = main, set_main(&p->c[i].pend, main);
}
static size_t pending_count(const Pending *p) {
    size_t n = p->n;
    for (size_t i = 0; i < p->n; i++) n += pending_count(&p->c[i].pend);
    return n;
}
static void flatten(Traced *t, const SapPlaces *sp, Traced **flat, size_t *k) {
    t->places = sp;
    t->flat = (int)*k;
    flat[(*k)++] = t;
    for (size_t i = 0; i < t->pend.n; i++) flatten(&t->pend.c[i], sp, flat, k);
}

/* SaplingLaw: the trunk's places (weber_sapling_trunk_places) and the fork each child goes
 * on: as Sapling turns by Rotate (± RotateV) from one place to the next, the trunk or clone
 * there whose azimuth is nearest that angle. Returns the bytes charged. */
static uint64_t trunk_places(WeberGen *g, Traced *root, SapPlaces *sp) {
    const WeberParams *w = &g->w;
    size_t most = w->Branches[1] < 1 ? 0 : (size_t)fmin(w->Branches[1], 1e9), nflat = 1 + pending_count(&root->pend);
    uint64_t bytes = (uint64_t)most * (sizeof *sp->t + sizeof *sp->owner) + nflat * sizeof(Traced *);
    if (!budget_charge(g->budget, bytes)) return g->failed = true, 0;
    sp->t = malloc(most * sizeof *sp->t + 1);
    sp->owner = malloc(most * sizeof *sp->owner + 1);
    Traced **flat = malloc(nflat * sizeof *flat);
    if (!sp->t || !sp->owner || !flat) {
        free(flat);
        return g->failed = true, bytes;
    }
    size_t k = 0;
    flatten(root, sp, flat, &k);
    Rng r = weber_rng(g, root->st.key, WRNG_PLACES);
    sp->n = weber_sapling_trunk_places(w, &r, sp->t);
    double rot = 0;
    for (size_t i = 0; i < sp->n; i++) {
        rot = w->Rotate[1] < 0 ? -copysign(w->Rotate[1], rot) : rot + w->Rotate[1];
        double want = fmod(rot + weber_var(&r, w->RotateV[1]), 360), at = sp->t[i] * root->st.nseg, best = INFINITY;
        int seg = (int)at;
        sp->owner[i] = 0;
        for (size_t f = 0; f < nflat; f++) {
            const Traced *c = flat[f];
            if (c->st.first_seg > seg) continue;
            const Frame *fr = &c->segs[seg].f;
            double d = (at - seg) * c->st.seglen, x = fr->t[0] + fr->z[0] * d, y = fr->t[1] + fr->z[1] * d;
            double off = fmod(want - atan2(x, -y) * (180 / M_PI) + 720, 360);
            off = fmin(off, 360 - off);
            if (off < best) best = off, sp->owner[i] = (int)f;
        }
    }
    free(flat);
    return bytes;
}

/* Whether the caller asked to stop; if so every loop ends as after a failure (failed). */
bool weber_stop(WeberGen *g) {
    if (!g->failed && syl_cancelled(g->cancel)) g->cancelled = g->failed = true;
    return g->cancelled;
}

bool weber_make_stem(WeberGen *g, WStem st) {
    const WeberParams *w = &g->w;
    if (st.level <= 1 && weber_stop(g)) return false; /* asked before each trunk and main branch */
    Rng self = weber_rng(g, st.key, WRNG_SELF);
    st.nseg = (int)w->CurveRes[weber_lv(st.level)];
    st.first_seg = 0;
    st.clone = false;
    st.from = st.parent;
    st.split_corr = 0;
    st.length = weber_stem_length(g, &st, &self);
    st.seglen = st.length / st.nseg;
    st.base_radius = weber_base_radius(g, &st);
    bool prune = st.level > 0 && (w->PruneRatio > 0 || g->envelope);
    Traced t = {0};
    int bad = -1;
    if (prune && !w->SaplingLaw && st.length > WEBER_MIN_LEN && st.base_radius > WEBER_MIN_RADIUS) {
        /* made at once, the envelope checked as it is: when it stays inside, pruning's first
         * test would have found so and left it as it is (the trace reads none of what
         * prepare_children sets but what it stores); else all undone and pruned as ever */
        WStem whole = st;
        Rng self0 = self;
        double split_err[10];
        memcpy(split_err, g->split_err, sizeof split_err);
        prepare_children(g, &st, &self);
        t = (Traced){.st = st, .segs = malloc((size_t)st.nseg * sizeof *t.segs)};
        if (!t.segs) return g->failed = true, false;
        bad = trace_in(g, &t.st, 0, t.st.start, false, true, t.segs, &t.pend);
        if (bad >= 0 || g->failed) {
            free(t.segs);
            free_pending(g, &t.pend);
            t = (Traced){0};
            if (g->failed) return false;
            st = whole, self = self0;
            memcpy(g->split_err, split_err, sizeof split_err);
        }
    }
    int id;
    if (!t.segs) {
        if (prune) weber_prune(g, &st, bad); /* (where it left: the same as a test trace finds) */
        if (!(st.length > WEBER_MIN_LEN && st.base_radius > WEBER_MIN_RADIUS)) return false;
        prepare_children(g, &st, &self);
        t = (Traced){.st = st, .segs = malloc((size_t)st.nseg * sizeof *t.segs)};
        if (!t.segs) return g->failed = true, false;
        trace_in(g, &t.st, 0, t.st.start, false, false, t.segs, &t.pend);
    }
    if (w->SaplingLaw && t.st.level > 0 && !g->failed) {
        int segs = t.st.nseg + pending_segments(&t.pend);
        t.st.sap_main = (int)fmin(round(t.st.sap_n * t.st.nseg / segs), 1e9); /* Branches may be huge: the budget stops it */
        set_main(&t.pend, t.st.sap_main);
    }
    SapPlaces sp = {0};
    uint64_t sp_bytes = 0;
    if (w->SaplingLaw && t.st.level == 0 && g->levels > 1 && !g->failed) sp_bytes = trunk_places(g, &t, &sp);
    if (!g->failed && add_stem(g, &t.st, &id)) run_stem(g, id, &t);
    free(sp.t);
    free(sp.owner);
    budget_release(g->budget, sp_bytes);
    free(t.segs);
    free_pending(g, &t.pend);
    return !g->failed;
}

/* The arrays presized from the tree's estimate (weber.c), packed once the stems are made:
 * each presized array holds room it did not use, and the 2 MB pages the later arrays reach
 * (the nodes, the leaves) are zeroed whole at their first write, which was a third of the
 * willow's time. Moving the points and the leaves' stems and frames down against the
 * stems (memmove, in the pages already written) pays when the tree then reaches fewer pages:
 * the willow 16 where it reached 18, the sassafras 5 where 6. later: the bytes taken after
 * them (nodes and leaves), at most. */
typedef struct Packed {
    void **arr;
    size_t *cap, n, size;
} Packed;
static size_t round64(size_t n) { return (n + 63) & ~(size_t)63; } /* (a fixed arena's arrays: util/arena.h) */
/* [from, to)'s 2 MB pages not counted yet (those up to *last were), counted */
static size_t new_pages(size_t from, size_t to, size_t *last) {
    if (to <= from) return 0;
    size_t first = from / PAGES_HUGE, end = (to - 1) / PAGES_HUGE + 1; /* (*last: one past the last counted) */
    if (first < *last) first = *last;
    if (end <= first) return 0;
    *last = end;
    return end - first;
}

void weber_pack(WeberGen *g, size_t later) {
    Packed a[4] = {{(void **)&g->stems, &g->stems_cap, g->nstems, sizeof *g->stems},
                   {(void **)&g->pts, &g->pts_cap, g->npts, sizeof *g->pts},
                   {(void **)&g->leafy, &g->leafy_cap, g->nleafy, sizeof *g->leafy},
                   {(void **)&g->leafy_f, &g->leafy_f_cap, g->nleafy_f, sizeof *g->leafy_f}};
    int k = 0;
    for (int i = 0; i < 4; i++)
        if (*a[i].arr) a[k++] = a[i];
    if (k < 2 || !g->arena.fixed) return;
    /* they must be the arena's arrays, one after the other from its start: presize's */
    const unsigned char *base = *a[0].arr;
    size_t at = 0, packed = 0, last = 0, now = 0;
    for (int i = 0; i < k; i++) {
        if (!arena_holds(&g->arena, *a[i].arr) || (const unsigned char *)*a[i].arr != base + at) return;
        now += new_pages(at, at + a[i].n * a[i].size, &last);
        at += round64(*a[i].cap * a[i].size);
        packed += round64(a[i].n * a[i].size);
    }
    if (at != g->arena.used) return;
    now += new_pages(at, at + later, &last);
    size_t none = 0;
    if (new_pages(0, packed + later, &none) >= now) return;
    for (int i = k - 1; i > 0; i--) arena_pop(&g->arena, *a[i].arr, *a[i].cap * a[i].size);
    for (int i = 0; i < k; i++) { /* each moves down (memmove: it may overlap where it was) */
        void *q = *a[i].arr;
        if (i == 0) arena_trim(&g->arena, q, *a[i].cap * a[i].size, a[i].n * a[i].size);
        else memmove(q = arena_take(&g->arena, a[i].n * a[i].size), *a[i].arr, a[i].n * a[i].size);
        budget_resize(g->budget, (uint64_t)*a[i].cap * a[i].size, (uint64_t)a[i].n * a[i].size);
        g->charged -= (uint64_t)(*a[i].cap - a[i].n) * a[i].size;
        *a[i].arr = q;
        *a[i].cap = a[i].n;
    }
}
