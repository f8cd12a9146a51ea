/* Diagnostics as records (sylva.h, SylSink): a stream whose lines, written as util/diag.c and
 * every "sylva: error: ..." message write them, are handed to the sink one record each. The
 * text form is the library's one format (`path:line:col: severity: message`, then the source
 * line as `%5d | text` and a caret line), so the records are read back from it here, in one
 * place, rather than at each of the library's diagnostics. */
#include <ctype.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/sylva.h"

typedef struct Sink {
    SylSink sink;
    char *line; /* the line being written */
    size_t len, cap;
    bool pending; /* a record waits for its source line */
    SylDiagnostic d;
    char *path, *message, *source;
} Sink;

static void deliver(Sink *s) {
    if (!s->pending) return;
    s->d.path = s->path, s->d.message = s->message, s->d.source_line = s->source;
    if (s->sink.report) s->sink.report(s->sink.user, &s->d);
    free(s->path), free(s->message), free(s->source);
    s->path = s->message = s->source = NULL;
    s->pending = false;
}

static const char *const severities[] = {": error: ", ": warning: ", ": note: "};

/* `PATH:LINE:COL: SEVERITY: MESSAGE` or `PATH: SEVERITY: MESSAGE`: the earliest severity tag */
static bool header(Sink *s, const char *l) {
    const char *at = NULL;
    int sev = 0;
    for (int k = 0; k < 3; k++) {
        const char *f = strstr(l, severities[k]);
        if (f && (!at || f < at)) at = f, sev = k;
    }
    if (!at) return false;
    deliver(s);
    s->d = (SylDiagnostic){.severity = (SylSeverity)sev};
    size_t n = (size_t)(at - l);
    /* ":LINE:COL" at the end of the path part */
    const char *e = l + n, *c2 = e;
    while (c2 > l && isdigit((unsigned char)c2[-1])) c2--;
    if (c2 < e && c2 > l && c2[-1] == ':') {
        const char *c1 = c2 - 1;
        while (c1 > l && isdigit((unsigned char)c1[-1])) c1--;
        if (c1 < c2 - 1 && c1 > l && c1[-1] == ':') {
            s->d.line = atoi(c1), s->d.column = atoi(c2);
            n = (size_t)(c1 - 1 - l);
        }
    }
    if (!(n == 5 && !memcmp(l, "sylva", 5))) s->path = strndup(l, n); /* "sylva: error:" names no file */
    s->message = strdup(at + strlen(severities[sev]));
    s->pending = true;
    if (!s->d.line) deliver(s); /* no source line follows */
    return true;
}

static void take_line(Sink *s, const char *l) {
    if (header(s, l)) return;
    const char *p = l;
    while (*p == ' ') p++;
    if (s->pending && isdigit((unsigned char)*p)) { /* "%5d | text" */
        while (isdigit((unsigned char)*p)) p++;
        if (!strncmp(p, " | ", 3) && !s->source) {
            s->source = strdup(p + 3);
            return;
        }
    }
    if (s->pending && s->source && !strncmp(l, "      | ", 8)) { /* the caret: the record is whole */
        deliver(s);
        return;
    }
    if (s->pending && !s->source) { /* a message that spans lines */
        size_t a = strlen(s->message), b = strlen(l);
        char *m = realloc(s->message, a + b + 2);
        if (m) m[a] = '\n', memcpy(m + a + 1, l, b + 1), s->message = m;
        return;
    }
    deliver(s); /* a line of its own: a note */
    s->d = (SylDiagnostic){.severity = SYL_DIAG_NOTE};
    s->message = strdup(l);
    s->pending = true;
    deliver(s);
}

static ssize_t sink_write(void *cookie, const char *buf, size_t n) {
    Sink *s = cookie;
    for (size_t i = 0; i < n; i++) {
        if (s->len + 1 >= s->cap) {
            size_t cap = s->cap ? 2 * s->cap : 256;
            char *l = realloc(s->line, cap);
            if (!l) return 0; /* fopencookie: 0 is an error */
            s->line = l, s->cap = cap;
        }
        if (buf[i] == '\n') {
            s->line[s->len] = 0;
            take_line(s, s->line);
            s->len = 0;
        } else {
            s->line[s->len++] = buf[i];
        }
    }
    return (ssize_t)n;
}

static int sink_close(void *cookie) {
    Sink *s = cookie;
    if (s->len) {
        s->line[s->len] = 0;
        take_line(s, s->line);
    }
    deliver(s);
    free(s->line);
    free(s);
    return 0;
}

FILE *syl_sink_open(const SylSink *sink) {
    Sink *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->sink = *sink;
    FILE *f = fopencookie(s, "w", (cookie_io_functions_t){.write = sink_write, .close = sink_close});
    if (!f) free(s);
    else setvbuf(f, NULL, _IONBF, 0); /* each record as soon as it is whole */
    return f;
}

void syl_diagnostic_write(const SylDiagnostic *d, FILE *out) {
    static const char *const names[] = {"error", "warning", "note"};
    const char *sev = names[d->severity <= SYL_DIAG_NOTE ? d->severity : 0];
    const char *path = d->path ? d->path : "sylva";
    if (d->line > 0) fprintf(out, "%s:%d:%d: %s: %s\n", path, d->line, d->column, sev, d->message);
    else fprintf(out, "%s: %s: %s\n", path, sev, d->message);
    if (d->line <= 0 || !d->source_line) return;
    fprintf(out, "%5d | %s\n      | ", d->line, d->source_line);
    for (int i = 0; i < d->column - 1 && d->source_line[i]; i++) fputc(d->source_line[i] == '\t' ? '\t' : ' ', out);
    fputs("^\n", out);
}
