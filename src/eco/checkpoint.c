/* Checkpoints of an ecosystem run (docs/distributed.md, "Checkpoints"): a 64-byte header
 * (magic, version, the size of a plant record, the model's hash, the year, the plant count),
 * the years' counts so far, the plants sorted by id as the bytes of SylEcoPlant, and a hash
 * of all that. The state is the plants alone: every random draw is keyed by (seed, year,
 * plant id, purpose), so nothing else needs saving. Little-endian, as the machines MPI runs on. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "eco/eco.h"
#include "util/file.h"
#include "util/diag.h"
#include "util/outfile.h"
#include "util/rng.h"

enum { CK_VERSION = 1, CK_HEADER = 64, CK_YEAR = 4 + SYL_ECO_MAX_SPECIES * (4 + 8 + 8) };
static const char ck_magic[8] = "SYLVAECK";

typedef struct Hash {
    uint64_t h, word;
    unsigned fill;
} Hash;

/* Word by word through splitmix64: fast enough for 10 M plants in well under a second. The
 * same bytes give the same hash however they are cut into calls. */
static void hash_byte(Hash *h, uint8_t v) {
    h->word |= (uint64_t)v << (8 * h->fill);
    if (++h->fill == 8) {
        h->h = rng_mix(h->h ^ h->word);
        h->word = 0;
        h->fill = 0;
    }
}
static void hash_bytes(Hash *h, const void *p, size_t n) {
    const uint8_t *b = p;
    size_t i = 0;
    for (; i < n && h->fill; i++) hash_byte(h, b[i]);
    for (; i + 8 <= n; i += 8) {
        uint64_t w;
        memcpy(&w, b + i, 8);
        h->h = rng_mix(h->h ^ w);
    }
    for (; i < n; i++) hash_byte(h, b[i]);
}
static uint64_t hash_end(Hash *h) { return rng_mix(h->h ^ h->word ^ ((uint64_t)h->fill << 56)); }

static void mix_double(uint64_t *h, double v) {
    uint64_t w;
    memcpy(&w, &v, sizeof w);
    *h = rng_mix(*h ^ w);
}

uint64_t syl_ecosystem_hash(const SylEcoModel *m, const SylTerrain *t, uint64_t seed) {
    uint64_t h = rng_mix(seed ^ 0xec05757e3ull);
    h = rng_mix(h ^ (uint64_t)m->nspecies ^ (uint64_t)m->combine << 8);
    mix_double(&h, m->cell), mix_double(&h, m->height_lo), mix_double(&h, m->height_hi);
    mix_double(&h, m->latitude);
    for (int s = 0; s < m->nspecies; s++) {
        const SylEcoSpecies *S = &m->species[s];
        const double v[] = {S->maturity,    S->old_age,    S->max_age,         S->height_max,      S->growth_rate,
                            S->start_height, S->radius_ratio, S->seeds,         S->dispersal,       S->arrivals,
                            S->arrive_until, S->shade_tolerance, S->stress_mortality};
        for (size_t i = 0; i < sizeof v / sizeof *v; i++) mix_double(&h, v[i]);
        for (int f = 0; f <= SYL_TERRAIN_WIND; f++) { /* the GIS factors, as before Zamuda's */
            mix_double(&h, S->set[f] ? S->optimum[f] : 0), mix_double(&h, S->set[f] ? S->range[f] : 0);
            mix_double(&h, S->set[f] ? S->falloff[f] : 0);
        }
    }
    /* what later versions added, mixed only when not the default: older checkpoints still match */
    if (m->measures || m->mortality) h = rng_mix(h ^ (uint64_t)m->measures << 1 ^ (uint64_t)m->mortality << 9 ^ 0x2a3da);
    if (m->wind_set) mix_double(&h, m->wind_from);
    for (int s = 0; s < m->nspecies; s++)
        for (int f = SYL_TERRAIN_WIND + 1; f < SYL_TERRAIN_FACTORS; f++) {
            const SylEcoSpecies *S = &m->species[s];
            if (S->set[f]) mix_double(&h, S->optimum[f]), mix_double(&h, S->range[f]), mix_double(&h, S->falloff[f]);
        }
    h = rng_mix(h ^ (uint64_t)(unsigned)t->nx << 32 ^ (uint64_t)(unsigned)t->nz);
    mix_double(&h, t->cell), mix_double(&h, t->x0), mix_double(&h, t->z0);
    Hash d = {.h = h};
    hash_bytes(&d, t->height, (size_t)t->nx * t->nz * sizeof *t->height);
    hash_bytes(&d, t->valid, (size_t)t->nx * t->nz);
    return hash_end(&d);
}

static void put32(uint8_t *p, uint32_t v) { memcpy(p, &v, 4); }
static void put64(uint8_t *p, uint64_t v) { memcpy(p, &v, 8); }
static uint32_t get32(const uint8_t *p) {
    uint32_t v;
    memcpy(&v, p, 4);
    return v;
}
static uint64_t get64(const uint8_t *p) {
    uint64_t v;
    memcpy(&v, p, 8);
    return v;
}

static void year_bytes(uint8_t *b, const SylEcoYear *y) {
    put32(b, (uint32_t)y->year);
    for (int s = 0; s < SYL_ECO_MAX_SPECIES; s++) {
        put32(b + 4 + 4 * s, y->count[s]);
        memcpy(b + 4 + 4 * SYL_ECO_MAX_SPECIES + 8 * s, &y->cover[s], 8);
        memcpy(b + 4 + 12 * SYL_ECO_MAX_SPECIES + 8 * s, &y->mean_height[s], 8);
    }
}

static void emit(FILE *f, Hash *h, const void *p, size_t n) {
    hash_bytes(h, p, n);
    fwrite(p, 1, n, f);
}

int syl_ecosystem_checkpoint_write(const char *path, const SylEcoCheckpoint *c, const SylSink *sink) {
    OutFile o;
    if (!outfile_open(&o, path, NULL, sink)) return SYL_EIO;
    uint8_t head[CK_HEADER] = {0}, yb[CK_YEAR];
    memcpy(head, ck_magic, 8);
    put32(head + 8, CK_VERSION);
    put32(head + 12, (uint32_t)sizeof(SylEcoPlant));
    put64(head + 16, c->model_hash);
    put32(head + 24, (uint32_t)c->year);
    put64(head + 32, (uint64_t)c->nplants);
    Hash h = {0};
    emit(o.f, &h, head, sizeof head);
    for (int y = 0; y < c->year; y++) {
        year_bytes(yb, &c->years[y]);
        emit(o.f, &h, yb, sizeof yb);
    }
    emit(o.f, &h, c->plants, c->nplants * sizeof *c->plants);
    uint8_t tail[8];
    put64(tail, hash_end(&h));
    fwrite(tail, 1, 8, o.f);
    return outfile_close(&o, true, sink) ? SYL_OK : SYL_EIO;
}

static int bad(const SylSink *sink, const char *name, const char *what) {
    sink_error(sink, "checkpoint '%s': %s", name, what);
    return SYL_EMODEL;
}

int syl_ecosystem_checkpoint_parse(const void *buf, size_t len, const char *name, SylEcoCheckpoint *c, const SylSink *sink) {
    const uint8_t *b = buf;
    memset(c, 0, sizeof *c);
    char what[160];
    if (len < 8 || memcmp(b, ck_magic, 8)) return bad(sink, name, "not a Sylva ecosystem checkpoint");
    if (len < CK_HEADER + 8) return bad(sink, name, "truncated");
    if (get32(b + 8) != CK_VERSION) return bad(sink, name, "written by another version of Sylva");
    if (get32(b + 12) != sizeof(SylEcoPlant)) {
        snprintf(what, sizeof what, "plants of %u bytes, not this build's %zu", get32(b + 12), sizeof(SylEcoPlant));
        return bad(sink, name, what);
    }
    uint32_t year = get32(b + 24);
    uint64_t n = get64(b + 32);
    if (year < 1 || year > 60000) return bad(sink, name, "a year out of 1 .. 60000");
    uint64_t body = len - CK_HEADER - 8 - (uint64_t)year * CK_YEAR;
    if ((uint64_t)year * CK_YEAR > len - CK_HEADER - 8 || n > body / sizeof(SylEcoPlant) ||
        body != n * sizeof(SylEcoPlant)) {
        snprintf(what, sizeof what, "%zu bytes, not the %llu its header says (truncated?)", len,
                 (unsigned long long)(CK_HEADER + 8 + (uint64_t)year * CK_YEAR + n * sizeof(SylEcoPlant)));
        return bad(sink, name, what);
    }
    c->model_hash = get64(b + 16);
    c->year = (int)year;
    c->nplants = (size_t)n;
    c->years = calloc(year, sizeof *c->years); /* deaths by cause are not kept: 0 */
    c->plants = malloc((n ? n : 1) * sizeof *c->plants);
    if (!c->years || !c->plants) {
        syl_ecosystem_checkpoint_free(c);
        return SYL_ELIMIT;
    }
    const uint8_t *p = b + CK_HEADER;
    int st = SYL_OK;
    for (uint32_t y = 0; !st && y < year; y++, p += CK_YEAR) {
        SylEcoYear *Y = &c->years[y];
        Y->year = (int)get32(p);
        for (int s = 0; s < SYL_ECO_MAX_SPECIES; s++) {
            Y->count[s] = get32(p + 4 + 4 * s);
            memcpy(&Y->cover[s], p + 4 + 4 * SYL_ECO_MAX_SPECIES + 8 * s, 8);
            memcpy(&Y->mean_height[s], p + 4 + 12 * SYL_ECO_MAX_SPECIES + 8 * s, 8);
            if (!isfinite(Y->cover[s]) || !isfinite(Y->mean_height[s])) st = SYL_EMODEL;
        }
        if (Y->year != (int)y + 1 || st) {
            snprintf(what, sizeof what, "the counts of year %u are damaged", y + 1);
            st = bad(sink, name, what);
        }
    }
    if (!st && n) memcpy(c->plants, p, n * sizeof *c->plants);
    for (size_t j = 0; !st && j < n; j++) {
        const SylEcoPlant *q = &c->plants[j];
        if ((j && q->id <= c->plants[j - 1].id) || q->species >= SYL_ECO_MAX_SPECIES || q->state > SYL_ECO_DOMINATED ||
            !isfinite(q->x) || !isfinite(q->z) || !(q->height > 0 && q->height <= 1000) ||
            !(q->vigour >= 0 && q->vigour <= 1)) {
            snprintf(what, sizeof what, "plant %zu of %llu is damaged", j + 1, (unsigned long long)n);
            st = bad(sink, name, what);
        }
    }
    if (!st) {
        Hash h = {0};
        hash_bytes(&h, b, len - 8);
        if (hash_end(&h) != get64(b + len - 8)) st = bad(sink, name, "its checksum does not match: the file is damaged");
    }
    if (st) syl_ecosystem_checkpoint_free(c);
    return st;
}

int syl_ecosystem_checkpoint_check(const SylEcoCheckpoint *c, const SylEcoModel *m, const SylTerrain *t, const char *name,
                                   const SylSink *sink) {
    char what[256];
    for (size_t j = 0; j < c->nplants; j++) {
        const SylEcoPlant *q = &c->plants[j];
        const char *why = NULL;
        double i = floor((q->x - t->x0) / t->cell), k = floor((q->z - t->z0) / t->cell); /* as the simulation places it */
        const SylEcoSpecies *s = q->species < m->nspecies ? &m->species[q->species] : NULL;
        if (!s) why = "a species the block does not have";
        else if (!(i >= 0 && k >= 0 && i < t->nx && k < t->nz)) why = "off the terrain";
        else if (!t->valid[(size_t)k * (size_t)t->nx + (size_t)i]) why = "on a cell the DEM has no data for";
        else if (q->cell != (uint32_t)((size_t)k * (size_t)t->nx + (size_t)i)) why = "its cell is not the one it stands on";
        else if (q->height > (float)s->height_max * (1 + 1e-6f)) why = "taller than its species' height_max";
        else if (q->age > s->max_age || q->age > c->year) why = "older than its species' max_age or the run";
        if (!why) continue;
        snprintf(what, sizeof what, "plant %zu of %zu (id %016llx) is %s: not a state the simulation makes", j + 1,
                 c->nplants, (unsigned long long)q->id, why);
        return bad(sink, name, what);
    }
    return SYL_OK;
}

int syl_ecosystem_checkpoint_read(const char *path, SylEcoCheckpoint *c, const SylSink *sink) {
    memset(c, 0, sizeof *c);
    /* a regular file only (O_NONBLOCK: a FIFO without a writer would wait for one), mapped,
     * not copied (10 M plants: 320 MB read once) */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    struct stat sb;
    int err = fd < 0                    ? errno
              : fstat(fd, &sb)          ? errno
              : S_ISDIR(sb.st_mode)     ? EISDIR
              : !S_ISREG(sb.st_mode)    ? FILE_ENOTREG
              : (uint64_t)sb.st_size > SIZE_MAX / 2 ? EFBIG : 0;
    void *map = NULL;
    size_t size = err ? 0 : (size_t)sb.st_size;
    if (!err && size && (map = mmap(NULL, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0)) == MAP_FAILED)
        err = errno;
    if (fd >= 0) close(fd);
    if (err) {
        sink_error(sink, "cannot read the checkpoint '%s': %s", path, file_strerror(err));
        return err == ENOMEM ? SYL_ELIMIT : SYL_EIO;
    }
    int st = syl_ecosystem_checkpoint_parse(map ? map : (const void *)"", size, path, c, sink);
    if (map) munmap(map, size);
    return st;
}

void syl_ecosystem_checkpoint_free(SylEcoCheckpoint *c) {
    free(c->years);
    free(c->plants);
    c->years = NULL;
    c->plants = NULL;
    c->nplants = 0;
}
