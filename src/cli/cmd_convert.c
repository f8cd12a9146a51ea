/* sylva convert: a weber block, or a species of an Arbaro XML file, written as Arbaro XML or
 * as a .syl weber block (docs/arbaro.md); a grow block, or a grow preset file, written as a
 * grow preset or a .syl grow block (docs/growth.md#presets); a pafco block or Pafčo file
 * written as a Pafčo file or a .syl pafco block (docs/pafco.md). */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"
#include "lang/program.h"
#include "lang/textures.h"
#include "sylva/grow.h"
#include "pafco/params.h"
#include "weber/params.h"
#include "weber/xml.h"

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

/* A grow block as a preset (*.xml) or a grow block (*.syl), through a temporary file. */
static int convert_grow(const SylProgram *p, const char *path, const char *output, bool xml) {
    OutFile out;
    if (!out_open(&out, output)) return SYL_EIO;
    const char *src = strrchr(path, '/');
    char note[4200];
    snprintf(note, sizeof note, "%s, converted by `sylva convert`", src ? src + 1 : path);
    int status = xml ? syl_grow_write_preset(p, out.f, stderr) : syl_grow_write_syl(p, note, out.f, stderr);
    if (status == SYL_ELIMIT) fprintf(stderr, "sylva convert: error: out of memory\n");
    return out_close(&out, status);
}

/* A pafco model as a Pafčo file (*.cfg) or a .syl pafco block. */
static int convert_pafco(const SylProgram *p, const char *output, bool cfg) {
    PafcoParams P;
    if (pafco_params_read(p, &P, stderr)) return SYL_EMODEL;
    OutFile out;
    if (!out_open(&out, output)) return SYL_EIO;
    int status = cfg ? pafco_write_cfg(&P, out.f) : pafco_write_syl(&P, syl_program_name(p), out.f);
    return out_close(&out, status);
}

int cmd_convert(int argc, char **argv) {
    ModelArgs m = {0};
    CliArgs a = {.m = &m};
    int done = cli_parse(&cli_convert_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    const char *output = a.output;
    bool xml = output && ends_with(output, ".xml"), syl = output && ends_with(output, ".syl"),
         cfg = output && ends_with(output, ".cfg");
    if (!xml && !syl && !cfg) {
        fprintf(stderr, "sylva convert: error: %s: name the output *.xml (Arbaro XML, a grow preset), *.cfg (a Pafčo "
                        "file) or *.syl (a block) with -o\n", output ? "cannot tell the format" : "no output");
        return SYL_EUSAGE;
    }
    cli_model_spec(&m, a.files[0]);
    int status;
    SylProgram *p = cli_compile(&m, SYL_WARN_MISTAKES, &status);
    if (!p) return status;
    if (syl_program_kind(p) == SYL_MODEL_WEBER || syl_program_kind(p) == SYL_MODEL_GROW) {
        SylTextureSpec t; /* the texture lines are written as they stand: checked first, as sylva check does */
        status = lang_textures(p, &t, stderr);
        lang_textures_free(&t);
        if (status) {
            syl_program_free(p);
            return status;
        }
    }
    if (syl_program_kind(p) == SYL_MODEL_GROW && !cfg) {
        status = convert_grow(p, m.path, output, xml);
        syl_program_free(p);
        return status;
    }
    if (syl_program_kind(p) == SYL_MODEL_PAFCO && !xml) {
        status = convert_pafco(p, output, cfg);
        syl_program_free(p);
        return status;
    }
    if (syl_program_kind(p) != SYL_MODEL_WEBER || cfg) {
        fprintf(stderr, "sylva convert: error: '%s' is a %s: convert writes weber blocks as *.xml or *.syl, grow "
                        "blocks as *.xml or *.syl, pafco blocks as *.cfg or *.syl\n",
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
            status = xml ? weber_write_xml(&w, species_name(p), p, out.f)
                         : weber_write_syl(&w, species_name(p), p, note, out.f);
            if (status == SYL_ELIMIT) fprintf(stderr, "sylva convert: error: out of memory\n");
            status = out_close(&out, status);
        }
    }
    syl_program_free(p);
    return status;
}
