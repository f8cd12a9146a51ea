/* NameMap: string → int, open addressing, storage in an arena. */
#ifndef SYL_NAMEMAP_H
#define SYL_NAMEMAP_H
#include "util/arena.h"

typedef struct NameMap {
    const char **keys;
    int *vals;
    int cap, n;
    Arena *arena;
} NameMap;

void namemap_init(NameMap *m, Arena *a);
int namemap_get(const NameMap *m, const char *key, int len); /* -1 if absent; len < 0: strlen */
void namemap_put(NameMap *m, const char *key, int val);      /* key must outlive the map */

#endif
