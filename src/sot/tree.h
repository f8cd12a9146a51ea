/* A self-organizing tree: its metamers (nodes) and buds in flat arrays, parents before
 * children, so a pass toward the root is a backward loop and one toward the tips a forward
 * loop — no recursion, no pointers, no allocation per bud.
 *
 * Node 0 is the tree's base (a zero-length root); node i > 0 is the end of the metamer that
 * starts at its parent. A node's main child continues its axis; its other children start
 * lateral axes. Buds sit on nodes: the apical bud of an axis at its tip, lateral buds where
 * the phyllotaxis put them. A bud that breaks becomes the apical bud of the shoot it grows. */
#ifndef SYL_SOT_TREE_H
#define SYL_SOT_TREE_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sot/params.h"
#include "sot/shoot_rule.h"
#include "util/budget.h"

enum { NODE_LATERAL = 1, NODE_DEAD = 2 };
enum { BUD_APICAL, BUD_LATERAL };

typedef struct Node {
    float pos[3];     /* the metamer's end */
    float h[3], l[3]; /* heading and a lateral reference (unit, perpendicular) */
    int32_t parent;   /* -1 for the base */
    int32_t main;     /* the child continuing the axis, or -1 */
    int32_t axis;
    float light;      /* this year's light at the node (shedding) */
    float pipe;       /* memory of shed branches: the sum of their r^n */
    uint16_t order;   /* branch order */
    uint16_t born;    /* year */
    uint16_t rank;    /* metamers before it on its axis (phyllotaxis) */
    uint8_t flags;    /* NODE_* */
    uint8_t pad;
} Node;

typedef struct Bud {
    float dir[3];     /* orientation (unit) */
    int32_t node;     /* where it sits */
    uint64_t key;     /* its random stream, derived from its parent's */
    float q;          /* light (or space) this year */
    float z;          /* demand: g * q^c */
    double v;         /* resource allocated */
    float seg;        /* metamer length this year */
    int32_t len;      /* metamers still to grow this year */
    int32_t plan;     /* this year's shoot plan (Tree.plans), -1: none */
    uint32_t cursor;  /* the plan's next attachment */
    uint16_t grown;   /* metamers of this year's shoot grown so far */
    uint16_t born;
    uint8_t kind;     /* BUD_* */
    uint8_t alive;
} Bud;

/* What a shoot rule hung on the tree: organs, and twigs drawn by F in a branch (neither
 * takes part in the light or the pipe model). */
typedef struct TreeOrgan {
    float pos[3], h[3], l[3];
    float size;
    int32_t node;
    uint16_t born;
    uint8_t kind, material;
} TreeOrgan;

typedef struct TreeTwig {
    float from[3], to[3], h[3], l[3];
    float radius;
    int32_t node;     /* the metamer it hangs on */
    int32_t parent;   /* the twig it continues, -1: it starts at the node (or at from) */
    uint16_t born;
    uint8_t material;
    uint8_t detached; /* it starts at from, away from its node and parent */
} TreeTwig;

typedef struct Tree {
    GrowParams P;
    int index;        /* in the forest */
    int start_year;   /* its first year in the forest's count */
    float base[3];
    Node *nodes;
    size_t n, cap;
    Bud *buds;
    size_t nb, bcap;
    int32_t axes;     /* axis ids handed out */
    /* a shoot rule, this year's plans, and what the rule hung on the tree */
    ShootRule *rule;
    ShootPlan *plans;
    size_t nplans, plans_cap;
    TreeOrgan *organs;
    size_t norgans, organs_cap;
    TreeTwig *twigs;
    size_t ntwigs, twigs_cap;
    /* per-node scratch of the yearly passes */
    double *acc, *acc2, *acc3;
    size_t scratch_cap;
    /* totals */
    uint64_t grown, shed_branches, shed_metamers;
    /* the memory budget its arrays count against (NULL: none), and what they count */
    Budget *mem;
    uint64_t charged;
    bool rule_shared; /* rule belongs to the forest */
} Tree;

/* A tree with its base and its first bud (pointing up), and its shoot rule compiled when P
 * names one. False when out of memory. */
bool tree_init(Tree *t, const GrowParams *P, int index, const float base[3], int start_year);
void tree_free(Tree *t);
/* Append a node or a bud; -1 when out of memory. Pointers into the arrays move. */
int32_t tree_add_node(Tree *t, const Node *n);
int32_t tree_add_bud(Tree *t, const Bud *b);
/* array_reserve that counts the growth against t->mem first: false when out of memory or
 * beyond the budget (the array unchanged). */
bool tree_reserve(Tree *t, void *arrp, size_t *cap, size_t need, size_t elem);
/* Room for the per-node scratch arrays. */
bool tree_scratch(Tree *t);
/* Drop dead nodes (NODE_DEAD) and buds (alive == 0), keeping order; indices are remapped.
 * dead (unless NULL) receives the dropped nodes' positions, 3 floats each, in order. */
bool tree_compact(Tree *t, float *dead);
/* Drop dead buds only, keeping order. */
void tree_compact_buds(Tree *t);
/* The key of a bud's k-th child stream. */
static inline uint64_t tree_child_key(uint64_t key, uint64_t k) {
    uint64_t z = key + 0x9e3779b97f4a7c15ull * (k + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

#endif
