/* Reading a whole file into memory (util/file.h). */
#include "util/file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

char *file_read(const char *path, size_t *len) {
    FILE *f = strcmp(path, "-") ? fopen(path, "rb") : stdin;
    if (!f) return NULL;
    errno = 0;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    int err = 0;
    for (size_t got; buf && (got = fread(buf + n, 1, cap - n, f)) > 0;) {
        n += got;
        if (n > FILE_MAX_BYTES) { /* /dev/zero, or a stream without end */
            err = EFBIG;
            break;
        }
        if (n == cap) {
            char *nb = realloc(buf, cap *= 2);
            if (!nb) { free(buf); buf = NULL; }
            buf = nb;
        }
    }
    if (!err) err = ferror(f) ? (errno ? errno : EIO) : 0;
    if (f != stdin) fclose(f);
    if (err || !buf) {
        free(buf);
        errno = err ? err : ENOMEM;
        return NULL;
    }
    buf[n] = 0; /* n < cap: the loop grows the buffer when it fills */
    *len = n;
    return buf;
}

char *file_read_named(const char *path, size_t *len, Budget *mem) {
    /* O_NONBLOCK: opening a FIFO without a writer would wait for one */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) return NULL;
    struct stat sb;
    int err = 0;
    if (fstat(fd, &sb)) err = errno;
    else if (S_ISDIR(sb.st_mode)) err = EISDIR;
    else if (!S_ISREG(sb.st_mode)) err = FILE_ENOTREG;
    else if ((uint64_t)sb.st_size > FILE_MAX_BYTES) err = EFBIG;
    size_t size = err ? 0 : (size_t)sb.st_size;
    if (!err && !budget_charge(mem, (uint64_t)size + 1)) err = FILE_EBUDGET;
    char *buf = err ? NULL : malloc(size + 1);
    if (!err && !buf) err = ENOMEM, budget_release(mem, (uint64_t)size + 1);
    size_t n = 0;
    while (!err && n < size) { /* a file that shrinks meanwhile ends early */
        ssize_t got = read(fd, buf + n, size - n);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) err = errno;
        else if (got == 0) break;
        else n += (size_t)got;
    }
    close(fd);
    if (err) {
        if (buf) free(buf), budget_release(mem, (uint64_t)size + 1);
        errno = err;
        return NULL;
    }
    budget_release(mem, (uint64_t)(size - n));
    buf[n] = 0;
    *len = n;
    return buf;
}

void file_free_named(char *text, size_t len, Budget *mem) {
    if (!text) return;
    free(text);
    budget_release(mem, (uint64_t)len + 1);
}

const char *file_strerror(int err) {
    switch (err) {
    case FILE_ENOTREG: return "not a regular file: Sylva reads only regular files here (no devices, FIFOs or sockets)";
    case EFBIG: return "larger than 1 GiB, the most Sylva reads of one file";
    case FILE_EBUDGET: return "reading it would go beyond --max-memory";
    default: return strerror(err);
    }
}

char *file_beside(const char *model_path, const char *name) {
    const char *slash = strrchr(model_path, '/');
    size_t dir = name[0] == '/' || !slash || !strcmp(model_path, "-") ? 0 : (size_t)(slash - model_path + 1);
    if (dir == 2 && model_path[0] == '.') dir = 0; /* "./model.syl" */
    char *path = malloc(dir + strlen(name) + 1);
    if (!path) return NULL;
    memcpy(path, model_path, dir); /* "dir/name"; as written when the model is in the working folder */
    strcpy(path + dir, name);
    return path;
}

size_t file_stem(const char *path, const char **stem) {
    const char *base = path ? strrchr(path, '/') : NULL;
    base = base ? base + 1 : path ? path : "";
    *stem = base;
    return strcspn(base, ".");
}
