/* The procedural textures' PNG bytes (bark, leaf, flower, a card's or a cluster's shape), kept
 * across .glb writes by the one who owns the cache (sylva view's server: a save of the file
 * writes the same textures again). The bytes are those glb_slot_png makes: the file does not
 * change, only the time to write it. */
#include <stdlib.h>
#include <string.h>

#include "io/glb.h"
#include "sylva/stream.h"

enum { SHAPES = 256 }; /* SylMesh.leaf_shape is a byte: the leaf outlines' cards are 128 and up */

struct SylTextureCache {
    uint8_t *png[GLB_SLOTS][SHAPES]; /* by slot and shape (the shape: cards and clusters) */
    size_t len[GLB_SLOTS][SHAPES];
};

SylTextureCache *syl_texture_cache_new(void) { return calloc(1, sizeof(SylTextureCache)); }

void syl_texture_cache_free(SylTextureCache *c) {
    if (!c) return;
    for (int k = 0; k < GLB_SLOTS; k++)
        for (int s = 0; s < SHAPES; s++) free(c->png[k][s]);
    free(c);
}

bool glb_slot_png_cached(SylTextureCache *c, IoBuf *b, int k, int shape, GlbPixels *px) {
    bool shaped = k == GLB_CARD || k == GLB_CLUSTER;
    int s = shaped ? shape : 0;
    if (!c || k < 0 || k >= GLB_SLOTS || s < 0 || s >= SHAPES) return glb_slot_png(b, k, shape, px);
    if (!c->png[k][s]) {
        IoBuf t = {0};
        if (!glb_slot_png(&t, k, shape, px) || t.nrefs) return io_free(&t), false;
        free(t.refs);
        c->png[k][s] = t.data, c->len[k][s] = t.len; /* taken over */
    }
    io_put(b, c->png[k][s], c->len[k][s]);
    return !b->failed;
}
