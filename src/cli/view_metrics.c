/* sylva view: the Numbers panel's form figures — what `sylva compare` measures (syl_metrics_compute:
 * height, crown, Strahler orders, stems by branch order, leaves, light interception, …) — of
 * the last build's plant. They are asked for after the frame is drawn (/api/metrics), so the
 * ray casting of light interception never delays the save → frame path. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/view.h"
#include "sylva/metrics.h"
#include "util/json.h"

static void number(FILE *f, double v, bool integer) {
    if (isnan(v) || isinf(v)) fputs("null", f);
    else if (integer && v == floor(v) && fabs(v) < 1e15) fprintf(f, "%.0f", v);
    else fprintf(f, "%.9g", v);
}

/* {"metrics":[{"key","label","unit","value"}…],"stems_by_order":[…],"leaves":N}: the rows of
 * `sylva compare --json` for one run (a per-order metric from order 1 to Strahler - 1). */
static char *metrics_json(const SylMetrics *m) {
    char *s = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&s, &n);
    if (!f) return NULL;
    fputs("{\"metrics\":[", f);
    int first = 1;
    for (int k = 0; k < syl_metrics_count; k++) {
        const SylMetricInfo *mi = &syl_metrics_info[k];
        int from = mi->per_order ? 1 : 0, to = mi->per_order ? (int)m->strahler : 1;
        for (int o = from; o < to; o++) {
            char key[80], label[80];
            snprintf(key, sizeof key, mi->per_order ? "%s_%d" : "%s", mi->key, o);
            if (mi->per_order) snprintf(label, sizeof label, "%s %d:%d", mi->label, o, o + 1);
            else snprintf(label, sizeof label, "%s", mi->label);
            fputs(first ? "{\"key\":" : ",{\"key\":", f);
            first = 0;
            json_string_file(f, key);
            fputs(",\"label\":", f);
            json_string_file(f, label);
            fputs(",\"unit\":", f);
            json_string_file(f, mi->unit);
            fputs(",\"value\":", f);
            number(f, syl_metrics_value(m, k, o), mi->integer);
            fputc('}', f);
        }
    }
    fputs("],\"stems_by_order\":[", f);
    for (int k = 0; k < m->stem_orders; k++) {
        fputs(k ? "," : "", f);
        number(f, m->stems_by_order[k], true);
    }
    fputs("],\"leaves\":", f);
    number(f, m->leaves, true);
    fputs("}", f);
    fclose(f);
    return s;
}

static void kept_free(ViewKept *k) {
    if (!k) return;
    syl_plant_free(&k->pl);
    syl_budget_free(k->budget); /* after the arrays counted against it */
    free(k);
}

/* Let the kept plant go: now, or when the metrics measuring it are done. */
static void drop(View *v) {
    ViewKept *k = v->kept;
    v->kept = NULL;
    if (k && k->refs) k->dropped = true;
    else kept_free(k);
}

void view_keep_free(View *v) {
    pthread_mutex_lock(&v->keep_lock);
    drop(v);
    pthread_mutex_unlock(&v->keep_lock);
}

void view_keep(View *v, unsigned id, SylPlant *pl, SylBudget **budget) {
    ViewKept *k = malloc(sizeof *k);
    pthread_mutex_lock(&v->keep_lock);
    drop(v);
    if (k) {
        *k = (ViewKept){.pl = *pl, .budget = *budget, .id = id};
        memset(pl, 0, sizeof *pl);
        *budget = NULL;
        v->kept = k;
    } /* else *pl stays the caller's to free */
    pthread_mutex_unlock(&v->keep_lock);
}

static ViewBuild *entry(View *v, unsigned id) {
    for (int i = 0; i < VIEW_CACHE; i++)
        if (id && v->cache[i].id == id && !v->cache[i].status) return &v->cache[i];
    return NULL;
}

char *view_metrics(View *v, unsigned id, char **diag) {
    *diag = NULL;
    pthread_mutex_lock(&v->lock);
    ViewBuild *b = entry(v, id);
    char *s = b && b->metrics ? strdup(b->metrics) : NULL;
    pthread_mutex_unlock(&v->lock);
    if (s || !b) return s;
    pthread_mutex_lock(&v->keep_lock);
    ViewKept *k = v->kept && v->kept->id == id && v->kept->pl.skeleton ? v->kept : NULL;
    if (k) k->refs++;
    pthread_mutex_unlock(&v->keep_lock);
    if (!k) return NULL;
    size_t dl = 0;
    FILE *df = open_memstream(diag, &dl);
    SylMetrics m;
    SylMetricsOptions o = {.mesh = k->pl.mesh, .threads = v->threads, .diag = df};
    if (df && !syl_metrics_compute(k->pl.skeleton, &o, &m)) s = metrics_json(&m);
    if (df) fclose(df);
    pthread_mutex_lock(&v->keep_lock);
    if (!--k->refs && k->dropped) kept_free(k);
    pthread_mutex_unlock(&v->keep_lock);
    pthread_mutex_lock(&v->lock);
    if (s && (b = entry(v, id)) && !b->metrics) b->metrics = strdup(s);
    pthread_mutex_unlock(&v->lock);
    return s;
}
