/* libFuzzer harness: the Arbaro XML reader (src/lang/arbaro.c, libxml2 underneath) on arbitrary
 * bytes. An input that does not read as XML gets `<arbaro>` in front, so that every input
 * reaches libxml2. Then what `sylva check` and `sylva convert` do with a weber model: the weber
 * reader's validation, the dump, and both writers (XML and .syl), all into the void. */
#include "fuzz.h"
#include "lang/arbaro.h"
#include "sylva/grow.h"
#include "weber/params.h"
#include "weber/xml.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    size_t n;
    char *text = fuzz_xml_text(data, size, "<arbaro>", &n);
    FILE *diag = fuzz_diag();
    SylProgram *p = fuzz_compile("fuzz.xml", text, n, 0);
    if (p) {
        syl_program_dump(p, diag);
        WeberParams w;
        if (syl_program_kind(p) == SYL_MODEL_WEBER && weber_params_read(p, &w, diag) == 0) {
            weber_write_xml(&w, syl_program_name(p), p, diag);
            weber_write_syl(&w, syl_program_name(p), p, "fuzz", diag);
        }
        syl_program_free(p);
    }
    free(text);
    return 0;
}
