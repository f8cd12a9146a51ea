/* The directive tables of every kind, as schema rows, from their .def files. The .def files
 * are data only (no code of their folder is used): the generator reads the same file for its
 * own storage (offsets into its parameter struct), so each list is written once. */
#include <math.h>

#include "lang/schema.h"
#include "sylva/lod.h"


static const SchRow lsystem_rows[] = {
#define SETTING(nm, ty, blk, na, rep, l, h, d, w, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .levels = 0, .def = {d}, .words = w, .unit = u, .doc = mean, \
     .def_text = w ? "forward" : NULL,},
#include "lang/settings.def"
#undef SETTING
};

#define LEAF_WORDS "0|disc|disc1|disc2|disc3|disc4|disc5|disc6|disc7|disc8|disc9|square|sphere|palm"
static const SchRow weber_rows[] = {
#define WP_G(f, nm, ty, l, h, lop, hop, d, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .lo_open = lop, .hi_open = hop, .def = {d}, \
     .words = (ty) == SCH_ENUM ? LEAF_WORDS : NULL, .def_text = (ty) == SCH_ENUM ? "0" : NULL, .unit = "", .doc = mean},
#define WP_L(f, nm, ty, l, h, lop, hop, d0, d1, d2, d3, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .lo_open = lop, .hi_open = hop, .levels = 4, \
     .def = {d0, d1, d2, d3}, .unit = "", .doc = mean},
#define WP_X(nm, ty, l, h, d, dt, w, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .def = {d}, .def_text = dt, .words = w, .unit = "", .doc = mean},
#include "weber/params.def"
};

static const SchRow strands_rows[] = {
#define ST_G(f, nm, sym, integer, l, h, d, u, mean) \
    {.name = nm, .type = integer ? SCH_INTEGER : SCH_NUMBER, .lo = l, .hi = h, .def = {d}, .unit = u, \
     .doc = mean},
#define ST_O(i, nm, sym, glo, ghi, wlo, whi, l, h, d, u, mean) \
    {.name = nm, .type = SCH_NUMBER, .lo = glo, .hi = ghi, .def = {d}, .unit = u, .doc = mean},
#define ST_X(nm, ty, l, h, d, dt, w, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .def = {d}, .def_text = dt, .words = w, .unit = u, .doc = mean},
#include "strands/params.def"
};

static const SchRow ecosystem_rows[] = {
#define ECO_B(nm, ty, l, h, d, dt, w, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .def = {d}, .def_text = dt, .words = w, .unit = u, .doc = mean},
#define ECO_W(nm, ty, mean) {.name = nm, .type = ty, .def = {NAN}, .unit = "", .doc = mean, .group = "species"},
#define ECO_S(f, nm, l, h, d, u, mean) \
    {.name = nm, .type = SCH_NUMBER, .lo = l, .hi = h, .def = {d}, .unit = u, .doc = mean, .group = "species"},
#define ECO_F(nm, u, mean) \
    {.name = nm, .type = SCH_LIST, .lo = -1e5, .hi = 1e5, .def = {NAN}, .unit = u, .doc = mean, .group = "species"},
#include "eco/params.def"
};

static const SchRow pafco_rows[] = {
#define PF(f, nm, al, ty, l, h, d, dt, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .def = {d}, .def_text = dt, .unit = u, .doc = mean, .aliases = al},
#include "pafco/params.def"
};

#define TABLE(var, k, nn, rows) const SchTable var = {k, nn, rows, (int)(sizeof rows / sizeof *rows)};
TABLE(sch_lsystem, "lsystem", "setting", lsystem_rows)
TABLE(sch_weber, "weber", "weber parameter", weber_rows)
TABLE(sch_strands, "strands", "strands parameter", strands_rows)
TABLE(sch_ecosystem, "ecosystem", "ecosystem directive", ecosystem_rows)
TABLE(sch_pafco, "pafco", "Pafčo parameter", pafco_rows)
