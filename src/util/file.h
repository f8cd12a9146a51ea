/* Reading a whole file into memory: sources, obstacle meshes, anything read at once. */
#ifndef SYL_FILE_H
#define SYL_FILE_H
#include <errno.h>
#include <stddef.h>

#include "util/budget.h"

/* The most bytes of one file Sylva reads (docs/cli.md#model-files-and-your-files). */
#define FILE_MAX_BYTES ((size_t)1 << 30)
/* errno values of file_read_named, said by file_strerror: no read or seek of its makes these */
#define FILE_ENOTREG ESPIPE  /* a device, FIFO or socket */
#define FILE_EBUDGET EDQUOT  /* the memory budget refused its bytes */

/* Read a whole file the user gave ("-": standard input), NUL-terminated (the NUL is not counted
 * in *len); NULL with errno set on failure (ENOMEM when out of memory, EFBIG past
 * FILE_MAX_BYTES). Free with free(). */
char *file_read(const char *path, size_t *len);
/* Read a file a model names (a splice, an obstacle, a DEM, a plant table, a checkpoint): only a
 * regular file (never standard input), of at most FILE_MAX_BYTES, its size charged to mem (NULL:
 * nothing charged) until file_free_named. NULL with errno set (FILE_ENOTREG, EISDIR, EFBIG,
 * FILE_EBUDGET, or the system's). Never waits on a FIFO. */
char *file_read_named(const char *path, size_t *len, Budget *mem);
void file_free_named(char *text, size_t len, Budget *mem);
/* The reason for errno err of the functions above, for a message. */
const char *file_strerror(int err);
/* The one "file beside the model" rule: name as written when absolute or when the model is in
 * the working folder (or standard input, "-"), else in the model file's folder (malloc'd; NULL
 * when out of memory). Whether the model may read it is syl_program_file's (sylva.h). */
char *file_beside(const char *model_path, const char *name);

/* A file's name without its folder and extensions ("a/oak.tree.cfg": "oak"): *stem points into
 * path; returns its length (0: none, or path NULL). A model read from a foreign file is named so. */
size_t file_stem(const char *path, const char **stem);

#endif
