/* Leaf outlines that are polygons: Weber–Penn's named leaf shapes (Arbaro's LeafShape words),
 * one list read by the mesher (which draws them) and the card textures (which fill them).
 *
 * A shape is one or two flat panels in leaf coordinates: s along the leaf, 0 at its base and
 * 1 at its tip, and t across, -1..1 over the leaf's full width. Each panel is counter-clockwise
 * in (s, t) and is drawn in the plane of H and cos(fold) L + sin(fold) U: the palm's two halves
 * are folded up about the midrib (a rotation, so the area stays the flat outline's). */
#ifndef SYL_LEAFOUTLINE_H
#define SYL_LEAFOUTLINE_H
#include <stdbool.h>

enum { LEAF_OUTLINE_OVAL, LEAF_OUTLINE_SQUARE, LEAF_OUTLINE_PALM, LEAF_OUTLINES };
enum { LEAF_OUTLINE_MAX_TRIS = 64, LEAF_OUTLINE_MAX_POINTS = LEAF_OUTLINE_MAX_TRIS + 2, LEAF_OUTLINE_MAX_PANELS = 2 };

/* A card's shape code for an outline (SylMesh.leaf_shape; below 128 are texture.h's shapes). */
#define LEAF_OUTLINE_CARD(kind, tris) (128 + 32 * (kind) + (tris))
#define LEAF_OUTLINE_CARD_MAX_TRIS 31

typedef struct LeafPanel {
    int n;      /* points; drawn as a fan of n - 2 triangles from the first */
    float fold; /* radians about the midrib, towards U */
    float st[LEAF_OUTLINE_MAX_POINTS][2];
} LeafPanel;

/* Is (kind, tris) an outline that can be drawn? tris: the oval's triangles (1..64). */
bool leaf_outline_valid(int kind, int tris);
/* The panels of a shape (out holds LEAF_OUTLINE_MAX_PANELS); returns how many (0: invalid). */
int leaf_outline_panels(int kind, int tris, LeafPanel *out);
/* Triangles of one face of the shape. */
int leaf_outline_tris(int kind, int tris);
/* Area of the shape for a leaf of length 1 and full width 1 (analytic, from its definition). */
double leaf_outline_area(int kind, int tris);
/* Is (s, t) inside the flat (unfolded) outline? */
bool leaf_outline_inside(int kind, int tris, float s, float t);

#endif
