/* sylva describe: every model of a file with every parameter, from the schema's rows
 * (schema.h) and the model's values. The JSON is the contract of sylva/describe.h. */
#include "sylva/describe.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/kinds.h"
#include "lang/program.h"
#include "lang/schema.h"
#include "lang/textures.h"

/* A value: none, a number, a list of numbers, or text. */
typedef struct Val {
    enum { V_NULL, V_NUM, V_LIST, V_TEXT } kind;
    double x[8];
    int n;
    char text[256];
} Val;

typedef struct Entry {
    char name[128];
    SchType type;
    double lo, hi; /* NAN: unbounded */
    Val def, val;
    const char *unit, *doc, *words, *aliases;
    int levels;
} Entry;

typedef struct DModel {
    const char *name, *kind;
    SylModelKind id; /* its row in lang/kinds.def: "caps" in JSON */
    int line;
    Entry *e;
    int n, cap;
} DModel;

static Entry *add(DModel *m) {
    if (m->n == m->cap) {
        int cap = m->cap ? 2 * m->cap : 64;
        Entry *e = realloc(m->e, (size_t)cap * sizeof *e);
        if (!e) return NULL;
        m->e = e, m->cap = cap;
    }
    Entry *e = &m->e[m->n++];
    memset(e, 0, sizeof *e);
    e->lo = e->hi = NAN;
    e->unit = "";
    e->doc = "";
    return e;
}

static void num(Val *v, double x) { *v = (Val){.kind = isnan(x) ? V_NULL : V_NUM, .x = {x}, .n = 1}; }
static void text(Val *v, const char *s) {
    v->kind = s ? V_TEXT : V_NULL;
    snprintf(v->text, sizeof v->text, "%s", s ? s : "");
}

static void row_default(const SchRow *r, Val *v) {
    if (r->levels) {
        *v = (Val){.kind = V_LIST, .n = r->levels};
        for (int l = 0; l < r->levels && l < 8; l++) v->x[l] = r->def[l];
    } else if (r->type == SCH_NUMBER || r->type == SCH_INTEGER || r->type == SCH_BOOLEAN)
        num(v, r->def[0]);
    else if (r->def_text)
        text(v, r->def_text);
    else
        v->kind = V_NULL;
}

static Entry *add_row(DModel *m, const SchRow *r, const char *prefix) {
    Entry *e = add(m);
    if (!e) return NULL;
    snprintf(e->name, sizeof e->name, "%s%s", prefix ? prefix : "", r->name);
    e->type = r->levels ? SCH_LIST : r->type;
    if ((r->type == SCH_NUMBER || r->type == SCH_INTEGER || r->type == SCH_LIST || r->type == SCH_VECTOR) &&
        !(r->lo == 0 && r->hi == 0)) {
        e->lo = isinf(r->lo) ? NAN : r->lo;
        e->hi = isinf(r->hi) ? NAN : r->hi;
    }
    row_default(r, &e->def);
    e->val = e->def;
    e->unit = r->unit ? r->unit : "";
    e->doc = r->doc ? r->doc : "";
    e->words = r->words;
    e->aliases = r->aliases;
    e->levels = r->levels;
    return e;
}

/* A directive's values as written: its number, its numbers, or its words. */
static void arg_text(const SylDirArg *a, char *buf, size_t size) {
    if (a->kind == SYL_DARG_NUMBER) snprintf(buf, size, "%.15g", a->num);
    else if (a->kind == SYL_DARG_TUPLE || a->kind == SYL_DARG_SYMBOL) {
        size_t k = (size_t)snprintf(buf, size, "%s(", a->kind == SYL_DARG_SYMBOL && a->text ? a->text : "");
        for (int i = 0; i < a->nvalues && k < size; i++)
            k += (size_t)snprintf(buf + k, size - k, "%s%.15g", i ? ", " : "", a->values[i]);
        if (k < size) snprintf(buf + k, size - k, ")");
    } else
        snprintf(buf, size, "%s", a->text ? a->text : "");
}

static void directive_value(const SylDirective *d, int level, Entry *e) {
    double x;
    if (e->levels) {
        if (e->val.kind != V_LIST) return;
        for (int k = 0; k < d->nargs; k++) {
            int l = level >= 0 ? level : k;
            if (l < e->levels && sch_number(&d->args[k], &x)) e->val.x[l] = x;
        }
        return;
    }
    bool all = d->nargs > 0 && d->nargs <= 8;
    for (int k = 0; all && k < d->nargs; k++) all = sch_number(&d->args[k], &x);
    if (all && d->nargs == 1 && e->type != SCH_LIST) {
        num(&e->val, d->args[0].kind == SYL_DARG_NUMBER ? d->args[0].num : d->args[0].values[0]);
        return;
    }
    if (all && e->type == SCH_LIST) {
        e->val = (Val){.kind = V_LIST, .n = d->nargs};
        for (int k = 0; k < d->nargs; k++) sch_number(&d->args[k], &e->val.x[k]);
        return;
    }
    e->val.kind = V_TEXT;
    size_t used = 0;
    for (int k = 0; k < d->nargs && used < sizeof e->val.text; k++) {
        char one[128];
        arg_text(&d->args[k], one, sizeof one);
        used += (size_t)snprintf(e->val.text + used, sizeof e->val.text - used, "%s%s", k ? " " : "", one);
    }
}

static Entry *find_entry(DModel *m, const char *name) {
    for (int i = 0; i < m->n; i++)
        if (!strcmp(m->e[i].name, name)) return &m->e[i];
    return NULL;
}

/* A lines block (weber, strands, curvetree, pafco): read by the schema's one reader of NAME
 * VALUE lines (schema_lines.c), which tells each line as it takes it (its values as written)
 * and each --set value (at its level). */
static void lines_line(void *ctx, const SchRow *row, int level, const SylDirective *d) {
    Entry *e = find_entry(ctx, row->name);
    if (e) directive_value(d, level, e);
}

static void lines_set(void *ctx, const SchRow *row, int level, const double *x, int n, const char *word) {
    (void)n, (void)word;
    Entry *e = find_entry(ctx, row->name);
    if (!e) return;
    if (e->levels && level >= 0 && level < e->levels && e->val.kind == V_LIST) e->val.x[level] = x[0];
    else if (!e->levels) num(&e->val, x[0]);
}

static void describe_lines(const SylProgram *p, const SchTable *t, DModel *m) {
    for (int i = 0; i < t->n; i++) add_row(m, &t->rows[i], NULL);
    sch_see_lines(p, t, &(SchSeen){.value = lines_set, .line = lines_line, .ctx = m});
}

/* A groups block (ecosystem): the same reader; the block's rows, then at each `species NAME`
 * its rows as NAME.ROW, as --set names them (NAME.maturity=30). */
typedef struct Groups {
    const SchTable *t;
    DModel *m;
    const char *names[64]; /* the groups' names, in order */
    int n;
} Groups;

static void group_row_name(const Groups *g, const SchRow *row, int elem, char *buf, size_t size) {
    if (row->group && elem >= 0 && elem < g->n) snprintf(buf, size, "%s.%s", g->names[elem], row->name);
    else snprintf(buf, size, "%s", row->name);
}

static void groups_line(void *ctx, const SchRow *row, int level, const SylDirective *d) {
    Groups *g = ctx;
    (void)level;
    bool head = false;
    for (int i = 0; i < g->t->n && !head; i++) head = g->t->rows[i].group && !strcmp(g->t->rows[i].group, row->name);
    if (head && d->nargs == 1 && d->args[0].text && g->n < 64) {
        g->names[g->n++] = d->args[0].text;
        char prefix[80];
        snprintf(prefix, sizeof prefix, "%s.", d->args[0].text);
        for (int i = 0; i < g->t->n; i++)
            if (g->t->rows[i].group) add_row(g->m, &g->t->rows[i], prefix);
        return;
    }
    char name[160];
    group_row_name(g, row, g->n - 1, name, sizeof name);
    Entry *e = find_entry(g->m, name);
    if (e) directive_value(d, -1, e);
}

static void groups_set(void *ctx, const SchRow *row, int elem, const double *x, int n, const char *word) {
    Groups *g = ctx;
    (void)n, (void)word;
    char name[160];
    if (row->group && elem < 0) return; /* every species': describe names none so */
    group_row_name(g, row, elem, name, sizeof name);
    Entry *e = find_entry(g->m, name);
    if (e && (e->type == SCH_NUMBER || e->type == SCH_INTEGER)) num(&e->val, x[0]);
}

static void describe_groups(const SylProgram *p, const SchTable *t, DModel *m) {
    for (int i = 0; i < t->n; i++)
        if (!t->rows[i].group) add_row(m, &t->rows[i], NULL);
    Groups g = {.t = t, .m = m};
    sch_see_lines(p, t, &(SchSeen){.value = groups_set, .line = groups_line, .ctx = &g});
}

/* A keyed block (grow): read by the schema's one keyed reader (schema_keyed.c), which tells
 * each value as it takes it, lines then --set. A directive's mode or bare value goes under its
 * name, its keys as DIRECTIVE.KEY; a repeated line's (organ) as organ.N and organ.N.KEY, N from
 * 1, as --set names them. */
typedef struct Keyed {
    const SchTable *t;
    DModel *m;
} Keyed;

/* row's name in element elem of its repeated line ("organ.size" of the 2nd: "organ.2.size"). */
static void elem_name(const SchRow *row, int elem, char *buf, size_t size) {
    const char *dot = strchr(row->name, '.');
    size_t len = dot ? (size_t)(dot - row->name) : strlen(row->name);
    if (elem < 0) snprintf(buf, size, "%s", row->name);
    else snprintf(buf, size, "%.*s.%d%s", (int)len, row->name, elem + 1, row->name + len);
}

static void keyed_element(void *ctx, const SchRow *head, int elem) {
    const Keyed *k = ctx;
    size_t len = strlen(head->name);
    for (int i = 0; i < k->t->n; i++) {
        const SchRow *r = &k->t->rows[i];
        if (!r->group || strncmp(r->name, head->name, len) || (r->name[len] && r->name[len] != '.')) continue;
        Entry *e = add_row(k->m, r, NULL);
        if (e) elem_name(r, elem, e->name, sizeof e->name);
    }
}

static void keyed_value(void *ctx, const SchRow *row, int elem, const double *x, int n, const char *word) {
    const Keyed *k = ctx;
    char name[160];
    elem_name(row, elem, name, sizeof name);
    Entry *e = find_entry(k->m, name);
    if (!e) return;
    if (word) text(&e->val, word);
    else if (n == 3) { /* a direction, as written */
        e->val.kind = V_TEXT;
        snprintf(e->val.text, sizeof e->val.text, "(%.15g, %.15g, %.15g)", x[0], x[1], x[2]);
    } else if (n == 1)
        num(&e->val, x[0]);
}

static void describe_keyed(const SylProgram *p, const SchTable *t, DModel *m) {
    for (int i = 0; i < t->n; i++)
        if (!t->rows[i].group) add_row(m, &t->rows[i], NULL);
    Keyed k = {t, m};
    sch_see_keyed(p, t, &(SchSeen){.element = keyed_element, .value = keyed_value, .ctx = &k});
}

/* A scene (scene/params.def): its lines as they are written (scene/spec.c checked them: a
 * value that is not of its row is shown as none), a plant or obstacle line an element of its
 * group with at (x, y, z) its rows x, y, z; then its --set values. Each is named as --set
 * takes it, scene.NAME (scene.plant.2.x). */
static void scene_element(const SchTable *t, DModel *m, const char *group, int elem, const SylDirective *d) {
    char name[160];
    for (int i = 0; i < t->n; i++)
        if (t->rows[i].group && !strcmp(t->rows[i].group, group)) {
            Entry *e = add_row(m, &t->rows[i], NULL);
            if (e) elem_name(&t->rows[i], elem, e->name, sizeof e->name);
        }
    snprintf(name, sizeof name, "%s.%d", group, elem + 1);
    Entry *head = find_entry(m, name);
    if (head && d->nargs) text(&head->val, d->args[0].text);
    for (int k = 1; k + 1 < d->nargs; k += 2) {
        const SylDirArg *key = &d->args[k], *v = &d->args[k + 1];
        if (key->kind != SYL_DARG_WORD) continue;
        if (!strcmp(key->text, "at") && v->kind == SYL_DARG_TUPLE && v->nvalues == 3) {
            for (int a = 0; a < 3; a++) {
                snprintf(name, sizeof name, "%s.%d.%c", group, elem + 1, "xyz"[a]);
                Entry *e = find_entry(m, name);
                if (e) num(&e->val, v->values[a]);
            }
            continue;
        }
        double x;
        snprintf(name, sizeof name, "%s.%d.%s", group, elem + 1, key->text);
        Entry *e = find_entry(m, name);
        if (e && e->type != SCH_STRING && e->type != SCH_FILE && sch_number(v, &x)) num(&e->val, x);
    }
}

static void describe_scene(const SylProgram *p, const SchTable *t, DModel *m) {
    for (int i = 0; i < t->n; i++)
        if (!t->rows[i].group) add_row(m, &t->rows[i], NULL);
    int n = 0, plants = 0, obstacles = 0;
    const SylDirective *d = syl_program_scene(p, &n);
    for (int i = 0; d && i < n; i++) {
        const SylDirArg *a0 = d[i].nargs ? &d[i].args[0] : NULL;
        bool file = a0 && a0->kind == SYL_DARG_STRING;
        double x;
        if (!strcmp(d[i].name, "plant") && a0) scene_element(t, m, "plant", plants++, &d[i]);
        else if (!strcmp(d[i].name, "obstacle") || (!strcmp(d[i].name, "ground") && file)) {
            if (file) scene_element(t, m, "obstacle", obstacles++, &d[i]);
        } else if (!strcmp(d[i].name, "ground") && a0 && sch_number(a0, &x))
            num(&find_entry(m, "ground")->val, x);
        else if (!strcmp(d[i].name, "sun") && d[i].nargs) {
            const SylDirArg *v = &d[i].args[d[i].nargs - 1]; /* sun [direction] (x, y, z) */
            Entry *e = find_entry(m, "sun");
            if (v->kind == SYL_DARG_TUPLE && v->nvalues == 3) {
                e->val.kind = V_TEXT;
                snprintf(e->val.text, sizeof e->val.text, "(%.15g, %.15g, %.15g)", v->values[0], v->values[1],
                         v->values[2]);
            }
        }
    }
    for (int i = 0; i < p->noverrides; i++) {
        Entry *e = strncmp(p->overrides[i].name, "scene.", 6) ? NULL : find_entry(m, p->overrides[i].name + 6);
        if (e && e->type != SCH_STRING && e->type != SCH_FILE && e->type != SCH_VECTOR) num(&e->val, p->overrides[i].value);
    }
    for (int i = 0; i < m->n; i++) { /* named as --set takes them: a scene's are never a model's own */
        char *name = m->e[i].name;
        size_t len = strnlen(name, sizeof m->e[i].name - 7);
        memmove(name + 6, name, len);
        memcpy(name, "scene.", 6);
        name[len + 6] = 0;
    }
}

static void describe_settings(const SylProgram *p, DModel *m) {
    for (int i = 0; i < sch_lsystem.n; i++) {
        const SchRow *r = &sch_lsystem.rows[i];
        Entry *e = add_row(m, r, NULL);
        if (!e) return;
        const char *s = r->name;
        if (!strcmp(s, "derive")) num(&e->val, p->derive);
        else if (!strcmp(s, "angle")) num(&e->val, p->angle);
        else if (!strcmp(s, "step")) num(&e->val, p->step);
        else if (!strcmp(s, "width")) num(&e->val, p->width);
        else if (!strcmp(s, "seed")) num(&e->val, (double)p->seed);
        else if (!strcmp(s, "widthfactor")) num(&e->val, p->widthfactor);
        else if (!strcmp(s, "lod")) num(&e->val, p->lod);
        else if (!strcmp(s, "direction")) text(&e->val, p->backward ? "backward" : "forward");
        else if (!strcmp(s, "tropism")) {
            e->val = (Val){.kind = V_LIST, .n = 4};
            for (int k = 0; k < 4; k++) e->val.x[k] = p->tropism[k];
        } else if (!strcmp(s, "maxdepth")) {
            num(&e->val, p->tables[TABLE_DECOMPOSE].maxdepth ? p->tables[TABLE_DECOMPOSE].maxdepth : r->def[0]);
        } else if (lang_texture_line(s)) { /* kept as a directive line (lang/textures.c) */
            int n = 0;
            const SylDirective *d = syl_program_directives(p, &n);
            e->val.kind = V_NULL;
            for (int k = 0; k < n; k++)
                if (!strcmp(d[k].name, s)) directive_value(&d[k], -1, e);
        } else
            e->val.kind = V_NULL; /* colour: one line per index */
    }
}

static void describe_params(const SylProgram *p, DModel *m) {
    for (int i = 0; i < p->nparams; i++) {
        Entry *e = add(m);
        if (!e) return;
        snprintf(e->name, sizeof e->name, "%s", p->params[i].name);
        e->type = SCH_NUMBER;
        e->doc = "a param of the file";
        num(&e->val, p->params[i].value);
        if (!p->params[i].overridden) e->def = e->val;
    }
}

/* The kind's table says which rows; its shape how the lines give their values. */
static void describe_model(const SylProgram *p, DModel *m) {
    m->name = syl_program_name(p);
    m->kind = lang_kind_keyword(p->kind);
    m->id = p->kind;
    m->line = p->model_loc.first_line;
    describe_params(p, m);
    const SchTable *t = lang_kind_schema(p->kind);
    if (!t) return;
    switch (t->shape) {
    case SCH_SETTINGS: describe_settings(p, m); break;
    case SCH_LINES: describe_lines(p, t, m); break;
    case SCH_GROUPS: describe_groups(p, t, m); break;
    case SCH_KEYED: describe_keyed(p, t, m); break;
    case SCH_SCENE: describe_scene(p, t, m); break;
    }
}

/* ---- JSON ---- */

static void jstr(FILE *out, const char *s) {
    fputc('"', out);
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') fprintf(out, "\\%c", c);
        else if (c < 0x20) fprintf(out, "\\u%04x", c);
        else fputc(c, out);
    }
    fputc('"', out);
}

static void jnum(FILE *out, double x) {
    if (isnan(x) || isinf(x)) fputs("null", out);
    else fprintf(out, "%.15g", x);
}

static void jval(FILE *out, const Val *v) {
    if (v->kind == V_NUM) jnum(out, v->x[0]);
    else if (v->kind == V_TEXT) jstr(out, v->text);
    else if (v->kind == V_LIST) {
        fputc('[', out);
        for (int i = 0; i < v->n; i++) {
            if (i) fputc(',', out);
            jnum(out, v->x[i]);
        }
        fputc(']', out);
    } else
        fputs("null", out);
}

/* "a|b" as ["a","b"] */
static void jwords(FILE *out, const char *words, bool null_if_none) {
    if (!words || !*words) {
        fputs(null_if_none ? "null" : "[]", out);
        return;
    }
    fputc('[', out);
    for (const char *w = words; w;) {
        const char *end = strchr(w, '|');
        size_t len = end ? (size_t)(end - w) : strlen(w);
        fprintf(out, "%s\"%.*s\"", w == words ? "" : ",", (int)len, w);
        w = end ? end + 1 : NULL;
    }
    fputc(']', out);
}

static void json_model(FILE *out, const DModel *m) {
    fputs("{\"name\":", out);
    jstr(out, m->name);
    fputs(",\"kind\":", out);
    jstr(out, m->kind);
    fputs(",\"caps\":[", out); /* what its kind can do, by the names front ends ask (kind_flags.def) */
    for (int i = 0, first = 1; syl_model_cap_name(i); i++)
        if (lang_kind_flags(m->id) >> i & 1) fprintf(out, "%s\"%s\"", first ? "" : ",", syl_model_cap_name(i)), first = 0;
    fprintf(out, "],\"line\":%d,\"params\":[", m->line);
    for (int i = 0; i < m->n; i++) {
        const Entry *e = &m->e[i];
        fputs(i ? ",\n  {\"name\":" : "\n  {\"name\":", out);
        jstr(out, e->name);
        fprintf(out, ",\"type\":\"%s\",\"min\":", sch_type_name(e->type));
        jnum(out, e->lo);
        fputs(",\"max\":", out);
        jnum(out, e->hi);
        fputs(",\"default\":", out);
        jval(out, &e->def);
        fputs(",\"value\":", out);
        jval(out, &e->val);
        fputs(",\"unit\":", out);
        jstr(out, e->unit);
        fputs(",\"doc\":", out);
        jstr(out, e->doc);
        fputs(",\"values\":", out);
        jwords(out, e->type == SCH_ENUM ? e->words : NULL, true);
        fputs(",\"aliases\":", out);
        jwords(out, e->aliases, false);
        if (e->levels) fprintf(out, ",\"levels\":%d", e->levels);
        fputc('}', out);
    }
    fputs("]}", out);
}

/* ---- text ---- */

static void tval(char *buf, size_t size, const Val *v) {
    if (v->kind == V_NUM) snprintf(buf, size, "%.15g", v->x[0]);
    else if (v->kind == V_TEXT) snprintf(buf, size, "%s", v->text);
    else if (v->kind == V_LIST) {
        size_t k = 0;
        buf[0] = 0;
        for (int i = 0; i < v->n && k < size; i++) k += (size_t)snprintf(buf + k, size - k, "%s%.15g", i ? " " : "", v->x[i]);
    } else
        snprintf(buf, size, "-");
}

static void text_model(FILE *out, const DModel *m) {
    fprintf(out, "%s (%s, line %d)\n", m->name, m->kind, m->line);
    for (int i = 0; i < m->n; i++) {
        const Entry *e = &m->e[i];
        char val[300], def[300], range[96] = "";
        tval(val, sizeof val, &e->val);
        tval(def, sizeof def, &e->def);
        if (e->type == SCH_ENUM && e->words) snprintf(range, sizeof range, "%s", e->words);
        else if (!isnan(e->lo) || !isnan(e->hi)) {
            char lo[32] = "-inf", hi[32] = "inf";
            if (!isnan(e->lo)) snprintf(lo, sizeof lo, "%g", e->lo);
            if (!isnan(e->hi)) snprintf(hi, sizeof hi, "%g", e->hi);
            snprintf(range, sizeof range, "%s .. %s", lo, hi);
        }
        fprintf(out, "  %-24s %-8s %-14s %-24s default %-12s %s%s%s%s\n", e->name, sch_type_name(e->type), val,
                range, def, e->unit, *e->unit ? "; " : "", e->doc, "");
    }
}

/* One model's entries (the written-th), then freed. */
static void emit(FILE *out, DModel *m, bool json, int written) {
    if (json) {
        if (written) fputs(",\n", out);
        json_model(out, m);
    } else {
        if (written) fputc('\n', out);
        text_model(out, m);
    }
    free(m->e);
}

/* Every model of the file, p's own first in file order, then the file's scene. */
static int describe(const SylProgram *p, FILE *out, bool json) {
    size_t len = 0;
    const char *src = syl_program_source(p, &len);
    const char *names[256];
    char buf[8192];
    int n = syl_model_list(syl_program_path(p), src, len, names, 256, buf, sizeof buf);
    if (n == 0) names[0] = syl_program_name(p), n = 1;
    if (json) {
        fputs("{\"file\":", out);
        jstr(out, syl_program_path(p));
        fputs(",\"models\":[", out);
    }
    int written = 0;
    for (int i = 0; i < n; i++) {
        int status;
        const SylProgram *q = p;
        SylProgram *own = NULL;
        if (strcmp(names[i], syl_program_name(p))) q = own = syl_compile_model(p, names[i], NULL, &status);
        if (!q) continue;
        DModel m = {0};
        describe_model(q, &m);
        emit(out, &m, json, written++);
        syl_program_free(own);
    }
    int nscene;
    if (!lang_kind_is(p->kind, KF_UNNAMED) && syl_program_scene(p, &nscene)) { /* the file's scene, last */
        DModel m = {.name = "scene", .kind = lang_kind_keyword(SYL_MODEL_SCENE), .id = SYL_MODEL_SCENE, .line = p->scene_loc.first_line};
        describe_scene(p, lang_kind_schema(SYL_MODEL_SCENE), &m);
        emit(out, &m, json, written);
    }
    if (json) fputs("]}\n", out);
    return ferror(out) ? SYL_EIO : SYL_OK;
}

int syl_describe_json(const SylProgram *p, FILE *out) { return describe(p, out, true); }
int syl_describe_text(const SylProgram *p, FILE *out) { return describe(p, out, false); }

/* ---- the reference of every table, for docs/directives.md (tests/unit/test_schema.c keeps
 * the doc equal to it; tools/gen-directives writes it) ---- */

static void md_cell(FILE *out, const char *s) {
    for (; s && *s; s++) {
        if (*s == '|') fputc('\\', out);
        fputc(*s, out);
    }
}

static void md_table(FILE *out, const SchTable *t) {
    fprintf(out, "\n## `%s` %ss\n\n%s\n\n| name | type | range | default | unit | meaning |\n|---|---|---|---|---|---|\n",
            t->kind, t->noun, t->intro);
    for (int i = 0; i < t->n; i++) {
        const SchRow *r = &t->rows[i];
        char range[96] = "", def[96] = "";
        if (r->type == SCH_ENUM && r->words) snprintf(range, sizeof range, "%s", r->words);
        else if ((r->type == SCH_NUMBER || r->type == SCH_INTEGER || r->levels || r->type == SCH_LIST ||
                  r->type == SCH_VECTOR) && !(r->lo == 0 && r->hi == 0))
            sch_range_text(r, range, sizeof range);
        Val v;
        row_default(r, &v);
        tval(def, sizeof def, &v);
        fprintf(out, "| `%s%s`%s%s%s | %s%s | ", r->levels ? "N" : "", r->name, r->group ? " (" : "",
                r->group ? r->group : "", r->group ? ")" : "",
                r->levels ? "list per level of " : "", sch_type_name(r->type));
        md_cell(out, range);
        fputs(" | ", out);
        md_cell(out, def);
        fprintf(out, " | %s | ", r->unit ? r->unit : "");
        md_cell(out, r->doc);
        fputs(" |\n", out);
    }
}

void lang_directives_reference(FILE *out) {
    fputs("# Directives: the reference tables\n\n"
          "Generated from the tables the readers check lines and `--set` against (src/lang/settings.def, and\n"
          "each kind's src/FOLDER/params.def, made a table by src/FOLDER/schema.inc) by `tools/gen-directives`;\n"
          "do not edit by hand (`build/tests/test_schema` fails when this file and the tables differ).\n"
          "`sylva describe FILE` prints the same rows with a model's values ([cli.md](cli.md#sylva-describe)).\n"
          "A range is written `[lo, hi]`, `(` `)` for an open end; `-` is no default.\n",
          out);
    for (int k = 0; k < LANG_KIND_COUNT; k++) /* in the kinds' order, each by its table */
        if (lang_kind_schema((SylModelKind)k)) md_table(out, lang_kind_schema((SylModelKind)k));
}
