/* Reading a whole file into memory: sources, obstacle meshes, anything read at once. */
#ifndef SYL_FILE_H
#define SYL_FILE_H
#include <stddef.h>

/* Read a whole file ("-": standard input), NUL-terminated (the NUL is not counted in *len);
 * NULL with errno set on failure (ENOMEM when out of memory). Free with free(). */
char *file_read(const char *path, size_t *len);

#endif
