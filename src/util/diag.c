#include "diag.h"

#include <stdarg.h>
#include <string.h>

static const char *const severity_name[] = {"error", "warning", "note"};

/* Print the source line of loc and a caret (with tildes for the rest of a one-line span),
 * keeping tabs so that the caret stays under the right character. */
static void show_line(FILE *out, const Source *src, SylLoc loc) {
    if (!src || !src->text || loc.first_line <= 0) return;
    const char *p = src->text, *end = src->text + src->len;
    for (int l = 1; l < loc.first_line && p < end; p++)
        if (*p == '\n') l++;
    if (p >= end && loc.first_line > 1) return;
    const char *e = p;
    while (e < end && *e != '\n') e++;
    int width = (int)(e - p);
    if (width > 400) return; /* a minified line helps no one */
    fprintf(out, "%5d | %.*s\n      | ", loc.first_line, width, p);
    int col = loc.first_column > 0 ? loc.first_column : 1;
    for (int i = 0; i < col - 1 && i < width; i++) fputc(p[i] == '\t' ? '\t' : ' ', out);
    fputc('^', out);
    if (loc.last_line == loc.first_line)
        for (int i = col; i < loc.last_column && i < width; i++) fputc('~', out);
    fputc('\n', out);
}

void diag_report(Diag *d, int severity, SylLoc loc, const char *fmt, ...) {
    if (severity == DIAG_ERROR) d->errors++;
    if (severity == DIAG_WARNING) d->warnings++;
    int limit = d->max_shown ? d->max_shown : 20;
    if (!d->out || (severity != DIAG_NOTE && d->errors + d->warnings > limit)) return;
    const char *path = d->src && d->src->path ? d->src->path : "sylva";
    if (loc.first_line > 0)
        fprintf(d->out, "%s:%d:%d: %s: ", path, loc.first_line, loc.first_column, severity_name[severity]);
    else
        fprintf(d->out, "%s: %s: ", path, severity_name[severity]);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(d->out, fmt, ap);
    va_end(ap);
    fputc('\n', d->out);
    show_line(d->out, d->src, loc);
}
