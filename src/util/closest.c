/* Close names: edit distance (optimal string alignment) and the lists of "did you mean". */
#include "util/closest.h"

#include <stdio.h>
#include <string.h>

enum { LONGEST = 64 }; /* longer names are compared on their first 64 letters */

int closest_distance(const char *a, const char *b, int limit) {
    int n = (int)strnlen(a, LONGEST), m = (int)strnlen(b, LONGEST);
    if (n - m > limit || m - n > limit) return limit + 1;
    int rows[3][LONGEST + 1]; /* the two rows before this one, for swaps */
    int *prev2 = rows[0], *prev = rows[1], *cur = rows[2];
    for (int j = 0; j <= m; j++) prev[j] = j;
    for (int i = 1; i <= n; i++) {
        cur[0] = i;
        for (int j = 1; j <= m; j++) {
            int cost = a[i - 1] != b[j - 1];
            int d = prev[j - 1] + cost;
            if (prev[j] + 1 < d) d = prev[j] + 1;
            if (cur[j - 1] + 1 < d) d = cur[j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && prev2[j - 2] + 1 < d)
                d = prev2[j - 2] + 1;
            cur[j] = d;
        }
        int *t = prev2;
        prev2 = prev, prev = cur, cur = t;
    }
    return prev[m] > limit ? limit + 1 : prev[m];
}

bool closest_near(const char *typed, const char *known) {
    if (!strcmp(typed, known)) return false;
    size_t len = strlen(typed);
    int limit = len <= 2 ? 0 : len <= 4 ? 1 : 2; /* any two short names are close */
    return closest_distance(typed, known, limit) <= limit;
}

int closest_list(const char *typed, const char *const *names, int n, char *buf, size_t size) {
    const char *near[5];
    int k = 0;
    for (int i = 0; i < n && k < 5; i++) {
        bool dup = false;
        for (int j = 0; j < k; j++) dup |= !strcmp(near[j], names[i]);
        if (!dup && closest_near(typed, names[i])) near[k++] = names[i];
    }
    size_t used = 0;
    if (size) buf[0] = 0;
    for (int i = 0; i < k; i++) {
        int w = snprintf(buf + used, size - used, "%s'%s'", i == 0 ? "" : i + 1 == k ? " or " : ", ", near[i]);
        if (w < 0 || (size_t)w >= size - used) break;
        used += (size_t)w;
    }
    return k;
}
