/* The directive tables, as schema rows: the lsystem's settings here, and each kind's from the
 * schema.inc in its folder that lang/kinds.def names after its row. The .def and .inc files
 * are data only (no code of their folder is used): the generator reads the same params.def
 * for its own storage (offsets into its parameter struct), so each list is written once. */
#include <math.h>

#include "lang/schema.h"
#include "sylva/lod.h"

/* noun: what a row is ("setting"; docs/directives.md's title, "`weber` parameters"); intro:
 * the title's paragraph there */
#undef SCH_TABLE
#define SCH_TABLE(var, k, nn, rows, shape, intro) \
    const SchTable var = {k, nn, rows, (int)(sizeof rows / sizeof *rows), shape, intro};

static const SchRow lsystem_rows[] = {
#define SETTING(nm, ty, blk, na, rep, l, h, d, w, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .levels = 0, .def = {d}, .words = w, .unit = u, .doc = mean, \
     .def_text = w ? "forward" : NULL,},
#include "lang/settings.def"
#undef SETTING
#define TEXTURE_LINE(nm, ty, mean) {.name = nm, .type = ty, .def = {NAN}, .unit = "", .doc = mean},
#include "lang/textures.def"
};
SCH_TABLE(sch_lsystem, "lsystem", "setting", lsystem_rows, SCH_SETTINGS,
          "[language.md §5](language.md#5-settings) explains them.")

#define SCH_ROWS
#define SYL_KIND(...)
#define SYL_KIND_SCHEMAS
#include "lang/kinds.def"
