/* The registry: each row of lang/kinds.def, its engine's functions. The switch is made from
 * the table and has no default: a value of SylModelKind without its row is a compiler
 * warning (an error under -Werror). */
#include "kinds/kinds.h"

#include <stddef.h>

#include "lang/kinds.h"
#include "lang/schema.h"
#include "sylva/ecosystem.h"
#include "util/diag.h"
/* the headers of the functions the rows name */
#define SYL_KIND(...)
#define SYL_KIND_HEADERS
#include "lang/kinds.def"
#undef SYL_KIND_HEADERS
#undef SYL_KIND

/* The ecosystem's check reports to a sink: the hook's stream as one. */
static int ecosystem_validate(const SylProgram *p, FILE *diag) {
    return syl_ecosystem_validate(p, diag_sink(&(SylSink){0}, diag, NULL));
}

const KindOps *kinds_ops(SylModelKind k) {
    static const KindOps none = {0};
    switch (k) {
#define SYL_KIND(id, keyword, noun, flags, instead, validate_, build_, describe_, converts_, convert_) \
    case SYL_MODEL_##id: {                                                                              \
        static const KindOps ops = {.validate = validate_, .build = build_, .describe = describe_,     \
                                    .converts = converts_, .convert = convert_};                       \
        return &ops;                                                                                    \
    }
#include "lang/kinds.def"
#undef SYL_KIND
    }
    return &none;
}
