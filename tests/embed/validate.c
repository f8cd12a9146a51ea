/* An embedding program that checks a model as `sylva check` does, through the library's hook
 * (docs/embedding.md): syl_validate reads every kind's block, the ecosystem's included, and
 * reports to the stream the caller gives, with file:line:col.
 *   validate MODEL.syl   prints the diagnostics and "status N" (SYL_EMODEL: 1 on an error) */
#include <stdio.h>

#include <sylva/sylva.h>

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s MODEL.syl\n", argv[0]);
        return 2;
    }
    int st;
    SylProgram *p = syl_compile(argv[1], NULL, 0, &(SylCompileOptions){.diag = stdout, .validate = syl_validate}, &st);
    printf("status %d\n", p ? 0 : st);
    syl_program_free(p);
    return 0;
}
