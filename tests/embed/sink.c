/* The library writes nothing to stderr: an embedding program's diagnostics reach the sink it
 * gives at compile time (SylCompileOptions.sink) as records made where the error is found,
 * with their line and column as numbers (docs/embedding.md, "Diagnostics").
 *   sink MODEL.syl ERRFILE   compiles MODEL.syl (it must fail) with fd 2 sent to ERRFILE and
 *                            no FILE * diag at all, and prints each record as "record
 *                            severity path line column end_column message", "source LINE",
 *                            "caret CARET", then its text form (syl_diagnostic_write) and
 *                            "status N" */
#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <sylva/sylva.h>

static void report(void *user, const SylDiagnostic *d) {
    ++*(int *)user;
    printf("record %d %s %d %d %d %s\n", (int)d->severity, d->path ? d->path : "-", d->line, d->column, d->end_column,
           d->message);
    printf("source %s\n", d->source_line ? d->source_line : "-");
    printf("caret %s\n", d->caret ? d->caret : "-");
    syl_diagnostic_write(d, stdout);
}

int main(int argc, char **argv) {
    if (argc != 3) return 2;
    int fd = open(argv[2], O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || dup2(fd, 2) < 0) return 2; /* whatever the library wrote to stderr lands here */
    close(fd);
    int records = 0;
    SylSink sink = {report, &records};
    int st;
    SylProgram *p = syl_compile(argv[1], NULL, 0, &(SylCompileOptions){.sink = &sink, .validate = syl_validate}, &st);
    printf("records %d\n", records);
    printf("status %d\n", p ? 0 : st);
    syl_program_free(p);
    return 0;
}
