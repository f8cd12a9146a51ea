/* sylva describe: every model of a file with every parameter (sylva/describe.h). */
#include "cli/cli.h"
#include "sylva/describe.h"

const CliCommand cli_describe_command = {
    .name = "describe",
    .what = "list every parameter of every model: type, range, default, unit, value",
    .run = cmd_describe,
    .usage = "sylva describe FILE [--json] [--set NAME=VALUE]...",
    .about = "Print every model of the file with every parameter it takes: its `param`s, an\n"
             "L-system's settings, a block's directives (from its kind's table, docs/directives.md),\n"
             "each with its type, range, default, unit, meaning and the value the model gives it\n"
             "(after --set). --json writes the form the viewer, Python and Blender read.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_JSON, .help = "JSON (docs/cli.md shows its shape) instead of the table"},
        {.option = CLI_OPT_SET, .help = "describe the models with this value; repeatable"},
        {0},
    },
    .width = 18,
};

int cmd_describe(int argc, char **argv) {
    ModelArgs m = {0};
    CliArgs a = {.m = &m};
    int done = cli_parse(&cli_describe_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    cli_model_spec(&m, a.files[0]);
    int status;
    SylProgram *p = cli_compile(&m, 0, &status);
    if (!p) return status;
    int r = a.format == CLI_FORMAT_JSON ? syl_describe_json(p, stdout) : syl_describe_text(p, stdout);
    syl_program_free(p);
    if (fflush(stdout) || r) {
        fprintf(stderr, "sylva: error: cannot write the description\n");
        return SYL_EIO;
    }
    return SYL_OK;
}
