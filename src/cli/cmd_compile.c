/* sylva compile: compile a model; --dump shows what each rule became. */
#include <getopt.h>
#include <stdlib.h>

#include "cli.h"

static const char usage[] =
    "usage: sylva compile FILE[:Model] [--dump] [--set NAME=VALUE]...\n"
    "\n"
    "Compile the model and report errors. With --dump, print the compiled program: modules,\n"
    "settings, parameters, the axiom, every rule's contexts, condition, weight and successor,\n"
    "and the bytecode of each expression.\n";

int cmd_compile(int argc, char **argv) {
    static const struct option opts[] = {
        {"dump", no_argument, 0, 'd'}, {"set", required_argument, 0, 'S'}, {"help", no_argument, 0, 'h'}, {0, 0, 0, 0}};
    ModelArgs m = {0};
    int dump = 0, c;
    optind = 1;
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        if (c == 'd') dump = 1;
        else if (c == 'S') {
            if (!cli_set(&m, optarg)) return SYL_EUSAGE;
        } else if (c == 'h') {
            fputs(usage, stdout);
            return SYL_OK;
        } else {
            fputs(usage, stderr);
            return SYL_EUSAGE;
        }
    }
    if (optind != argc - 1) {
        fputs(usage, stderr);
        return SYL_EUSAGE;
    }
    cli_model_spec(&m, argv[optind]);
    int status;
    SylProgram *p = cli_compile(&m, 0, &status);
    if (p && dump) syl_program_dump(p, stdout);
    syl_program_free(p);
    return p ? SYL_OK : status;
}
