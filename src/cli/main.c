/* sylva: the command line. Each subcommand lives in its own file. */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

static const struct {
    const char *name;
    int (*run)(int, char **);
    const char *what;
} commands[] = {
    {"derive", cmd_derive, "derive a model and print the resulting string"},
    {"check", cmd_check, "report errors and warnings in model files"},
    {"compile", cmd_compile, "compile a model; --dump prints rules and bytecode"},
    {"skeleton", cmd_skeleton, "draw a model with the turtle and export its skeleton (CSV, JSON)"},
    {"mesh", cmd_mesh, "draw a model and write a triangle mesh (.glb, .obj, .ply)"},
    {"render", cmd_render, "draw a model and ray-trace a PNG picture of it"},
    {"grow", cmd_grow, "grow a self-organizing tree or a scene; picture, mesh or skeleton"},
    {"compare", cmd_compare, "print a table of metrics of several models; --image draws them side by side"},
};

static void help(FILE *out) {
    fprintf(out, "usage: sylva COMMAND [options]\n\nSylva %s: plant models from grammar files.\n\ncommands:\n",
            SYLVA_VERSION);
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
        fprintf(out, "  %-9s %s\n", commands[i].name, commands[i].what);
    fprintf(out, "\n`sylva FILE` alone writes out/NAME.png and out/NAME.glb (see `sylva FILE --help`).\n"
                 "`sylva COMMAND --help` describes a command. A model is named FILE or FILE:Model\n"
                 "when a file holds several. Exit codes: 0 ok, 1 the model is wrong, 2 bad command\n"
                 "line, 3 a resource limit was hit, 4 an I/O error.\n");
}

int main(int argc, char **argv) {
    if (argc < 2) {
        help(stderr);
        return SYL_EUSAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        if (argc > 2 && strcmp(cmd, "help") == 0)
            for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
                if (!strcmp(commands[i].name, argv[2])) {
                    char *args[] = {argv[2], "--help", NULL};
                    return commands[i].run(2, args);
                }
        help(stdout);
        return SYL_OK;
    }
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "-V")) {
        printf("sylva %s\n", SYLVA_VERSION);
        return SYL_OK;
    }
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
        if (!strcmp(commands[i].name, cmd)) {
            char name[64]; /* getopt's messages begin with argv[0]: "sylva derive: ..." */
            snprintf(name, sizeof name, "sylva %s", cmd);
            argv[1] = name;
            return commands[i].run(argc - 1, argv + 1);
        }
    ModelArgs m; /* `sylva FILE[:Model]`: a picture and a mesh in out/ */
    cli_model_spec(&m, cmd);
    if (access(m.path, R_OK) == 0 || !strcmp(cmd, "-")) return cmd_plant(argc, argv);
    fprintf(stderr, "sylva: unknown command '%s'\n\n", cmd);
    help(stderr);
    return SYL_EUSAGE;
}
