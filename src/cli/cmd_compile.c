/* sylva compile: compile a model; --dump shows what each rule became. */
#include <stdlib.h>

#include "cli/cli.h"

const CliCommand cli_compile_command = {
    .name = "compile",
    .what = "compile a model; --dump prints rules and bytecode",
    .run = cmd_compile,
    .usage = "sylva compile FILE[:Model] [--dump] [--set NAME=VALUE]... [--allow-path DIR]...",
    .about = "Compile the model and report errors. With --dump, print the compiled program: modules,\n"
             "settings, parameters, the axiom, every rule's contexts, condition, weight and successor,\n"
             "and the bytecode of each expression.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_DUMP, .help = ""}, /* no rows: the usage line names them */
        {.option = CLI_OPT_SET, .help = ""},
        {.option = CLI_OPT_ALLOW_PATH, .help = ""},
        {0},
    },
};

int cmd_compile(int argc, char **argv) {
    ModelArgs m = {0};
    CliArgs a = {.m = &m};
    int done = cli_parse(&cli_compile_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    cli_model_spec(&m, a.files[0]);
    int status;
    SylProgram *p = cli_compile(&m, SYL_WARN_MISTAKES, &status);
    if (p && a.dump) syl_program_dump(p, stdout);
    syl_program_free(p);
    return p ? SYL_OK : status;
}
