/* The Blender plug-in's curve-driven tree (thesis 2009, §4; docs/curvetree.md): a trunk along
 * a user's curve, two levels of monopodial branches that grow only inside a crown envelope and
 * are shortened until they fit, leaves denser toward the tips. Internal to src/curvetree/. */
#ifndef CURVETREE_CURVETREE_H
#define CURVETREE_CURVETREE_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/skeleton.h"
#include "sylva/sylva.h"

/* The block's directives (params.def), defaults where absent. The curve and the files are
 * kept as the lines that name them: they live as long as the program. */
typedef struct CtParams {
#define CT_N(f, nm, ty, l, h, d, u, mean) double f;
#include "curvetree/params.def"
    const SylDirective *trunk_at, *envelope_at;
} CtParams;

/* Read and check the block; the error count (each reported at its line with a caret). */
int ct_params_read(const SylProgram *p, CtParams *P, FILE *diag);
/* The same for `sylva check`: negative when every error was of --set. */
int ct_params_check(const SylProgram *p, FILE *diag);

/* A curve as a dense polyline: n points, their arc length s (s[0] = 0, s[n-1] = length), and
 * which of them are control points (a Bézier's anchors, a polyline's vertices): the trunk's
 * width varies at those. */
typedef struct CtCurve {
    double (*p)[3];
    double *s;
    int n;
    int *ctrl; /* indices into p, increasing, first 0 and last n - 1 */
    int nctrl;
    double length;
} CtCurve;

enum { CT_BEZIER_STEPS = 32 }; /* polyline points per cubic Bézier segment */

/* From control points: kind 'b' a chain of cubic Béziers (1 + 3k points), 'p' a polyline
 * (2 or more). false: too few points (or out of memory). */
bool ct_curve_make(CtCurve *c, int kind, const double (*pts)[3], int n);
/* The trunk line of a block: `trunk bezier (x,y,z) ...`, `trunk polyline ...` or
 * `trunk "file.obj"` (read beside the model, as syl_program_file allows). SYL_OK, or an error
 * reported at the line (SYL_EMODEL, SYL_EIO, SYL_ELIMIT). read_files false: only the inline
 * forms are checked (a file is read by the build). */
int ct_curve_of_directive(const SylProgram *p, const SylDirective *d, bool read_files, CtCurve *c, FILE *diag);
/* An OBJ file's curve: its `v` vertices joined by its `l` lines into one open chain (as
 * Blender exports a curve), from the end lower in y (Y is up). Errors as file:line:col (its
 * lines are not shown: a file a model names may be anything). SYL_OK, SYL_EMODEL or
 * SYL_ELIMIT. */
int ct_curve_obj(const char *path, const char *text, size_t len, CtCurve *c, FILE *diag);
void ct_curve_free(CtCurve *c);
/* The point at arc length s (clamped), the heading of its piece, and the piece's index. */
int ct_curve_at(const CtCurve *c, double s, double pos[3], double dir[3]);

/* Is a point inside the crown envelope? */
typedef bool (*CtInside)(void *user, const double p[3]);

/* Build the tree into sk (appended; its first node the trunk's root). SYL_OK, SYL_ELIMIT
 * (out of memory), SYL_ECANCELED when cancel (NULL: never), asked before the trunk's nodes and
 * before each first-level branch's, said stop (sk then holds part of the tree: free it).
 * leaf_aspect: the leaves' length / width. */
int ct_build(const CtParams *P, const CtCurve *trunk, CtInside inside, void *inside_user, double leaf_aspect,
             uint64_t seed, SylSkeleton *sk, const SylCancel *cancel);
/* Leaves per branch by the plug-in's step rule (the same for every length): the first at one
 * step from the base, step = length / 10 / density, x 19/20 after each leaf, never below
 * length / 30, while inside the branch. */
int ct_leaves_per_branch(double density);
/* The most nodes and leaves a tree of P can have (counted against the budget first). */
void ct_bounds(const CtParams *P, const CtCurve *trunk, uint64_t *nodes, uint64_t *leaves);

#endif
