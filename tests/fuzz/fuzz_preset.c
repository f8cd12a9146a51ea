/* libFuzzer harness: grow preset files (<grow-presets>, read by src/lang/arbaro.c with libxml2;
 * written by src/lang/preset.c) on arbitrary bytes. An input that does not read as XML gets
 * `<grow-presets>` in front, so that every input reaches libxml2. A grow model that reads
 * without an error is written as a preset and as a grow block; the preset read back must
 * write the same bytes again (the round trip `sylva convert` promises), else abort. */
#include "fuzz.h"
#include "lang/arbaro.h"
#include "sylva/grow.h"

/* The preset p writes (malloc'ed, *n bytes; NULL: p cannot be written as one). */
static char *preset_of(const SylProgram *p, size_t *n) {
    char *buf = NULL;
    FILE *f = open_memstream(&buf, n);
    if (!f) abort();
    int st = syl_grow_write_preset(p, f, fuzz_diag());
    fclose(f);
    if (st) {
        free(buf);
        return NULL;
    }
    return buf;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    size_t n;
    char *text = fuzz_xml_text(data, size, "<" SYL_GROW_PRESET_ROOT ">", &n);
    FILE *diag = fuzz_diag();
    SylProgram *p = fuzz_compile("fuzz.xml", text, n, 0);
    if (p && syl_program_kind(p) == SYL_MODEL_GROW) {
        syl_grow_write_syl(p, "fuzz", diag, diag);
        size_t n1, n2;
        char *once = preset_of(p, &n1);
        SylProgram *q = once ? fuzz_compile("again.xml", once, n1, 0) : NULL;
        if (once && !q) abort(); /* what it wrote does not read back */
        char *twice = q ? preset_of(q, &n2) : NULL;
        if (once && (!twice || n1 != n2 || memcmp(once, twice, n1))) abort();
        free(once);
        free(twice);
        syl_program_free(q);
    }
    syl_program_free(p);
    free(text);
    return 0;
}
