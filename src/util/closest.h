/* Close names: edit distance, for "did you mean" in messages. */
#ifndef SYL_CLOSEST_H
#define SYL_CLOSEST_H
#include <stdbool.h>
#include <stddef.h>

/* Levenshtein distance between a and b (insert, delete, replace, and swap of two
 * neighbours each count 1); stops counting at limit + 1. */
int closest_distance(const char *a, const char *b, int limit);
/* Whether a typed name is close enough to a known one to suggest it: none for names of 1 or
 * 2 letters, at most 1 edit up to 4 letters, 2 beyond; never the same name. */
bool closest_near(const char *typed, const char *known);
/* The list "'a', 'b' or 'c'" of the names near typed (at most 5) into buf; returns how many. */
int closest_list(const char *typed, const char *const *names, int n, char *buf, size_t size);

#endif
