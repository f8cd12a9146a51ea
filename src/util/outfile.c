/* Output files: see outfile.h for what happens to each kind of path. */
#include "util/outfile.h"
#include "util/diag.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

enum { MAX_LINKS = 40, MAX_TRIES = 100 };

static void report(const SylSink *sink, const char *path, int err) {
    if (!sink) return;
    if (!strcmp(path, "-")) sink_error(sink, "cannot write standard output: %s", strerror(err));
    else sink_error(sink, "cannot write '%s': %s", path, strerror(err));
}

/* The stream writes through here so that the first failure keeps its reason. */
static ssize_t cookie_write(void *cookie, const char *buf, size_t n) {
    OutFile *o = cookie;
    if (o->err) return 0;
    size_t done = 0;
    while (done < n) {
        ssize_t w = write(o->fd, buf + done, n - done);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            o->err = w < 0 ? errno : EIO;
            return 0; /* fopencookie: 0 is an error; the stream's error flag is set */
        }
        done += (size_t)w;
    }
    return (ssize_t)n;
}

static int cookie_close(void *cookie) {
    (void)cookie; /* the descriptor is closed by outfile_close */
    return 0;
}

/* path with its symlinks followed, also a dangling one's; NULL with errno on failure. */
static char *follow(const char *path) {
    char *cur = strdup(path);
    for (int hops = 0; cur; hops++) {
        struct stat st;
        if (lstat(cur, &st) || !S_ISLNK(st.st_mode)) return cur; /* open will say what is wrong */
        char link[PATH_MAX];
        ssize_t n = hops < MAX_LINKS ? readlink(cur, link, sizeof link - 1) : -1;
        if (n < 0) {
            if (hops >= MAX_LINKS) errno = ELOOP;
            free(cur);
            return NULL;
        }
        link[n] = 0;
        const char *slash = strrchr(cur, '/');
        size_t dir = link[0] != '/' && slash ? (size_t)(slash - cur) + 1 : 0; /* relative to the link */
        char *next = malloc(dir + (size_t)n + 1);
        if (next) {
            memcpy(next, cur, dir);
            memcpy(next + dir, link, (size_t)n + 1);
        }
        free(cur);
        cur = next;
    }
    return NULL;
}

char *outfile_follow(const char *path) { return follow(path); }

static char *dir_of(const char *path) {
    const char *slash = strrchr(path, '/');
    if (!slash) return strdup(".");
    if (slash == path) return strdup("/");
    return strndup(path, (size_t)(slash - path));
}

/* Copy all of from (read from its start) over to's start, and cut to there; false with errno. */
static bool copy_fd(int from, int to) {
    char buf[1 << 16];
    for (off_t at = 0;;) {
        ssize_t n = pread(from, buf, sizeof buf, at);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return false;
        if (n == 0) return !ftruncate(to, at);
        for (ssize_t done = 0; done < n;) {
            ssize_t w = write(to, buf + done, (size_t)(n - done));
            if (w < 0 && errno == EINTR) continue;
            if (w <= 0) {
                if (w == 0) errno = EIO;
                return false;
            }
            done += w;
        }
        at += n;
    }
}

/* Make o->tmp a fresh name PATH.tmpPID-N and tell the hooks (before it exists). */
static bool name_temp(OutFile *o, int n) {
    size_t len = strlen(o->target) + 48;
    free(o->tmp);
    o->tmp = malloc(len);
    if (!o->tmp) return false;
    snprintf(o->tmp, len, "%s.tmp%ld-%d", o->target, (long)getpid(), n);
    if (o->hooks && o->hooks->created) o->hooks->created(o->hooks->ctx, o->tmp);
    return true;
}

static void drop_temp(OutFile *o, bool unlink_it) {
    if (!o->tmp) return;
    if (unlink_it) unlink(o->tmp);
    if (o->hooks && o->hooks->gone) o->hooks->gone(o->hooks->ctx, o->tmp);
    free(o->tmp);
    o->tmp = NULL;
}

/* A new named temporary file, opened; -1 with errno. */
static int open_named(OutFile *o) {
    for (int n = 0; n < MAX_TRIES; n++) {
        if (!name_temp(o, n)) return -1;
        int fd = open(o->tmp, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666); /* the umask applies */
        if (fd >= 0) return fd;
        int e = errno;
        drop_temp(o, false);
        errno = e;
        if (e != EEXIST) return -1;
    }
    return -1;
}

/* The new file replacing o's target gets its mode, and its owner when we may (root). */
static void keep_mode(const OutFile *o, int fd) {
    if (geteuid() == 0 && fchown(fd, o->uid, o->gid)) { /* best effort, and before fchmod: */
    }                                                    /* chown clears set-user-id bits */
    if (fchmod(fd, o->mode)) { /* best effort: it keeps a new file's mode */
    }
}

static void free_names(OutFile *o) {
    free(o->path);
    free(o->target);
    o->path = o->target = NULL;
}

bool outfile_open(OutFile *o, const char *path, const OutHooks *hooks, const SylSink *sink) {
    memset(o, 0, sizeof *o);
    o->fd = -1;
    o->hooks = hooks;
    o->path = strdup(path);
    int e = ENOMEM;
    if (!o->path) goto fail;
    if (!strcmp(path, "-")) {
        fflush(stdout); /* what was printed before comes first */
        o->how = OUTFILE_STDOUT;
        o->fd = STDOUT_FILENO;
    } else {
        o->target = follow(path);
        if (!o->target) {
            e = errno;
            goto fail;
        }
        struct stat st;
        bool found = !stat(o->target, &st);
        if (found && !S_ISREG(st.st_mode)) {
            /* A FIFO, a device, a socket: stream into it; never replace it. */
            if (S_ISDIR(st.st_mode)) {
                e = EISDIR;
                goto fail;
            }
            o->how = OUTFILE_STREAM;
            o->fd = open(o->target, O_WRONLY | O_TRUNC | O_CLOEXEC | O_NOCTTY);
        } else {
            o->how = OUTFILE_TEMP;
            o->exists = found;
            if (found) o->mode = st.st_mode & 07777, o->uid = st.st_uid, o->gid = st.st_gid, o->nlink = st.st_nlink;
            char *dir = dir_of(o->target);
            if (!dir) goto fail;
            o->fd = hooks ? -1 : open(dir, O_TMPFILE | O_RDWR | O_CLOEXEC, 0666);
            free(dir);
            if (o->fd < 0) o->fd = open_named(o);
            if (o->fd >= 0 && o->exists && o->nlink == 1) keep_mode(o, o->fd);
        }
        if (o->fd < 0) {
            e = errno;
            drop_temp(o, true);
            goto fail;
        }
    }
    o->f = fopencookie(o, "w", (cookie_io_functions_t){.write = cookie_write, .close = cookie_close});
    if (!o->f) {
        o->err = ENOMEM;
        outfile_close(o, false, NULL);
        e = ENOMEM;
        goto fail;
    }
    setvbuf(o->f, NULL, _IOFBF, 1 << 16);
    return true;
fail:
    report(sink, path, e);
    free_names(o);
    return false;
}

/* Link the anonymous temporary file at to; false with errno (EEXIST: to exists). */
static bool link_anon(int fd, const char *to) {
    if (!linkat(fd, "", AT_FDCWD, to, AT_EMPTY_PATH)) return true;
    if (errno == EEXIST) return false;
    char proc[64]; /* AT_EMPTY_PATH needs a capability; this does not, but needs /proc */
    snprintf(proc, sizeof proc, "/proc/self/fd/%d", fd);
    return !linkat(AT_FDCWD, proc, AT_FDCWD, to, AT_SYMLINK_FOLLOW);
}

/* Put the finished temporary file in place; false with errno. */
static bool commit(OutFile *o) {
    if (fsync(o->fd)) return false;
    if (o->exists && o->nlink > 1) {
        /* Renaming would split the links: copy into the file they share. What was there is
         * kept until the whole output is ready, but a failed copy leaves it half-written. */
        int to = open(o->target, O_WRONLY | O_CLOEXEC); /* cut at the end: a failed first read keeps it */
        if (to < 0) return false;
        bool ok = copy_fd(o->fd, to) && !fsync(to);
        int e = errno;
        if (close(to) && ok) return false;
        errno = e;
        return ok;
    }
    if (!o->tmp) { /* anonymous: link it at the path, or under a temporary name to rename */
        if (!o->exists && link_anon(o->fd, o->target)) return true;
        bool linked = false;
        for (int n = 0; n < MAX_TRIES && !linked; n++) {
            if (!name_temp(o, n)) return false;
            linked = link_anon(o->fd, o->tmp);
            if (!linked) {
                int e = errno;
                drop_temp(o, false);
                errno = e;
                if (e != EEXIST) break;
            }
        }
        if (!linked) { /* no way to link it (no /proc?): copy it into a named file */
            int to = open_named(o);
            if (to < 0) return false;
            if (o->exists) keep_mode(o, to);
            bool ok = copy_fd(o->fd, to) && !fsync(to);
            int e = errno;
            if (close(to) && ok) ok = false, e = errno;
            errno = e;
            if (!ok) return false;
        }
    }
    if (rename(o->tmp, o->target)) return false;
    drop_temp(o, false); /* renamed: the name is the output's now */
    return true;
}

bool outfile_close(OutFile *o, bool commit_it, const SylSink *sink) {
    if (o->f && fclose(o->f) && !o->err) o->err = EIO; /* fclose flushes through cookie_write */
    o->f = NULL;
    bool ok = !o->err;
    if (o->how == OUTFILE_TEMP) {
        if (ok && commit_it && !commit(o)) {
            o->err = errno ? errno : EIO;
            ok = false;
        }
        drop_temp(o, true); /* what is left of it */
    }
    if (o->fd >= 0 && o->how != OUTFILE_STDOUT && close(o->fd) && ok && o->how == OUTFILE_STREAM) {
        o->err = errno;
        ok = false;
    }
    o->fd = -1;
    if (!ok && o->path) report(sink, o->path, o->err);
    free_names(o);
    return ok;
}
