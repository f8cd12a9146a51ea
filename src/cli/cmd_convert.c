/* sylva convert: a weber block, or a species of an Arbaro XML file, written as Arbaro XML or
 * as a .syl weber block (docs/arbaro.md). */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"
#include "weber/params.h"
#include "weber/xml.h"

const CliCommand cli_convert_command = {
    .name = "convert",
    .what = "write a weber block as Arbaro XML, or an Arbaro species file as a .syl block",
    .run = cmd_convert,
    .usage = "sylva convert FILE[:Model] -o OUT.xml|OUT.syl [--set NAME=VALUE]...",
    .about = "Read a weber model (a `weber` block of a .syl file, or a species of an Arbaro XML\n"
             "file) and write every one of its parameters: as an Arbaro species file for *.xml, in\n"
             "Arbaro's order and spelling, or as a `weber` block for *.syl, per-level parameters as\n"
             "lists over levels 0 to 3. Values are written so that they read back exactly: converting\n"
             "the written file again gives the same bytes.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUTPUT, .help = "write to FILE (required): Arbaro XML for *.xml, a weber block\n"
                                           "for *.syl"},
        {.option = CLI_OPT_SET},
        {.option = CLI_OPT_ALLOW_PATH},
        {0},
    },
    .epilogue = "\n" CLI_EXIT_CODES,
    .args_error = "expects one model file",
};

static bool ends_with(const char *s, const char *ext) {
    size_t n = strlen(s), e = strlen(ext);
    return n > e && !strcasecmp(s + n - e, ext);
}

/* The species' name: a `Species "…"` line (kept by a .syl written from XML), else the model's. */
static const char *species_name(const SylProgram *p) {
    int n;
    const SylDirective *ds = syl_program_directives(p, &n);
    const char *name = syl_program_name(p);
    for (int i = 0; i < n; i++)
        if (!strcmp(ds[i].name, "Species") && ds[i].nargs == 1 &&
            (ds[i].args[0].kind == SYL_DARG_STRING || ds[i].args[0].kind == SYL_DARG_WORD))
            name = ds[i].args[0].text;
    return name;
}

int cmd_convert(int argc, char **argv) {
    ModelArgs m = {0};
    CliArgs a = {.m = &m};
    int done = cli_parse(&cli_convert_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    const char *output = a.output;
    bool xml = output && ends_with(output, ".xml"), syl = output && ends_with(output, ".syl");
    if (!xml && !syl) {
        fprintf(stderr, "sylva convert: error: %s: name the output *.xml (Arbaro XML) or *.syl (a weber block) "
                        "with -o\n", output ? "cannot tell the format" : "no output");
        return SYL_EUSAGE;
    }
    cli_model_spec(&m, a.files[0]);
    int status;
    SylProgram *p = cli_compile(&m, SYL_WARN_MISTAKES, &status);
    if (!p) return status;
    if (syl_program_kind(p) != SYL_MODEL_WEBER) {
        fprintf(stderr, "sylva convert: error: '%s' is a %s: convert writes weber blocks and Arbaro species\n",
                syl_program_name(p), syl_model_kind_name(syl_program_kind(p)));
        syl_program_free(p);
        return SYL_EUSAGE;
    }
    WeberParams w;
    status = weber_params_read(p, &w, stderr) ? SYL_EMODEL : SYL_OK;
    if (!status) {
        OutFile out; /* through a temporary file: nothing half-written on an error */
        if (!out_open(&out, output)) status = SYL_EIO;
        else {
            const char *src = strrchr(m.path, '/');
            char note[4200];
            snprintf(note, sizeof note, "%s, converted by `sylva convert`", src ? src + 1 : m.path);
            status = xml ? weber_write_xml(&w, species_name(p), out.f)
                         : weber_write_syl(&w, species_name(p), note, out.f);
            if (status == SYL_ELIMIT) fprintf(stderr, "sylva convert: error: out of memory\n");
            status = out_close(&out, status);
        }
    }
    syl_program_free(p);
    return status;
}
