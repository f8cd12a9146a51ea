/* The outputs of one command as one transaction: all written, or none changed. Each output
 * is still written by util/outfile (atomically, symlinks followed, FIFOs streamed); before it
 * is, outgroup_add notes what is at its path: a regular file is copied under a second name
 * (PATH.keepPID-N beside it, its mode and owner kept), a free path is noted as free. When one output fails,
 * outgroup_undo puts every kept file back and removes what the command made where nothing
 * was; when all succeeded, outgroup_commit drops the kept names. A FIFO or a device is written
 * through and cannot be taken back, and neither can a file with other hard links (rewritten in
 * place once its output is ready). A signal that stops the command leaves each output whole,
 * old or new, and the old contents of the replaced ones under their .keep names. */
#ifndef SYL_OUTGROUP_H
#define SYL_OUTGROUP_H
#include <stdbool.h>
#include <stdio.h>

#include "sylva/sylva.h"

typedef struct OutGroupItem {
    char *target; /* the file written: the path with its symlinks followed */
    char *keep;   /* its old contents' second name, or NULL */
    bool made;    /* nothing was at the path */
} OutGroupItem;

typedef struct OutGroup {
    OutGroupItem *v;
    int n, cap;
} OutGroup;

/* Before path is written. false (reported on sink) when its old contents cannot be kept. */
bool outgroup_add(OutGroup *g, const char *path, const SylSink *sink);
/* Every output was written: drop the kept names. */
void outgroup_commit(OutGroup *g);
/* One failed: every path as it was before the command. */
void outgroup_undo(OutGroup *g);

#endif
