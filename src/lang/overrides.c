/* --set NAME=VALUE: which model a name is meant for, and what in it the value replaces. */
#include <string.h>

#include "lang/compiler.h"
#include "lang/kinds.h"
#include "util/closest.h"

/* "Birch.lambda" is meant for the model Birch when the file has one of that name, and
 * "scene.ground" for the file's scene (no model); any other name, dotted or not
 * ("tropism.2", "allocate.lambda"), for every model that has it. */
void cc_localise_overrides(Compiler *c) {
    SylProgram *p = c->p;
    if (!p->noverrides) return;
    p->set_local = arena_alloc(&p->arena, sizeof *p->set_local * (size_t)p->noverrides);
    for (int i = 0; i < p->noverrides; i++) {
        const char *name = p->overrides[i].name, *dot = strchr(name, '.');
        p->set_local[i] = name;
        for (int m = 0; dot && c->ast && m < c->ast->nmodels; m++) {
            const char *mn = c->ast->models[m].name;
            if (strlen(mn) == (size_t)(dot - name) && !strncmp(mn, name, (size_t)(dot - name)))
                /* scene.ground: the scene's reader takes it (scene/spec.c) */
                p->set_local[i] = strcmp(mn, p->name) || lang_kind_is(c->ast->models[m].kind, KF_UNNAMED) ? NULL : dot + 1;
        }
    }
}

const SylOverride *cc_find_override(Compiler *c, const char *name) {
    const SylProgram *p = c->p;
    for (int i = p->noverrides - 1; i >= 0; i--)
        if (p->set_local[i] && !strcmp(p->set_local[i], name)) return &p->overrides[i];
    return NULL;
}

static bool is_param(Compiler *c, const char *name) {
    int id = namemap_get(&c->values, name, -1);
    return id >= 0 && c->vals[id].is_param;
}

/* "model 'A' has no parameter or setting 'angel' (did you mean 'angle'?)" */
static void unknown(Compiler *c, const char *typed, const char *local) {
    SylProgram *p = c->p;
    const char *names[256];
    int n = 0;
    for (int i = 0; i < c->nvals && n < 200; i++)
        if (c->vals[i].is_param) names[n++] = c->vals[i].name;
    if (!syl_kind_has_directives(p->kind)) n += cc_setting_names(names + n, 256 - n);
    char near[256];
    int k = closest_list(local, names, n, near, sizeof near);
    const char *dot = strchr(typed, '.');
    char model[256] = "";
    for (int m = 0; !k && dot && c->ast && m < c->ast->nmodels; m++) { /* Brich.lambda */
        char prefix[128];
        snprintf(prefix, sizeof prefix, "%.*s", (int)(dot - typed), typed);
        if (closest_near(prefix, c->ast->models[m].name))
            snprintf(model, sizeof model, " (no model '%s' in this file: did you mean '%s%s'?)", prefix,
                     c->ast->models[m].name, dot);
    }
    int id = namemap_get(&c->values, local, -1);
    diag_error(c->d, (SylLoc){0}, "--set %s: model '%s' has no %s '%s'%s%s%s%s", typed, p->name,
               syl_kind_has_directives(p->kind) ? "parameter" : "parameter or setting", local,
               id >= 0 ? " (it is a const; declare it with `param` to set it)" : "", k ? " (did you mean " : "",
               k ? near : "", k ? "?)" : model);
    c->usage_error = true;
}

/* Every name meant for this model is a param, or a setting of an L-system; a grow block's
 * directives are checked by its reader (sot/params.c), which knows them. A sibling's
 * names are the other model's. */
void cc_check_overrides(Compiler *c) {
    SylProgram *p = c->p;
    if (c->opt->sibling) return;
    for (int i = 0; i < p->noverrides; i++) {
        const char *local = p->set_local[i];
        if (!local || is_param(c, local)) continue;
        if (syl_kind_has_directives(p->kind) && namemap_get(&c->values, local, -1) < 0) continue;
        if (!syl_kind_has_directives(p->kind) && !strncmp(local, "colour.", 7)) continue; /* colour.I.r: applied and checked there */
        const char *names[64];
        int n = syl_kind_has_directives(p->kind) ? 0 : cc_setting_names(names, 64), j = 0;
        while (j < n && strcmp(names[j], local)) j++;
        if (j == n) unknown(c, p->overrides[i].name, local);
    }
}

/* The settings: over the model's own lines, in the order given (the last one wins). A param
 * of the same name takes the value instead (cc_evaluate). */
void cc_apply_overrides(Compiler *c) {
    SylProgram *p = c->p;
    if (syl_kind_has_directives(p->kind)) return;
    for (int i = 0; i < p->noverrides; i++) {
        const char *local = p->set_local[i];
        if (local && !is_param(c, local) && cc_setting_override(c, local, p->overrides[i].value, p->overrides[i].name) == 0)
            c->usage_error = true;
    }
}
