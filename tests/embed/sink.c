/* The library writes nothing to stderr: an embedding program's diagnostics reach the sink it
 * gives (syl_sink_open) as records, with their line and column (docs/embedding.md).
 *   sink MODEL.syl ERRFILE   compiles MODEL.syl (it must fail) with fd 2 sent to ERRFILE, and
 *                            prints each record as "severity path line column message", then
 *                            its text form (syl_diagnostic_write) and "status N" */
#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <sylva/sylva.h>

static void report(void *user, const SylDiagnostic *d) {
    (void)user;
    printf("record %d %s %d %d %s\n", (int)d->severity, d->path ? d->path : "-", d->line, d->column, d->message);
    printf("source %s\n", d->source_line ? d->source_line : "-");
    syl_diagnostic_write(d, stdout);
}

int main(int argc, char **argv) {
    if (argc != 3) return 2;
    int fd = open(argv[2], O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || dup2(fd, 2) < 0) return 2; /* whatever the library wrote to stderr lands here */
    close(fd);
    SylSink sink = {report, NULL};
    FILE *diag = syl_sink_open(&sink);
    if (!diag) return 2;
    int st;
    SylProgram *p = syl_compile(argv[1], NULL, 0, &(SylCompileOptions){.diag = diag, .validate = syl_validate}, &st);
    fclose(diag); /* the last record arrives */
    printf("status %d\n", p ? 0 : st);
    syl_program_free(p);
    return 0;
}
