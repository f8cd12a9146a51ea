/* Whole files written for cpfg (.l) or L-Py (.lpy): one error that says how Sylva writes them. */
#include <ctype.h>
#include <string.h>

#include "lang/parse_state.h"

/* Lines that open only in those files: none is a statement of Sylva's. */
static const struct {
    const char *text;
    bool cpfg; /* cpfg's alone; the others are L-Py's (and cpfg's too) */
} marks[] = {{"Lsystem:", true}, {"production:", false}, {"endlsystem", false}, {"derivation length:", false}};

bool syl_foreign_file(const Source *src, Diag *diag) {
    SylLoc found = {0}, cpfg = {0};
    const char *p = src->text, *end = src->text + src->len;
    bool comment = false; /* inside a Sylva comment: a .syl file may quote another program's */
    for (int line = 1; p < end; line++) {
        const char *nl = memchr(p, '\n', (size_t)(end - p)), *e = nl ? nl : end, *b = p;
        if (comment) {
            const char *q = memmem(b, (size_t)(e - b), "*/", 2);
            comment = !q;
            b = q ? q + 2 : e;
        }
        while (b < e && (*b == ' ' || *b == '\t')) b++;
        for (const char *q = b; q + 1 < e; q++) /* a comment that opens here and goes on */
            if (q[0] == '/' && q[1] == '*') {
                const char *c = memmem(q + 2, (size_t)(e - q - 2), "*/", 2);
                if (!c) {
                    comment = true;
                    break;
                }
                q = c + 1;
            }
        for (size_t k = 0; k < sizeof marks / sizeof *marks; k++) {
            size_t n = strlen(marks[k].text);
            if ((size_t)(e - b) < n || memcmp(b, marks[k].text, n)) continue;
            if (n == strlen("endlsystem") && b + n < e && (isalnum((unsigned char)b[n]) || b[n] == '_')) continue;
            SylLoc loc = {line, (int)(b - p) + 1, line, (int)(b - p) + (int)n};
            if (!found.first_line) found = loc;
            if (marks[k].cpfg && !cpfg.first_line) cpfg = loc;
        }
        p = nl ? nl + 1 : end;
    }
    if (!found.first_line) return false;
    size_t pl = src->path ? strlen(src->path) : 0;
    bool dot_l = pl > 2 && !strcmp(src->path + pl - 2, ".l");
    if (cpfg.first_line || dot_l)
        diag_error(diag, cpfg.first_line ? cpfg : found,
                   "this is a cpfg (.l) file, not Sylva's: write the model as 'lsystem Name { … }' with "
                   "'derive N', 'axiom …' and its rules without '*' contexts (docs/language.md §18)");
    else
        diag_error(diag, found,
                   "this is an L-Py (.lpy) file, not Sylva's: write the model as 'lsystem Name { … }' with "
                   "'derive N', 'axiom …' and one rule per successor (docs/language.md §18)");
    return true;
}
