/* Reading a `curvetree` block: the schema's reader of NAME VALUE lines (lang/schema_lines.c)
 * with params.def's rows; what is curvetree's own is here: where each value is kept, the
 * trunk's curve, the messages' words, and that a trunk and an envelope are given. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "curvetree/curvetree.h"
#include "lang/program.h"
#include "lang/schema.h"

#define CT_OFF_KIND(f) 0
#define CT_OFF_NONE(f) 0
#define CT_OFF_LINE(f) offsetof(CtParams, f)
static const SchSlot slots[] = {
#define CT_N(f, ...) {.store = SCH_AT_F64, .off = offsetof(CtParams, f)},
#define CT_X(at, f, ...) {.store = SCH_AT_##at, .off = CT_OFF_##at(f)},
#include "curvetree/params.def"
};

/* The words of curvetree's messages (the reader's own where none). */
static void say(SchProblem *pr, char *buf, size_t size) {
    bool file = pr->row && pr->row->type == SCH_FILE;
    switch (pr->what) {
    case SCH_BAD_UNKNOWN:
        snprintf(buf, size, "a curvetree block has no parameter '%s'%s", pr->name,
                 pr->hint[0] ? pr->hint : " (docs/curvetree.md lists them)");
        break;
    case SCH_BAD_COUNT:
    case SCH_BAD_FILE:
        if (file) snprintf(buf, size, "%s takes one file name in quotes (a closed mesh in an .obj file)", pr->name);
        else snprintf(buf, size, "%s takes one number", pr->name);
        break;
    case SCH_BAD_NUMBER: snprintf(buf, size, "%s takes one number", pr->name); break;
    default: break;
    }
}

/* The trunk: its inline forms checked now, a file at build. */
static int trunk_line(SchLineRead *r, const SchRow *row, const SylDirective *d, void *base) {
    (void)row;
    CtCurve c;
    int st = ct_curve_of_directive(sch_lines_program(r), d, false, &c, sch_lines_diag(r));
    ct_curve_free(&c);
    if (st) return 1;
    ((CtParams *)base)->trunk_at = d;
    return 0;
}

/* A trunk and an envelope must be given (when the lines are otherwise right). */
static int must_give(SchLineRead *r, void *base) {
    const CtParams *P = base;
    const SylProgram *p = sch_lines_program(r);
    FILE *diag = sch_lines_diag(r);
    int line = p->model_loc.first_line, col = p->model_loc.first_column;
    if (sch_lines_errors(r)) return 0;
    if (!P->trunk_at) {
        syl_program_report_error(p, diag, line, col,
                                 "curvetree block '%s' has no trunk: write `trunk bezier (x,y,z) ...`, `trunk polyline ...` "
                                 "or `trunk \"curve.obj\"`",
                                 syl_program_name(p));
        return 1;
    }
    if (!P->envelope_at) {
        syl_program_report_error(p, diag, line, col,
                                 "curvetree block '%s' has no envelope: write `envelope \"crown.obj\"`, a closed mesh",
                                 syl_program_name(p));
        return 1;
    }
    return 0;
}

static const SchLines ct_lines = {
    .t = &sch_curvetree,
    .slots = slots,
    .nslots = (int)(sizeof slots / sizeof *slots),
    .textures = true,
    .say = say,
    .line = trunk_line,
    .lines_done = must_give,
};

static int read_all(const SylProgram *p, void *params, FILE *diag, int *set_errors) {
    CtParams *P = params;
    memset(P, 0, sizeof *P);
    sch_lines_defaults(&ct_lines, P);
    sch_count_read(p);
    return sch_read_lines(p, &ct_lines, P, diag, set_errors);
}

int ct_params_read(const SylProgram *p, CtParams *P, FILE *diag) {
    return sch_read_once(p, P, sizeof *P, read_all, diag);
}

int ct_params_check(const SylProgram *p, FILE *diag) {
    CtParams P;
    return sch_check_once(p, &P, sizeof P, read_all, diag);
}
