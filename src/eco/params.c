/* Reading an `ecosystem` block's directives: the block's own lines, then after each
 * `species NAME` line the lines of that species (docs/ecosystem.md). The schema's reader of
 * lines (lang/schema_lines.c) reads them, its groups the species; what is the ecosystem's is
 * here: where each value is kept, the rows it reads itself, its messages' words, its checks. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "sylva/ecosystem.h"
#include "lang/program.h"
#include "lang/schema.h"
#include "util/closest.h"

typedef struct NumInfo {
    const char *name;
    size_t offset;   /* in SylEcoSpecies */
    double lo, hi, def;
    const char *what;
} NumInfo;

#define SP(f) offsetof(SylEcoSpecies, f)
static const NumInfo species_nums[] = {
#define ECO_S(f, nm, lo, hi, d, unit, mean) {nm, SP(f), lo, hi, d, unit},
#include "params.def"
};
enum { NNUMS = sizeof species_nums / sizeof species_nums[0] };
static const char *const block_words[] = {
#define ECO_B(at, f, nm, ...) nm,
#include "params.def"
};
enum { NBLOCK = sizeof block_words / sizeof block_words[0] };

#define number_of sch_number

/* The factor a directive names, or -1 (flow has no curve: wetness is its ecological form). */
static int factor_named(const char *s) {
    for (int f = 0; f < SYL_TERRAIN_FACTORS; f++)
        if (f != SYL_TERRAIN_FLOW && !strcmp(s, syl_terrain_factor_name((SylTerrainFactor)f))) return f;
    return -1;
}

static int number(const SylProgram *p, const SylSink *sink, const SylDirective *d, int i, double lo, double hi,
                  bool whole, double *out) {
    if (i >= d->nargs) {
        directive_error_to(p, sink, d, NULL, "%s needs %s value", d->name, i ? "another" : "a");
        return 1;
    }
    const SylDirArg *a = &d->args[i];
    double x;
    if (!number_of(a, &x)) {
        directive_error_to(p, sink, d, a, "%s takes a number", d->name);
        return 1;
    }
    if (isnan(x) || x < lo || x > hi) {
        directive_error_to(p, sink, d, a, "%s must be in [%g, %g], not %g", d->name, lo, hi, x);
        return 1;
    }
    if (whole && x != floor(x)) {
        directive_error_to(p, sink, d, a, "%s takes a whole number, not %g", d->name, x);
        return 1;
    }
    *out = x;
    return 0;
}

static int arity(const SylProgram *p, const SylSink *sink, const SylDirective *d, int lo, int hi) {
    if (d->nargs >= lo && d->nargs <= hi) return 0;
    const SylDirArg *a = d->nargs > hi ? &d->args[hi] : NULL;
    if (lo == hi) directive_error_to(p, sink, d, a, "%s takes %d value%s", d->name, lo, lo == 1 ? "" : "s");
    else if (hi == 3) directive_error_to(p, sink, d, a, "%s takes an optimum, a range and maybe a falloff", d->name);
    else directive_error_to(p, sink, d, a, "%s takes %d to %d values", d->name, lo, hi);
    return 1;
}

static void species_default(SylEcoSpecies *s) {
    memset(s, 0, sizeof *s);
    for (int i = 0; i < NNUMS; i++) *(double *)((char *)s + species_nums[i].offset) = species_nums[i].def;
}

static int read_terrain(const SylProgram *p, const SylSink *sink, const SylDirective *d, SylEcoModel *m) {
    if (!d->nargs || (d->args[0].kind != SYL_DARG_STRING && d->args[0].kind != SYL_DARG_WORD)) {
        directive_error_to(p, sink, d, d->nargs ? &d->args[0] : NULL, "terrain takes a file name, e.g. terrain \"valley.png\"");
        return 1;
    }
    snprintf(m->terrain, sizeof m->terrain, "%s", d->args[0].text);
    int errors = 0;
    for (int i = 1; i < d->nargs && !errors;) {
        const SylDirArg *a = &d->args[i];
        if (a->kind == SYL_DARG_WORD && !strcmp(a->text, "cell")) {
            errors += number(p, sink, d, i + 1, 1e-6, 1e6, false, &m->cell);
            i += 2;
        } else if (a->kind == SYL_DARG_WORD && !strcmp(a->text, "heights")) {
            errors += number(p, sink, d, i + 1, -1e6, 1e6, false, &m->height_lo);
            if (!errors) errors += number(p, sink, d, i + 2, -1e6, 1e6, false, &m->height_hi);
            if (!errors && m->height_hi <= m->height_lo) {
                directive_error_to(p, sink, d, &d->args[i + 2], "the height of white must be above that of black");
                errors++;
            }
            i += 3;
        } else {
            static const char *const words[] = {"cell", "heights"};
            char near[80];
            int k = a->kind == SYL_DARG_WORD ? closest_list(a->text, words, 2, near, sizeof near) : 0;
            directive_error_to(p, sink, d, a, "terrain takes `cell SIZE` and `heights LO HI` after the file%s%s%s",
                                k ? " (did you mean " : "", k ? near : "", k ? "?)" : "");
            errors++;
        }
    }
    return errors;
}

/* Whether the file holds a model called name (not the block itself). */
static bool model_exists(const SylProgram *p, const char *name) {
    size_t len;
    const char *text = syl_program_source(p, &len);
    const char *names[256];
    char buf[8192];
    int n = syl_model_list(syl_program_path(p), text, len, names, 256, buf, sizeof buf);
    for (int i = 0; i < n && i < 256; i++)
        if (!strcmp(names[i], name) && strcmp(name, syl_program_name(p))) return true;
    return false;
}

/* The words for a line of no row (in_species: after a `species NAME` line). */
static void unknown_text(const char *name, bool in_species, char *buf, size_t size) {
    const char *names[NNUMS + NBLOCK + SYL_TERRAIN_FACTORS + 1];
    int n = 0;
    for (int i = 0; i < NBLOCK; i++) names[n++] = block_words[i];
    names[n++] = "model";
    for (int i = 0; i < NNUMS; i++) names[n++] = species_nums[i].name;
    for (int f = 0; f < SYL_TERRAIN_FACTORS; f++)
        if (f != SYL_TERRAIN_FLOW) names[n++] = syl_terrain_factor_name((SylTerrainFactor)f);
    char near[200];
    int k = closest_list(name, names, n, near, sizeof near);
    if (k) snprintf(buf, size, "unknown ecosystem directive '%s' (did you mean %s?)", name, near);
    else if (!in_species && (factor_named(name) >= 0 || !strcmp(name, "model")))
        snprintf(buf, size, "'%s' belongs to a species: write it after a `species NAME` line", name);
    else snprintf(buf, size, "unknown ecosystem directive '%s' (docs/ecosystem.md lists them)", name);
}

/* A species' tolerance curve: OPT RANGE [FALLOFF]. */
static int read_factor(SchLineRead *r, const SchRow *row, const SylDirective *d, void *elem) {
    (void)row;
    const SylProgram *p = sch_lines_program(r);
    const SylSink *sink = sch_lines_sink(r);
    SylEcoSpecies *s = elem;
    int f = factor_named(d->name);
    if (arity(p, sink, d, 2, 3)) return 1;
    double lo = f == SYL_TERRAIN_ALTITUDE ? -1e5 : -1e4, hi = 1e5;
    int e = number(p, sink, d, 0, lo, hi, false, &s->optimum[f]);
    if (!e) e = number(p, sink, d, 1, 0, 1e5, false, &s->range[f]);
    s->falloff[f] = s->range[f] > 0 ? s->range[f] : 1;
    if (!e && d->nargs == 3) e = number(p, sink, d, 2, 1e-9, 1e9, false, &s->falloff[f]);
    s->set[f] = 1;
    return e;
}

static int read_model(SchLineRead *r, const SylDirective *d, SylEcoSpecies *s) {
    const SylProgram *p = sch_lines_program(r);
    const SylSink *sink = sch_lines_sink(r);
    if (arity(p, sink, d, 1, 1)) return 1;
    const SylDirArg *a = &d->args[0];
    if (a->kind != SYL_DARG_WORD && a->kind != SYL_DARG_STRING) {
        directive_error_to(p, sink, d, a, "model takes the name of a model of this file");
        return 1;
    }
    if (!model_exists(p, a->text)) {
        directive_error_to(p, sink, d, a, "no model called '%s' in this file", a->text);
        return 1;
    }
    snprintf(s->model, sizeof s->model, "%s", a->text);
    return 0;
}

static int read_snapshots(SylEcoModel *m, const SylProgram *p, const SylSink *sink, const SylDirective *d) {
    double x;
    if (arity(p, sink, d, 1, SYL_ECO_MAX_SNAPSHOTS)) return 1;
    m->nsnapshots = 0;
    for (int i = 0; i < d->nargs; i++) {
        if (number(p, sink, d, i, 0, SYL_ECO_MAX_YEARS, true, &x)) return 1;
        if (m->nsnapshots && x <= m->snapshots[m->nsnapshots - 1]) {
            directive_error_to(p, sink, d, &d->args[i], "snapshots must be increasing years");
            return 1;
        }
        m->snapshots[m->nsnapshots++] = (int)x;
    }
    return 0;
}

/* The rows the reader leaves to the ecosystem: terrain, snapshots, a species' model and curves. */
static int read_own(SchLineRead *r, const SchRow *row, const SylDirective *d, void *base) {
    const SylProgram *p = sch_lines_program(r);
    const SylSink *sink = sch_lines_sink(r);
    if (!strcmp(row->name, "terrain")) return read_terrain(p, sink, d, base);
    if (!strcmp(row->name, "snapshots")) return read_snapshots(base, p, sink, d);
    if (!strcmp(row->name, "model")) return read_model(r, d, base);
    return read_factor(r, row, d, base);
}

/* `species NAME`: the element its lines go to (NULL: none, reported). */
static void *open_species(SchLineRead *r, const SylDirective *d, void *base) {
    SylEcoModel *m = base;
    if (d->nargs != 1 || (d->args[0].kind != SYL_DARG_WORD && d->args[0].kind != SYL_DARG_STRING)) {
        sch_lines_error(r, d, d->nargs ? &d->args[0] : NULL, "species takes one name: species beech");
        return NULL;
    }
    if (m->nspecies == SYL_ECO_MAX_SPECIES) {
        sch_lines_error(r, d, NULL, "at most %d species", SYL_ECO_MAX_SPECIES);
        sch_lines_stop(r);
        return NULL;
    }
    for (int k = 0; k < m->nspecies; k++)
        if (!strcmp(m->species[k].name, d->args[0].text))
            sch_lines_error(r, d, &d->args[0], "species '%s' was already given on line %d", d->args[0].text,
                            m->species[k].line);
    SylEcoSpecies *cur = &m->species[m->nspecies++];
    species_default(cur);
    snprintf(cur->name, sizeof cur->name, "%s", d->args[0].text);
    cur->line = d->line;
    cur->col = d->col;
    return cur;
}

static void took(void *base, const SchRow *row) {
    SylEcoModel *m = base;
    if (!strcmp(row->name, "latitude")) m->latitude_set = true;
    else if (!strcmp(row->name, "wind_from")) m->wind_set = true;
}

/* The ecosystem's words for what the reader finds wrong (its messages as they were). */
static void say(SchProblem *pr, char *buf, size_t size) {
    const SchRow *row = pr->row;
    switch (pr->what) {
    case SCH_BAD_UNKNOWN: unknown_text(pr->name, pr->in_group, buf, size); break;
    case SCH_BAD_COUNT: snprintf(buf, size, "%s takes 1 value", pr->name); break;
    case SCH_BAD_NUMBER: snprintf(buf, size, "%s takes a number", pr->name); break;
    case SCH_BAD_RANGE:
        if (isnan(pr->x) || pr->x < row->lo || pr->x > row->hi)
            snprintf(buf, size, "%s must be in [%g, %g], not %g", pr->name, row->lo, row->hi, pr->x);
        else snprintf(buf, size, "%s takes a whole number, not %g", pr->name, pr->x);
        break;
    case SCH_BAD_WORD: {
        char list[200] = "";
        for (const char *w = row->words; *w;) { /* 'a', 'b' or 'c' */
            size_t len = strcspn(w, "|"), used = strlen(list);
            snprintf(list + used, sizeof list - used, "%s'%.*s'", !used ? "" : w[len] ? ", " : " or ", (int)len, w);
            w += len + (w[len] == '|');
        }
        snprintf(buf, size, "%s is %s%s", pr->name, list, pr->hint);
        break;
    }
    case SCH_BAD_SET_ELEMENT:
        snprintf(buf, size, "--set %s: ecosystem '%s' has no species '%s'%s", pr->typed, pr->block, pr->name, pr->hint);
        break;
    case SCH_BAD_SET_NOT_GROUP:
        snprintf(buf, size, "--set %s: '%s' is the block's, not a species': write --set %s=%g", pr->typed, pr->name,
                 pr->name, pr->x);
        break;
    default: break; /* the reader's (lang/schema.c's --set words) */
    }
}

static int check_species(const SylProgram *p, const SylSink *sink, const SylEcoSpecies *s) {
    int e = 0;
    if (s->old_age < s->maturity) {
        program_error_to(p, sink, s->line, s->col, "species '%s': old_age (%g) is before maturity (%g)", s->name,
                          s->old_age, s->maturity);
        e++;
    }
    if (s->max_age < s->old_age) {
        program_error_to(p, sink, s->line, s->col, "species '%s': max_age (%g) is before old_age (%g)", s->name,
                          s->max_age, s->old_age);
        e++;
    }
    if (s->start_height > s->height_max) {
        program_error_to(p, sink, s->line, s->col, "species '%s': start_height (%g) is above height_max (%g)",
                          s->name, s->start_height, s->height_max);
        e++;
    }
    return e;
}

/* A species' curves must read the measures the block computes. */
static int check_measures(const SylProgram *p, const SylSink *sink, const SylEcoModel *m, const SylEcoSpecies *s) {
    static const int gis[] = {SYL_TERRAIN_WETNESS, SYL_TERRAIN_INSOLATION, SYL_TERRAIN_WIND},
                     zam[] = {SYL_TERRAIN_HUMIDITY, SYL_TERRAIN_SUNNINESS, SYL_TERRAIN_WINDINESS};
    int e = 0;
    for (int k = 0; k < 3; k++) {
        int bad = m->measures == SYL_ECO_ZAMUDA ? gis[k] : zam[k], good = m->measures == SYL_ECO_ZAMUDA ? zam[k] : gis[k];
        if (!s->set[bad]) continue;
        program_error_to(p, sink, s->line, s->col, "species '%s': '%s' is a curve of %s measures, and the block's are %s: "
                          "write its curve as '%s'%s", s->name, syl_terrain_factor_name((SylTerrainFactor)bad),
                          m->measures == SYL_ECO_ZAMUDA ? "the GIS" : "Zamuda's", m->measures == SYL_ECO_ZAMUDA ? "Zamuda's" : "GIS's",
                          syl_terrain_factor_name((SylTerrainFactor)good),
                          m->measures == SYL_ECO_ZAMUDA ? "" : ", or choose his with `measures zamuda`");
        e++;
    }
    return e;
}

/* After the lines and --set: what a species and the block must hold. */
static int check_block(SchLineRead *r, void *base) {
    const SylProgram *p = sch_lines_program(r);
    const SylSink *sink = sch_lines_sink(r);
    SylEcoModel *m = base;
    int errors = sch_lines_errors(r), e = 0, set_errors = sch_lines_set_errors(r);
    int line_errors = errors; /* a misspelt `measures` says nothing of the curves */
    for (int k = 0; k < m->nspecies && !set_errors; k++)
        e += check_species(p, sink, &m->species[k]) + (line_errors ? 0 : check_measures(p, sink, m, &m->species[k]));
    if (!errors && !e && !m->terrain[0]) {
        program_error_to(p, sink, 0, 0, "ecosystem '%s' names no terrain (terrain \"dem.png\" cell 10 heights 0 400)",
                          syl_program_name(p));
        e++;
    }
    if (!errors && !e && !m->nspecies) {
        program_error_to(p, sink, 0, 0, "ecosystem '%s' has no species", syl_program_name(p));
        e++;
    }
    return e;
}

/* Where each row is kept (params.def's order, the table's): the block's in SylEcoModel, a
 * species' in its SylEcoSpecies; terrain, snapshots, model and the curves are read above. */
#define MO(f) offsetof(SylEcoModel, f)
#define ECO_OFF_INT(f) MO(f)
#define ECO_OFF_U64(f) MO(f)
#define ECO_OFF_F64(f) MO(f)
#define ECO_OFF_KIND(f) 0
#define ECO_OFF_NONE(f) 0
static const SchSlot slots[] = {
#define ECO_B(at, f, ...) {.store = SCH_AT_##at, .off = ECO_OFF_##at(f)},
#define ECO_W(nm, ...) {.store = SCH_AT_KIND},
#define ECO_S(f, ...) {.store = SCH_AT_F64, .off = SP(f)},
#define ECO_F(...) {.store = SCH_AT_KIND},
#include "params.def"
};
enum {
    NROWS = 0
#define ECO_B(...) +1
#define ECO_W(...) +1
#define ECO_S(...) +1
#define ECO_F(...) +1
#include "params.def"
};
_Static_assert(sizeof slots / sizeof *slots == NROWS, "a slot for each row of params.def, in its order");

static const SchLines eco_lines = {
    .t = &sch_ecosystem,
    .slots = slots,
    .nslots = sizeof slots / sizeof *slots,
    .again = true,
    .say = say,
    .line = read_own,
    .took = took,
    .done = check_block,
    .group = {.dir = "species", .off = MO(species), .size = sizeof(SylEcoSpecies), .count_off = MO(nspecies),
              .name_off = SP(name), .open = open_species},
    .set_if_clean = true,
};

static int read_lines(const SylProgram *p, SylEcoModel *m, const SylSink *sink, int *set_errors) {
    memset(m, 0, sizeof *m);
    sch_count_read(p);
    m->years = 100;
    m->seed = syl_program_seed(p);
    m->combine = SYL_ECO_MEAN;
    m->wind_from = 270;
    return sch_read_lines_to(p, &eco_lines, m, sink, set_errors);
}

int syl_ecosystem_read(const SylProgram *p, SylEcoModel *m, const SylSink *sink) {
    if (sch_kept(p, m, sizeof *m)) return 0;
    int set_errors;
    return read_lines(p, m, sink, &set_errors);
}

int syl_ecosystem_validate(const SylProgram *p, const SylSink *sink) {
    if (syl_program_kind(p) != SYL_MODEL_ECOSYSTEM) return 0;
    SylEcoModel m;
    int set_errors, errors = read_lines(p, &m, sink, &set_errors);
    if (!errors) sch_keep(p, &m, sizeof m); /* the run takes it: read once */
    return errors && errors == set_errors ? -errors : errors; /* negative: only the command line's */
}
