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
#define TEXTURE_LINE(nm, ty, mean) {.name = nm, .type = ty, .def = {NAN}, .unit = "", .doc = mean},
#include "lang/textures.def"
};

#define LEAF_WORDS "0|disc|disc1|disc2|disc3|disc4|disc5|disc6|disc7|disc8|disc9|square|sphere|palm"
static const SchRow weber_rows[] = {
#define WP_G(f, nm, ty, l, h, lop, hop, d, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .lo_open = lop, .hi_open = hop, .def = {d}, \
     .words = (ty) == SCH_ENUM ? LEAF_WORDS : NULL, .def_text = (ty) == SCH_ENUM ? "0" : NULL, .unit = u, .doc = mean},
#define WP_L(f, nm, ty, l, h, lop, hop, d0, d1, d2, d3, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .lo_open = lop, .hi_open = hop, .levels = 4, \
     .def = {d0, d1, d2, d3}, .unit = u, .doc = mean},
#define WP_X(at, f, nm, ty, l, h, d, dt, w, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .def = {d}, .def_text = dt, .words = w, .unit = u, .doc = mean},
#include "weber/params.def"
#define TEXTURE_LINE(nm, ty, mean) {.name = nm, .type = ty, .def = {NAN}, .unit = "", .doc = mean},
#include "lang/textures.def"
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
#define TEXTURE_LINE(nm, ty, mean) {.name = nm, .type = ty, .def = {NAN}, .unit = "", .doc = mean},
#include "lang/textures.def"
};

static const SchRow curvetree_rows[] = {
#define CT_N(f, nm, ty, l, h, d, u, mean) {.name = nm, .type = ty, .lo = l, .hi = h, .def = {d}, .unit = u, .doc = mean},
#define CT_X(at, f, nm, ty, l, h, d, dt, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .def = {d}, .def_text = dt, .unit = u, .doc = mean},
#include "curvetree/params.def"
#define TEXTURE_LINE(nm, ty, mean) {.name = nm, .type = ty, .def = {NAN}, .unit = "", .doc = mean},
#include "lang/textures.def"
};

static const SchRow ecosystem_rows[] = {
#define ECO_B(at, f, nm, ty, l, h, d, dt, w, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .def = {d}, .def_text = dt, .words = w, .unit = u, .doc = mean},
#define ECO_W(nm, ty, mean) {.name = nm, .type = ty, .def = {NAN}, .unit = "", .doc = mean, .group = "species"},
#define ECO_S(f, nm, l, h, d, u, mean) \
    {.name = nm, .type = SCH_NUMBER, .lo = l, .hi = h, .def = {d}, .unit = u, .doc = mean, .group = "species"},
#define ECO_F(nm, u, mean) \
    {.name = nm, .type = SCH_LIST, .lo = -1e5, .hi = 1e5, .def = {NAN}, .unit = u, .doc = mean, .group = "species"},
#include "eco/params.def"
};

/* a grow block: a bare value by its directive's name (years), a mode by its directive's
 * (buds: alternate|opposite|whorled), a key as DIRECTIVE.KEY (buds.angle), as --set names them */
#define GT_NUM SCH_NUMBER
#define GT_INT SCH_INTEGER
#define GT_SEED SCH_INTEGER
#define GT_BOOL SCH_BOOLEAN
#define GT_VEC3 SCH_VECTOR
#define GT_WORD SCH_ENUM
#define GT_NAME SCH_STRING
#define GROUP_G NULL
#define GROUP_O "organ line" /* OrganSpec: the rows of each organ line */
#define GD_NUM(d) d
#define GD_INT(d) d
#define GD_SEED(d) d
#define GD_BOOL(d) d
#define GD_VEC3(d) d
#define GD_NAME(d) d
#define GD_WORD(d) NAN /* a word's default is its text */
#define GW_WORD(d) d
#define GW_NUM(d) NULL
#define GW_INT(d) NULL
#define GW_SEED(d) NULL
#define GW_BOOL(d) NULL
#define GW_VEC3(d) NULL
#define GW_NAME(d) NULL
static const SchRow grow_rows[] = {
#define GROW_VALUE(nm, ty, l, h, f, d, u, mean) \
    {.name = nm, .type = GT_##ty, .lo = l, .hi = h, .def = {d}, .unit = u, .doc = mean},
#define GROW_MODES(base, f, dir, dw, w, values, grp, mean, ...) \
    {.name = dir, .type = SCH_ENUM, .def = {NAN}, .def_text = dw, .words = w, .unit = "", .doc = mean, .group = grp, \
     __VA_ARGS__},
#define GROW_KEY(base, f, dir, wh, nm, ty, l, h, d, w, u, mean) \
    {.name = dir "." nm, .type = GT_##ty, .lo = l, .hi = h, .def = {GD_##ty(d)}, .def_text = GW_##ty(d), \
     .words = w, .unit = u, .doc = mean, .group = GROUP_##base, .when = wh},
#include "sot/params.def"
#define TEXTURE_LINE(nm, ty, mean) {.name = nm, .type = ty, .def = {NAN}, .unit = "", .doc = mean},
#include "lang/textures.def"
};

static const SchRow pafco_rows[] = {
#define PF(f, nm, al, ty, l, h, d, dt, u, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .def = {d}, .def_text = dt, .unit = u, .doc = mean, .aliases = al},
#include "pafco/params.def"
/* its K_SUBOR and TEX_SUBORY are the texture lines, bark and leaf_texture their aliases */
};

static const SchRow scene_rows[] = {
#define SCENE_ROW(id, nm, ty, l, h, lop, d, u, grp, mean) \
    {.name = nm, .type = ty, .lo = l, .hi = h, .lo_open = lop, .def = {d}, .unit = u, .doc = mean, .group = grp},
#include "scene/params.def"
};

/* noun: what a row is ("setting"; docs/directives.md's title, "`weber` parameters"); intro:
 * the title's paragraph there */
#define TABLE(var, k, nn, rows, shape, intro) \
    const SchTable var = {k, nn, rows, (int)(sizeof rows / sizeof *rows), shape, intro};
TABLE(sch_lsystem, "lsystem", "setting", lsystem_rows, SCH_SETTINGS,
      "[language.md §5](language.md#5-settings) explains them.")
TABLE(sch_grow, "grow", "directive", grow_rows, SCH_KEYED,
      "[growth.md](growth.md#directives) explains them. A line is `DIRECTIVE [MODE [N]] [VALUE] [KEY VALUE]...`: "
      "a row `DIRECTIVE` is its mode or value, `DIRECTIVE.KEY` a key (`--set buds.angle=35`); an organ "
      "line's rows are `organ.N` and `organ.N.KEY` for the N-th line from 1. `unit` is the model's unit "
      "of length.")
TABLE(sch_weber, "weber", "parameter", weber_rows, SCH_LINES,
      "[weberpenn.md](weberpenn.md) explains them. `N` is a level, 0 to 3: `1DownAngle 60` sets level 1, "
      "`DownAngle 0 60 45 45` levels 0 to 3.")
TABLE(sch_strands, "strands", "parameter", strands_rows, SCH_LINES,
      "[strands.md](strands.md#parameters) explains them. A per-order parameter's range is its Gravelius "
      "factor's.")
TABLE(sch_ecosystem, "ecosystem", "directive", ecosystem_rows, SCH_GROUPS,
      "[ecosystem.md](ecosystem.md) explains them; a species' lines follow its `species NAME` line "
      "(`--set NAME.maturity=30` for one species).")
TABLE(sch_curvetree, "curvetree", "parameter", curvetree_rows, SCH_LINES,
      "[curvetree.md](curvetree.md#parameters) explains them: the Blender plug-in's names, as its panel "
      "shows them.")
TABLE(sch_pafco, "pafco", "parameter", pafco_rows, SCH_LINES,
      "[pafco.md](pafco.md#parameters) explains them, with their English aliases; a Pafčo file "
      "(`NAME=value`) takes the same names.")
TABLE(sch_scene, "scene", "line", scene_rows, SCH_SCENE,
      "[growth.md](growth.md#scenes) explains them. A plant or obstacle line's rows are `plant.N.KEY` and "
      "`obstacle.N.KEY` for the N-th line from 1 (`--set scene.plant.2.x=3`; a terrain `ground \"file.obj\"` "
      "line is an obstacle line); `at (x, y, z)` is its rows `x`, `y` and `z`. The scene's reader checks "
      "more than a row says: each plant's model is in the file and can stand in a scene, and the sun is "
      "above the horizon.")
