/* A weber block's `from "species.xml" [Name]`: the parameters of another file's weber model
 * (an Arbaro species file, usually) go before the block's own lines, which override them.
 * Each spliced line keeps its file, so that an error in its value names that file and shows
 * its line (SylDirective.file, syl_directive_report_error). */
#include <errno.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

#include "lang/compiler.h"
#include "util/file.h"

static const Source *read_source(Compiler *c, const char *path, SylLoc at) {
    size_t len;
    char *text = file_read_named(path, &len, NULL);
    if (!text) {
        int e = errno; /* before the message, which may change it */
        char shown[256];
        diag_error(c->d, at, "cannot read '%s': %s", diag_quote(shown, sizeof shown, path, strlen(path)),
                   file_strerror(e));
        return NULL;
    }
    Arena *pa = &c->p->arena;
    Source *src = arena_alloc(pa, sizeof *src);
    size_t skip = len >= 3 && !memcmp(text, "\xef\xbb\xbf", 3) ? 3 : 0; /* a byte order mark, as syl_compile */
    src->path = arena_strndup(pa, path, strlen(path));
    src->text = arena_strndup(pa, text + skip, len - skip);
    src->len = len - skip;
    free(text);
    return src;
}

/* The file's weber model: the one named, else its first. */
static const Model *pick(Compiler *c, const FileAst *fa, const char *name, const Source *src, SylLoc at) {
    for (int i = 0; i < fa->nmodels; i++)
        if (fa->models[i].kind == SYL_MODEL_WEBER && (!name || !strcmp(fa->models[i].name, name))) return &fa->models[i];
    char shown[256], names[512] = "";
    size_t used = 0;
    for (int i = 0; i < fa->nmodels && used + 2 < sizeof names; i++)
        if (fa->models[i].kind == SYL_MODEL_WEBER)
            used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", used ? ", " : "", fa->models[i].name);
    diag_quote(shown, sizeof shown, src->path, strlen(src->path));
    if (name) diag_error(c->d, at, "'%s' has no weber model '%s'%s%s%s", shown, name, used ? " (it has " : "", names, used ? ")" : "");
    else diag_error(c->d, at, "'%s' holds no weber model", shown);
    return NULL;
}

void cc_splice_from(Compiler *c, Model *m) {
    if (m->kind != SYL_MODEL_WEBER) return;
    int at = -1;
    for (int i = 0; i < m->n; i++) {
        const Stmt *s = &m->v[i];
        if (s->kind != ST_DIRECTIVE || strcmp(s->name, "from")) continue;
        if (at >= 0) diag_error(c->d, s->loc, "a weber block has one `from` line (the first is at line %d)", m->v[at].loc.first_line);
        else at = i;
    }
    if (at < 0) return;
    const Stmt *f = &m->v[at];
    const DirArgs *a = &f->dargs;
    if (a->n < 1 || a->n > 2 || a->v[0].kind != DARG_STRING || (a->n == 2 && a->v[1].kind != DARG_WORD && a->v[1].kind != DARG_STRING)) {
        diag_error(c->d, a->n ? a->v[0].loc : f->loc,
                   "`from` takes a file in quotes and, for a file of several species, a species' name: "
                   "from \"aspen.xml\" [Name]");
        return;
    }
    char *path = NULL, shown[256];
    int st = syl_program_file(c->p, a->v[0].text, &path);
    if (st == SYL_ELIMIT) longjmp(*c->tmp->oom, 1);
    if (st) {
        diag_error(c->d, a->v[0].loc, "cannot read '%s': %s", diag_quote(shown, sizeof shown, a->v[0].text, strlen(a->v[0].text)),
                   syl_file_refused);
        return;
    }
    const Source *src = read_source(c, path, a->v[0].loc);
    free(path);
    if (!src) return;
    if (!syl_text_is_model(src->text, src->len)) { /* its lines are not shown: it may be anything */
        diag_error(c->d, a->v[0].loc, "'%s' is not a species file (no weber block, no Arbaro XML)",
                   diag_quote(shown, sizeof shown, src->path, strlen(src->path)));
        return;
    }
    Diag sub = {.out = c->d->out, .sink = c->d->sink, .src = src, .max_shown = c->d->max_shown};
    FileAst fa;
    int errors = syl_parse(src, c->tmp, &sub, &fa);
    c->d->errors += sub.errors;
    c->d->warnings += sub.warnings;
    if (errors) return;
    const Model *from = pick(c, &fa, a->n == 2 ? a->v[1].text : NULL, src, a->n == 2 ? a->v[1].loc : a->v[0].loc);
    if (!from) return;
    /* the file's lines first, then the block's own but the `from` */
    Stmt *v = arena_alloc(c->tmp, sizeof *v * (size_t)(from->n + m->n));
    int n = 0;
    for (int i = 0; i < from->n; i++) {
        const Stmt *s = &from->v[i];
        if (s->kind != ST_DIRECTIVE) continue;
        if (!strcmp(s->name, "from")) {
            sub.errors = 0;
            diag_error(&sub, s->loc, "a file that `from` reads cannot itself read another with `from`");
            c->d->errors += sub.errors;
            continue;
        }
        v[n] = *s;
        v[n++].file = src;
    }
    for (int i = 0; i < m->n; i++)
        if (i != at) v[n++] = m->v[i];
    m->v = v;
    m->n = m->cap = n;
}
