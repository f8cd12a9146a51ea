/* The texture lines of every kind of plant (lang/textures.def, docs/language.md#21-textures-bark-and-leaf-images). */
#ifndef SYL_LANG_TEXTURES_H
#define SYL_LANG_TEXTURES_H
#include <stdbool.h>
#include <stdio.h>

#include "lang/program.h"
#include "sylva/skeleton.h"
#include "util/paramxml.h"

/* Whether a directive's name is a texture line (which the kinds' own readers leave alone). */
bool lang_texture_line(const char *name);
/* Read p's texture lines into spec (zeroed first; spec->images NULL when there are none), every
 * file read under the model's path rule (syl_program_file) and checked to be a whole PNG.
 * SYL_OK; else spec is empty and the errors were reported to diag: SYL_EMODEL (a line, or a
 * file that is not a PNG), SYL_EIO (a file that cannot be read, or outside the folders the
 * model may read) or SYL_ELIMIT, the worst of them. */
int lang_textures(const SylProgram *p, SylTextureSpec *spec, FILE *diag);
/* One image named by argument a of d added to spec (the same name once): *idx its 1 + index.
 * SYL_OK, or SYL_EMODEL / SYL_EIO reported at a, or SYL_ELIMIT. */
int lang_texture_image(const SylProgram *p, const SylDirective *d, const SylDirArg *a, SylTextureSpec *spec,
                       int *idx, FILE *diag);
void lang_textures_free(SylTextureSpec *spec);
/* The check of sylva check (syl_validate): the lines read and their files checked; 1 when
 * there were errors (reported), else 0. */
int lang_textures_check(const SylProgram *p, FILE *diag);

/* Whether p's texture lines read, their images included (lang_textures, its spec freed):
 * what a writer that copies the lines checks first. */
static inline int lang_textures_read(const SylProgram *p, FILE *diag) {
    SylTextureSpec t;
    int st = lang_textures(p, &t, diag);
    lang_textures_free(&t);
    return st;
}

/* sylva convert's writers (docs/language.md#21-textures-bark-and-leaf-images): p's texture
 * lines as a species file holds them, <bark file='F' tile='U V'/> and one
 * <leaf_texture file='F'/> per image (elements Arbaro's reader skips, lang/arbaro.c reads
 * back), or as .syl lines `  bark "F" tile U V`. The file names go as written. */
void lang_textures_xml(const SylProgram *p, ParamXml *x);
void lang_textures_syl(const SylProgram *p, FILE *out);

/* A generator's last step: give its skeleton sk the model's textures (lang_textures, then
 * syl_skeleton_apply_textures with the tree's seed). SYL_OK, or lang_textures' status, or
 * SYL_ELIMIT. */
static inline int lang_textures_apply(const SylProgram *p, SylSkeleton *sk, uint64_t seed, FILE *diag) {
    SylTextureSpec t;
    int st = lang_textures(p, &t, diag);
    if (st) return st;
    st = syl_skeleton_apply_textures(sk, &t, seed);
    if (st) program_say_error(p, diag, "'%s': its leaf textures need more than 256 materials", syl_program_name(p));
    lang_textures_free(&t);
    return st;
}

#endif
