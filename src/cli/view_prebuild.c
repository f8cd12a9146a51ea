/* sylva view: a save's build started at once. The first build the pages asked for after the
 * previous change (a preview, or the full mesh of a plant quick to build) is built again as soon
 * as the files change, while the change's event travels to the pages: their request then finds
 * it in the cache, or waits for it on the build lock, instead of only starting it. */
#include <string.h>

#include "cli/view.h"

/* Its --set names point into the request itself: a copy points into its own. */
static void copy_request(ViewRequest *to, const ViewRequest *from) {
    *to = *from;
    for (int i = 0; i < to->nsets; i++) to->sets[i].name = to->names[i];
}

void view_first_request(View *v, const ViewRequest *rq, const char *key) {
    pthread_mutex_lock(&v->gen_lock);
    if (!v->first.any || v->first.gen != v->gen) {
        v->first.any = true;
        v->first.gen = v->gen;
        /* an edited text (plants placed by clicks) is the page's alone: nothing is built ahead */
        v->first.have = !rq->text && strlen(key) < sizeof v->first.key;
        if (v->first.have) {
            copy_request(&v->first.rq, rq);
            v->first.rq.tab = 0; /* built for whichever page asks: never stopped as replaced */
            snprintf(v->first.key, sizeof v->first.key, "%s", key);
        }
    }
    pthread_mutex_unlock(&v->gen_lock);
}

static void *run(void *arg) {
    View *v = arg;
    pthread_mutex_lock(&v->gen_lock);
    unsigned seen = v->gen;
    for (;;) {
        while (!v->stopping && v->gen == seen) pthread_cond_wait(&v->changed, &v->gen_lock);
        if (v->stopping) break;
        seen = v->gen;
        if (!v->first.have) continue;
        ViewRequest rq;
        char key[sizeof v->first.key];
        copy_request(&rq, &v->first.rq);
        memcpy(key, v->first.key, sizeof key);
        pthread_mutex_unlock(&v->gen_lock);
        pthread_mutex_lock(&v->lock);
        view_build(v, &rq, key); /* kept in the cache for the files' generation it saw */
        pthread_mutex_unlock(&v->lock);
        pthread_mutex_lock(&v->gen_lock);
    }
    pthread_mutex_unlock(&v->gen_lock);
    return NULL;
}

bool view_prebuild_start(View *v, pthread_t *thread) { return pthread_create(thread, NULL, run, v) == 0; }
