/* JSON strings, the one escaper of every JSON writer (glTF, skeletons, compare tables). */
#ifndef SYL_JSON_H
#define SYL_JSON_H
#include <stddef.h>
#include <stdio.h>

typedef void (*JsonPut)(void *ctx, const void *p, size_t n);

/* s as a quoted JSON string, through put: '"', '\' and control characters are escaped, and
 * bytes that are not UTF-8 become U+FFFD, so any C string gives valid JSON. */
void json_string(const char *s, JsonPut put, void *ctx);
void json_string_file(FILE *out, const char *s); /* the same into a stream */

#endif
