/* A grow block written by `sylva convert` (lang/preset.c; the writers themselves are public,
 * syl_grow_write_preset and syl_grow_write_syl in sylva/grow.h). */
#ifndef SYL_LANG_PRESET_H
#define SYL_LANG_PRESET_H
#include <stdio.h>

#include "sylva/sylva.h"

/* The grow kind's convert (kinds/kinds.h, KindOps.convert): its texture lines read first,
 * then the block as a preset (KC_XML) or a .syl grow block (KC_SYL) with note. */
int lang_grow_convert(const SylProgram *p, unsigned format, const char *note, FILE *out, FILE *diag);

#endif
