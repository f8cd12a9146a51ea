/* sylva check: report errors and warnings without deriving. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "sylva/ecosystem.h"

const CliCommand cli_check_command = {
    .name = "check",
    .what = "report errors and warnings in model files",
    .run = cmd_check,
    .usage = "sylva check FILE[:Model]...",
    .about = "Compile every model of each file (or the one named) and report errors and warnings:\n"
             "unknown names, rules that can never apply, weights that are not positive, modules,\n"
             "constants and functions that are never used, words close to a declared module,\n"
             "models that draw or grow nothing, scene files that cannot be read. Exit code 0\n"
             "when there is no error, 1 otherwise (warnings alone do not fail).\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_WERROR},
        {.option = CLI_OPT_SET, .help = "check the model with this value, as other commands would\n"
                                         "take it; repeatable"},
        {.option = CLI_OPT_ALLOW_PATH},
        {0},
    },
    .width = 18,
    .several = true,
};

int cmd_check(int argc, char **argv) {
    ModelArgs sets = {0}; /* --set, for every file */
    CliArgs a = {.m = &sets};
    int done = cli_parse(&cli_check_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    bool werror = a.werror;
    int files = 1; /* the scene's files are looked at too */
    int worst = SYL_OK, models = 0;
    for (int f = 0; f < a.nfiles; f++) {
        ModelArgs m = {0};
        cli_model_spec(&m, a.files[f]);
        memcpy(m.sets, sets.sets, sizeof m.sets);
        m.nsets = sets.nsets;
        size_t len = 0;
        char *text = syl_read_file(m.path, &len);
        if (!text) {
            fprintf(stderr, "sylva: error: cannot read '%s': %s\n", m.path, strerror(errno));
            worst = SYL_EIO;
            continue;
        }
        const char *names[256];
        char buf[8192];
        int n = m.model ? 0 : syl_model_list(m.path, text, len, names, 256, buf, sizeof buf);
        if (n == 0) { /* one model named, or a file that does not parse: report as is */
            names[0] = m.model;
            n = 1;
        }
        for (int i = 0; i < n; i++) {
            /* collect into memory to count warnings, then pass them on */
            char *msg = NULL;
            size_t msglen = 0;
            FILE *mem = open_memstream(&msg, &msglen);
            SylCompileOptions opt = {.model = names[i], .diag = mem ? mem : stderr, .lint = 1,
                                     .overrides = m.sets, .noverrides = m.nsets,
                                     .validate = syl_validate, .validate_user = &files,
                                     .allow_paths = sets.allow, .nallow_paths = sets.nallow};
            int status;
            SylProgram *p = syl_compile(m.path, text, len, &opt, &status);
            /* an ecosystem's DEM is parsed as the run parses it (0 for other kinds): malformed is an error */
            if (p && syl_ecosystem_check_terrain(p, &(SylSink){syl_diagnostic_print, mem ? mem : stderr})) {
                syl_program_free(p);
                p = NULL;
                status = SYL_EMODEL;
            }
            if (mem) fclose(mem);
            if (msg) fputs(msg, stderr);
            bool warned = msg && strstr(msg, ": warning: ");
            free(msg);
            models++;
            if (!p) {
                if (status > worst) worst = status;
            } else if (werror && warned && worst == SYL_OK) {
                worst = SYL_EMODEL;
            }
            syl_program_free(p);
        }
        free(text);
    }
    if (worst == SYL_OK) fprintf(stderr, "sylva check: %d model%s ok\n", models, models == 1 ? "" : "s");
    return worst;
}
