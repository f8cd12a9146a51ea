/* sylva view: the HTTP side (libmicrohttpd, a thread per connection). Every request must
 * carry the token of the printed address — in the query of the first page load, then in the
 * cookie that load sets or in an X-Sylva-Token header — or it is refused (403): another web
 * page open in the same browser cannot drive the viewer. It serves the page's own files (web/
 * and the three.js package npm installed there) and what view_build.c makes of the model;
 * never a listing, never a path with "..". */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include "cli/mhd_lazy.h"
#include <netinet/in.h>
#include <arpa/inet.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli/view.h"
#include "util/json.h"

enum { MAX_UPLOAD = 4 << 20 };

typedef struct Conn {
    char *body; /* a POST's body */
    size_t len;
    bool too_big;
} Conn;

static enum MHD_Result send_bytes(struct MHD_Connection *c, unsigned code, const char *type, const void *data,
                                  size_t len, enum MHD_ResponseMemoryMode mode) {
    struct MHD_Response *r = MHD_create_response_from_buffer(len, (void *)data, mode);
    if (!r) return MHD_NO;
    MHD_add_response_header(r, "Content-Type", type);
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(r, "Referrer-Policy", "no-referrer");
    enum MHD_Result ok = MHD_queue_response(c, code, r);
    MHD_destroy_response(r);
    return ok;
}

static enum MHD_Result send_text(struct MHD_Connection *c, unsigned code, const char *text) {
    return send_bytes(c, code, "text/plain; charset=utf-8", text, strlen(text), MHD_RESPMEM_MUST_COPY);
}

/* {"error": message} */
static enum MHD_Result send_error_json(struct MHD_Connection *c, unsigned code, const char *msg, const char *diag) {
    char *s = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&s, &n);
    if (!f) return MHD_NO;
    fputs("{\"error\":", f);
    json_string_file(f, msg);
    fputs(",\"diag\":", f);
    json_string_file(f, diag ? diag : "");
    fputs("}", f);
    fclose(f);
    enum MHD_Result r = send_bytes(c, code, "application/json", s, n, MHD_RESPMEM_MUST_FREE);
    return r;
}

static const char *mime(const char *path) {
    const char *dot = strrchr(path, '.');
    static const char *const types[][2] = {
        {".html", "text/html; charset=utf-8"}, {".js", "text/javascript; charset=utf-8"},
        {".css", "text/css; charset=utf-8"},   {".png", "image/png"},
        {".svg", "image/svg+xml"},             {".json", "application/json"},
    };
    for (size_t i = 0; dot && i < sizeof types / sizeof *types; i++)
        if (!strcmp(dot, types[i][0])) return types[i][1];
    return NULL;
}

/* A file under root (a regular file, whose real path stays under root's), or 404. */
static enum MHD_Result send_file(struct MHD_Connection *c, const char *root, const char *rel, bool set_cookie,
                                 const View *v, int port) {
    char path[PATH_MAX + 64], real[PATH_MAX], realroot[PATH_MAX];
    const char *type = mime(rel);
    if (!type || strlen(root) + strlen(rel) + 2 > PATH_MAX || !snprintf(path, sizeof path, "%s/%s", root, rel) || !realpath(root, realroot) ||
        !realpath(path, real) || strncmp(real, realroot, strlen(realroot)) || real[strlen(realroot)] != '/')
        return send_text(c, MHD_HTTP_NOT_FOUND, "not found\n");
    int fd = open(real, O_RDONLY | O_CLOEXEC);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) || !S_ISREG(st.st_mode)) {
        if (fd >= 0) close(fd);
        return send_text(c, MHD_HTTP_NOT_FOUND, "not found\n");
    }
    struct MHD_Response *r = MHD_create_response_from_fd((uint64_t)st.st_size, fd);
    if (!r) return close(fd), MHD_NO;
    MHD_add_response_header(r, "Content-Type", type);
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(r, "Referrer-Policy", "no-referrer");
    if (set_cookie) {
        char cookie[160];
        snprintf(cookie, sizeof cookie, "sylva_token_%d=%s; Path=/; HttpOnly; SameSite=Strict", port, v->token);
        MHD_add_response_header(r, "Set-Cookie", cookie);
        MHD_add_response_header(r, "Content-Security-Policy",
                                "default-src 'self'; script-src 'self' 'unsafe-inline'; style-src 'self' "
                                "'unsafe-inline'; img-src 'self' blob: data:; connect-src 'self' blob: data:; "
                                "frame-ancestors 'none'");
    }
    enum MHD_Result ok = MHD_queue_response(c, MHD_HTTP_OK, r);
    MHD_destroy_response(r);
    return ok;
}

/* Constant-time comparison of a token candidate. */
static bool token_is(const View *v, const char *t) {
    if (!t || strlen(t) != VIEW_TOKEN) return false;
    unsigned d = 0;
    for (int i = 0; i < VIEW_TOKEN; i++) d |= (unsigned char)(t[i] ^ v->token[i]);
    return d == 0;
}

typedef struct Server {
    View *v;
    int port;
} Server;

/* ---- the query: the model, --set values, seed, ... ---- */

typedef struct Query {
    ViewRequest rq;
    char key[2048];
    size_t klen;
    char err[160];
    bool bad;
    const char *format, *name;
    bool overwrite;
    bool with_part; /* /api/build: the .glb (or a preview's segments) in the same answer */
    unsigned id;
} Query;

static enum MHD_Result query_arg(void *cls, enum MHD_ValueKind kind, const char *key, const char *value) {
    (void)kind;
    Query *q = cls;
    if (!strcmp(key, "token") || !strcmp(key, "t")) return MHD_YES;
    if (!strcmp(key, "tab")) return q->rq.tab = value ? strtoull(value, NULL, 10) : 0, MHD_YES; /* not the build's */
    if (!strcmp(key, "seq")) return q->rq.seq = value ? (unsigned)strtoul(value, NULL, 10) : 0, MHD_YES;
    if (!strcmp(key, "with")) return q->with_part = value && !strcmp(value, "part"), MHD_YES; /* nor this */
    if (!strcmp(key, "format")) q->format = value;
    else if (!strcmp(key, "name")) q->name = value;
    else if (!strcmp(key, "overwrite")) q->overwrite = value && !strcmp(value, "yes");
    else if (!strcmp(key, "id")) q->id = value ? (unsigned)strtoul(value, NULL, 10) : 0;
    else if (!q->bad && !view_request_arg(&q->rq, key, value, q->err, sizeof q->err)) q->bad = true;
    int n = snprintf(q->key + q->klen, sizeof q->key - q->klen, "%s=%s&", key, value ? value : "");
    if (n > 0 && q->klen + (size_t)n < sizeof q->key) q->klen += (size_t)n;
    else q->bad = true, snprintf(q->err, sizeof q->err, "the request is too long");
    return MHD_YES;
}

static bool read_query(struct MHD_Connection *c, Query *q) {
    memset(q, 0, sizeof *q);
    view_request_init(&q->rq);
    MHD_get_connection_values(c, MHD_GET_ARGUMENT_KIND, query_arg, q);
    return !q->bad;
}

/* ---- the event stream (Server-Sent Events): one "change" event per change of the files ---- */

typedef struct Stream {
    View *v;
    unsigned seen;
    bool hello;
} Stream;

static ssize_t stream_read(void *cls, uint64_t pos, char *buf, size_t max) {
    (void)pos;
    Stream *s = cls;
    View *v = s->v;
    if (max < 64) return 0;
    pthread_mutex_lock(&v->gen_lock);
    if (!s->hello) {
        s->hello = true;
        s->seen = v->gen;
        pthread_mutex_unlock(&v->gen_lock);
        return snprintf(buf, max, "retry: 500\nevent: hello\ndata: %u\n\n", s->seen);
    }
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_sec += 15;
    int rc = 0;
    while (!v->stopping && v->gen == s->seen && rc != ETIMEDOUT)
        rc = pthread_cond_timedwait(&v->changed, &v->gen_lock, &until);
    bool stop = v->stopping;
    unsigned gen = v->gen;
    pthread_mutex_unlock(&v->gen_lock);
    if (stop) return MHD_CONTENT_READER_END_OF_STREAM;
    if (gen == s->seen) return snprintf(buf, max, ": still here\n\n"); /* keeps proxies and the socket awake */
    s->seen = gen;
    return snprintf(buf, max, "event: change\ndata: %u\n\n", gen);
}

static enum MHD_Result send_events(struct MHD_Connection *c, View *v) {
    Stream *s = calloc(1, sizeof *s);
    if (!s) return MHD_NO;
    s->v = v;
    struct MHD_Response *r = MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 256, stream_read, s, free);
    if (!r) return free(s), MHD_NO;
    MHD_add_response_header(r, "Content-Type", "text/event-stream");
    MHD_add_response_header(r, "Cache-Control", "no-store");
    enum MHD_Result ok = MHD_queue_response(c, MHD_HTTP_OK, r);
    MHD_destroy_response(r);
    return ok;
}

/* ---- the API ---- */

/* {"id":N,"status":S,"ok":bool,"diag":"...","obstacles":bool,"stats":{...}}; with=part: that
 * JSON's length (4 bytes, little-endian), the JSON, then the build's .glb or segments (none
 * when it failed) — one request instead of two, a round trip less between a save and its frame */
static enum MHD_Result api_build(struct MHD_Connection *c, View *v, Query *q) {
    view_tab_saw(v, &q->rq); /* before waiting for the build lock: a build running sees it */
    view_first_request(v, &q->rq, q->key);
    pthread_mutex_lock(&v->lock);
    ViewBuild *b = view_build(v, &q->rq, q->key);
    char *s = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&s, &n);
    if (f) {
        fprintf(f, "{\"id\":%u,\"gen\":%u,\"status\":%d,\"ok\":%s,\"superseded\":%s,\"lines\":%s,\"diag\":", b->id,
                b->gen, b->status, b->status ? "false" : "true", b->status == VIEW_SUPERSEDED ? "true" : "false",
                b->lines ? "true" : "false");
        json_string_file(f, b->diag ? b->diag : "");
        fprintf(f, ",\"obstacles\":%s,\"stats\":%s,\"model\":", b->obstacles ? "true" : "false",
                b->stats ? b->stats : "null");
        json_string_file(f, q->rq.model);
        fputs("}", f);
        fclose(f);
    }
    char *whole = NULL;
    size_t wlen = 0;
    if (f && q->with_part) {
        const char *part = b->status ? NULL : b->lines ? b->lines : b->glb;
        size_t plen = !part ? 0 : b->lines ? b->lines_len : b->glb_len;
        wlen = 4 + n + plen;
        whole = n <= UINT32_MAX ? malloc(wlen) : NULL;
        if (whole) {
            for (int k = 0; k < 4; k++) whole[k] = (char)(n >> (8 * k) & 0xff);
            memcpy(whole + 4, s, n);
            if (plen) memcpy(whole + 4 + n, part, plen);
        }
        free(s);
        if (!whole) f = NULL;
    }
    pthread_mutex_unlock(&v->lock);
    if (!f) return MHD_NO;
    if (whole) return send_bytes(c, MHD_HTTP_OK, "application/octet-stream", whole, wlen, MHD_RESPMEM_MUST_FREE);
    return send_bytes(c, MHD_HTTP_OK, "application/json", s, n, MHD_RESPMEM_MUST_FREE);
}

/* A part of build id (from the cache: the page asks right after): its .glb, its skeleton's
 * CSV or its obstacles' .glb. */
typedef enum { PART_GLB, PART_SKELETON, PART_OBSTACLES, PART_LINES } Part;

static enum MHD_Result api_part(struct MHD_Connection *c, View *v, unsigned id, Part part) {
    pthread_mutex_lock(&v->lock);
    ViewBuild *b = NULL;
    for (int i = 0; i < VIEW_CACHE; i++)
        if (id && v->cache[i].id == id) b = &v->cache[i];
    enum MHD_Result r;
    if (b && !b->status && part == PART_SKELETON && !b->csv && v->kept && v->kept->id == b->id) { /* made when first asked for */
        FILE *out = view_bytes_open(&b->csv, &b->csv_len);
        if (out && syl_skeleton_write_csv(v->kept->pl.skeleton, out)) fclose(out), free(b->csv), b->csv = NULL;
        else if (out) fclose(out);
    }
    if (!b || b->status || (part == PART_OBSTACLES && !b->obstacles) || (part == PART_SKELETON && !b->csv) ||
        (part == PART_LINES && !b->lines) || (part == PART_GLB && !b->glb))
        r = send_text(c, MHD_HTTP_NOT_FOUND, "no such build\n");
    else if (part == PART_GLB) r = send_bytes(c, MHD_HTTP_OK, "model/gltf-binary", b->glb, b->glb_len, MHD_RESPMEM_MUST_COPY);
    else if (part == PART_LINES)
        r = send_bytes(c, MHD_HTTP_OK, "application/octet-stream", b->lines, b->lines_len, MHD_RESPMEM_MUST_COPY);
    else if (part == PART_OBSTACLES)
        r = send_bytes(c, MHD_HTTP_OK, "model/gltf-binary", b->obstacles, b->obstacles_len, MHD_RESPMEM_MUST_COPY);
    else r = send_bytes(c, MHD_HTTP_OK, "text/csv", b->csv, b->csv_len, MHD_RESPMEM_MUST_COPY);
    pthread_mutex_unlock(&v->lock);
    return r;
}

/* The metrics of build id (`sylva compare`'s), made at the first asking: 404 when a newer
 * build has replaced its plant. */
static enum MHD_Result api_metrics(struct MHD_Connection *c, View *v, unsigned id) {
    char *diag = NULL;
    char *m = view_metrics(v, id, &diag); /* beside a build: it takes the locks it needs */
    enum MHD_Result r = m ? send_bytes(c, MHD_HTTP_OK, "application/json", m, strlen(m), MHD_RESPMEM_MUST_FREE)
                          : send_error_json(c, MHD_HTTP_NOT_FOUND, "no metrics of that build", diag);
    free(diag);
    return r;
}

static enum MHD_Result api_export(struct MHD_Connection *c, View *v, Query *q) {
    static const char *const formats[][3] = {{"glb", "model/gltf-binary", "glb"}, {"obj", "text/plain", "obj"},
                                             {"png", "image/png", "png"}, {"csv", "text/csv", "csv"},
                                             {"segments", "application/octet-stream", "bin"}};
    int k = 0;
    while (k < 5 && (!q->format || strcmp(q->format, formats[k][0]))) k++;
    if (k == 5) return send_error_json(c, MHD_HTTP_BAD_REQUEST, "format: glb, obj, png, csv or segments", NULL);
    char *out, *diag;
    size_t len;
    pthread_mutex_lock(&v->lock);
    int status = view_export(v, &q->rq, formats[k][0], &out, &len, &diag);
    pthread_mutex_unlock(&v->lock);
    enum MHD_Result r;
    if (status) {
        free(out);
        r = send_error_json(c, MHD_HTTP_UNPROCESSABLE_CONTENT, "the export failed", diag);
    } else {
        struct MHD_Response *resp = MHD_create_response_from_buffer(len, out, MHD_RESPMEM_MUST_FREE);
        if (!resp) return free(out), free(diag), MHD_NO;
        char disp[256];
        const char *base = strrchr(v->path, '/');
        base = base ? base + 1 : v->path;
        const char *dot = strrchr(base, '.');
        int stem = dot ? (int)(dot - base) : (int)strlen(base);
        snprintf(disp, sizeof disp, "attachment; filename=\"%.*s%s%s.%s\"", stem > 100 ? 100 : stem, base,
                 q->rq.model[0] ? "_" : "", q->rq.model[0] && !strpbrk(q->rq.model, "\"\\/") ? q->rq.model : "",
                 formats[k][2]);
        MHD_add_response_header(resp, "Content-Type", formats[k][1]);
        MHD_add_response_header(resp, "Content-Disposition", disp);
        MHD_add_response_header(resp, "Cache-Control", "no-store");
        r = MHD_queue_response(c, MHD_HTTP_OK, resp);
        MHD_destroy_response(resp);
    }
    free(diag);
    return r;
}

static enum MHD_Result api_describe(struct MHD_Connection *c, View *v, Query *q) {
    char *diag;
    pthread_mutex_lock(&v->lock);
    char *s = view_describe_json(v, &q->rq, &diag);
    pthread_mutex_unlock(&v->lock);
    enum MHD_Result r = s ? send_bytes(c, MHD_HTTP_OK, "application/json", s, strlen(s), MHD_RESPMEM_MUST_FREE)
                          : send_error_json(c, MHD_HTTP_UNPROCESSABLE_CONTENT, "the model does not compile", diag);
    free(diag);
    return r;
}

/* A factor map of the ecosystem on show (the PNG of syl_terrain_write_map). */
static enum MHD_Result api_map(struct MHD_Connection *c, View *v, const char *factor) {
    char *png;
    size_t len;
    pthread_mutex_lock(&v->lock);
    int st = view_eco_map(v, factor, &png, &len);
    pthread_mutex_unlock(&v->lock);
    if (st) return send_text(c, MHD_HTTP_NOT_FOUND, "no such map\n");
    return send_bytes(c, MHD_HTTP_OK, "image/png", png, len, MHD_RESPMEM_MUST_FREE);
}

/* The impostor of look K of the ecosystem on show: the forest's far level. */
static enum MHD_Result api_impostor(struct MHD_Connection *c, View *v, const char *look) {
    const char *glb;
    size_t len;
    pthread_mutex_lock(&v->lock);
    int st = look && *look ? view_eco_impostor(v, atoi(look), &glb, &len) : SYL_EUSAGE;
    enum MHD_Result r = st ? send_text(c, MHD_HTTP_NOT_FOUND, "no such look\n")
                           : send_bytes(c, MHD_HTTP_OK, "model/gltf-binary", glb, len, MHD_RESPMEM_MUST_COPY);
    pthread_mutex_unlock(&v->lock);
    return r;
}

/* "Save as…": a new file beside the model (a plain name, no directory); an existing one only
 * with overwrite=yes, which the page sends after the user confirmed. Through util/outfile:
 * nothing half-written. */
static enum MHD_Result api_save(struct MHD_Connection *c, View *v, Query *q, Conn *body) {
    const char *name = q->name;
    if (!name || !*name || strchr(name, '/') || name[0] == '.' || strlen(name) > 200)
        return send_error_json(c, MHD_HTTP_BAD_REQUEST, "name: a file name in the model's directory", NULL);
    if (body->too_big) return send_error_json(c, MHD_HTTP_CONTENT_TOO_LARGE, "the text is too long", NULL);
    char path[sizeof v->dir + 256];
    snprintf(path, sizeof path, "%s/%s", v->dir, name);
    struct stat st;
    if (!q->overwrite && !lstat(path, &st))
        return send_error_json(c, MHD_HTTP_CONFLICT, "the file exists; confirm to overwrite it", NULL);
    char *diag = NULL;
    size_t dl = 0;
    FILE *df = open_memstream(&diag, &dl);
    OutFile o;
    bool ok = df && outfile_open(&o, path, NULL, cli_text_sink(df));
    if (ok) {
        fwrite(body->body ? body->body : "", 1, body->len, o.f);
        ok = outfile_close(&o, true, cli_text_sink(df));
    }
    if (df) fclose(df);
    enum MHD_Result r = ok ? send_text(c, MHD_HTTP_OK, "saved\n")
                           : send_error_json(c, MHD_HTTP_INTERNAL_SERVER_ERROR, "cannot save", diag);
    free(diag);
    return r;
}

static enum MHD_Result api_source(struct MHD_Connection *c, View *v) {
    size_t len = 0;
    char *text = syl_read_file(v->path, &len);
    if (!text) return send_error_json(c, MHD_HTTP_NOT_FOUND, strerror(errno), NULL);
    return send_bytes(c, MHD_HTTP_OK, "text/plain; charset=utf-8", text, len, MHD_RESPMEM_MUST_FREE);
}

static enum MHD_Result answer(void *cls, struct MHD_Connection *c, const char *url, const char *method,
                              const char *version, const char *upload, size_t *upload_size, void **con_cls) {
    (void)version;
    Server *srv = cls;
    View *v = srv->v;
    bool post = !strcmp(method, "POST");
    if (!*con_cls) { /* the headers: decide now, before any body */
        Conn *conn = calloc(1, sizeof *conn);
        if (!conn) return MHD_NO;
        *con_cls = conn;
        if (post) return MHD_YES;
    }
    Conn *conn = *con_cls;
    if (post && *upload_size) {
        if (conn->len + *upload_size > MAX_UPLOAD) conn->too_big = true;
        else {
            char *b = realloc(conn->body, conn->len + *upload_size + 1);
            if (!b) return MHD_NO;
            memcpy(b + conn->len, upload, *upload_size);
            conn->body = b, conn->len += *upload_size;
            b[conn->len] = 0;
        }
        *upload_size = 0;
        return MHD_YES;
    }
    if (!post && strcmp(method, "GET") && strcmp(method, "HEAD"))
        return send_text(c, MHD_HTTP_METHOD_NOT_ALLOWED, "method not allowed\n");
    if (strstr(url, "..") || strchr(url, '\\') || url[0] != '/')
        return send_text(c, MHD_HTTP_FORBIDDEN, "refused: a path outside the viewer's files\n");
    char cookie_name[32];
    snprintf(cookie_name, sizeof cookie_name, "sylva_token_%d", srv->port);
    const char *qtoken = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "token");
    bool page = !strcmp(url, "/") || !strcmp(url, "/index.html");
    bool authorised = token_is(v, MHD_lookup_connection_value(c, MHD_COOKIE_KIND, cookie_name)) ||
                      token_is(v, MHD_lookup_connection_value(c, MHD_HEADER_KIND, "X-Sylva-Token")) ||
                      (page && token_is(v, qtoken));
    if (!authorised) return send_text(c, MHD_HTTP_FORBIDDEN, "refused: open the address with its token that `sylva view` printed\n");
    if (page) return send_file(c, v->web, "index.html", true, v, srv->port);
    if (!strncmp(url, "/app/", 5)) return send_file(c, v->web, url + 5, false, v, srv->port);
    if (!strncmp(url, "/three/", 7)) {
        char root[sizeof v->web + 32];
        snprintf(root, sizeof root, "%s/node_modules/three", v->web);
        return send_file(c, root, url + 7, false, v, srv->port);
    }
    if (!strcmp(url, "/api/events")) return send_events(c, v);
    if (!strcmp(url, "/api/source")) return api_source(c, v);
    if (!strcmp(url, "/api/models")) {
        char *s = view_models_json(v);
        return s ? send_bytes(c, MHD_HTTP_OK, "application/json", s, strlen(s), MHD_RESPMEM_MUST_FREE) : MHD_NO;
    }
    Query q;
    bool ok = read_query(c, &q);
    if (post && strcmp(url, "/api/save")) { /* the page's edited text, built in place of the file's */
        if (conn->too_big) return send_error_json(c, MHD_HTTP_CONTENT_TOO_LARGE, "the text is too long", NULL);
        q.rq.text = conn->body ? conn->body : "";
        q.rq.text_len = conn->len;
        /* the cache knows it by its hash (FNV-1a) */
        uint64_t h = 1469598103934665603ull;
        for (size_t i = 0; i < conn->len; i++) h = (h ^ (unsigned char)conn->body[i]) * 1099511628211ull;
        int n = snprintf(q.key + q.klen, sizeof q.key - q.klen, "text=%016llx&", (unsigned long long)h);
        if (n > 0 && q.klen + (size_t)n < sizeof q.key) q.klen += (size_t)n;
    }
    if (!strncmp(url, "/api/", 5) && !ok) return send_error_json(c, MHD_HTTP_BAD_REQUEST, q.err, NULL);
    if (!strcmp(url, "/api/build")) return api_build(c, v, &q);
    if (!strcmp(url, "/api/glb")) return api_part(c, v, q.id, PART_GLB);
    if (!strcmp(url, "/api/skeleton")) return api_part(c, v, q.id, PART_SKELETON);
    if (!strcmp(url, "/api/lines")) return api_part(c, v, q.id, PART_LINES);
    if (!strcmp(url, "/api/obstacles")) return api_part(c, v, q.id, PART_OBSTACLES);
    if (!strcmp(url, "/api/impostor"))
        return api_impostor(c, v, MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "look"));
    if (!strcmp(url, "/api/metrics")) return api_metrics(c, v, q.id);
    if (!strcmp(url, "/api/export")) return api_export(c, v, &q);
    if (!strcmp(url, "/api/describe")) return api_describe(c, v, &q);
    if (!strcmp(url, "/api/map")) return api_map(c, v, MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "factor"));
    if (!strcmp(url, "/api/save") && post) return api_save(c, v, &q, conn);
    if (post) return send_text(c, MHD_HTTP_METHOD_NOT_ALLOWED, "method not allowed\n");
    return send_text(c, MHD_HTTP_NOT_FOUND, "not found\n");
}

static void done(void *cls, struct MHD_Connection *c, void **con_cls, enum MHD_RequestTerminationCode code) {
    (void)cls, (void)c, (void)code;
    Conn *conn = *con_cls;
    if (conn) free(conn->body), free(conn);
    *con_cls = NULL;
}

struct MHD_Daemon *view_http_start(View *v, const char *host, int port, int *bound_port) {
    static Server srv; /* one server a process: the daemon's handlers point at it */
    struct sockaddr_in addr = {.sin_family = AF_INET, .sin_port = htons((uint16_t)port)};
    if (inet_pton(AF_INET, host, &addr.sin_addr) != 1) {
        fprintf(stderr, "sylva view: error: --host '%s' is not an IPv4 address\n", host);
        return NULL;
    }
    srv.v = v;
    srv.port = port;
    struct MHD_Daemon *d = MHD_start_daemon(
        MHD_USE_THREAD_PER_CONNECTION | MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_ERROR_LOG, (uint16_t)port, NULL,
        NULL, answer, &srv, MHD_OPTION_SOCK_ADDR, (struct sockaddr *)&addr, MHD_OPTION_NOTIFY_COMPLETED, done, NULL,
        MHD_OPTION_CONNECTION_LIMIT, 64u, MHD_OPTION_END);
    if (!d) {
        fprintf(stderr, "sylva view: error: cannot listen on %s:%d (%s)\n", host, port,
                errno ? strerror(errno) : "in use?");
        return NULL;
    }
    const union MHD_DaemonInfo *info = MHD_get_daemon_info(d, MHD_DAEMON_INFO_BIND_PORT);
    *bound_port = info ? info->port : port;
    srv.port = *bound_port;
    return d;
}
