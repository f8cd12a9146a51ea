/* Whole files written for cpfg (.l) or L-Py (.lpy): one error that says how Sylva writes them. */
#include <ctype.h>
#include <stdlib.h>
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

/* Files people give by mistake, told by their first bytes (their "magic"): what each is. */
static const struct {
    size_t at;
    const char *magic;
    size_t n;
    const char *what;
} kinds[] = {
    {0, "\x89PNG\r\n\x1a\n", 8, "a PNG image"},
    {0, "\xff\xd8\xff", 3, "a JPEG image"},
    {0, "GIF8", 4, "a GIF image"},
    {0, "II*\0", 4, "a TIFF image"},
    {0, "MM\0*", 4, "a TIFF image"},
    {0, "glTF", 4, "a binary glTF (.glb) file"},
    {0, "ply\n", 4, "a PLY mesh"},
    {0, "ply\r\n", 5, "a PLY mesh"},
    {0, "PK\x03\x04", 4, "a ZIP archive"},
    {0, "\x1f\x8b", 2, "a gzip archive"},
    {0, "\xfd" "7zXZ", 5, "an xz archive"},
    {0, "BZh", 3, "a bzip2 archive"},
    {0, "7z\xbc\xaf\x27\x1c", 6, "a 7-Zip archive"},
    {257, "ustar", 5, "a tar archive"},
    {0, "%PDF-", 5, "a PDF document"},
    {0, "\x7f" "ELF", 4, "an executable (ELF)"},
    {0, "SQLite format 3", 15, "an SQLite database"},
};

/* A Wavefront OBJ mesh: every line that is not blank or a comment opens with one of its
 * keywords, and a `v x y z` line is among them (a rule `v -> F` is not). Its material library
 * opens with `newmtl`. */
static const char *wavefront(const char *p, const char *end) {
    static const char *const keys[] = {"v", "vt", "vn", "vp", "f", "l", "p", "o", "g", "s", "usemtl", "mtllib"};
    bool vertex = false;
    for (int lines = 0; p < end && lines < 200; lines++) {
        const char *nl = memchr(p, '\n', (size_t)(end - p)), *e = nl ? nl : end;
        while (p < e && (*p == ' ' || *p == '\t')) p++;
        const char *w = p;
        while (w < e && !isspace((unsigned char)*w)) w++;
        if (p < e && *p != '#') {
            size_t k = 0, n = (size_t)(w - p);
            if (n == 6 && !memcmp(p, "newmtl", 6) && !vertex) return "a Wavefront MTL material library";
            while (k < sizeof keys / sizeof *keys && (strlen(keys[k]) != n || memcmp(keys[k], p, n))) k++;
            if (k == sizeof keys / sizeof *keys) return NULL;
            if (k == 0) {
                char *stop;
                const char *q = w;
                int numbers = 0;
                for (; numbers < 3; numbers++, q = stop) {
                    strtod(q, &stop);
                    if (stop == q || stop > e) break;
                }
                if (numbers < 3) return NULL;
                vertex = true;
            }
        }
        p = nl ? nl + 1 : end;
    }
    return vertex ? "a Wavefront OBJ mesh" : NULL;
}

bool syl_not_a_model(const Source *src, Diag *diag) {
    const char *t = src->text, *what = NULL;
    size_t len = src->len;
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds && !what; k++)
        if (len >= kinds[k].at + kinds[k].n && !memcmp(t + kinds[k].at, kinds[k].magic, kinds[k].n))
            what = kinds[k].what;
    if (!what) { /* a text has few control bytes; a stray one is an error at its place, later */
        size_t n = len < 4096 ? len : 4096, control = 0;
        for (size_t i = 0; i < n; i++) {
            unsigned char c = (unsigned char)t[i];
            control += c < 0x20 && !isspace(c);
        }
        if (n && control * 10 > n) what = "a binary file";
    }
    if (!what) what = wavefront(t, t + len);
    if (!what) return false;
    diag_error(diag, (SylLoc){0}, "this is %s, not a model: give a .syl file, or a Pícek, Arbaro, cpfg or L-Py file "
               "(docs/language.md)", what);
    return true;
}
