/* Shared pieces of the `sylva` subcommands. */
#ifndef SYL_CLI_H
#define SYL_CLI_H
#include <stdbool.h>
#include <stdio.h>

#include "sylva/sylva.h"

enum { MAX_SETS = 64 };

/* What every command that compiles a model accepts. */
typedef struct ModelArgs {
    const char *spec;  /* FILE or FILE:Model, as typed */
    char path[4096];
    const char *model; /* NULL: the first */
    SylOverride sets[MAX_SETS];
    int nsets;
} ModelArgs;

/* Split FILE:Model. */
void cli_model_spec(ModelArgs *m, const char *spec);
/* Parse `name=value` for --set; prints the problem and returns false on error. */
bool cli_set(ModelArgs *m, char *arg);
bool cli_number(const char *opt, const char *arg, double min, double max, double *out);
bool cli_integer(const char *opt, const char *arg, double min, double max, double *out);
bool cli_size(const char *opt, const char *arg, unsigned long long *out); /* 512M, 2G */
SylProgram *cli_compile(ModelArgs *m, int lint, int *status);

/* Write through a temporary file renamed into place, so a failed run leaves nothing. */
typedef struct OutFile {
    FILE *f;
    char *path, *tmp;
} OutFile;
bool out_open(OutFile *o, const char *path); /* NULL or "-": standard output */
int out_close(OutFile *o, int status);       /* commit when status is SYL_OK */

double cli_now(void);
double cli_peak_mb(void);

int cmd_derive(int argc, char **argv);
int cmd_check(int argc, char **argv);
int cmd_compile(int argc, char **argv);

#endif
