/* The harnesses without libFuzzer: each file named on the command line (a directory: each file
 * in it) is fed once to LLVMFuzzerTestOneInput. make builds one replay_NAME per harness in
 * every tree with the tree's own compiler and sanitizers, so `make test` runs the seeds and the
 * kept regression inputs under ASan+UBSan as a deterministic test (tests/fuzz/replay), and the
 * clang/libFuzzer tree is needed only to search for new inputs (make fuzz). */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int replay_file(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) { perror(path); return 1; }
    size_t cap = 1 << 16, n = 0;
    uint8_t *buf = malloc(cap);
    for (size_t got; buf && (got = fread(buf + n, 1, cap - n, f)) > 0;) {
        n += got;
        if (n == cap) buf = realloc(buf, cap *= 2);
    }
    fclose(f);
    if (!buf) { fprintf(stderr, "%s: out of memory\n", path); return 1; }
    /* an exact-size copy, so that a read past the input's end is ASan's to see */
    uint8_t *data = malloc(n ? n : 1);
    if (!data) { free(buf); return 1; }
    memcpy(data, buf, n);
    free(buf);
    LLVMFuzzerTestOneInput(data, n);
    free(data);
    return 0;
}

int main(int argc, char **argv) {
    int bad = 0, count = 0;
    for (int i = 1; i < argc; i++) {
        struct stat st;
        if (stat(argv[i], &st) != 0) { perror(argv[i]); bad++; continue; }
        if (!S_ISDIR(st.st_mode)) { bad += replay_file(argv[i]); count++; continue; }
        struct dirent **list;
        int k = scandir(argv[i], &list, NULL, alphasort); /* a fixed order: the same run every time */
        if (k < 0) { perror(argv[i]); bad++; continue; }
        for (int j = 0; j < k; j++) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", argv[i], list[j]->d_name);
            if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) { bad += replay_file(path); count++; }
            free(list[j]);
        }
        free(list);
    }
    fprintf(stderr, "replayed %d inputs\n", count); /* stderr: the CLI harness sends stdout to /dev/null */
    return bad ? 1 : 0;
}
