/* The compiled Program: its accessors (sylva.h) and its freeing. */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "lang/program.h"
#include "lang/schema.h"
#include "util/diag.h"

void syl_program_free(SylProgram *p) {
    if (!p) return;
    if (p->read_cache) free(p->read_cache->value);
    arena_free(&p->arena);
    free(p->text);
    free(p);
}

const char *syl_program_name(const SylProgram *p) { return p->name; }
SylModelKind syl_program_kind(const SylProgram *p) { return p->kind; }

const Curve *lang_curve_find(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->ncurves; i++)
        if (p->curves[i].n && !strcmp(p->curves[i].name, name)) return &p->curves[i];
    return NULL;
}
const char *syl_program_path(const SylProgram *p) { return p->src.path; }
const char *syl_program_source(const SylProgram *p, size_t *len) {
    *len = p->src.len;
    return p->src.text;
}

const SylDirective *syl_program_directives(const SylProgram *p, int *n) {
    *n = p->ndirectives;
    return p->directives;
}

const SylDirective *syl_program_scene(const SylProgram *p, int *n) {
    *n = p->nscene;
    return p->has_scene ? p->scene : NULL;
}

/* A message at (line, col) of the program's source, with the line and a caret. */
static void report_at(const SylProgram *p, FILE *out, const SylSink *sink, int severity, int line, int col,
                      const char *fmt, va_list ap) {
    char msg[1024];
    vsnprintf(msg, sizeof msg, fmt, ap);
    Diag d = {.out = out, .sink = program_sink(p) ? program_sink(p) : sink, .src = &p->src};
    diag_report(&d, severity, ((SylLoc){line, col, line, col}), "%s", msg);
}

void syl_program_report_error(const SylProgram *p, FILE *out, int line, int col, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    report_at(p, out, NULL, DIAG_ERROR, line, col, fmt, ap);
    va_end(ap);
}
void program_error_to(const SylProgram *p, const SylSink *sink, int line, int col, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    report_at(p, NULL, sink, DIAG_ERROR, line, col, fmt, ap);
    va_end(ap);
}
static void directive_verror(const SylProgram *p, FILE *out, const SylSink *sink, const SylDirective *d,
                             const SylDirArg *a, const char *fmt, va_list ap) {
    int line = a ? a->line : d->line, col = a ? a->col : d->col;
    if (d->file) { /* spliced from another file: its path and its line */
        char msg[1024];
        vsnprintf(msg, sizeof msg, fmt, ap);
        Source src = {.path = d->file, .text = d->file_text, .len = d->file_len};
        Diag dg = {.out = out, .sink = program_sink(p) ? program_sink(p) : sink, .src = &src};
        diag_report(&dg, DIAG_ERROR, ((SylLoc){line, col, line, col}), "%s", msg);
    } else {
        report_at(p, out, sink, DIAG_ERROR, line, col, fmt, ap);
    }
}
void syl_directive_report_error(const SylProgram *p, FILE *out, const SylDirective *d, const SylDirArg *a,
                                const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    directive_verror(p, out, NULL, d, a, fmt, ap);
    va_end(ap);
}
void directive_error_to(const SylProgram *p, const SylSink *sink, const SylDirective *d, const SylDirArg *a,
                        const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    directive_verror(p, NULL, sink, d, a, fmt, ap);
    va_end(ap);
}
void program_warning(const SylProgram *p, FILE *out, int line, int col, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    report_at(p, out, NULL, DIAG_WARNING, line, col, fmt, ap);
    va_end(ap);
}
void program_say(const SylProgram *p, FILE *out, int severity, const char *path, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    diag_vsay(out, p ? program_sink(p) : NULL, severity, path, fmt, ap);
    va_end(ap);
}
void program_say_to(const SylProgram *p, const SylSink *sink, int severity, const char *path, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    diag_vsay(NULL, p && program_sink(p) ? program_sink(p) : sink, severity, path, fmt, ap);
    va_end(ap);
}
int syl_program_steps(const SylProgram *p) { return p->derive; }
uint64_t syl_program_seed(const SylProgram *p) { return p->seed; }
int syl_program_symbol_count(const SylProgram *p) { return p->nsyms; }
const char *syl_program_symbol_name(const SylProgram *p, int sym) {
    return sym >= 0 && sym < p->nsyms ? p->syms[sym].name : NULL;
}
int syl_program_symbol_find(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nsyms; i++)
        if (!strcmp(p->syms[i].name, name)) return i;
    return -1;
}
double syl_program_setting(const SylProgram *p, const char *name) {
    if (!strcmp(name, "angle")) return p->angle;
    if (!strcmp(name, "step")) return p->step;
    if (!strcmp(name, "width")) return p->width;
    if (!strcmp(name, "derive")) return p->derive;
    if (!strcmp(name, "widthfactor")) return p->widthfactor;
    if (!strcmp(name, "lod")) return syl_kind_has_directives(p->kind) ? lang_directive_lod(p) : p->lod;
    return NAN;
}
