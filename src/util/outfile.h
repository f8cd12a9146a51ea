/* Output files that never destroy what is at the path, and leave nothing half-written.
 *
 *   "-"                      standard output
 *   a symlink                followed: its target is written, the link stays
 *   a FIFO, device, ...      written through (opened with truncation, streamed into)
 *   a regular file           written to a temporary file in the same directory, fsync'ed,
 *                            given the original's mode (and owner, as root), renamed over it;
 *                            with hard links, copied into it instead, so the links stay
 *   a new path               a temporary file (mode 0666 less the umask) renamed into place
 *
 * The temporary file is anonymous (O_TMPFILE) when no hooks are given and the filesystem
 * allows it, so a killed program leaves nothing. With hooks it is named PATH.tmpPID-N and
 * reported to the hooks, so that the program can remove it when a signal stops it. */
#ifndef SYL_OUTFILE_H
#define SYL_OUTFILE_H
#include <stdbool.h>
#include <stdio.h>

#include "sylva/sylva.h"

/* Called before a named temporary file is created and after it is gone (renamed into place
 * or removed). Both may run with the path not existing. */
typedef struct OutHooks {
    void (*created)(void *ctx, const char *tmp);
    void (*gone)(void *ctx, const char *tmp);
    void *ctx;
} OutHooks;

typedef struct OutFile {
    FILE *f;       /* write here */
    int fd;        /* what f writes into */
    int err;       /* the first errno of a failed write, 0 when all went well */
    int how;       /* OUTFILE_STDOUT, OUTFILE_STREAM, OUTFILE_TEMP */
    char *path;    /* as named: for messages */
    char *target;  /* the file that is written: path with its symlinks followed */
    char *tmp;     /* the named temporary file, NULL when anonymous or none */
    bool exists;   /* target is an existing regular file: */
    unsigned mode, uid, gid, nlink; /* its permissions, owner and number of links */
    const OutHooks *hooks;
} OutFile;

enum { OUTFILE_STDOUT = 1, OUTFILE_STREAM, OUTFILE_TEMP };

/* Open path for writing; false (reported on sink as "sylva: error: cannot write 'PATH':
 * REASON") when it cannot be. hooks may be NULL. o must stay where it is until closed. */
bool outfile_open(OutFile *o, const char *path, const OutHooks *hooks, const SylSink *sink);
/* Close. When commit is set, put the file in place; otherwise remove the temporary file and
 * leave what was at the path as it was. False (reported) when a write or the commit failed;
 * a write error is reported whether or not commit is set. */
bool outfile_close(OutFile *o, bool commit, const SylSink *sink);

/* path with its symlinks followed (also a dangling one's): the file outfile_open writes;
 * malloc'd, NULL with errno on failure. */
char *outfile_follow(const char *path);

#endif
