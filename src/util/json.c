/* JSON string escaping. */
#include "util/json.h"

#include <stdbool.h>

/* The length of the UTF-8 sequence at s (1..4), 0 when it is not one (RFC 3629). */
static int utf8_length(const unsigned char *s) {
    unsigned char c = s[0];
    int n = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
    if (!n) return 0;
    unsigned char lo = 0x80, hi = 0xbf; /* the second byte: no overlong forms, surrogates, > U+10FFFF */
    if (c == 0xe0) lo = 0xa0;
    else if (c == 0xed) hi = 0x9f;
    else if (c == 0xf0) lo = 0x90;
    else if (c == 0xf4) hi = 0x8f;
    if (s[1] < lo || s[1] > hi) return 0;
    for (int i = 2; i < n; i++)
        if (s[i] < 0x80 || s[i] > 0xbf) return 0;
    return n;
}

void json_string(const char *str, JsonPut put, void *ctx) {
    static const char hex[] = "0123456789abcdef";
    const unsigned char *s = (const unsigned char *)str;
    put(ctx, "\"", 1);
    while (*s) {
        const unsigned char *run = s; /* bytes that go out as they are */
        while (*s >= 0x20 && *s != '"' && *s != '\\' && *s < 0x80) s++;
        if (s > run) put(ctx, run, (size_t)(s - run));
        if (!*s) break;
        if (*s >= 0x80) {
            int n = utf8_length(s);
            if (n) put(ctx, s, (size_t)n), s += n;
            else put(ctx, "\\ufffd", 6), s++;
        } else if (*s == '"' || *s == '\\') {
            char e[2] = {'\\', (char)*s++};
            put(ctx, e, 2);
        } else {
            char e[6] = {'\\', 'u', '0', '0', hex[*s >> 4], hex[*s & 15]};
            put(ctx, e, 6);
            s++;
        }
    }
    put(ctx, "\"", 1);
}

static void put_file(void *ctx, const void *p, size_t n) { fwrite(p, 1, n, ctx); }

void json_string_file(FILE *out, const char *s) { json_string(s, put_file, out); }
