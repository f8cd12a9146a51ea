/* The OBJ reader: see objread.h. */
#include "env/objread.h"
#include "util/array.h"
#include "util/coord.h"
#include "util/diag.h"
#include "util/file.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/sylva.h"

typedef struct Reader {
    const char *path;
    int line;
    const char *bol; /* where the line starts: columns count bytes from it */
    const SylSink *sink;
    ObjMesh *m;
    size_t vcap, tcap;
} Reader;

/* at: where on the line the error is (NULL: the whole line). */
static int fail(Reader *r, const char *at, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail(Reader *r, const char *at, const char *fmt, ...) {
    if (r->sink && r->sink->report) {
        char msg[512];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        /* a record about the OBJ's line; a whole line's column is 1 */
        SylDiagnostic d = {.severity = SYL_DIAG_ERROR, .path = r->path, .line = r->line, .message = msg};
        if (r->line > 0) d.column = d.end_column = at ? (int)(at - r->bol) + 1 : 1;
        r->sink->report(r->sink->user, &d);
    }
    return SYL_EMODEL;
}

/* The next whitespace-separated token of [*s, end): its start and length (0 at the end). */
static size_t token(const char **s, const char *end, const char **tok) {
    const char *p = *s;
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) p++;
    *tok = p;
    while (p < end && !isspace((unsigned char)*p)) p++;
    *s = p;
    return (size_t)(p - *tok);
}

static int vertex(Reader *r, const char *s, const char *end) {
    float xyz[3];
    for (int k = 0; k < 3; k++) {
        const char *t;
        size_t n = token(&s, end, &t);
        if (!n) return fail(r, t, "a vertex needs three coordinates ('v x y z')");
        char buf[64], *stop;
        if (n >= sizeof buf) return fail(r, t, "coordinate '%.*s' is not a number", 20, t);
        memcpy(buf, t, n);
        buf[n] = 0;
        errno = 0;
        double v = strtod(buf, &stop);
        if (*stop || isnan(v)) return fail(r, t, "coordinate '%s' is not a number", buf);
        if (!coord_ok(v)) /* Embree traces in float: see util/coord.h */
            return fail(r, t, "coordinate %s is out of range (at most %g from the origin)", buf, COORD_MAX);
        xyz[k] = (float)v;
    }
    const char *t; /* an optional w, and nothing more */
    size_t n = token(&s, end, &t);
    if (n) {
        char buf[64], *stop;
        if (n < sizeof buf) memcpy(buf, t, n), buf[n] = 0;
        if (n >= sizeof buf || (strtod(buf, &stop), *stop) || token(&s, end, &t))
            return fail(r, t, "unexpected '%.*s' after a vertex's coordinates", (int)(n < 20 ? n : 20), t);
    }
    if (!array_reserve(&r->m->v, &r->vcap, 3 * (r->m->nv + 1), sizeof(float))) return SYL_ELIMIT;
    memcpy(r->m->v + 3 * r->m->nv++, xyz, sizeof xyz);
    return SYL_OK;
}

/* One face reference: the vertex index (0-based) of i, i/t, i//n or i/t/n. */
static int reference(Reader *r, const char *t, size_t n, uint32_t *out) {
    char buf[64], *stop;
    size_t k = 0;
    while (k < n && t[k] != '/') k++;
    if (k == 0 || k >= sizeof buf) return fail(r, t, "face vertex '%.*s' is not an index", (int)(n < 20 ? n : 20), t);
    memcpy(buf, t, k);
    buf[k] = 0;
    errno = 0;
    long long i = strtoll(buf, &stop, 10);
    if (*stop || errno) return fail(r, t, "face vertex '%.*s' is not an index", (int)(n < 20 ? n : 20), t);
    long long nv = (long long)r->m->nv;
    if (i < 0) i = nv + i + 1;
    if (i < 1 || i > nv)
        return fail(r, t, "face vertex %s is out of range (%lld vertices so far)", buf, nv);
    *out = (uint32_t)(i - 1);
    return SYL_OK;
}

static int face(Reader *r, const char *s, const char *end) {
    const char *f = s - 1; /* the 'f' */
    uint32_t first = 0, prev = 0, cur = 0;
    int count = 0;
    for (;;) {
        const char *t;
        size_t n = token(&s, end, &t);
        if (!n) break;
        int st = reference(r, t, n, &cur);
        if (st) return st;
        if (count >= 2) {
            if (!array_reserve(&r->m->tri, &r->tcap, 3 * (r->m->nt + 1), sizeof(uint32_t))) return SYL_ELIMIT;
            uint32_t *tri = r->m->tri + 3 * r->m->nt++;
            tri[0] = first, tri[1] = prev, tri[2] = cur;
        }
        if (count == 0) first = cur;
        prev = cur;
        count++;
    }
    if (count < 3) return fail(r, f, "a face needs at least three vertices, not %d", count);
    return SYL_OK;
}

int obj_parse(const char *path, const char *text, size_t len, ObjMesh *out, const SylSink *sink) {
    memset(out, 0, sizeof *out);
    Reader r = {.path = path, .sink = sink, .m = out};
    const char *s = text, *end = text + len;
    if (len >= 3 && !memcmp(s, "\xef\xbb\xbf", 3)) s += 3; /* a UTF-8 byte order mark */
    int st = SYL_OK;
    while (s < end && !st) {
        const char *eol = memchr(s, '\n', (size_t)(end - s));
        if (!eol) eol = end;
        r.line++;
        r.bol = s;
        const char *p = s, *t;
        size_t n = token(&p, eol, &t);
        if (n == 1 && t[0] == 'v') st = vertex(&r, p, eol);
        else if (n == 1 && t[0] == 'f') st = face(&r, p, eol);
        else if (n && memchr(t, 0, n)) st = fail(&r, NULL, "not a text file");
        /* comments, normals, texture coordinates, groups, materials: skipped */
        s = eol + 1;
    }
    if (!st && out->nt == 0) {
        r.line = 0;
        st = fail(&r, NULL, "no faces: an obstacle needs triangles ('f a b c')");
    }
    if (st == SYL_ELIMIT) diag_say(NULL, sink, DIAG_ERROR, path, "out of memory");
    if (st) obj_free(out);
    return st;
}

int obj_read(const char *path, ObjMesh *out, const SylSink *sink) {
    memset(out, 0, sizeof *out);
    size_t len = 0;
    char *text = file_read_named(path, &len, NULL);
    if (!text) {
        int e = errno; /* before the message, which may change it */
        sink_error(sink, "cannot read '%s': %s", path, file_strerror(e));
        return e == ENOMEM ? SYL_ELIMIT : SYL_EIO;
    }
    int st = obj_parse(path, text, len, out, sink);
    free(text);
    return st;
}

void obj_free(ObjMesh *m) {
    free(m->v);
    free(m->tri);
    memset(m, 0, sizeof *m);
}
