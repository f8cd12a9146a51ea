/* Messages without a place in a model reach the embedder's sink too: a model file that cannot
 * be read, and a derivation past the memory limit. No FILE * is given anywhere, and fd 2 goes
 * to ERRFILE, which must stay empty.
 *   sink_limits MISSING.syl GROWING.syl ERRFILE   prints each record as "record severity path
 *                                                 line column message", then "compile N" (the
 *                                                 missing file's status) and "derive N" */
#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <sylva/sylva.h>

static void report(void *user, const SylDiagnostic *d) {
    ++*(int *)user;
    printf("record %d %s %d %d %s\n", (int)d->severity, d->path ? d->path : "-", d->line, d->column, d->message);
}

int main(int argc, char **argv) {
    if (argc != 4) return 2;
    int fd = open(argv[3], O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || dup2(fd, 2) < 0) return 2; /* whatever the library wrote to stderr lands here */
    close(fd);
    int records = 0;
    SylSink sink = {report, &records};
    int st = 0;
    SylProgram *p = syl_compile(argv[1], NULL, 0, &(SylCompileOptions){.sink = &sink}, &st);
    printf("compile %d\n", p ? 0 : st);
    syl_program_free(p);
    p = syl_compile(argv[2], NULL, 0, &(SylCompileOptions){.sink = &sink}, &st);
    if (!p) return 3;
    SylString *s = NULL;
    st = syl_derive(p, &(SylDeriveOptions){.steps = -1, .max_memory = 1 << 20}, &s);
    printf("derive %d\n", st);
    syl_string_free(s);
    syl_program_free(p);
    printf("records %d\n", records);
    return 0;
}
