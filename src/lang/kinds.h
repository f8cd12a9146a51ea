/* The kinds of model as the language knows them: one row each in lang/kinds.def. Code that
 * must know what a kind does asks its flags here, never compares it with a list of kinds;
 * the functions of each kind (validate, build, convert) are columns of its row that only
 * src/kinds reads. */
#ifndef SYL_LANG_KINDS_H
#define SYL_LANG_KINDS_H
#include <stdbool.h>
#include <stdio.h>

#include "sylva/sylva.h"

/* KF_ID = 1 << its place in lang/kind_flags.def; KF_COUNT bits in all. */
enum {
#define SYL_KIND_FLAG(id, name, meaning) KF_BIT_##id,
#include "lang/kind_flags.def"
#undef SYL_KIND_FLAG
    KF_COUNT
};
enum {
#define SYL_KIND_FLAG(id, name, meaning) KF_##id = 1 << KF_BIT_##id,
#include "lang/kind_flags.def"
#undef SYL_KIND_FLAG
};

/* The files `sylva convert` writes a model as, its row's converts column: XML (Arbaro's species
 * file, a grow preset), a Pafčo file, a .syl block. One bit each, in the order a message lists
 * them; lang_convert_ext names the bit's extension (NULL: not one bit of these). */
enum { KC_XML = 1 << 0, KC_CFG = 1 << 1, KC_SYL = 1 << 2, KC_ALL = KC_XML | KC_CFG | KC_SYL };
const char *lang_convert_ext(unsigned format);

/* How many kinds kinds.def lists (SylModelKind runs 0 .. LANG_KIND_COUNT - 1). */
enum {
#define SYL_KIND(id, keyword, noun, flags, instead, validate, build, describe, converts, convert) +1
    LANG_KIND_COUNT = 0
#include "lang/kinds.def"
#undef SYL_KIND
};

/* A kind's flags (0 for a value outside the enum), keyword ("weber") and noun ("weber block";
 * syl_model_kind_name). lang_kind_of_keyword: the kind a keyword opens, or -1. */
unsigned lang_kind_flags(SylModelKind k);
const char *lang_kind_keyword(SylModelKind k);
/* The kind's directive table, its row's describe column (lang/schema.h); NULL: none. */
const struct SchTable *lang_kind_schema(SylModelKind k);
int lang_kind_of_keyword(const char *word, size_t len);

/* Why a model of kind k cannot be what it was asked to be, to p's sink (p may be NULL), else
 * as text on diag: "'T' is a strands block, not an lsystem: it has no string; mesh or render
 * it" (as_plant: "..., not a plant: ...", what a KF_NOT_A_PLANT kind says whatever it was
 * asked). */
void lang_kind_refuse(const SylProgram *p, FILE *diag, const char *name, SylModelKind k, bool as_plant);
/* "a" or "an", before the kind's noun */
const char *lang_kind_article(SylModelKind k);

static inline bool lang_kind_is(SylModelKind k, unsigned flags) { return (lang_kind_flags(k) & flags) != 0; }

#endif
