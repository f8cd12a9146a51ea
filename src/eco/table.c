/* plants-YEAR.csv, the plant table of a snapshot: its one writer and its strict reader. x, z
 * and height are written with as many decimals as it takes to read back the same float, so a
 * table read back places every plant where the simulation had it (the same picture). */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/ecosystem.h"
#include "util/closest.h"
#include "util/diag.h"
#include "util/file.h"
#include "util/number.h"

const char syl_ecosystem_table_header[] = "id,species,x,y,z,age,height,radius,vigour,state";

/* The fewest decimals (at least 3) that read back as v; %.9g past 12 (tiny values). */
static void put_float(FILE *f, float v) {
    char buf[64];
    for (int d = 3; d <= 12; d++) {
        snprintf(buf, sizeof buf, "%.*f", d, (double)v);
        if (strtof(buf, NULL) == v) {
            fputs(buf, f);
            return;
        }
    }
    fprintf(f, "%.9g", (double)v);
}

void syl_ecosystem_write_csv_text(FILE *f, const char *s) {
    if (!s[strcspn(s, ",\"\r\n")]) {
        fputs(s, f);
        return;
    }
    fputc('"', f); /* RFC 4180: quoted, a quote doubled */
    for (; *s; s++) {
        if (*s == '"') fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

void syl_ecosystem_table_write_row(FILE *f, const SylEcoModel *m, const SylTerrain *t, const SylEcoPlant *p) {
    const SylEcoSpecies *s = &m->species[p->species];
    fprintf(f, "%016llx,", (unsigned long long)p->id);
    syl_ecosystem_write_csv_text(f, s->name);
    fputc(',', f);
    put_float(f, p->x);
    fprintf(f, ",%.3f,", syl_terrain_factor_at(t, SYL_TERRAIN_ALTITUDE, p->x, p->z));
    put_float(f, p->z);
    fprintf(f, ",%u,", p->age);
    put_float(f, p->height);
    fprintf(f, ",%.3f,%.4f,%s\n", s->radius_ratio * p->height, p->vigour,
            p->state == SYL_ECO_DOMINATED ? "dominated" : "free");
}

enum { F_ID, F_SPECIES, F_X, F_Y, F_Z, F_AGE, F_HEIGHT, F_RADIUS, F_VIGOUR, F_STATE, NFIELDS };

typedef struct Reader {
    const SylEcoModel *m;
    const SylTerrain *t;
    Diag d;
    int line;
} Reader;

static SylLoc at(const Reader *r, const char *line, const char *s, size_t n) {
    int c = (int)(s - line) + 1;
    return (SylLoc){r->line, c, r->line, n ? c + (int)n - 1 : c};
}

/* A whole field as a finite number, unsigned as the writer writes it. */
static bool number(const char *s, size_t n, double *out) { return n && s[0] != '+' && number_read(s, n, out); }

static bool hex_id(const char *s, size_t n, uint64_t *out) {
    if (n == 0 || n > 16) return false;
    uint64_t v = 0;
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0) return false;
        v = v << 4 | (uint64_t)d;
    }
    *out = v;
    return true;
}

/* s[0..n): a field's text, within quotes when quoted (a quote there is doubled) */
static int species_named(const SylEcoModel *m, const char *s, size_t n, bool quoted) {
    for (int k = 0; k < m->nspecies; k++) {
        const char *name = m->species[k].name;
        size_t i = 0;
        for (; i < n && *name == s[i]; name++, i++)
            if (quoted && s[i] == '"') i++; /* the second of the pair */
        if (i == n && !*name) return k;
    }
    return -1;
}

static int cell_of(double v, double v0, double g, int n) {
    double c = floor((v - v0) / g);
    return c < 0 ? 0 : c >= n ? n - 1 : (int)c;
}

/* One row (line[0..len), no newline) into *p; false when reported. */
static bool row(Reader *r, const char *line, size_t len, uint64_t last_id, bool first, SylEcoPlant *p) {
    const char *f[NFIELDS];
    size_t n[NFIELDS];
    bool quoted[NFIELDS];
    const char *s = line, *end = line + len;
    int k = 0;
    for (;; k++) {
        if (k == NFIELDS) {
            diag_error(&r->d, at(r, line, s, (size_t)(end - s)), "a row has %d fields (%s); this one has more", NFIELDS,
                       syl_ecosystem_table_header);
            return false;
        }
        const char *c;
        quoted[k] = s < end && *s == '"'; /* RFC 4180: "a, b" with a quote doubled */
        if (quoted[k]) {
            const char *e = s + 1;
            while (e < end && (*e != '"' || (e + 1 < end && e[1] == '"'))) e += *e == '"' ? 2 : 1;
            if (e >= end || (e + 1 < end && e[1] != ',')) {
                diag_error(&r->d, at(r, line, s, (size_t)(end - s)), "a quoted field that does not end with a quote before a comma");
                return false;
            }
            f[k] = s + 1, n[k] = (size_t)(e - s - 1);
            c = e + 1 < end ? e + 1 : NULL;
        } else {
            c = memchr(s, ',', (size_t)(end - s));
            f[k] = s, n[k] = (size_t)((c ? c : end) - s);
        }
        if (!c) break;
        s = c + 1;
    }
    if (k + 1 < NFIELDS) {
        diag_error(&r->d, at(r, line, end, 0), "a row has %d fields (%s); this one has %d", NFIELDS,
                   syl_ecosystem_table_header, k + 1);
        return false;
    }
    char q[64];
    double v[NFIELDS] = {0};
    static const int numeric[] = {F_X, F_Y, F_Z, F_AGE, F_HEIGHT, F_RADIUS, F_VIGOUR};
    static const char *const names[NFIELDS] = {"id", "species", "x", "y", "z", "age", "height", "radius", "vigour", "state"};
    for (size_t j = 0; j < sizeof numeric / sizeof *numeric; j++) {
        int i = numeric[j];
        if (!number(f[i], n[i], &v[i])) {
            diag_error(&r->d, at(r, line, f[i], n[i]), "the %s '%s' is not a number", names[i],
                       diag_quote(q, sizeof q, f[i], n[i]));
            return false;
        }
    }
    uint64_t id;
    if (!hex_id(f[F_ID], n[F_ID], &id)) {
        diag_error(&r->d, at(r, line, f[F_ID], n[F_ID]), "the id '%s' is not a hexadecimal number of 1 to 16 digits",
                   diag_quote(q, sizeof q, f[F_ID], n[F_ID]));
        return false;
    }
    if (!first && id <= last_id) {
        diag_error(&r->d, at(r, line, f[F_ID], n[F_ID]),
                   "the id %016llx is not above the row before's (%016llx): the rows go by increasing id, each plant once",
                   (unsigned long long)id, (unsigned long long)last_id);
        return false;
    }
    int sp = species_named(r->m, f[F_SPECIES], n[F_SPECIES], quoted[F_SPECIES]);
    if (sp < 0) {
        char near[256], name[64];
        const char *known[SYL_ECO_MAX_SPECIES];
        for (int i = 0; i < r->m->nspecies; i++) known[i] = r->m->species[i].name;
        diag_quote(name, sizeof name, f[F_SPECIES], n[F_SPECIES]);
        bool hint = closest_list(name, known, r->m->nspecies, near, sizeof near) > 0;
        diag_error(&r->d, at(r, line, f[F_SPECIES], n[F_SPECIES]), "no species '%s' in the ecosystem block%s%s%s", name,
                   hint ? " (did you mean " : "", hint ? near : "", hint ? "?)" : "");
        return false;
    }
    const SylTerrain *t = r->t;
    double x1 = t->x0 + t->nx * t->cell, z1 = t->z0 + t->nz * t->cell;
    for (int i = F_X; i <= F_Z; i += 2) {
        double lo = i == F_X ? t->x0 : t->z0, hi = i == F_X ? x1 : z1;
        if (v[i] < lo || v[i] > hi) {
            diag_error(&r->d, at(r, line, f[i], n[i]), "%s %g is off the terrain, which spans %s %g to %g", names[i], v[i],
                       names[i], lo, hi);
            return false;
        }
    }
    if (v[F_AGE] != floor(v[F_AGE]) || v[F_AGE] < 0 || v[F_AGE] > 65535) {
        diag_error(&r->d, at(r, line, f[F_AGE], n[F_AGE]), "the age must be a whole number of years from 0 to 65535");
        return false;
    }
    if (v[F_HEIGHT] < 0 || v[F_HEIGHT] > 1e6) {
        diag_error(&r->d, at(r, line, f[F_HEIGHT], n[F_HEIGHT]), "the height must be from 0 to 1000000 metres");
        return false;
    }
    if (v[F_VIGOUR] < 0 || v[F_VIGOUR] > 1) {
        diag_error(&r->d, at(r, line, f[F_VIGOUR], n[F_VIGOUR]), "the vigour must be from 0 to 1");
        return false;
    }
    bool dominated = n[F_STATE] == 9 && !memcmp(f[F_STATE], "dominated", 9);
    if (!dominated && !(n[F_STATE] == 4 && !memcmp(f[F_STATE], "free", 4))) {
        diag_error(&r->d, at(r, line, f[F_STATE], n[F_STATE]), "the state '%s' is neither free nor dominated",
                   diag_quote(q, sizeof q, f[F_STATE], n[F_STATE]));
        return false;
    }
    *p = (SylEcoPlant){.id = id, .x = (float)v[F_X], .z = (float)v[F_Z], .height = (float)v[F_HEIGHT],
                       .vigour = (float)v[F_VIGOUR], .age = (uint16_t)v[F_AGE], .species = (uint8_t)sp,
                       .state = dominated ? SYL_ECO_DOMINATED : SYL_ECO_FREE};
    p->cell = (uint32_t)((size_t)cell_of(p->z, t->z0, t->cell, t->nz) * (size_t)t->nx +
                         (size_t)cell_of(p->x, t->x0, t->cell, t->nx));
    return true;
}

int syl_ecosystem_table_parse(const char *text, size_t len, const char *name, const SylEcoModel *m,
                              const SylTerrain *t, SylEcoPlant **plants, size_t *nplants, const SylSink *sink) {
    *plants = NULL;
    *nplants = 0;
    Source src = {name, text, len};
    Reader r = {.m = m, .t = t, .d = {.sink = sink, .src = &src, .max_shown = 1}, .line = 1};
    SylEcoPlant *v = NULL;
    size_t n = 0, cap = 0;
    uint64_t last = 0;
    for (const char *s = text, *end = text + len; s < end; r.line++) {
        const char *nl = memchr(s, '\n', (size_t)(end - s));
        size_t l = (size_t)((nl ? nl : end) - s);
        if (l && s[l - 1] == '\r') l--; /* a table saved with CRLF line ends */
        const char *z = memchr(s, 0, l);
        if (z) {
            diag_error(&r.d, at(&r, s, z, 1), "a NUL byte: this is not a plant table");
            goto bad;
        }
        if (r.line == 1) {
            if (l != strlen(syl_ecosystem_table_header) || memcmp(s, syl_ecosystem_table_header, l)) {
                diag_error(&r.d, at(&r, s, s, l), "the first line of a plant table is '%s'", syl_ecosystem_table_header);
                goto bad;
            }
        } else if (!l) {
            diag_error(&r.d, at(&r, s, s, 0), "an empty row");
            goto bad;
        } else {
            if (n == cap) {
                size_t nc = cap ? 2 * cap : 1024;
                SylEcoPlant *g = realloc(v, nc * sizeof *g);
                if (!g) {
                    sink_error(sink, "out of memory reading '%s'", name);
                    free(v);
                    return SYL_ELIMIT;
                }
                v = g, cap = nc;
            }
            if (!row(&r, s, l, last, n == 0, &v[n])) goto bad;
            last = v[n++].id;
        }
        if (!nl) break;
        s = nl + 1;
    }
    if (r.line == 1 && len == 0) {
        diag_error(&r.d, ((SylLoc){1, 1, 1, 1}), "an empty file: the first line of a plant table is '%s'",
                   syl_ecosystem_table_header);
        goto bad;
    }
    *plants = v;
    *nplants = n;
    return SYL_OK;
bad:
    free(v);
    return SYL_EMODEL;
}

int syl_ecosystem_table_read(const char *path, const SylEcoModel *m, const SylTerrain *t, SylEcoPlant **plants,
                             size_t *nplants, const SylSink *sink) {
    *plants = NULL;
    *nplants = 0;
    size_t len;
    char *text = file_read(path, &len);
    if (!text) {
        int e = errno; /* before the message, which may change it */
        sink_error(sink, "cannot read the plant table '%s': %s", path, strerror(e));
        return e == ENOMEM ? SYL_ELIMIT : SYL_EIO;
    }
    int st = syl_ecosystem_table_parse(text, len, path, m, t, plants, nplants, sink);
    free(text);
    return st;
}
