/* The `lod N` line of a block of directives (grow, weber, strands): the levels of detail
 * `sylva mesh` writes, as an lsystem's `lod` setting asks (settings.c). One range and one
 * message for every kind of block. */
#include <math.h>
#include <string.h>

#include "lang/kinds.h"
#include "lang/program.h"
#include "lang/schema.h"
#include "sylva/lod.h"

/* Its one value: a number, or (expr), which arrives evaluated as a one-value tuple. */
static bool lod_value(const SylDirective *d, double *v) {
    if (d->nargs != 1) return false;
    return sch_number(&d->args[0], v);
}

static bool lod_ok(double v) { return v >= 0 && v <= SYL_LOD_MAX && v == floor(v); }

int lang_lod_check(const SylProgram *p, const SylDirective *d, FILE *diag) {
    double v;
    if (lod_value(d, &v) && lod_ok(v)) return 0;
    const SylDirArg *a = d->nargs ? &d->args[d->nargs > 1 ? 1 : 0] : NULL;
    if (d->nargs == 1 && lod_value(d, &v))
        syl_directive_report_error(p, diag, d, a, "'lod' expects a whole number from 0 to %d, not %g", SYL_LOD_MAX, v);
    else
        syl_directive_report_error(p, diag, d, a, "'lod' takes one value, a whole number from 0 to %d", SYL_LOD_MAX);
    return 1;
}

int lang_lod_set_check(const SylProgram *p, double v, const char *typed, FILE *diag) {
    if (lod_ok(v)) return 0;
    syl_program_report_error(p, diag, 0, 0, "--set %s: 'lod' expects a whole number from 0 to %d, not %g", typed, SYL_LOD_MAX, v);
    return 1;
}

/* The block's last `lod` line, then the last --set lod= (unless `lod` is a param, whose
 * value the line then has already): scanned once, by syl_compile (lang_keep_lod), and kept. */
double lang_directive_lod(const SylProgram *p) {
    if (p->read_cache && p->read_cache->lod_kept) return p->read_cache->lod;
    if (p->read_cache) p->read_cache->lod_scans++;
    double v = 0, x;
    for (int i = 0; i < p->ndirectives; i++)
        if (!strcmp(p->directives[i].name, "lod") && lod_value(&p->directives[i], &x)) v = x;
    bool param = false;
    for (int i = 0; i < p->nparams; i++) param |= !strcmp(p->params[i].name, "lod");
    for (int i = 0; i < p->noverrides && !param; i++)
        if (p->set_local && p->set_local[i] && !strcmp(p->set_local[i], "lod")) v = p->overrides[i].value;
    return lod_ok(v) ? v : 0;
}

void lang_keep_lod(SylProgram *p) {
    if (!p->read_cache || !lang_kind_is(p->kind, KF_DIRECTIVES)) return;
    p->read_cache->lod = lang_directive_lod(p);
    p->read_cache->lod_kept = true;
}
