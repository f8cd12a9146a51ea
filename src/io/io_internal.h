/* Pieces shared by the mesh writers. */
#ifndef SYL_IO_INTERNAL_H
#define SYL_IO_INTERNAL_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/mesh.h"

/* A file written under a temporary name and renamed into place by io_commit. */
typedef struct IoFile {
    FILE *f;
    char *path, *tmp;
} IoFile;

bool io_open(IoFile *o, const char *path, FILE *diag);
/* Close; when status is SYL_OK and the writes went well, keep the file (rename it into place
 * if rename is set, else leave it under its temporary name for io_rename); otherwise remove
 * it. Returns the status, SYL_EIO when writing failed. */
int io_close(IoFile *o, int status, bool rename, FILE *diag);
int io_rename(IoFile *o, FILE *diag);
void io_discard(IoFile *o); /* remove a closed, unrenamed file and forget it */

/* A growable byte buffer. */
typedef struct IoBuf {
    uint8_t *data;
    size_t len, cap;
    bool failed; /* out of memory */
} IoBuf;

void io_put(IoBuf *b, const void *p, size_t n);
void io_printf(IoBuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void io_json_string(IoBuf *b, const char *s); /* a quoted, escaped JSON string */
void io_free(IoBuf *b);

/* Short decimal form of x with about sig significant digits ("0.25", "-3", "1e-07"). */
char *io_float(char *p, float x, int sig);

/* A material's name in files: its kind and index ("bark0", "leaf1", "plain3"). */
void io_material_name(const SylMesh *m, int material, char *buf, size_t n);
/* The texture kind name of a material ("bark", "leaf", "flower"), NULL for plain ones. */
const char *io_texture_kind(const SylMesh *m, int material);

/* Encode size x size RGB as PNG into b. */
bool io_png(IoBuf *b, const uint8_t *rgb, int size);

#endif
