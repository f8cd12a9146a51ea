/* The kinds of model, read from lang/kinds.def: flags, keywords and names. */
#include "lang/kinds.h"

#include <string.h>

#include "lang/program.h"
#include "lang/schema.h"

/* kinds.def lists the kinds in the order of the public enum, whose values are explicit */
enum {
#define SYL_KIND(id, keyword, noun, flags, instead, validate, build, describe, converts, convert) KIND_ROW_##id,
#include "lang/kinds.def"
#undef SYL_KIND
};
#define SYL_KIND(id, keyword, noun, flags, instead, validate, build, describe, converts, convert) \
    _Static_assert((int)SYL_MODEL_##id == (int)KIND_ROW_##id, "lang/kinds.def is in SylModelKind order");
#include "lang/kinds.def"
#undef SYL_KIND

typedef struct KindRow {
    const char *keyword, *noun;
    unsigned flags;
    const char *instead;
    const SchTable *schema;
} KindRow;

static const KindRow rows[LANG_KIND_COUNT] = {
#define SYL_KIND(id, keyword, noun, flags, instead, validate, build, describe, converts, convert) [SYL_MODEL_##id] = {keyword, noun, flags, instead, describe},
#include "lang/kinds.def"
#undef SYL_KIND
};

static const KindRow *row(SylModelKind k) { return (unsigned)k < LANG_KIND_COUNT ? &rows[k] : NULL; }

unsigned lang_kind_flags(SylModelKind k) { return row(k) ? row(k)->flags : 0; }
const char *lang_kind_keyword(SylModelKind k) { return row(k) ? row(k)->keyword : NULL; }
const char *syl_model_kind_keyword(SylModelKind k) { return lang_kind_keyword(k); }

int syl_model_kind_is(SylModelKind k, SylModelTrait t) {
    if (!row(k)) return 0;
    switch (t) {
    case SYL_MODEL_HAS_STRING: return lang_kind_is(k, KF_STRING);
    case SYL_MODEL_HAS_STEPS: return lang_kind_is(k, KF_RULES | KF_GROWS);
    case SYL_MODEL_IS_PLANT: return !lang_kind_is(k, KF_NOT_A_PLANT);
    }
    return 0;
}
static const char *const cap_names[KF_COUNT] = {
#define SYL_KIND_FLAG(id, name, meaning) name,
#include "lang/kind_flags.def"
#undef SYL_KIND_FLAG
};
static const char *const cap_docs[KF_COUNT] = {
#define SYL_KIND_FLAG(id, name, meaning) meaning,
#include "lang/kind_flags.def"
#undef SYL_KIND_FLAG
};
const char *syl_model_cap_name(int i) { return i >= 0 && i < KF_COUNT ? cap_names[i] : NULL; }
const char *syl_model_cap_doc(int i) { return i >= 0 && i < KF_COUNT ? cap_docs[i] : NULL; }
unsigned syl_model_kind_caps(SylModelKind k) { return lang_kind_flags(k); }

const char *syl_model_kind_name(SylModelKind k) { return row(k) ? row(k)->noun : "model"; }
const struct SchTable *lang_kind_schema(SylModelKind k) { return row(k) ? row(k)->schema : NULL; }

int lang_kind_of_keyword(const char *word, size_t len) {
    for (int k = 0; k < LANG_KIND_COUNT; k++)
        if (strlen(rows[k].keyword) == len && !memcmp(rows[k].keyword, word, len)) return k;
    return -1;
}

const char *lang_convert_ext(unsigned format) {
    return format == KC_XML ? ".xml" : format == KC_CFG ? ".cfg" : format == KC_SYL ? ".syl" : NULL;
}

const char *lang_kind_article(SylModelKind k) { return strchr("aeiou", syl_model_kind_name(k)[0]) ? "an" : "a"; }

void lang_kind_refuse(const SylProgram *p, FILE *diag, const char *name, SylModelKind k, bool as_plant) {
    as_plant |= lang_kind_is(k, KF_NOT_A_PLANT);
    diag_say(diag, p ? program_sink(p) : NULL, DIAG_ERROR, NULL, "'%s' is %s %s, not %s: %s", name, lang_kind_article(k), syl_model_kind_name(k),
             as_plant ? "a plant" : "an lsystem", row(k) ? row(k)->instead : "");
}
