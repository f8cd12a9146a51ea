/* Diagnostics: made as records (SylDiagnostic: severity, path, line, column, message, the
 * source line and a caret under it) and handed to the caller's sink, or to the text sink of a
 * FILE, which writes `file:line:col: error: message`, the source line and the caret. */
#ifndef SYL_DIAG_H
#define SYL_DIAG_H
#include <stdbool.h>
#include <stddef.h>
#include <stdarg.h>
#include <stdio.h>

#include "sylva/sylva.h"

/* Field names follow bison's YYLTYPE so the parser can use SylLoc directly. Columns count
 * bytes from 1. A zero line means "no location". */
typedef struct SylLoc {
    int first_line, first_column, last_line, last_column;
} SylLoc;

typedef struct Source {
    const char *path; /* as the user named it */
    const char *text;
    size_t len;
} Source;

enum { DIAG_ERROR, DIAG_WARNING, DIAG_NOTE };

typedef struct Diag {
    FILE *out;          /* the text sink's stream; NULL (and no sink): count only */
    const SylSink *sink; /* the records go here instead of out */
    const Source *src;
    int errors, warnings;
    int max_shown;      /* stop printing after this many errors (0: 20) */
} Diag;

/* One diagnostic at loc of d->src, as a record to d->sink or as text to d->out. The message
 * and the path are shown escaped as diag_quote does (tabs and newlines kept), and so is the
 * source line under them. */
void diag_report(Diag *d, int severity, SylLoc loc, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* A message without a place in a model (a file that cannot be read, a limit, MPI): a record
 * with no line, about path (NULL: the library's own, shown "sylva"), to sink when given, else
 * as text to out (`sylva: error: message`); neither: dropped. The message is not escaped, so
 * the text is what fprintf would have written. */
void diag_say(FILE *out, const SylSink *sink, int severity, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
void diag_vsay(FILE *out, const SylSink *sink, int severity, const char *path, const char *fmt, va_list ap);
/* An error without a place, to sink (NULL: dropped): `sylva: error: message` in text. */
#define sink_error(sink, ...) diag_say(NULL, (sink), DIAG_ERROR, NULL, __VA_ARGS__)
/* The sink a call reports to: sink when given, else the text sink of out in *store (NULL
 * when out is NULL too), for the options that still carry a FILE * diag beside their sink. */
const SylSink *diag_sink(SylSink *store, FILE *out, const SylSink *sink);
/* diag_sink of an options struct's diag and sink, for a call's argument (it lives in the
 * enclosing block). */
#define opt_sink(opt) diag_sink(&(SylSink){0}, (opt)->diag, (opt)->sink)
/* s[0..n) made safe to print (see diag.c: controls escaped, visible UTF-8 kept) into buf,
 * cut to fit cap; returns buf. For text from the user that a message quotes. */
const char *diag_quote(char *buf, size_t cap, const char *s, size_t n);
#define diag_error(d, loc, ...) diag_report((d), DIAG_ERROR, (loc), __VA_ARGS__)
#define diag_warning(d, loc, ...) diag_report((d), DIAG_WARNING, (loc), __VA_ARGS__)
#define diag_note(d, loc, ...) diag_report((d), DIAG_NOTE, (loc), __VA_ARGS__)

#endif
