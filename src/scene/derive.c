/* syl_derive and syl_derive_begin: the engine's deriver with the caller's query environment,
 * or the stand-alone one (the plant alone on the ground) when the caller gives none. */
#include <stdlib.h>

#include "lang/program.h"
#include "lsys/derive.h"
#include "scene/open.h"
#include "turtle/turtle.h"

/* ?P ?H ?L ?U without ?E: the turtle's query pass is the whole environment. */
static int turtle_only(void *user, const SylProgram *p, SylString *s, int step) {
    (void)user;
    (void)step;
    return syl_turtle_query(p, s, NULL);
}

static const SylQueryOps turtle_ops = {.fill = turtle_only};

static void release_standalone(void *user) { syl_env_standalone_free(user); }

int syl_derive_begin(const SylProgram *p, SylDeriveOptions *opt, const SylString *start, SylDeriver **out) {
    LsysQueries q = {0};
    if (opt && opt->queries) q = (LsysQueries){.ops = opt->queries, .user = opt->queries_user};
    else if (lang_kind_is(p->kind, KF_RULES) && p->uses_env) {
        q = (LsysQueries){.ops = syl_env_standalone_ops(), .release = release_standalone,
                          .user = syl_env_standalone_new(p, program_sink(p) ? program_sink(p) /* as the derivation's */
                                                            : diag_sink(&(SylSink){0}, opt ? opt->diag : NULL, NULL))};
        if (!q.user) {
            *out = NULL;
            if (opt) program_say(p, opt->diag, DIAG_ERROR, NULL, "step 0: out of memory");
            return SYL_ELIMIT;
        }
    } else if (p->uses_queries) q.ops = &turtle_ops;
    return lsys_derive_begin(p, opt, start, &q, out);
}

int syl_derive(const SylProgram *p, SylDeriveOptions *opt, SylString **out) {
    SylDeriveOptions defaults = {.steps = -1};
    if (!opt) opt = &defaults;
    *out = NULL;
    SylDeriver *d;
    int st = syl_derive_begin(p, opt, NULL, &d);
    int steps = opt->steps >= 0 ? opt->steps : p->derive;
    for (int step = 1; step <= steps && !st; step++) st = syl_derive_step(d);
    if (!d) return st;
    return syl_derive_end(d, out);
}
