/* One row per kind of lang/kinds.def. The switch has no default: a kind added to the enum
 * without its row here is a compiler warning (an error under -Werror). */
#include "kinds/kinds.h"

#include "sot/params.h"
#include "sylva/ecosystem.h"
#include "sylva/trees.h"

const KindOps *kinds_ops(SylModelKind k) {
    static const KindOps none = {0};
    static const KindOps grow = {.validate = sot_check_grow};
    static const KindOps weber = {.validate = syl_weber_validate, .build = syl_weber};
    static const KindOps strands = {.validate = syl_strands_validate, .build = syl_strands};
    static const KindOps ecosystem = {.validate = syl_ecosystem_validate};
    switch (k) {
    case SYL_MODEL_LSYSTEM: return &none; /* lsys derives it; the language checks it */
    case SYL_MODEL_SCENE: return &none;   /* syl_validate checks the scene of any model */
    case SYL_MODEL_GROW: return &grow;
    case SYL_MODEL_WEBER: return &weber;
    case SYL_MODEL_STRANDS: return &strands;
    case SYL_MODEL_ECOSYSTEM: return &ecosystem;
    }
    return &none;
}
