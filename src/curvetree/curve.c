/* The trunk curve: inline control points (a chain of cubic Béziers or a polyline) or an OBJ
 * file's `l` lines (as Blender exports a curve), made into a dense polyline with its arc
 * length. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curvetree/curvetree.h"
#include "util/coord.h"
#include "util/diag.h"

enum { MAX_POINTS = 1 << 20 }; /* control points of one curve */

void ct_curve_free(CtCurve *c) {
    free(c->p);
    free(c->s);
    free(c->ctrl);
    memset(c, 0, sizeof *c);
}

bool ct_curve_make(CtCurve *c, int kind, const double (*pts)[3], int n) {
    memset(c, 0, sizeof *c);
    int segs = kind == 'b' ? (n - 1) / 3 : n - 1;
    if (n < 2 || n > MAX_POINTS || (kind == 'b' && (n < 4 || (n - 1) % 3))) return false;
    int total = kind == 'b' ? segs * CT_BEZIER_STEPS + 1 : n;
    c->p = malloc((size_t)total * sizeof *c->p);
    c->s = malloc((size_t)total * sizeof *c->s);
    c->ctrl = malloc((size_t)(segs + 1) * sizeof *c->ctrl);
    if (!c->p || !c->s || !c->ctrl) {
        ct_curve_free(c);
        return false;
    }
    if (kind == 'b') {
        for (int k = 0; k < segs; k++) {
            const double *a = pts[3 * k], *b = pts[3 * k + 1], *d = pts[3 * k + 2], *e = pts[3 * k + 3];
            c->ctrl[k] = k * CT_BEZIER_STEPS;
            for (int i = 0; i < CT_BEZIER_STEPS + (k == segs - 1); i++) {
                double t = (double)i / CT_BEZIER_STEPS, u = 1 - t;
                double w0 = u * u * u, w1 = 3 * u * u * t, w2 = 3 * u * t * t, w3 = t * t * t;
                for (int j = 0; j < 3; j++)
                    c->p[k * CT_BEZIER_STEPS + i][j] = w0 * a[j] + w1 * b[j] + w2 * d[j] + w3 * e[j];
            }
        }
        c->ctrl[segs] = total - 1;
    } else {
        memcpy(c->p, pts, (size_t)n * sizeof *c->p);
        for (int i = 0; i < n; i++) c->ctrl[i] = i;
    }
    c->n = total;
    c->nctrl = segs + 1;
    c->s[0] = 0;
    for (int i = 1; i < total; i++) {
        double d[3] = {c->p[i][0] - c->p[i - 1][0], c->p[i][1] - c->p[i - 1][1], c->p[i][2] - c->p[i - 1][2]};
        c->s[i] = c->s[i - 1] + sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    c->length = c->s[total - 1];
    return true;
}

int ct_curve_at(const CtCurve *c, double s, double pos[3], double dir[3]) {
    int lo = 0, hi = c->n - 1; /* the piece [lo, lo + 1] holding s */
    if (s < 0) s = 0;
    if (s > c->length) s = c->length;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (c->s[mid] <= s) lo = mid; else hi = mid;
    }
    /* a piece of zero length (repeated points) takes the next piece's heading */
    int k = lo;
    while (k + 1 < c->n - 1 && c->s[k + 1] - c->s[k] <= 0) k++;
    double piece = c->s[lo + 1] - c->s[lo], t = piece > 0 ? (s - c->s[lo]) / piece : 0;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
    double d[3], n2 = 0;
    for (int j = 0; j < 3; j++) {
        pos[j] = c->p[lo][j] + (c->p[lo + 1][j] - c->p[lo][j]) * t;
        d[j] = c->p[k + 1][j] - c->p[k][j], n2 += d[j] * d[j];
    }
    n2 = sqrt(n2);
    for (int j = 0; j < 3; j++) dir[j] = n2 > 0 ? d[j] / n2 : (j == 1);
    return lo;
}

/* ---- inline control points ---- */

int ct_curve_of_directive(const SylProgram *p, const SylDirective *d, bool read_files, CtCurve *c, FILE *diag) {
    memset(c, 0, sizeof *c);
    static const char usage[] = "trunk takes `bezier` or `polyline` and points (x,y,z), or an .obj file in quotes";
    if (d->nargs == 1 && d->args[0].kind == SYL_DARG_STRING) {
        if (!read_files) return SYL_OK;
        char *path = NULL;
        int st = syl_program_file(p, d->args[0].text, &path);
        if (st == SYL_ELIMIT) return st;
        if (st) {
            syl_directive_report_error(p, diag, d, &d->args[0], "cannot read '%s': %s", d->args[0].text, syl_file_refused);
            return SYL_EIO;
        }
        size_t len = 0;
        char *text = syl_read_file(path, &len);
        if (!text) {
            syl_directive_report_error(p, diag, d, &d->args[0], "cannot read the trunk curve '%s': %s", d->args[0].text,
                                       strerror(errno));
            free(path);
            return SYL_EIO;
        }
        st = ct_curve_obj(path, text, len, c, diag);
        if (st == SYL_EMODEL)
            syl_directive_report_error(p, diag, d, &d->args[0], "cannot use the trunk curve \"%s\" (an .obj file of `l` lines)",
                                       d->args[0].text);
        free(text);
        free(path);
        return st;
    }
    int kind = d->nargs && d->args[0].kind == SYL_DARG_WORD
                   ? (!strcmp(d->args[0].text, "bezier") ? 'b' : !strcmp(d->args[0].text, "polyline") ? 'p' : 0)
                   : 0;
    if (!kind) {
        syl_directive_report_error(p, diag, d, d->nargs ? &d->args[0] : NULL, "%s", usage);
        return SYL_EMODEL;
    }
    int n = d->nargs - 1;
    if (n > MAX_POINTS) n = MAX_POINTS + 1;
    double (*pts)[3] = malloc((size_t)(n > 0 ? n : 1) * sizeof *pts);
    if (!pts) return SYL_ELIMIT;
    for (int i = 0; i < n; i++) {
        const SylDirArg *a = &d->args[i + 1];
        if (a->kind != SYL_DARG_TUPLE || a->nvalues != 3) {
            syl_directive_report_error(p, diag, d, a, "a control point is written (x,y,z)");
            free(pts);
            return SYL_EMODEL;
        }
        for (int j = 0; j < 3; j++)
            if (!coord_ok(a->values[j])) {
                syl_directive_report_error(p, diag, d, a, "a control point must be finite and within %g of the origin",
                                           COORD_MAX);
                free(pts);
                return SYL_EMODEL;
            }
        memcpy(pts[i], a->values, sizeof pts[i]);
    }
    bool ok = n <= MAX_POINTS && ct_curve_make(c, kind, (const double (*)[3])pts, n);
    free(pts);
    if (!ok) {
        if (kind == 'b' && n >= 4 && n <= MAX_POINTS && (n - 1) % 3 == 0) return SYL_ELIMIT;
        if (kind == 'p' && n >= 2 && n <= MAX_POINTS) return SYL_ELIMIT;
        syl_directive_report_error(p, diag, d, d->nargs > 1 ? &d->args[d->nargs - 1] : &d->args[0],
                                   kind == 'b' ? "a bezier trunk takes 4, 7, 10 … control points (each cubic piece 3 more), "
                                                 "at most %d, not %d"
                                               : "a polyline trunk takes 2 to %d points, not %d",
                                   MAX_POINTS, d->nargs - 1);
        return SYL_EMODEL;
    }
    if (!(c->length > 0)) {
        syl_directive_report_error(p, diag, d, &d->args[0], "the trunk curve has no length: its points are all the same");
        ct_curve_free(c);
        return SYL_EMODEL;
    }
    return SYL_OK;
}

/* ---- OBJ lines ---- */

typedef struct ObjText {
    Diag diag;
    Source src;
    const char *line; /* the current line */
    int lineno;
} ObjText;

static int obj_error(ObjText *o, const char *at, const char *what) {
    SylLoc loc = {o->lineno, (int)(at - o->line) + 1, o->lineno, (int)(at - o->line) + 1};
    diag_error(&o->diag, loc, "%s", what);
    return SYL_EMODEL;
}

/* One vertex index of an `l` line: i, i/t, negative ones counting back from the last vertex. */
static bool obj_index(const char **q, const char *end, size_t nv, size_t *out) {
    char num[32], *e; /* the text is not NUL-terminated: the number is copied */
    size_t k = 0;
    while (*q + k < end && k < sizeof num - 1 && (*q)[k] != ' ' && (*q)[k] != '\t' && (*q)[k] != '\r' &&
           (*q)[k] != '/')
        num[k] = (*q)[k], k++;
    num[k] = 0;
    errno = 0;
    long long v = strtoll(num, &e, 10);
    if (e == num || *e || errno) return false;
    const char *at = *q + k;
    if (at < end && *at == '/') /* a texture coordinate: skipped */
        for (at++; at < end && *at != ' ' && *at != '\t' && *at != '\r'; at++) {}
    *q = at;
    if (v > 0 && (unsigned long long)v <= nv) return *out = (size_t)v - 1, true;
    if (v < 0 && (unsigned long long)(-v) <= nv) return *out = nv - (size_t)(-v), true;
    return false;
}

int ct_curve_obj(const char *path, const char *text, size_t len, CtCurve *c, FILE *diag) {
    memset(c, 0, sizeof *c);
    /* its lines are not shown (as the obstacles' reader): a file a model names may be anything */
    ObjText o = {.src = {path, NULL, 0}};
    o.diag = (Diag){.out = diag, .src = &o.src};
    double (*v)[3] = NULL;
    size_t nv = 0, vcap = 0, ne = 0, ecap = 0;
    size_t (*edge)[2] = NULL;
    int *edge_line = NULL;
    int st = SYL_OK;
    const char *end = text + len;
    for (const char *ln = text; ln < end && st == SYL_OK; o.lineno = o.lineno) {
        const char *nl = memchr(ln, '\n', (size_t)(end - ln));
        const char *le = nl ? nl : end;
        o.line = ln, o.lineno++;
        const char *q = ln;
        while (q < le && (*q == ' ' || *q == '\t')) q++;
        if (q + 1 < le && q[0] == 'v' && (q[1] == ' ' || q[1] == '\t')) {
            if (nv == vcap) {
                size_t cap = vcap ? 2 * vcap : 64;
                void *t = cap <= MAX_POINTS ? realloc(v, cap * sizeof *v) : NULL;
                if (!t) {
                    st = cap <= MAX_POINTS ? SYL_ELIMIT : obj_error(&o, q, "more than 1048576 vertices");
                    break;
                }
                v = t, vcap = cap;
            }
            const char *at = q + 2;
            for (int j = 0; j < 3; j++) {
                while (at < le && (*at == ' ' || *at == '\t')) at++;
                char num[64];
                size_t k = 0;
                while (at + k < le && k < sizeof num - 1 && at[k] != ' ' && at[k] != '\t' && at[k] != '\r')
                    num[k] = at[k], k++;
                num[k] = 0;
                char *e;
                double x = k ? strtod(num, &e) : 0;
                if (!k || *e) {
                    st = obj_error(&o, at, "a vertex is `v x y z`: expected a number here");
                    break;
                }
                if (!coord_ok(x)) {
                    st = obj_error(&o, at, "a coordinate must be finite and within 1e12 of the origin");
                    break;
                }
                v[nv][j] = x;
                at += k;
            }
            nv++;
        } else if (q + 1 < le && q[0] == 'l' && (q[1] == ' ' || q[1] == '\t')) {
            const char *at = q + 2;
            size_t prev = 0;
            int count = 0;
            for (;;) {
                while (at < le && (*at == ' ' || *at == '\t' || *at == '\r')) at++;
                if (at >= le || *at == '#') break;
                size_t k;
                const char *here = at;
                if (!obj_index(&at, le, nv, &k)) {
                    st = obj_error(&o, here, "an `l` line lists vertices already given (1 to the count, or -1 back)");
                    break;
                }
                if (count++) {
                    if (ne == ecap) {
                        size_t cap = ecap ? 2 * ecap : 64;
                        void *t = cap <= MAX_POINTS ? realloc(edge, cap * sizeof *edge) : NULL;
                        void *u = t ? realloc(edge_line, cap * sizeof *edge_line) : NULL;
                        if (t) edge = t;
                        if (!t || !u) {
                            st = cap <= MAX_POINTS ? SYL_ELIMIT : obj_error(&o, here, "more than 1048576 line pieces");
                            break;
                        }
                        edge_line = u, ecap = cap;
                    }
                    edge_line[ne] = o.lineno;
                    edge[ne][0] = prev, edge[ne][1] = k, ne++;
                }
                prev = k;
            }
            if (st == SYL_OK && count < 2) st = obj_error(&o, q, "an `l` line joins at least two vertices");
        } else if (q + 4 < le && !strncmp(q, "curv", 4)) {
            st = obj_error(&o, q, "a free-form curve: export the curve from Blender as lines (an .obj of `l` lines)");
        }
        ln = nl ? nl + 1 : end;
    }
    /* one open chain: every vertex on at most two pieces, exactly two ends, all connected */
    int *deg = NULL, *nb = NULL, *order = NULL;
    if (st == SYL_OK && !ne) {
        o.line = text, o.lineno = 0;
        SylLoc none = {0, 0, 0, 0};
        diag_error(&o.diag, none, "%s: no `l` lines: a trunk curve is a chain of lines", path);
        st = SYL_EMODEL;
    }
    if (st == SYL_OK) {
        deg = calloc(nv, sizeof *deg), nb = malloc(2 * nv * sizeof *nb), order = malloc((ne + 1) * sizeof *order);
        if (!deg || !nb || !order) st = SYL_ELIMIT;
    }
    for (size_t e = 0; st == SYL_OK && e < ne; e++)
        for (int s = 0; s < 2 && st == SYL_OK; s++) {
            size_t a = edge[e][s], b = edge[e][!s];
            if (a == b || deg[a] == 2 || (deg[a] == 1 && nb[2 * a] == (int)b)) {
                char msg[160];
                snprintf(msg, sizeof msg, "vertex %zu %s: a trunk curve is one open chain", a + 1,
                         a == b ? "is joined to itself" : "is on more than two pieces, or a piece is repeated");
                SylLoc loc = {edge_line[e], 1, edge_line[e], 1};
                diag_error(&o.diag, loc, "%s", msg);
                st = SYL_EMODEL;
                break;
            }
            nb[2 * a + deg[a]++] = (int)b;
        }
    if (st == SYL_OK) {
        size_t start = nv, ends = 0;
        for (size_t i = 0; i < nv; i++)
            if (deg[i] == 1) {
                ends++;
                if (start == nv || v[i][1] < v[start][1]) start = i;
            }
        int n = 0;
        if (ends == 2) {
            int prev = -1, cur = (int)start;
            for (;;) {
                order[n++] = cur;
                int next = nb[2 * cur] != prev ? nb[2 * cur] : deg[cur] == 2 ? nb[2 * cur + 1] : -1;
                if (deg[cur] == 1 && prev >= 0) break;
                prev = cur, cur = next;
                if (cur < 0 || n > (int)ne) break;
            }
        }
        if (ends != 2 || n != (int)ne + 1) {
            SylLoc loc = {edge_line[0], 1, edge_line[0], 1};
            diag_error(&o.diag, loc, "the lines make %s, not one open chain (a trunk curve)",
                       ends == 0 ? "a closed loop" : "more than one piece");
            st = SYL_EMODEL;
        } else {
            double (*pts)[3] = malloc((size_t)n * sizeof *pts);
            if (!pts) st = SYL_ELIMIT;
            for (int i = 0; pts && i < n; i++) memcpy(pts[i], v[order[i]], sizeof pts[i]);
            if (pts && !ct_curve_make(c, 'p', (const double (*)[3])pts, n)) st = SYL_ELIMIT;
            free(pts);
            if (st == SYL_OK && !(c->length > 0)) {
                SylLoc loc = {edge_line[0], 1, edge_line[0], 1};
                diag_error(&o.diag, loc, "the trunk curve has no length: its vertices are all the same");
                ct_curve_free(c);
                st = SYL_EMODEL;
            }
        }
    }
    free(deg);
    free(nb);
    free(order);
    free(v);
    free(edge);
    free(edge_line);
    return st;
}
