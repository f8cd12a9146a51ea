/* A weber block's parameters written back: as an Arbaro species file (XML, through libxml2's
 * xmlTextWriter) or as a `.syl` weber block; `sylva convert` calls these (docs/arbaro.md). */
#ifndef WEBER_XML_H
#define WEBER_XML_H
#include <stdio.h>

#include "sylva/sylva.h"
#include "weber/params.h"

/* Every parameter, in Arbaro's order and spelling, each value the shortest text that reads
 * back to the same double; Sylva's own settings (convention paper, Seed, envelope, ZScale)
 * only where they differ from what an Arbaro file means. SYL_OK, SYL_ELIMIT (out of memory)
 * or SYL_EIO (a write failed). The texture lines of tex (NULL: none) follow, as elements
 * Arbaro skips (lang_textures_xml). */
int weber_write_xml(const WeberParams *w, const char *species, const SylProgram *tex, FILE *out);
/* A `weber NAME { … }` block of every parameter, per-level ones as lists over levels 0..3;
 * note (may be NULL) becomes its first comment line. The species name is kept in a
 * `Species "…"` line when it is not a name the language reads; tex's texture lines (NULL:
 * none) close it. */
int weber_write_syl(const WeberParams *w, const char *species, const SylProgram *tex, const char *note, FILE *out);
/* The weber kind's convert (kinds/kinds.h, KindOps.convert): the texture lines and the
 * parameters read first, then every parameter as Arbaro XML (KC_XML) or a .syl block (KC_SYL),
 * under the species' name (a `Species "…"` line, which a .syl written from XML keeps, else
 * the model's). */
int weber_convert(const SylProgram *p, unsigned format, const char *note, FILE *out, FILE *diag);

#endif
