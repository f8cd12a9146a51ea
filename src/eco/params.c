/* Reading an `ecosystem` block's directives: the block's own lines, then after each
 * `species NAME` line the lines of that species (docs/ecosystem.md). */
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
#define ECO_B(nm, ...) nm,
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

static int unknown(const SylProgram *p, const SylSink *sink, const SylDirective *d, bool in_species) {
    const char *names[NNUMS + NBLOCK + SYL_TERRAIN_FACTORS + 1];
    int n = 0;
    for (int i = 0; i < NBLOCK; i++) names[n++] = block_words[i];
    names[n++] = "model";
    for (int i = 0; i < NNUMS; i++) names[n++] = species_nums[i].name;
    for (int f = 0; f < SYL_TERRAIN_FACTORS; f++)
        if (f != SYL_TERRAIN_FLOW) names[n++] = syl_terrain_factor_name((SylTerrainFactor)f);
    char near[200];
    int k = closest_list(d->name, names, n, near, sizeof near);
    if (k)
        directive_error_to(p, sink, d, NULL, "unknown ecosystem directive '%s' (did you mean %s?)", d->name, near);
    else if (!in_species && (factor_named(d->name) >= 0 || !strcmp(d->name, "model")))
        directive_error_to(p, sink, d, NULL, "'%s' belongs to a species: write it after a `species NAME` line", d->name);
    else
        directive_error_to(p, sink, d, NULL, "unknown ecosystem directive '%s' (docs/ecosystem.md lists them)", d->name);
    return 1;
}

static int read_species_line(const SylProgram *p, const SylSink *sink, const SylDirective *d, SylEcoSpecies *s) {
    for (int i = 0; i < NNUMS; i++)
        if (!strcmp(d->name, species_nums[i].name)) {
            if (arity(p, sink, d, 1, 1)) return 1;
            return number(p, sink, d, 0, species_nums[i].lo, species_nums[i].hi, false,
                          (double *)((char *)s + species_nums[i].offset));
        }
    int f = factor_named(d->name);
    if (f >= 0) {
        if (arity(p, sink, d, 2, 3)) return 1;
        double lo = f == SYL_TERRAIN_ALTITUDE ? -1e5 : -1e4, hi = 1e5;
        int e = number(p, sink, d, 0, lo, hi, false, &s->optimum[f]);
        if (!e) e = number(p, sink, d, 1, 0, 1e5, false, &s->range[f]);
        s->falloff[f] = s->range[f] > 0 ? s->range[f] : 1;
        if (!e && d->nargs == 3) e = number(p, sink, d, 2, 1e-9, 1e9, false, &s->falloff[f]);
        s->set[f] = 1;
        return e;
    }
    if (!strcmp(d->name, "model")) {
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
    return unknown(p, sink, d, true);
}

/* The index of the directive's word in its row (the enum's value), or -1 reported with a guess. */
static int word_of(const SylProgram *p, const SylSink *sink, const SylDirective *d) {
    const char *words = sch_find(&sch_ecosystem, d->name, NULL)->words; /* in the enum's order */
    if (arity(p, sink, d, 1, 1)) return -1;
    int k = d->args[0].kind == SYL_DARG_WORD ? sch_word_index(words, d->args[0].text) : -1;
    if (k >= 0) return k;
    char near[200] = "", list[200] = "";
    if (d->args[0].kind == SYL_DARG_WORD) sch_suggest_word(words, d->args[0].text, near, sizeof near);
    for (const char *w = words; *w;) { /* 'a', 'b' or 'c' */
        size_t len = strcspn(w, "|"), used = strlen(list);
        snprintf(list + used, sizeof list - used, "%s'%.*s'", !used ? "" : w[len] ? ", " : " or ", (int)len, w);
        w += len + (w[len] == '|');
    }
    directive_error_to(p, sink, d, &d->args[0], "%s is %s%s", d->name, list, near);
    return -1;
}

static int read_block_line(const SylProgram *p, const SylSink *sink, const SylDirective *d, SylEcoModel *m) {
    double x;
    if (!strcmp(d->name, "terrain")) return read_terrain(p, sink, d, m);
    if (!strcmp(d->name, "years")) {
        int e = arity(p, sink, d, 1, 1) || number(p, sink, d, 0, 1, SYL_ECO_MAX_YEARS, true, &x);
        if (!e) m->years = (int)x;
        return e;
    }
    if (!strcmp(d->name, "seed")) {
        int e = arity(p, sink, d, 1, 1) || number(p, sink, d, 0, 0, 9007199254740991.0, true, &x);
        if (!e) m->seed = (uint64_t)x;
        return e;
    }
    if (!strcmp(d->name, "latitude")) {
        int e = arity(p, sink, d, 1, 1) || number(p, sink, d, 0, -90, 90, false, &m->latitude);
        m->latitude_set = !e;
        return e;
    }
    if (!strcmp(d->name, "wind_from")) {
        int e = arity(p, sink, d, 1, 1) || number(p, sink, d, 0, 0, 360, false, &m->wind_from);
        m->wind_set = !e;
        return e;
    }
    bool vigour = !strcmp(d->name, "vigour"), measures = !strcmp(d->name, "measures");
    if (vigour || measures || !strcmp(d->name, "mortality")) {
        int k = word_of(p, sink, d);
        if (k < 0) return 1;
        if (vigour) m->combine = (SylEcoCombine)k;
        else if (measures) m->measures = (SylEcoMeasures)k;
        else m->mortality = (SylEcoMortality)k;
        return 0;
    }
    if (!strcmp(d->name, "snapshots")) {
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
    return unknown(p, sink, d, false);
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

static bool is_param(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nparams; i++)
        if (!strcmp(p->params[i].name, name)) return true;
    return false;
}

/* --set NAME=VALUE over the block's lines, in the order given: a number of the block
 * (`years`, `seed`, `latitude`), a species' number for every species (`maturity`) or for
 * one (`beech.maturity`), checked by the schema's reader (lang/schema.c) for name and range.
 * The line numbers of later messages stay the file's. */
static int apply_sets(const SylProgram *p, SylEcoModel *m, const SylSink *sink) {
    int errors = 0;
    for (int i = 0; i < p->noverrides; i++) {
        const char *name = p->set_local ? p->set_local[i] : NULL, *typed = p->overrides[i].name;
        if (!name || is_param(p, name)) continue;
        double v = p->overrides[i].value;
        const char *dot = strchr(name, '.');
        int only = -1; /* the species named, -1: every species */
        if (dot) {
            for (int k = 0; k < m->nspecies; k++)
                if (strlen(m->species[k].name) == (size_t)(dot - name) &&
                    !strncmp(m->species[k].name, name, (size_t)(dot - name)))
                    only = k;
            if (only < 0) {
                const char *names[SYL_ECO_MAX_SPECIES];
                char prefix[96], near[400];
                for (int k = 0; k < m->nspecies; k++) names[k] = m->species[k].name;
                snprintf(prefix, sizeof prefix, "%.*s", (int)(dot - name), name);
                int n = closest_list(prefix, names, m->nspecies, near, sizeof near);
                program_error_to(p, sink, 0, 0, "--set %s: ecosystem '%s' has no species '%s'%s%s%s", typed,
                                  syl_program_name(p), prefix, n ? " (did you mean " : "", n ? near : "", n ? "?)" : "");
                errors++;
                continue;
            }
            name = dot + 1;
        }
        const SchRow *row;
        int level;
        if (sch_set_check_to(p, sink, &sch_ecosystem, typed, name, v, &row, &level)) {
            errors++;
            continue;
        }
        if (dot && !row->group) {
            program_error_to(p, sink, 0, 0, "--set %s: '%s' is the block's, not a species': write --set %s=%g",
                              typed, name, name, v);
            errors++;
            continue;
        }
        if (!strcmp(name, "years")) m->years = (int)v;
        else if (!strcmp(name, "seed")) m->seed = (uint64_t)v;
        else if (!strcmp(name, "latitude")) m->latitude = v, m->latitude_set = true;
        else if (!strcmp(name, "wind_from")) m->wind_from = v, m->wind_set = true;
        for (int n = 0; n < NNUMS; n++)
            if (!strcmp(name, species_nums[n].name))
                for (int k = 0; k < m->nspecies; k++)
                    if (only < 0 || only == k) *(double *)((char *)&m->species[k] + species_nums[n].offset) = v;
    }
    return errors;
}

static int read_lines(const SylProgram *p, SylEcoModel *m, const SylSink *sink, int *set_errors);

int syl_ecosystem_read(const SylProgram *p, SylEcoModel *m, const SylSink *sink) {
    if (sch_kept(p, m, sizeof *m)) return 0;
    int set_errors;
    return read_lines(p, m, sink, &set_errors);
}

static int read_lines(const SylProgram *p, SylEcoModel *m, const SylSink *sink, int *set_errors) {
    memset(m, 0, sizeof *m);
    sch_count_read(p);
    m->years = 100;
    m->seed = syl_program_seed(p);
    m->combine = SYL_ECO_MEAN;
    m->wind_from = 270;
    int n = 0, errors = 0;
    const SylDirective *ds = syl_program_directives(p, &n);
    SylEcoSpecies *cur = NULL;
    for (int i = 0; i < n; i++) {
        const SylDirective *d = &ds[i];
        if (!strcmp(d->name, "species")) {
            if (d->nargs != 1 || (d->args[0].kind != SYL_DARG_WORD && d->args[0].kind != SYL_DARG_STRING)) {
                directive_error_to(p, sink, d, d->nargs ? &d->args[0] : NULL, "species takes one name: species beech");
                errors++;
                cur = NULL;
                continue;
            }
            if (m->nspecies == SYL_ECO_MAX_SPECIES) {
                directive_error_to(p, sink, d, NULL, "at most %d species", SYL_ECO_MAX_SPECIES);
                return errors + 1;
            }
            for (int k = 0; k < m->nspecies; k++)
                if (!strcmp(m->species[k].name, d->args[0].text)) {
                    directive_error_to(p, sink, d, &d->args[0], "species '%s' was already given on line %d",
                                        d->args[0].text, m->species[k].line);
                    errors++;
                }
            cur = &m->species[m->nspecies++];
            species_default(cur);
            snprintf(cur->name, sizeof cur->name, "%s", d->args[0].text);
            cur->line = d->line;
            cur->col = d->col;
            continue;
        }
        bool block = false;
        for (int k = 0; k < NBLOCK; k++) block |= !strcmp(d->name, block_words[k]);
        if (cur && !block) errors += read_species_line(p, sink, d, cur);
        else errors += read_block_line(p, sink, d, m);
    }
    *set_errors = errors ? 0 : apply_sets(p, m, sink);
    errors += *set_errors;
    int line_errors = errors; /* a misspelt `measures` says nothing of the curves */
    for (int k = 0; k < m->nspecies && !*set_errors; k++)
        errors += check_species(p, sink, &m->species[k]) + (line_errors ? 0 : check_measures(p, sink, m, &m->species[k]));
    if (!errors && !m->terrain[0]) {
        program_error_to(p, sink, 0, 0, "ecosystem '%s' names no terrain (terrain \"dem.png\" cell 10 heights 0 400)",
                          syl_program_name(p));
        errors++;
    }
    if (!errors && !m->nspecies) {
        program_error_to(p, sink, 0, 0, "ecosystem '%s' has no species", syl_program_name(p));
        errors++;
    }
    return errors;
}

int syl_ecosystem_validate(const SylProgram *p, const SylSink *sink) {
    if (syl_program_kind(p) != SYL_MODEL_ECOSYSTEM) return 0;
    SylEcoModel m;
    int set_errors, errors = read_lines(p, &m, sink, &set_errors);
    if (!errors) sch_keep(p, &m, sizeof m); /* the run takes it: read once */
    return errors && errors == set_errors ? -errors : errors; /* negative: only the command line's */
}
