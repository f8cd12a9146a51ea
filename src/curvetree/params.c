/* Reading a `curvetree` block: each line checked against its row of params.def by the schema
 * reader (lang/schema.c): names and did-you-mean, numbers and ranges, --set NAME=VALUE. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curvetree/curvetree.h"
#include "lang/program.h"
#include "lang/schema.h"
#include "lang/textures.h"

typedef struct Num {
    const char *name;
    size_t off;
} Num;
static const Num nums[] = {
#define CT_N(f, nm, ty, l, h, d, u, mean) {nm, offsetof(CtParams, f)},
#include "curvetree/params.def"
};
enum { NNUMS = sizeof nums / sizeof *nums };

static double *slot(CtParams *P, const char *name) {
    for (int i = 0; i < NNUMS; i++)
        if (!strcmp(nums[i].name, name)) return (double *)((char *)P + nums[i].off);
    return NULL;
}

static void defaults(CtParams *P) {
    memset(P, 0, sizeof *P);
    for (int i = 0; i < NNUMS; i++) *slot(P, nums[i].name) = sch_find(&sch_curvetree, nums[i].name, NULL)->def[0];
}

static bool is_param(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nparams; i++)
        if (!strcmp(p->params[i].name, name)) return true;
    return false;
}

/* A file name in quotes (envelope). */
static int read_file_line(const SylProgram *p, const SylDirective *d, FILE *diag, const char *what,
                          const SylDirective **at) {
    if (d->nargs != 1 || d->args[0].kind != SYL_DARG_STRING) {
        syl_directive_error(p, diag, d, d->nargs ? &d->args[d->nargs > 1 ? 1 : 0] : NULL,
                            "%s takes one file name in quotes (%s)", d->name, what);
        return 1;
    }
    *at = d;
    return 0;
}

static int read_all(const SylProgram *p, void *params, FILE *diag, int *set_errors) {
    CtParams *P = params;
    defaults(P);
    sch_count_read(p);
    int n = 0, errors = 0;
    const SylDirective *ds = syl_program_directives(p, &n);
    const SylDirective *seen[64] = {0};
    for (int i = 0; i < n; i++) {
        const SylDirective *d = &ds[i];
        if (lang_texture_line(d->name)) continue; /* lang/textures.c reads it */
        const SchRow *row = sch_find(&sch_curvetree, d->name, NULL);
        if (!row) {
            char near[480];
            sch_suggest(&sch_curvetree, d->name, near, sizeof near);
            syl_directive_error(p, diag, d, NULL, "a curvetree block has no parameter '%s'%s", d->name,
                                near[0] ? near : " (docs/curvetree.md lists them)");
            errors++;
            continue;
        }
        int k = (int)(row - sch_curvetree.rows);
        if (seen[k]) {
            syl_directive_error(p, diag, d, NULL, "'%s' is given twice (first on line %d)", d->name, seen[k]->line);
            errors++;
            continue;
        }
        seen[k] = d;
        if (!strcmp(row->name, "lod")) errors += lang_lod_check(p, d, diag); /* sylva mesh reads it */
        else if (!strcmp(row->name, "envelope"))
            errors += read_file_line(p, d, diag, "a closed mesh in an .obj file", &P->envelope_at);
        else if (!strcmp(row->name, "trunk")) {
            CtCurve c;
            int st = ct_curve_of_directive(p, d, false, &c, diag); /* the inline forms; a file at build */
            ct_curve_free(&c);
            if (st) errors++;
            else P->trunk_at = d;
        } else {
            double x;
            char why[160];
            if (d->nargs != 1 || !sch_number(&d->args[0], &x)) {
                syl_directive_error(p, diag, d, d->nargs ? &d->args[d->nargs > 1 ? 1 : 0] : NULL,
                                    "%s takes one number", d->name);
                errors++;
            } else if (!sch_value_ok(row, x, why, sizeof why)) {
                syl_directive_error(p, diag, d, &d->args[0], "%s %s", d->name, why);
                errors++;
            } else
                *slot(P, row->name) = x;
        }
    }
    if (!P->trunk_at && !errors) {
        syl_program_error(p, diag, p->model_loc.first_line, p->model_loc.first_column,
                          "curvetree block '%s' has no trunk: write `trunk bezier (x,y,z) ...`, `trunk polyline ...` "
                          "or `trunk \"curve.obj\"`",
                          syl_program_name(p));
        errors++;
    }
    if (!P->envelope_at && !errors) {
        syl_program_error(p, diag, p->model_loc.first_line, p->model_loc.first_column,
                          "curvetree block '%s' has no envelope: write `envelope \"crown.obj\"`, a closed mesh",
                          syl_program_name(p));
        errors++;
    }
    /* --set NAME=VALUE over the lines (the last one wins); a param takes its own value */
    int before = errors;
    for (int i = 0; i < p->noverrides; i++) {
        const char *name = p->set_local ? p->set_local[i] : NULL;
        if (!name || is_param(p, name)) continue;
        if (!strcmp(name, "lod")) {
            errors += lang_lod_set_check(p, p->overrides[i].value, p->overrides[i].name, diag);
            continue;
        }
        const SchRow *row;
        int level;
        if (p->sibling && !sch_find(&sch_curvetree, name, &level)) continue; /* meant for another model */
        if (sch_set_check(p, diag, &sch_curvetree, p->overrides[i].name, name, p->overrides[i].value, &row, &level))
            errors++;
        else
            *slot(P, row->name) = p->overrides[i].value;
    }
    *set_errors = errors - before;
    return errors;
}

int ct_params_read(const SylProgram *p, CtParams *P, FILE *diag) {
    return sch_read_once(p, P, sizeof *P, read_all, diag);
}

int ct_params_check(const SylProgram *p, FILE *diag) {
    CtParams P;
    return sch_check_once(p, &P, sizeof P, read_all, diag);
}
