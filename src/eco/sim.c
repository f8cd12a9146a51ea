/* The simulation, one year per step and tile by tile (docs/ecosystem.md):
 *   A. every tile posts its plants near another tile's edge to that tile (its halo);
 *   B. every tile, on its own plants and its halo as they were at the year's start: who is
 *      dominated (a more powerful plant's ecological circle overlaps, Deussen et al. 1998;
 *      power v h p_r as Zamuda 2006), deaths
 *      (age, domination, stress or, as Zamuda, each factor), growth, seeds and random arrivals on its own cells, each
 *      germinating (or not) where it fell and posted as a seedling to the tile there;
 *   C. every tile takes the seedlings posted to it and merges them into its plants, kept
 *      sorted by (cell, id).
 * Each decision depends only on the start-of-year state and on streams keyed by (plant id,
 * year, purpose), so any tiling and any thread count give the same plants. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "eco/eco.h"
#include "util/budget.h"
#include "util/diag.h"
#include "util/parallel.h"
#include "util/rng.h"

typedef struct Buf {
    SylEcoPlant *p;
    size_t n, cap;
    Budget *mem;  /* what its array is counted against (NULL: nothing) */
} Buf;

typedef struct Inbox {
    const SylEcoPlant *p;
    size_t n;
} Inbox;

typedef struct Tile {
    int i0, i1, k0, k1;       /* its cells: columns [i0, i1), rows [k0, k1) */
    double x0, x1, z0, z1;    /* its rectangle */
    Buf own, halo;            /* its plants (sorted by key), its neighbours' border plants */
    Buf *out, *border;        /* per destination tile: seedlings; border plants (its halo) */
    Inbox *inbox;             /* the seedlings posted to it, per sending tile */
    uint32_t *cell_start, *order; /* the spatial grid over own + halo */
    size_t grid_cap, order_cap;
    int64_t area_u[SYL_ECO_MAX_SPECIES], height_u[SYL_ECO_MAX_SPECIES]; /* fixed point: exact sums */
    uint32_t count[SYL_ECO_MAX_SPECIES];
    uint32_t deaths[SYL_ECO_MAX_SPECIES][SYL_ECO_DEATH_CAUSES]; /* this year's, by cause */
    uint64_t alive_start;
    size_t peak_bytes;        /* this year's most memory held at once */
    int failed;
} Tile;

typedef struct Sim {
    const SylEcoModel *m;
    const SylTerrain *t;
    const SylEcoExchange *x;
    Tile *tile;
    int tx, tz, ntiles;
    int *tile_of_i, *tile_of_k;
    double halo;        /* twice the largest ecological radius any plant can reach */
    double rel_life[SYL_ECO_MAX_SPECIES]; /* max_age / the longest max_age: Zamuda's p_r */
    uint64_t seed;
    int year;
    int phase;
    int next;           /* the next tile a worker takes */
} Sim;

static bool buf_reserve(Buf *b, size_t need) {
    if (need <= b->cap) return true;
    size_t cap = need + need / 8 + 64;
    if (!budget_resize(b->mem, (uint64_t)b->cap * sizeof *b->p, (uint64_t)cap * sizeof *b->p)) return false;
    SylEcoPlant *p = realloc(b->p, cap * sizeof *p);
    if (!p) {
        budget_resize(b->mem, (uint64_t)cap * sizeof *b->p, (uint64_t)b->cap * sizeof *b->p);
        return false;
    }
    b->p = p;
    b->cap = cap;
    return true;
}

/* Free the array, release its charge; the buffer stays counted against the same budget. */
static void buf_free(Buf *b) {
    free(b->p);
    budget_release(b->mem, (uint64_t)b->cap * sizeof *b->p);
    *b = (Buf){.mem = b->mem};
}

static bool buf_push(Buf *b, const SylEcoPlant *p) {
    if (!buf_reserve(b, b->n + 1)) return false;
    b->p[b->n++] = *p;
    return true;
}

static int tile_at(const Sim *s, double x, double z) {
    const SylTerrain *t = s->t;
    int i = (int)floor((x - t->x0) / t->cell), k = (int)floor((z - t->z0) / t->cell);
    if (i < 0 || k < 0 || i >= t->nx || k >= t->nz) return -1;
    return s->tile_of_k[k] * s->tx + s->tile_of_i[i];
}

static double radius_of(const Sim *s, const SylEcoPlant *p) {
    return s->m->species[p->species].radius_ratio * p->height;
}

static int by_id(const void *a, const void *b) {
    uint64_t x = ((const SylEcoPlant *)a)->id, y = ((const SylEcoPlant *)b)->id;
    return x < y ? -1 : x > y;
}

/* Sorts plants in place by cmp with no scratch memory (heapsort): glibc's qsort would take a
 * copy of all of them, as much again as the plants, at each snapshot. */
static void sort_in_place(SylEcoPlant *p, size_t n, int (*cmp)(const void *, const void *)) {
    if (n < 2) return;
    for (size_t end = n, start = n / 2;;) {
        if (start > 0) start--; /* first build the heap, */
        else if (--end > 0) {   /* then move its top behind it */
            SylEcoPlant t = p[0];
            p[0] = p[end], p[end] = t;
        } else return;
        for (size_t r = start, c; (c = 2 * r + 1) < end; r = c) { /* sift down */
            if (c + 1 < end && cmp(&p[c], &p[c + 1]) < 0) c++;
            if (cmp(&p[r], &p[c]) >= 0) break;
            SylEcoPlant t = p[r];
            p[r] = p[c], p[c] = t;
        }
    }
}

/* A tile keeps its plants in (terrain cell, id) order: plants never move, so the order
 * survives the deaths, and neighbours lie near each other in memory for the grid's search
 * (ids are hashes: by id alone a search would jump all over the tile's plants). */
static inline bool key_less(const SylEcoPlant *p, const SylEcoPlant *q) {
    return p->cell != q->cell ? p->cell < q->cell : p->id < q->id;
}

static int by_key(const void *a, const void *b) {
    const SylEcoPlant *p = a, *q = b;
    return key_less(p, q) ? -1 : key_less(q, p);
}

/* Plant j of the grid's numbering: the tile's own, then its halo. */
static inline const SylEcoPlant *local_at(const Tile *T, size_t j) {
    return j < T->own.n ? &T->own.p[j] : &T->halo.p[j - T->own.n];
}

/* Phase A: the plants within the halo of another tile's rectangle go to it. */
static void post_halo(Sim *s, int ti) {
    Tile *T = &s->tile[ti];
    for (int u = 0; u < s->ntiles; u++) {
        if (u == ti) continue;
        const Tile *U = &s->tile[u];
        double h = s->halo;
        if (U->x0 - h > T->x1 || U->x1 + h < T->x0 || U->z0 - h > T->z1 || U->z1 + h < T->z0) continue;
        Buf *o = &T->border[u];
        o->n = 0;
        for (size_t j = 0; j < T->own.n; j++) {
            const SylEcoPlant *p = &T->own.p[j];
            if (p->x >= U->x0 - h && p->x <= U->x1 + h && p->z >= U->z0 - h && p->z <= U->z1 + h)
                if (!buf_push(o, p)) T->failed = 1;
        }
        s->x->post(s->x->ctx, SYL_ECO_HALO, ti, u, o->p, o->n);
    }
}

/* Zamuda's power, v h p_r (eq. 4.18-4.19): long-lived species outcompete short-lived ones of
 * the same height. */
static inline double power_of(const Sim *s, const SylEcoPlant *p) {
    return (double)p->vigour * p->height * s->rel_life[p->species];
}

/* The spatial grid over the tile's own plants and halo, one level per radius class (level L
 * holds the radii in (top / 2^(L+1), top / 2^L], the last also all below): each level's cells
 * are sized to its own largest radius, so a shrub looks at a few small cells of shrubs and a
 * few large cells of trees, never at a shrub-filled neighbourhood as wide as a tree's. Any
 * split finds the same overlaps: the split only decides how few plants are looked at. */
enum { GRID_LEVELS = 5 };

typedef struct Level {
    double x0, z0, g;  /* cells of size g from (x0, z0) */
    double rmax, pmax; /* the largest radius and power among its plants */
    int nx, nz;
    size_t cell0, n;   /* its first cell in the tile's cell_start; its plants */
} Level;

typedef struct Grid {
    double top; /* the largest radius of all */
    Level lv[GRID_LEVELS];
} Grid;

static int level_of(const Grid *G, double r) {
    int L = 0;
    for (double b = G->top * 0.5; L < GRID_LEVELS - 1 && r <= b; b *= 0.5) L++;
    return L;
}

/* The cell column (or row) of coordinate v, clamped to [0, n). */
static inline int cell_of(double v, double v0, double g, int n) {
    double c = floor((v - v0) / g);
    return c < 0 ? 0 : c >= n ? n - 1 : (int)c;
}

static inline size_t cell_index(const Level *l, const SylEcoPlant *p) {
    return l->cell0 + (size_t)cell_of(p->z, l->z0, l->g, l->nz) * l->nx + cell_of(p->x, l->x0, l->g, l->nx);
}

static bool build_grid(const Sim *s, Tile *T, Grid *G) {
    size_t n = T->own.n + T->halo.n;
    memset(G, 0, sizeof *G);
    for (size_t j = 0; j < n; j++) {
        double r = radius_of(s, local_at(T, j));
        if (r > G->top) G->top = r;
    }
    for (size_t j = 0; j < n; j++) {
        const SylEcoPlant *p = local_at(T, j);
        double r = radius_of(s, p), pw = power_of(s, p);
        Level *l = &G->lv[level_of(G, r)];
        l->n++;
        if (r > l->rmax) l->rmax = r;
        if (pw > l->pmax) l->pmax = pw;
    }
    double w = T->x1 - T->x0 + 2 * s->halo, d = T->z1 - T->z0 + 2 * s->halo;
    size_t cells = 0;
    for (int L = 0; L < GRID_LEVELS; L++) {
        Level *l = &G->lv[L];
        l->x0 = T->x0 - s->halo;
        l->z0 = T->z0 - s->halo;
        l->g = 2 * l->rmax; /* overlapping circles of this level lie in neighbouring cells */
        double least = sqrt(2 * w * d / (double)(l->n + 1)); /* about two plants per cell at most */
        if (l->g < least) l->g = least;
        if (l->g <= 0) l->g = 1;
        l->nx = l->n ? (int)(w / l->g) + 1 : 0;
        l->nz = l->n ? (int)(d / l->g) + 1 : 0;
        l->cell0 = cells;
        cells += (size_t)l->nx * (size_t)l->nz;
    }
    cells++;
    if (cells > T->grid_cap) {
        uint32_t *c = realloc(T->cell_start, cells * sizeof *c);
        if (!c) return false;
        T->cell_start = c;
        T->grid_cap = cells;
    }
    if (n > T->order_cap) {
        uint32_t *o = realloc(T->order, n * sizeof *o);
        if (!o) return false;
        T->order = o;
        T->order_cap = n;
    }
    memset(T->cell_start, 0, cells * sizeof *T->cell_start);
    for (size_t j = 0; j < n; j++) {
        const SylEcoPlant *p = local_at(T, j);
        T->cell_start[cell_index(&G->lv[level_of(G, radius_of(s, p))], p) + 1]++;
    }
    for (size_t c = 1; c < cells; c++) T->cell_start[c] += T->cell_start[c - 1];
    /* place each plant; cell_start[c] ends as the start of cell c + 1 */
    for (size_t j = 0; j < n; j++) {
        const SylEcoPlant *p = local_at(T, j);
        T->order[T->cell_start[cell_index(&G->lv[level_of(G, radius_of(s, p))], p)]++] = (uint32_t)j;
    }
    for (size_t c = cells - 1; c > 0; c--) T->cell_start[c] = T->cell_start[c - 1];
    T->cell_start[0] = 0;
    return true;
}

/* Whether a more powerful plant's circle overlaps p's (ties: the smaller id dominates). Each
 * level is searched over the cells within p's radius plus the level's largest; a level whose
 * most powerful plant is weaker than p is skipped. */
static bool is_dominated(const Sim *s, const Tile *T, const Grid *G, const SylEcoPlant *p) {
    double rp = radius_of(s, p), pp = power_of(s, p);
    for (int L = 0; L < GRID_LEVELS; L++) {
        const Level *l = &G->lv[L];
        if (!l->n || l->pmax < pp) continue;
        double reach = (rp + l->rmax) * (1 + 1e-9) + 1e-9; /* rounding never narrows the search */
        int i0 = cell_of(p->x - reach, l->x0, l->g, l->nx), i1 = cell_of(p->x + reach, l->x0, l->g, l->nx);
        int k0 = cell_of(p->z - reach, l->z0, l->g, l->nz), k1 = cell_of(p->z + reach, l->z0, l->g, l->nz);
        for (int k = k0; k <= k1; k++) {
            size_t row = l->cell0 + (size_t)k * l->nx;
            for (uint32_t a = T->cell_start[row + i0]; a < T->cell_start[row + i1 + 1]; a++) {
                const SylEcoPlant *q = local_at(T, T->order[a]);
                double pq = power_of(s, q);
                if (pq < pp || (pq == pp && q->id >= p->id)) continue;
                double dx = (double)q->x - p->x, dz = (double)q->z - p->z, rr = rp + radius_of(s, q);
                if (dx * dx + dz * dz < rr * rr) return true;
            }
        }
    }
    return false;
}

static uint64_t child_id(uint64_t parent, int year, int k) {
    return rng_mix(parent ^ rng_mix(((uint64_t)(unsigned)year << 20) ^ (uint64_t)(unsigned)k ^ 0x5eed000000000000ull));
}

static int poisson(Rng *r, double lambda) {
    if (lambda <= 0) return 0;
    if (lambda > 30) {
        double v = lambda + sqrt(lambda) * rng_normal(r);
        return v < 0 ? 0 : (int)floor(v + 0.5);
    }
    double l = exp(-lambda), p = 1;
    int k = 0;
    do {
        k++;
        p *= rng_unit(r);
    } while (p > l);
    return k - 1;
}

/* Zamuda's per-factor mortality: each factor the species has a curve for, in turn, kills the
 * plant with probability stress_mortality × (1 − its suitability), each from its own stream
 * (his generator of death per factor). The cause of the first that does, or -1. */
static int factor_death(const Sim *s, const SylEcoSpecies *sp, const SylEcoPlant *p) {
    for (int f = 0; f < SYL_TERRAIN_FACTORS; f++) {
        if (!sp->set[f]) continue;
        double v = eco_suitability(sp, f, syl_terrain_factor_at(s->t, (SylTerrainFactor)f, p->x, p->z));
        Rng r = rng_stream(s->seed, (uint64_t)s->year, ECO_RNG_FACTOR + (unsigned)f, p->id);
        if (rng_unit(&r) < sp->stress_mortality * (1 - v)) return syl_ecosystem_death_of((SylTerrainFactor)f);
    }
    return -1;
}

/* A seed (or an arrival) at (x, z): if it germinates (with probability its vigour there, on a
 * cell with data), the seedling is sent to the tile it fell on. The sender decides, as every
 * tile holds the whole terrain: only seedlings travel and wait, not every seed. */
static void send_seed(Sim *s, Tile *T, uint64_t id, int species, double x, double z) {
    const SylTerrain *t = s->t;
    int u = tile_at(s, x, z);
    if (u < 0) return; /* off the terrain */
    SylEcoPlant c = {.id = id, .x = (float)x, .z = (float)z, .species = (uint8_t)species};
    int i = (int)floor((c.x - t->x0) / t->cell), k = (int)floor((c.z - t->z0) / t->cell);
    if (i < 0 || k < 0 || i >= t->nx || k >= t->nz || !t->valid[(size_t)k * t->nx + i]) return;
    double v = syl_ecosystem_vigour(s->m, species, t, c.x, c.z);
    Rng r = rng_stream(s->seed, (uint64_t)s->year, ECO_RNG_GERMINATE, id);
    if (rng_unit(&r) >= v) return;
    c.vigour = (float)v;
    c.height = (float)s->m->species[species].start_height;
    c.cell = (uint32_t)((size_t)k * (size_t)t->nx + (size_t)i);
    if (!buf_push(&T->out[u], &c)) T->failed = 1;
}

/* The memory a tile holds now, beyond the terrain. */
static size_t tile_bytes(const Tile *T, int ntiles) {
    size_t b = (T->own.cap + T->halo.cap) * sizeof(SylEcoPlant) +
               (T->grid_cap + T->order_cap) * sizeof(uint32_t);
    for (int u = 0; u < ntiles; u++) b += (T->out[u].cap + T->border[u].cap) * sizeof(SylEcoPlant);
    return b;
}

static void note_bytes(Tile *T, int ntiles) {
    size_t b = tile_bytes(T, ntiles);
    if (b > T->peak_bytes) T->peak_bytes = b;
}

/* Phase B. */
static void step_tile(Sim *s, int ti) {
    Tile *T = &s->tile[ti];
    const SylEcoModel *m = s->m;
    const SylTerrain *t = s->t;
    int year = s->year;
    /* the halo: what the neighbours posted */
    T->halo.n = 0;
    for (int u = 0; u < s->ntiles; u++) {
        if (u == ti) continue;
        size_t n;
        const SylEcoPlant *h = s->x->take(s->x->ctx, SYL_ECO_HALO, ti, u, &n);
        if (!n) continue;
        if (!buf_reserve(&T->halo, T->halo.n + n)) {
            T->failed = 1;
            return;
        }
        memcpy(T->halo.p + T->halo.n, h, n * sizeof *h);
        T->halo.n += n;
    }
    Grid G;
    if (!build_grid(s, T, &G)) {
        T->failed = 1;
        return;
    }
    /* this year's domination goes in state at once: the search reads no plant's state */
    for (size_t j = 0; j < T->own.n; j++)
        T->own.p[j].state = is_dominated(s, T, &G, &T->own.p[j]) ? SYL_ECO_DOMINATED : SYL_ECO_FREE;
    /* the grid and the halo are done with: not held while the seedlings pile up */
    T->peak_bytes = 0;
    note_bytes(T, s->ntiles);
    free(T->cell_start), free(T->order), buf_free(&T->halo);
    T->cell_start = T->order = NULL;
    T->grid_cap = T->order_cap = 0;
    T->alive_start = T->own.n;
    for (int u = 0; u < s->ntiles; u++) T->out[u].n = 0;
    /* deaths, growth and seeds */
    memset(T->deaths, 0, sizeof T->deaths);
    size_t kept = 0;
    for (size_t j = 0; j < T->own.n; j++) {
        SylEcoPlant p = T->own.p[j];
        const SylEcoSpecies *sp = &m->species[p.species];
        bool dom = p.state == SYL_ECO_DOMINATED;
        Rng life = rng_stream(s->seed, 0, ECO_RNG_LIFE, p.id);
        double lifespan = sp->old_age + (sp->max_age - sp->old_age) * rng_unit(&life);
        double spread = 0.8 + 0.4 * rng_unit(&life); /* the plant's own growth rate, ±20 % */
        p.age = p.age < 65535 ? (uint16_t)(p.age + 1) : p.age;
        uint32_t *died = T->deaths[p.species];
        if (p.age > lifespan) {
            died[SYL_ECO_DEATH_AGE]++;
            continue;
        }
        if (dom) {
            Rng r = rng_stream(s->seed, (uint64_t)year, ECO_RNG_SHADE, p.id);
            if (rng_unit(&r) >= sp->shade_tolerance) {
                died[SYL_ECO_DEATH_DOMINANCE]++;
                continue;
            }
        }
        if (m->mortality == SYL_ECO_PER_FACTOR) {
            int cause = factor_death(s, sp, &p);
            if (cause >= 0) {
                died[cause]++;
                continue;
            }
        } else {
            Rng r = rng_stream(s->seed, (uint64_t)year, ECO_RNG_STRESS, p.id);
            if (rng_unit(&r) < sp->stress_mortality * (1 - p.vigour)) {
                died[SYL_ECO_DEATH_STRESS]++;
                continue;
            }
        }
        if (!dom && p.age <= sp->old_age) {
            double h = p.height + p.vigour * spread * sp->growth_rate * (sp->height_max - p.height);
            p.height = (float)(h < sp->height_max ? h : sp->height_max);
        }
        if (!dom && p.age >= sp->maturity && sp->seeds > 0) {
            Rng q = rng_stream(s->seed, (uint64_t)year, ECO_RNG_SEEDS, p.id);
            int n = (int)floor(sp->seeds * p.vigour + rng_unit(&q));
            for (int k = 0; k < n; k++) {
                double dx = rng_normal(&q) * sp->dispersal, dz = rng_normal(&q) * sp->dispersal;
                if (dx * dx + dz * dz > 9 * sp->dispersal * sp->dispersal) continue; /* the 3σ cutoff */
                send_seed(s, T, child_id(p.id, year, k), p.species, p.x + dx, p.z + dz);
            }
        }
        T->own.p[kept++] = p;
    }
    T->own.n = kept;
    /* random arrivals on the tile's own cells */
    double cell_ha = t->cell * t->cell / 1e4;
    for (int k = T->k0; k < T->k1; k++)
        for (int i = T->i0; i < T->i1; i++) {
            uint64_t cell = (uint64_t)k * (uint64_t)t->nx + (uint64_t)i;
            for (int sp = 0; sp < m->nspecies; sp++) {
                const SylEcoSpecies *S = &m->species[sp];
                if (S->arrivals <= 0 || (S->arrive_until > 0 && year > S->arrive_until)) continue;
                Rng r = rng_stream(s->seed, (uint64_t)year, ECO_RNG_ARRIVE, cell * SYL_ECO_MAX_SPECIES + (uint64_t)sp);
                int n = poisson(&r, S->arrivals * cell_ha);
                for (int a = 0; a < n; a++) {
                    double x = t->x0 + (i + rng_unit(&r)) * t->cell, z = t->z0 + (k + rng_unit(&r)) * t->cell;
                    uint64_t id = rng_mix(rng_mix(cell ^ ((uint64_t)(unsigned)year << 40)) ^
                                          ((uint64_t)sp << 24 | (uint64_t)a) ^ 0xa771a1000000000ull);
                    send_seed(s, T, id, sp, x, z);
                }
            }
        }
    note_bytes(T, s->ntiles);
    for (int u = 0; u < s->ntiles; u++) {
        if (T->out[u].n > 1) qsort(T->out[u].p, T->out[u].n, sizeof *T->out[u].p, by_key);
        s->x->post(s->x->ctx, SYL_ECO_SEEDS, ti, u, T->out[u].p, T->out[u].n);
    }
}

/* Phase C. */
static void settle_tile(Sim *s, int ti) {
    Tile *T = &s->tile[ti];
    /* the seedlings posted to it, each tile's sorted by key */
    int k = 0;
    size_t total = 0;
    for (int u = 0; u < s->ntiles; u++) {
        size_t n;
        const SylEcoPlant *in = s->x->take(s->x->ctx, SYL_ECO_SEEDS, ti, u, &n);
        if (n) T->inbox[k++] = (Inbox){in, n}, total += n;
    }
    /* merge them into the sorted survivors, from the back, in place (an id met twice in a
     * cell — two hashes alike — is kept once) */
    if (!buf_reserve(&T->own, T->own.n + total)) {
        T->failed = 1;
        return;
    }
    size_t a = T->own.n, w = T->own.n + total;
    for (;;) {
        Inbox *b = NULL;
        for (int q = 0; q < k; q++)
            if (T->inbox[q].n && (!b || key_less(&b->p[b->n - 1], &T->inbox[q].p[T->inbox[q].n - 1]))) b = &T->inbox[q];
        if (!b) break;
        const SylEcoPlant *c = &b->p[b->n - 1];
        if (a > 0 && key_less(c, &T->own.p[a - 1])) T->own.p[--w] = T->own.p[--a];
        else if (a > 0 && !key_less(&T->own.p[a - 1], c)) b->n--;
        else T->own.p[--w] = b->p[--b->n];
    }
    if (w > a) { /* duplicates dropped: close the gap */
        memmove(T->own.p + a, T->own.p + w, (T->own.n + total - w) * sizeof *T->own.p);
    }
    T->own.n = a + (T->own.n + total - w);
    note_bytes(T, s->ntiles);
    memset(T->count, 0, sizeof T->count);
    memset(T->area_u, 0, sizeof T->area_u);
    memset(T->height_u, 0, sizeof T->height_u);
    for (size_t j = 0; j < T->own.n; j++) {
        const SylEcoPlant *p = &T->own.p[j];
        double r = radius_of(s, p);
        T->count[p->species]++;
        T->area_u[p->species] += llround(M_PI * r * r * 1e4); /* cm² */
        T->height_u[p->species] += llround(p->height * 1e3); /* mm */
    }
}

static void run_phase(Sim *s, int ti) {
    if (s->phase == 0) post_halo(s, ti);
    else if (s->phase == 1) step_tile(s, ti);
    else settle_tile(s, ti);
}

static void worker(void *arg, int k) {
    (void)k;
    Sim *s = arg;
    for (;;) {
        int ti = __atomic_fetch_add(&s->next, 1, __ATOMIC_RELAXED);
        if (ti >= s->ntiles) return;
        if (!s->x->owns || s->x->owns(s->x->ctx, ti)) run_phase(s, ti); /* another process's tile */
    }
}

static void parallel(Sim *s, int phase, int threads) {
    s->phase = phase;
    s->next = 0;
    int n = threads < s->ntiles ? threads : s->ntiles;
    par_run(n > 64 ? 64 : n, worker, s); /* workers taking tiles in turn; this thread works too */
    s->x->barrier(s->x->ctx);
}

/* The plants of every tile, sorted by id; over processes, on the writing one only (*here
 * false elsewhere). */
static int gather(Sim *s, Buf *all, bool *here) {
    size_t n = 0;
    for (int ti = 0; ti < s->ntiles; ti++) n += s->tile[ti].own.n;
    if (!buf_reserve(all, n)) return SYL_ELIMIT;
    all->n = 0;
    for (int ti = 0; ti < s->ntiles; ti++) {
        if (s->tile[ti].own.n) memcpy(all->p + all->n, s->tile[ti].own.p, s->tile[ti].own.n * sizeof *all->p);
        all->n += s->tile[ti].own.n;
    }
    *here = true;
    if (s->x->gather) {
        SylEcoPlant *p = NULL;
        size_t np = 0;
        if (s->x->gather(s->x->ctx, all->p, all->n, &p, &np)) return SYL_ELIMIT;
        *here = p != NULL;
        free(all->p);
        all->p = p;
        all->n = all->cap = np;
    }
    if (all->n > 1) qsort(all->p, all->n, sizeof *all->p, by_id);
    return SYL_OK;
}

/* A resumed run's plants, each into the tile it stands on. */
static int place_start(Sim *s, const SylEcoOptions *o) {
    for (size_t j = 0; j < o->nstart; j++) {
        const SylEcoPlant *p = &o->start[j];
        int ti = tile_at(s, p->x, p->z);
        if (ti < 0 || p->species >= s->m->nspecies) {
            sink_error(opt_sink(o), "the saved plant %016llx is not on the terrain or of no species", (unsigned long long)p->id);
            return SYL_EMODEL;
        }
        if (s->x->owns && !s->x->owns(s->x->ctx, ti)) continue;
        if (!buf_push(&s->tile[ti].own, p)) return SYL_ELIMIT;
    }
    for (int ti = 0; ti < s->ntiles; ti++) /* a tile keeps (cell, id) order */
        sort_in_place(s->tile[ti].own.p, s->tile[ti].own.n, by_key);
    return SYL_OK;
}

/* Tiles that change process: their plants go to the new owner (SYL_ECO_MOVE). */
static int move_tiles(Sim *s) {
    uint8_t *was = malloc((size_t)s->ntiles);
    if (!was) return SYL_ELIMIT;
    for (int ti = 0; ti < s->ntiles; ti++) {
        Tile *T = &s->tile[ti];
        was[ti] = (uint8_t)s->x->owns(s->x->ctx, ti);
        if (was[ti]) s->x->post(s->x->ctx, SYL_ECO_MOVE, ti, ti, T->own.p, T->own.n);
    }
    s->x->barrier(s->x->ctx);
    int st = SYL_OK;
    for (int ti = 0; ti < s->ntiles; ti++) {
        Tile *T = &s->tile[ti];
        bool now = s->x->owns(s->x->ctx, ti);
        if (now && !was[ti]) {
            size_t n;
            const SylEcoPlant *p = s->x->take(s->x->ctx, SYL_ECO_MOVE, ti, ti, &n);
            if (!buf_reserve(&T->own, n)) st = SYL_ELIMIT;
            else if (n) memcpy(T->own.p, p, n * sizeof *p);
            T->own.n = st ? 0 : n;
        } else if (!now)
            T->own.n = 0;
    }
    free(was);
    return st;
}

static double cpu_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}
static double wall_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

int syl_ecosystem_simulate(const SylEcoModel *m, const SylTerrain *t, const SylEcoOptions *o, SylEcoStats *stats) {
    double w0 = wall_now(), c0 = cpu_now();
    Sim s = {.m = m, .t = t, .seed = o->use_seed ? o->seed : m->seed};
    s.tx = o->tiles_x > 0 ? o->tiles_x : 1;
    s.tz = o->tiles_z > 0 ? o->tiles_z : 1;
    if (s.tx > t->nx || s.tz > t->nz) {
        sink_error(opt_sink(o), "%d x %d tiles on a terrain of %d x %d cells: at most one tile per cell", s.tx, s.tz, t->nx, t->nz);
        return SYL_EUSAGE;
    }
    s.ntiles = s.tx * s.tz;
    int years = o->years > 0 ? o->years : m->years;
    const int *snaps = o->snapshots ? o->snapshots : m->snapshots;
    int nsnaps = o->snapshots ? o->nsnapshots : m->nsnapshots;
    for (int i = 0; i < m->nspecies; i++) {
        double r = 2 * m->species[i].radius_ratio * m->species[i].height_max;
        if (r > s.halo) s.halo = r;
    }
    double longest = 0;
    for (int i = 0; i < m->nspecies; i++)
        if (m->species[i].max_age > longest) longest = m->species[i].max_age;
    for (int i = 0; i < m->nspecies; i++) s.rel_life[i] = m->species[i].max_age / longest;
    int threads = o->threads > 0 ? o->threads : par_threads(0);
    if (threads < 1) threads = 1;
    SylEcoExchange local_ops;
    EcoLocal *local = NULL;
    if (o->exchange) s.x = o->exchange;
    else {
        local = eco_local_new(s.ntiles, &local_ops);
        s.x = &local_ops;
    }
    s.tile = calloc((size_t)s.ntiles, sizeof *s.tile);
    s.tile_of_i = malloc((size_t)t->nx * sizeof(int));
    s.tile_of_k = malloc((size_t)t->nz * sizeof(int));
    int st = SYL_OK;
    if (!s.tile || !s.tile_of_i || !s.tile_of_k || (!o->exchange && !local)) st = SYL_ELIMIT;
    for (int ti = 0; !st && ti < s.ntiles; ti++) {
        Tile *T = &s.tile[ti];
        int a = ti % s.tx, b = ti / s.tx;
        T->i0 = (int)((long)t->nx * a / s.tx);
        T->i1 = (int)((long)t->nx * (a + 1) / s.tx);
        T->k0 = (int)((long)t->nz * b / s.tz);
        T->k1 = (int)((long)t->nz * (b + 1) / s.tz);
        T->x0 = t->x0 + T->i0 * t->cell;
        T->x1 = t->x0 + T->i1 * t->cell;
        T->z0 = t->z0 + T->k0 * t->cell;
        T->z1 = t->z0 + T->k1 * t->cell;
        for (int i = T->i0; i < T->i1; i++) s.tile_of_i[i] = a;
        for (int k = T->k0; k < T->k1; k++) s.tile_of_k[k] = b;
        T->out = calloc((size_t)s.ntiles, sizeof *T->out);
        T->border = calloc((size_t)s.ntiles, sizeof *T->border);
        T->inbox = calloc((size_t)s.ntiles, sizeof *T->inbox);
        if (!T->out || !T->border || !T->inbox) st = SYL_ELIMIT;
        for (int u = 0; !st && u < s.ntiles; u++) T->out[u].mem = T->border[u].mem = o->budget;
        T->own.mem = T->halo.mem = o->budget;
    }
    if (!st) st = place_start(&s, o);
    /* what the processes add up each year: failed, alive, plant-years, bytes, then per species
     * count, area, height, then per tile its plants */
    enum { V_FAILED, V_ALIVE, V_PY, V_BYTES, V_COUNT, V_AREA = V_COUNT + SYL_ECO_MAX_SPECIES,
           V_HEIGHT = V_AREA + SYL_ECO_MAX_SPECIES, V_DEATHS = V_HEIGHT + SYL_ECO_MAX_SPECIES,
           V_TILE = V_DEATHS + SYL_ECO_MAX_SPECIES * SYL_ECO_DEATH_CAUSES };
    size_t nv = V_TILE + (size_t)s.ntiles;
    int64_t *v = calloc(nv, sizeof *v);
    if (!v) st = SYL_ELIMIT;
    Buf all = {0};
    SylEcoYear yr;
    size_t peak = 0, peak_bytes = 0;
    uint64_t plant_years = 0;
    int snap = 0;
    int first = o->start_year > 0 ? o->start_year + 1 : 1;
    while (snap < nsnaps && snaps[snap] < first) snap++; /* year 0 is bare ground; a resumed run's are done */
    for (int y = first; !st && y <= years; y++) {
        s.year = y;
        for (int ph = 0; ph < 3; ph++) parallel(&s, ph, threads);
        memset(&yr, 0, sizeof yr);
        yr.year = y;
        memset(v, 0, nv * sizeof *v);
        for (int ti = 0; ti < s.ntiles; ti++) {
            Tile *T = &s.tile[ti];
            if (s.x->owns && !s.x->owns(s.x->ctx, ti)) continue;
            if (T->failed) v[V_FAILED] = 1;
            v[V_PY] += (int64_t)T->alive_start;
            v[V_ALIVE] += (int64_t)T->own.n;
            v[V_BYTES] += (int64_t)T->peak_bytes;
            v[V_TILE + ti] = (int64_t)T->own.n;
            for (int sp = 0; sp < m->nspecies; sp++) {
                v[V_COUNT + sp] += T->count[sp];
                v[V_AREA + sp] += T->area_u[sp];
                v[V_HEIGHT + sp] += T->height_u[sp];
                for (int c = 0; c < SYL_ECO_DEATH_CAUSES; c++)
                    v[V_DEATHS + sp * SYL_ECO_DEATH_CAUSES + c] += T->deaths[sp][c];
            }
        }
        if (s.x->sum) s.x->sum(s.x->ctx, v, nv);
        if (v[V_FAILED]) {
            if (!o->budget) sink_error(opt_sink(o), "year %d: out of memory", y);
            else /* the buffers ran past the budget (or malloc failed) */
                sink_error(opt_sink(o),
                        "year %d: the plants need more memory than --max-memory allows (%llu MB in "
                        "all); raise the limit with --max-memory",
                        y, (unsigned long long)budget_limit_mb(o->budget));
            st = SYL_ELIMIT;
        }
        plant_years += (uint64_t)v[V_PY];
        size_t alive = (size_t)v[V_ALIVE], bytes = (size_t)v[V_BYTES];
        const int64_t *area = v + V_AREA, *height = v + V_HEIGHT;
        for (int sp = 0; sp < m->nspecies; sp++) {
            yr.count[sp] = (uint32_t)v[V_COUNT + sp];
            for (int c = 0; c < SYL_ECO_DEATH_CAUSES; c++)
                yr.deaths[sp][c] = (uint32_t)v[V_DEATHS + sp * SYL_ECO_DEATH_CAUSES + c];
        }
        if (!st && o->max_plants && alive > o->max_plants) {
            sink_error(opt_sink(o), "year %d: %zu plants, more than the limit of %llu; raise it with --max-plants", y, alive,
                        (unsigned long long)o->max_plants);
            st = SYL_ELIMIT;
        }
        if (st) break;
        /* the seedlings have settled: their buffers are not held until next year's seeds */
        for (int ti = 0; ti < s.ntiles; ti++)
            for (int u = 0; u < s.ntiles; u++) buf_free(&s.tile[ti].out[u]);
        double terrain_area = (double)t->nx * t->nz * t->cell * t->cell;
        for (int sp = 0; sp < m->nspecies; sp++) {
            yr.cover[sp] = (double)area[sp] * 1e-4 / terrain_area;
            yr.mean_height[sp] = yr.count[sp] ? (double)height[sp] * 1e-3 / yr.count[sp] : 0;
        }
        if (alive > peak) peak = alive;
        if (alive && alive >= peak) peak_bytes = bytes;
        if (o->on_year) o->on_year(o->user, &yr);
        bool checkpoint = o->every > 0 && o->on_checkpoint && y % o->every == 0 && y < years;
        if (checkpoint || (snap < nsnaps && snaps[snap] == y)) {
            bool here = true, one = s.ntiles == 1 && !s.x->gather; /* one tile in one process */
            Buf *own = &s.tile[0].own;
            if (one) { /* sorted by id in place, and back: no copy */
                sort_in_place(own->p, own->n, by_id);
                all = *own;
            } else st = gather(&s, &all, &here);
            while (!st && snap < nsnaps && snaps[snap] == y) {
                if (here && o->on_snapshot) st = o->on_snapshot(o->user, y, all.p, all.n);
                snap++;
            }
            if (!st && here && checkpoint) st = o->on_checkpoint(o->user, y, all.p, all.n);
            if (one) sort_in_place(own->p, own->n, by_key);
            else free(all.p); /* not held between snapshots */
            all = (Buf){0};
            if (s.x->sum) { /* the writer's status is every process's */
                int64_t e = st;
                s.x->sum(s.x->ctx, &e, 1);
                st = (int)e;
            }
        }
        if (!st && s.x->rebalance && s.x->rebalance(s.x->ctx, y, v + V_TILE, s.ntiles)) st = move_tiles(&s);
        if (o->progress) o->progress(o->user, (double)y / years);
    }
    if (stats) {
        stats->plant_years = plant_years;
        stats->peak_plants = peak;
        stats->bytes_per_plant = peak ? peak_bytes / peak : 0;
        stats->seconds = wall_now() - w0;
        stats->cpu_seconds = cpu_now() - c0;
    }
    for (int ti = 0; s.tile && ti < s.ntiles; ti++) {
        Tile *T = &s.tile[ti];
        buf_free(&T->own), buf_free(&T->halo), free(T->inbox);
        for (int u = 0; T->out && u < s.ntiles; u++) buf_free(&T->out[u]);
        for (int u = 0; T->border && u < s.ntiles; u++) buf_free(&T->border[u]);
        free(T->out), free(T->border), free(T->cell_start), free(T->order);
    }
    free(all.p);
    free(v);
    free(s.tile), free(s.tile_of_i), free(s.tile_of_k);
    eco_local_free(local);
    return st;
}
