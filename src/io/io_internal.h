/* Pieces shared by the mesh writers. */
#ifndef SYL_IO_INTERNAL_H
#define SYL_IO_INTERNAL_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/mesh.h"
#include "util/diag.h"
#include "util/outfile.h"

/* Files are written through util/outfile (no hooks: an anonymous temporary file). */
bool io_open(OutFile *o, const char *path, const SylSink *sink);
/* Close o; put it in place when status is SYL_OK, otherwise leave the path as it was.
 * Returns status, or SYL_EIO when writing failed (reported). */
int io_close(OutFile *o, int status, const SylSink *sink);

/* A byte span of the caller's memory, written in place of copying it (io_ref). */
typedef struct IoRef {
    size_t at; /* how many of data's own bytes come before it */
    const void *p;
    size_t n;
} IoRef;

/* A growable byte buffer: len bytes in all, of which len - ref_bytes are its own (data) and
 * the rest spans of memory it refers to. */
typedef struct IoBuf {
    uint8_t *data;
    size_t len, cap;
    bool failed; /* out of memory */
    IoRef *refs;
    size_t nrefs, ref_cap, ref_bytes;
} IoBuf;

void io_put(IoBuf *b, const void *p, size_t n);
/* n more own bytes appended for the caller to fill (a mesh's array converted in place, not a
 * call per element); NULL when out of memory. */
uint8_t *io_room(IoBuf *b, size_t n);
/* Room for n more own bytes at once, so that a known size grows the buffer once, not by
 * doubling and copying; a hint (what does not fit still grows). */
void io_reserve(IoBuf *b, size_t n);
/* Append n bytes of p by reference: p must stay as it is until b is written or freed. A big
 * array (a mesh's vertices) goes to the file without a copy in memory. */
void io_ref(IoBuf *b, const void *p, size_t n);
/* Write b's bytes, its own and those it refers to, in order. */
void io_write(const IoBuf *b, FILE *f);
void io_printf(IoBuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void io_json_string(IoBuf *b, const char *s); /* a quoted, escaped JSON string */
void io_free(IoBuf *b);

/* s made safe for one line of a text header (n bytes at most): control characters, and
 * spaces when no_spaces is set, become '_'. A name with a newline would end the line. */
void io_line_text(char *dst, size_t n, const char *s, bool no_spaces);

/* Short decimal form of x with about sig significant digits ("0.25", "-3", "1e-07"). */
char *io_float(char *p, float x, int sig);

/* A material's name in files: its kind and index ("bark0", "leaf1", "plain3"). */
void io_material_name(const SylMesh *m, int material, char *buf, size_t n);
/* The image of the model's own material i wears (SylMaterial.image), NULL: none (leaf clusters
 * draw their own cards). */
const SylImage *io_image(const SylMesh *m, int material);
/* The file an OBJ's copy of m's image k (0-based) is written to, beside the MTL: PREFIX_tex_NAME, NAME the
 * image file's own name (PREFIX_texK_NAME when an image before it has that name). */
void io_image_file(const SylMesh *m, int k, const char *prefix, char *buf, size_t n);
/* The texture kind name of a material ("bark", "leaf", "flower"), NULL for plain ones. */
const char *io_texture_kind(const SylMesh *m, int material);

/* Encode size x size RGB as PNG into b. */
bool io_png(IoBuf *b, const uint8_t *rgb, int size);
/* Encode w x h RGBA as PNG into b (leaf cards, impostor atlases). */
bool io_png_rgba(IoBuf *b, const uint8_t *rgba, int w, int h);

#endif
