/* Diagnostics: records made where the error is found (SylDiagnostic), handed to the caller's
 * sink or written as text (file:line:col messages with the source line and a caret). */
#include "util/diag.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const char *const severity_name[] = {"error", "warning", "note"};

/* A growing string, for a record's fields. */
typedef struct Text {
    char *s;
    size_t n, cap;
} Text;

static void text_put(Text *t, const char *s, size_t n) {
    if (t->n + n + 1 > t->cap) {
        size_t cap = t->cap ? t->cap : 128;
        while (cap < t->n + n + 1) cap *= 2;
        char *b = realloc(t->s, cap);
        if (!b) return; /* out of memory: the field is cut short */
        t->s = b, t->cap = cap;
    }
    memcpy(t->s + t->n, s, n);
    t->n += n;
    t->s[t->n] = 0;
}
static void text_char(Text *t, char c) { text_put(t, &c, 1); }
static const char *text_str(const Text *t) { return t->s ? t->s : ""; }

/* Characters that print nothing visible or reorder what follows: soft hyphen, zero-width
 * and bidirectional marks, the byte order mark. */
static bool invisible(uint32_t c) {
    return c == 0xad || (c >= 0x200b && c <= 0x200f) || (c >= 0x2028 && c <= 0x202e) ||
           (c >= 0x2060 && c <= 0x2069) || c == 0xfeff || (c >= 0xfff9 && c <= 0xfffb);
}

/* The valid UTF-8 character at s (n bytes left): its length, 0 if there is none. */
static size_t utf8(const unsigned char *s, size_t n, uint32_t *cp) {
    size_t len = s[0] >= 0xc2 && s[0] <= 0xdf ? 2 : s[0] >= 0xe0 && s[0] <= 0xef ? 3 : s[0] >= 0xf0 && s[0] <= 0xf4 ? 4 : 0;
    if (!len || len > n) return 0;
    uint32_t c = s[0] & (0x7f >> len);
    for (size_t i = 1; i < len; i++) {
        if ((s[i] & 0xc0) != 0x80) return 0;
        c = c << 6 | (s[i] & 0x3f);
    }
    if ((len == 3 && c < 0x800) || (len == 4 && (c < 0x10000 || c > 0x10ffff)) || (c >= 0xd800 && c <= 0xdfff))
        return 0; /* overlong, beyond Unicode, or a surrogate */
    *cp = c;
    return len;
}

/* How the character at s shows on a terminal, never raw when it could act on it: printable
 * ASCII and visible UTF-8 as they are, a control as ^X (DEL as ^?), a C1 control or an
 * invisible character as <U+XXXX>, a byte that starts no UTF-8 character as \xHH. Tab and
 * newline stay when keep_space is set. Writes out (NUL-terminated, at most 12 bytes); returns
 * the bytes of s taken, and *cols the columns shown. */
static size_t show_char(const char *s, size_t n, bool keep_space, char out[12], int *cols) {
    unsigned char b = (unsigned char)s[0];
    uint32_t cp;
    size_t len;
    if ((b >= 32 && b < 127) || (keep_space && (b == '\t' || b == '\n'))) {
        out[0] = (char)b, out[1] = 0, *cols = 1;
        return 1;
    }
    if (b < 32 || b == 127) {
        out[0] = '^', out[1] = b == 127 ? '?' : (char)(b + 64), out[2] = 0, *cols = 2;
        return 1;
    }
    if (!(len = utf8((const unsigned char *)s, n, &cp))) {
        snprintf(out, 12, "\\x%02x", b);
        *cols = 4;
        return 1;
    }
    if (cp < 0xa0 || invisible(cp)) {
        *cols = snprintf(out, 12, "<U+%04X>", (unsigned)cp);
        return len;
    }
    memcpy(out, s, len);
    out[len] = 0;
    *cols = 1;
    return len;
}

static void put_shown(Text *out, const char *s, size_t n, bool keep_space) {
    char c[12];
    int cols;
    for (size_t i = 0; i < n;) {
        i += show_char(s + i, n - i, keep_space, c, &cols);
        text_put(out, c, strlen(c));
    }
}

const char *diag_quote(char *buf, size_t cap, const char *s, size_t n) {
    size_t used = 0;
    char c[12];
    int cols;
    if (!cap) return buf;
    for (size_t i = 0; i < n;) {
        i += show_char(s + i, n - i, false, c, &cols);
        size_t l = strlen(c);
        if (used + l >= cap) break;
        memcpy(buf + used, c, l);
        used += l;
    }
    buf[used] = 0;
    return buf;
}

/* The source line of loc as shown and the caret line under it (with tildes for the rest of a
 * one-line span), false when there is none to show. Tabs are kept, in the line and under it,
 * so that the caret stays under the right character; control characters are shown escaped
 * (show_char), the caret line padded as wide as what they show. *last: the span's last
 * byte column on the line. */
static bool show_line(const Source *src, SylLoc loc, Text *line, Text *caret, int *last) {
    if (!src || !src->text || loc.first_line <= 0) return false;
    const char *p = src->text, *end = src->text + src->len;
    for (int l = 1; l < loc.first_line && p < end; p++)
        if (*p == '\n') l++;
    if (p >= end && loc.first_line > 1) return false;
    const char *e = p;
    while (e < end && *e != '\n') e++;
    int width = (int)(e - p);
    if (width > 400) return false; /* a minified line helps no one */
    put_shown(line, p, (size_t)width, true);
    /* columns count bytes from 1: pad to the byte col - 1, then mark bytes col .. last */
    int col = loc.first_column > 0 ? loc.first_column : 1;
    *last = loc.last_line == loc.first_line && loc.last_column > col ? loc.last_column : col;
    char c[12];
    int cols;
    for (int i = 0; i < width && i < col - 1;) {
        if (p[i] == '\t') {
            text_char(caret, '\t');
            i++;
            continue;
        }
        i += (int)show_char(p + i, (size_t)(width - i), true, c, &cols);
        for (int k = 0; k < cols; k++) text_char(caret, ' ');
    }
    text_char(caret, '^');
    int at = col - 1;
    if (at < width) { /* the marked character may show wider than one column */
        at += (int)show_char(p + at, (size_t)(width - at), true, c, &cols);
        for (int k = 1; k < cols; k++) text_char(caret, '~');
    }
    while (at < width && at < *last) {
        at += (int)show_char(p + at, (size_t)(width - at), true, c, &cols);
        for (int k = 0; k < cols; k++) text_char(caret, '~');
    }
    return true;
}

void diag_report(Diag *d, int severity, SylLoc loc, const char *fmt, ...) {
    if (severity == DIAG_ERROR) d->errors++;
    if (severity == DIAG_WARNING) d->warnings++;
    int limit = d->max_shown ? d->max_shown : 20;
    if ((!d->out && !d->sink) || (severity != DIAG_NOTE && d->errors + d->warnings > limit)) return;
    char msg[2048];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (n < 0) n = 0;
    Text path = {0}, message = {0}, line = {0}, caret = {0};
    if (d->src && d->src->path) put_shown(&path, d->src->path, strlen(d->src->path), false); /* a path may come from anywhere */
    put_shown(&message, msg, (size_t)n < sizeof msg ? (size_t)n : sizeof msg - 1, true);
    int last = 0;
    bool shown = show_line(d->src, loc, &line, &caret, &last);
    SylDiagnostic r = {.severity = (SylSeverity)severity, .path = path.s, .message = text_str(&message)};
    if (loc.first_line > 0) r.line = loc.first_line, r.column = loc.first_column, r.end_column = last;
    if (shown) r.source_line = text_str(&line), r.caret = text_str(&caret);
    if (d->sink) {
        if (d->sink->report) d->sink->report(d->sink->user, &r);
    } else {
        syl_diagnostic_write(&r, d->out);
    }
    free(path.s), free(message.s), free(line.s), free(caret.s);
}

void diag_vsay(FILE *out, const SylSink *sink, int severity, const char *path, const char *fmt, va_list ap) {
    if (!out && !(sink && sink->report)) return;
    char msg[2048];
    vsnprintf(msg, sizeof msg, fmt, ap);
    SylDiagnostic r = {.severity = (SylSeverity)severity, .path = path, .message = msg};
    if (sink && sink->report) sink->report(sink->user, &r);
    else syl_diagnostic_write(&r, out);
}

void diag_say(FILE *out, const SylSink *sink, int severity, const char *path, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    diag_vsay(out, sink, severity, path, fmt, ap);
    va_end(ap);
}

const SylSink *diag_sink(SylSink *store, FILE *out, const SylSink *sink) {
    if (sink) return sink;
    if (!out) return NULL;
    *store = (SylSink){syl_diagnostic_print, out};
    return store;
}

void syl_diagnostic_print(void *file, const SylDiagnostic *d) { syl_diagnostic_write(d, file); }

/* The text sink: the one place the text form is written. */
void syl_diagnostic_write(const SylDiagnostic *d, FILE *out) {
    const char *sev = severity_name[d->severity <= SYL_DIAG_NOTE ? d->severity : 0];
    const char *path = d->path ? d->path : "sylva";
    if (d->line > 0) fprintf(out, "%s:%d:%d: %s: %s\n", path, d->line, d->column, sev, d->message);
    else fprintf(out, "%s: %s: %s\n", path, sev, d->message);
    if (d->line <= 0 || !d->source_line) return;
    fprintf(out, "%5d | %s\n      | ", d->line, d->source_line);
    if (d->caret) {
        fputs(d->caret, out);
    } else { /* a record made elsewhere: a caret under the column */
        for (int i = 0; i < d->column - 1 && d->source_line[i]; i++) fputc(d->source_line[i] == '\t' ? '\t' : ' ', out);
        fputc('^', out);
    }
    fputc('\n', out);
}
