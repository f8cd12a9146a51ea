/* sylva convert: a weber block, or a species of an Arbaro XML file, written as Arbaro XML or
 * as a .syl weber block (docs/arbaro.md); a grow block, or a grow preset file, written as a
 * grow preset or a .syl grow block (docs/growth.md#presets); a pafco block or Pafčo file
 * written as a Pafčo file or a .syl pafco block (docs/pafco.md). */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"
#include "kinds/kinds.h"
#include "lang/kinds.h"

const CliCommand cli_convert_command = {
    .name = "convert",
    .what = "write a weber, grow or pafco block as its file (Arbaro XML, a grow preset, a Pafčo file), or such a file as a .syl block",
    .run = cmd_convert,
    .usage = "sylva convert FILE[:Model] -o OUT.xml|OUT.cfg|OUT.syl [--set NAME=VALUE]...",
    .about = "Read a weber model (a `weber` block of a .syl file, or a species of an Arbaro XML\n"
             "file) and write every one of its parameters: as an Arbaro species file for *.xml, in\n"
             "Arbaro's order and spelling, or as a `weber` block for *.syl, per-level parameters as\n"
             "lists over levels 0 to 3. Values are written so that they read back exactly: converting\n"
             "the written file again gives the same bytes.\n"
             "A grow model (a `grow` block, or a grow preset file) is written as a grow preset for\n"
             "*.xml (<grow-presets>) or a `grow` block for *.syl: each directive with its values\n"
             "worked out (params and expressions), read back to the same bytes.\n"
             "A pafco model (a `pafco` block, or a Pafčo file) is written as a Pafčo file\n"
             "(PARAMETER=value) for *.cfg, as a `pafco` block for *.syl.\n"
             "The texture lines (bark, leaf_texture) are written too, their images read first; in\n"
             "XML as <bark file=… tile=…/> and <leaf_texture file=…/>, which Arbaro skips.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUTPUT, .help = "write to FILE (required): Arbaro XML for *.xml, a Pafčo file\n"
                                           "for *.cfg, a weber or pafco block for *.syl"},
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

/* "weber blocks as *.xml or *.syl, ...": what the registry says each kind converts to. */
static void say_what_converts(FILE *f) {
    const char *sep = "";
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        unsigned converts = kinds_ops((SylModelKind)k)->converts;
        if (!converts) continue;
        fprintf(f, "%s%ss as", sep, syl_model_kind_name((SylModelKind)k));
        const char *or = " ";
        for (unsigned fmt = 1; fmt <= KC_ALL; fmt <<= 1)
            if (converts & fmt) fprintf(f, "%s*%s", or, lang_convert_ext(fmt)), or = " or ";
        sep = ", ";
    }
}

int cmd_convert(int argc, char **argv) {
    ModelArgs m = {0};
    CliArgs a = {.m = &m};
    int done = cli_parse(&cli_convert_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    const char *output = a.output;
    unsigned format = 0;
    for (unsigned fmt = 1; output && fmt <= KC_ALL; fmt <<= 1)
        if (ends_with(output, lang_convert_ext(fmt))) format = fmt;
    if (!format) {
        fprintf(stderr, "sylva convert: error: %s: name the output *.xml (Arbaro XML, a grow preset), *.cfg (a Pafčo "
                        "file) or *.syl (a block) with -o\n", output ? "cannot tell the format" : "no output");
        return SYL_EUSAGE;
    }
    cli_model_spec(&m, a.files[0]);
    int status;
    SylProgram *p = cli_compile(&m, SYL_WARN_MISTAKES, &status);
    if (!p) return status;
    const KindOps *ops = kinds_ops(syl_program_kind(p));
    if (!(ops->converts & format)) {
        fprintf(stderr, "sylva convert: error: '%s' is a %s: convert writes ", syl_program_name(p),
                syl_model_kind_name(syl_program_kind(p)));
        say_what_converts(stderr);
        fputc('\n', stderr);
        syl_program_free(p);
        return SYL_EUSAGE;
    }
    OutFile out; /* through a temporary file: nothing half-written on an error */
    if (!out_open(&out, output)) status = SYL_EIO;
    else {
        const char *src = strrchr(m.path, '/');
        char note[4200];
        snprintf(note, sizeof note, "%s, converted by `sylva convert`", src ? src + 1 : m.path);
        status = ops->convert(p, format, note, out.f, stderr);
        if (status == SYL_ELIMIT) fprintf(stderr, "sylva convert: error: out of memory\n");
        status = out_close(&out, status);
    }
    syl_program_free(p);
    return status;
}
