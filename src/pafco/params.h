/* The parameters of a `pafco` block or a Pafčo `PARAMETER=value` file (Pafčo 2007,
 * Appendix 1; docs/pafco.md), read and checked against their table (params.def). */
#ifndef PAFCO_PARAMS_H
#define PAFCO_PARAMS_H
#include <stdbool.h>
#include <stdio.h>

#include "sylva/sylva.h"

enum { PAFCO_NPARAMS = 42, PAFCO_MAX_TEX = 16, PAFCO_PATH = 256 };

/* Generation g's values are at [g - 1] (gen[0] is always true: the first generation). */
typedef struct PafcoParams {
    double height, trunk_dev, width_ratio, crown_ratio;
    int seg_branch, seg_trunk;
    double alfa_kor, scatter, trunk_dratio, branch_dratio;
    double sph_radius, sph_count, bil_length, bil_width, bil_angle, leaf_size;
    int ltex_count;
    bool sph_leaves, bil_leaves, round_crown;
    int whorl;
    double transluc;
    char bark_file[PAFCO_PATH];
    int h_tex, v_tex;
    double angle[3], uhp, nextg, grav[3], sun[3], maxlen[3];
    bool gen[3];
    int detail;
    char tex_files[PAFCO_MAX_TEX][PAFCO_PATH];
    int ntex;
} PafcoParams;

/* Every parameter's default (the table's). */
void pafco_defaults(PafcoParams *P);
/* Read and check a pafco block; the number of errors, each reported on diag with
 * file:line:col and a caret. From a Pafčo file (PARAMETER=value), as the thesis's own reader
 * did, a bad value is a warning and its default is kept, and the parameters it leaves out are
 * named in one warning; an unknown name is an error either way. */
int pafco_params_read(const SylProgram *p, PafcoParams *P, FILE *diag);
/* The same for `sylva check`: the error count, negative when every error was of --set. */
int pafco_params_check(const SylProgram *p, FILE *diag);

/* P as a Pafčo file (every parameter, one a line, in the appendix's order) or as a .syl
 * `pafco` block named name; values are written so that they read back exactly. */
int pafco_write_cfg(const PafcoParams *P, FILE *out);
int pafco_write_syl(const PafcoParams *P, const char *name, FILE *out);
/* The pafco kind's convert (kinds/kinds.h, KindOps.convert): the block read, then written as a
 * Pafčo file (KC_CFG) or a .syl block (KC_SYL; note unused: the block says where it is from). */
int pafco_convert(const SylProgram *p, unsigned format, const char *note, FILE *out, FILE *diag);

/* Table T.1: points of a ring around the trunk and generations 1..3 at DETAIL d (1..3). */
int pafco_ring_points(int detail, int generation);

#endif
