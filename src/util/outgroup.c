/* The outputs of one command as one transaction (util/outgroup.h). */
#include "util/outgroup.h"
#include "util/diag.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/outfile.h"

/* A copy of target (its mode and owner too) under a fresh name PATH.keepPID-N: a copy, not a
 * second link, which outfile would take for a hard-linked file and rewrite in place. */
static int keep_copy(const char *target, char *keep, size_t cap, const struct stat *st) {
    int from = open(target, O_RDONLY | O_CLOEXEC), to = -1, e = 0;
    for (int k = 0; from >= 0 && to < 0 && k < 100; k++) {
        snprintf(keep, cap, "%s.keep%ld-%d", target, (long)getpid(), k);
        to = open(keep, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
        if (to < 0 && errno != EEXIST) break;
    }
    if (from < 0 || to < 0) e = errno;
    for (off_t left = st->st_size; !e && left > 0;) {
        ssize_t n = copy_file_range(from, NULL, to, NULL, (size_t)left, 0);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) e = n < 0 ? errno : EIO;
        else left -= n;
    }
    if (!e && (fchmod(to, st->st_mode & 07777) || (!geteuid() && fchown(to, st->st_uid, st->st_gid)))) e = errno;
    if (to >= 0 && close(to) && !e) e = errno;
    if (from >= 0) close(from);
    if (e && to >= 0) unlink(keep);
    return e;
}

bool outgroup_add(OutGroup *g, const char *path, const SylSink *sink) {
    if (g->n == g->cap) {
        int cap = g->cap ? 2 * g->cap : 16;
        OutGroupItem *v = realloc(g->v, (size_t)cap * sizeof *v);
        if (!v) {
            sink_error(sink, "out of memory");
            return false;
        }
        g->v = v, g->cap = cap;
    }
    OutGroupItem it = {.target = outfile_follow(path)};
    if (!it.target) return true; /* the writer will say why it cannot write there */
    struct stat st;
    if (lstat(it.target, &st)) {
        it.made = errno == ENOENT;
    } else if (S_ISREG(st.st_mode) && st.st_nlink == 1) {
        size_t n = strlen(it.target) + 48;
        it.keep = malloc(n);
        int e = it.keep ? keep_copy(it.target, it.keep, n, &st) : ENOMEM;
        if (e) {
            sink_error(sink, "cannot keep '%s' while it is replaced: %s", path, strerror(e));
            free(it.keep), free(it.target);
            return false;
        }
    }
    g->v[g->n++] = it;
    return true;
}

static void done(OutGroup *g) {
    for (int i = 0; i < g->n; i++) free(g->v[i].target), free(g->v[i].keep);
    free(g->v);
    memset(g, 0, sizeof *g);
}

void outgroup_commit(OutGroup *g) {
    for (int i = 0; i < g->n; i++)
        if (g->v[i].keep) unlink(g->v[i].keep);
    done(g);
}

void outgroup_undo(OutGroup *g) {
    for (int i = g->n; i-- > 0;) {
        const OutGroupItem *it = &g->v[i];
        if (it->keep) rename(it->keep, it->target); /* the old inode back, atomically */
        else if (it->made) unlink(it->target);
    }
    done(g);
}
