/* New contexts (lpfg's `<<` and `>>`): a pass that matches them in the string it writes. */
#ifndef SYL_LSYS_NEWCTX_H
#define SYL_LSYS_NEWCTX_H
#include <stdbool.h>

#include "lsys/rewrite.h"

struct NewctxScratch;

/* Rewrite modules w->lo..w->hi of w->in into w->out in one thread: forward (first module
 * first), matching `<<` contexts on the output written so far, or backward (last module
 * first), matching `>>` contexts on the output to the right. The output is in normal order
 * either way; random streams are keyed by input position as in rewrite_chunk. A fault is
 * left in w->fault. */
void newctx_chunk(Work *w, bool backward, struct NewctxScratch **scratch);
/* The arrays a pass keeps for the next one (*scratch: NULL at first, and again after this). */
void newctx_release(struct NewctxScratch **scratch);

#endif
