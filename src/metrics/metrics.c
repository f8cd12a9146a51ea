/* syl_metrics_compute: every figure of a skeleton, and the table that names them for every output
 * (docs/compare.md). The simple sums are here; the others have files of their own. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/metrics_internal.h"
#include "util/diag.h"

#define FIELD(name) offsetof(SylMetrics, name)

/* Where each metric of syl_metrics_info lives in SylMetrics (per-order ones: SIZE_MAX). */
static const size_t offsets[] = {
    FIELD(height),       FIELD(crown_width),     FIELD(crown_depth),   FIELD(crown_volume),
    FIELD(internodes),   FIELD(tips),            FIELD(max_order),     FIELD(strahler),
    FIELD(bifurcation),  SIZE_MAX,               FIELD(total_length),  FIELD(branching_angle),
    FIELD(box_dimension), FIELD(light_interception), FIELD(biomass),
};

const SylMetricInfo syl_metrics_info[] = {
    {"height", "height", "m", "highest point above the ground (the lowest root)", 0, 0},
    {"crown_width", "crown width", "m", "largest horizontal distance between two crown points", 0, 0},
    {"crown_depth", "crown depth", "m", "highest crown point above the lowest branching node", 0, 0},
    {"crown_volume", "crown volume", "m^3", "volume of the convex hull of the crown points", 0, 0},
    {"internodes", "internodes", "", "drawn segments", 1, 0},
    {"tips", "tips", "", "segments that no segment continues", 1, 0},
    {"max_order", "max branch order", "", "highest branch order (trunk 0)", 1, 0},
    {"strahler", "Strahler order", "", "Horton-Strahler order of the plant", 1, 0},
    {"bifurcation_ratio", "bifurcation ratio", "", "Horton's ratio (N_1 / N_S)^(1 / (S - 1))", 0, 0},
    {"bifurcation_ratio", "bifurcation ratio", "", "R_b = N_i / N_(i+1), streams of Strahler order i", 0, 1},
    {"total_length", "total length", "m", "sum of the segments' lengths", 0, 0},
    {"branching_angle", "branching angle", "deg", "mean angle of a lateral to its parent's continuation", 0, 0},
    {"box_dimension", "box dimension", "", "box-counting dimension of the segments", 0, 0},
    {"light_interception", "light interception", "", "share of sky rays from under the crown that it stops", 0, 0},
    {"biomass", "biomass proxy", "m^3", "sum of radius^2 x length over the segments", 0, 0},
};
const int syl_metrics_count = (int)(sizeof syl_metrics_info / sizeof *syl_metrics_info);
_Static_assert(sizeof offsets / sizeof *offsets == sizeof syl_metrics_info / sizeof *syl_metrics_info,
               "one offset per metric");

double syl_metrics_value(const SylMetrics *m, int metric, int order) {
    if (metric < 0 || metric >= syl_metrics_count) return NAN;
    if (syl_metrics_info[metric].per_order) {
        if (order < 1 || order >= SYL_METRICS_MAX_STRAHLER || !(m->streams[order + 1] > 0)) return NAN;
        return m->streams[order] / m->streams[order + 1];
    }
    double v;
    memcpy(&v, (const char *)m + offsets[metric], sizeof v);
    return v;
}

static void report(const SylMetricsOptions *o, const char *msg) {
    sink_error(opt_sink(o), "metrics: %s", msg);
}

/* Children lists, after checking that parents precede their children. */
static int build_tree(const SylSkeleton *s, const SylMetricsOptions *o, MetricsTree *t) {
    t->s = s;
    t->first = calloc(s->nnodes + 2, sizeof *t->first);
    t->kids = malloc((s->nnodes ? s->nnodes : 1) * sizeof *t->kids);
    if (!t->first || !t->kids) {
        report(o, "out of memory");
        return SYL_ELIMIT;
    }
    for (size_t i = 0; i < s->nnodes; i++) {
        int32_t p = s->nodes[i].parent;
        if (p < -1 || p >= (int32_t)i) {
            sink_error(opt_sink(o), "metrics: node %zu has parent %d: parents must come before their children", i, p);
            return SYL_EMODEL;
        }
        if (p >= 0) t->first[p + 2]++;
    }
    for (size_t i = 0; i < s->nnodes; i++) t->first[i + 2] += t->first[i + 1];
    for (size_t i = 0; i < s->nnodes; i++) /* in increasing order: i grows */
        if (s->nodes[i].parent >= 0) t->kids[t->first[s->nodes[i].parent + 1]++] = (int32_t)i;
    return SYL_OK;
}

int syl_metrics_compute(const SylSkeleton *s, const SylMetricsOptions *opt, SylMetrics *out) {
    static const SylMetricsOptions defaults = {0};
    const SylMetricsOptions *o = opt ? opt : &defaults;
    memset(out, 0, sizeof *out);
    MetricsTree t = {0};
    int *order = NULL;
    SylMesh *own = NULL;
    int status = build_tree(s, o, &t);
    if (status) goto done;

    /* Ground, height, counts, lengths. */
    double ground = INFINITY, top = -INFINITY, low = INFINITY;
    for (size_t i = 0; i < s->nnodes; i++) {
        const SylNode *n = &s->nodes[i];
        top = fmax(top, n->pos[1]);
        low = fmin(low, n->pos[1]);
        if (n->parent < 0) {
            ground = fmin(ground, n->pos[1]);
            continue;
        }
        const SylNode *p = &s->nodes[n->parent];
        double d[3] = {(double)n->pos[0] - p->pos[0], (double)n->pos[1] - p->pos[1], (double)n->pos[2] - p->pos[2]};
        double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        out->internodes++;
        out->tips += tree_nkids(&t, i) == 0;
        out->total_length += len;
        out->biomass += (double)n->radius * n->radius * len;
        if (n->order > out->max_order) out->max_order = n->order;
    }
    for (size_t i = 0; i < s->norgans; i++) {
        top = fmax(top, s->organs[i].pos[1]);
        low = fmin(low, s->organs[i].pos[1]);
    }
    for (size_t i = 0; i < s->nverts; i++) {
        top = fmax(top, s->poly_verts[i][1]);
        low = fmin(low, s->poly_verts[i][1]);
    }
    if (ground == INFINITY) ground = low == INFINITY ? 0 : low;
    out->ground = ground;
    out->height = top == -INFINITY ? 0 : top - ground;

    /* Orders and streams. */
    order = malloc((s->nnodes ? s->nnodes : 1) * sizeof *order);
    if (!order) goto oom;
    int strahler = metrics_strahler(&t, order, out->streams);
    out->strahler = strahler;
    out->bifurcation = strahler >= 2 && out->streams[strahler] > 0
                           ? pow(out->streams[1] / out->streams[strahler], 1.0 / (strahler - 1))
                           : NAN;
    out->branching_angle = metrics_branching_angle(&t);
    if (!metrics_counts(s, out) || !metrics_crown(&t, ground, out) || !metrics_box_dimension(s, &out->box_dimension)) goto oom;

    /* Light, on the mesh. */
    const SylMesh *mesh = o->mesh;
    if (!mesh && (s->nnodes || s->norgans || s->npolys)) {
        SylMeshOptions mo = {.threads = o->threads, .diag = o->diag};
        status = syl_mesh_build(s, &mo, &own);
        if (status) goto done;
        mesh = own;
    }
    status = metrics_light(mesh, out->crown_base, o, &out->light_interception);
    goto done;
oom:
    report(o, "out of memory");
    status = SYL_ELIMIT;
done:
    syl_mesh_free(own);
    free(order);
    free(t.first);
    free(t.kids);
    return status;
}
