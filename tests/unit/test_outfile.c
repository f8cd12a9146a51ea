/* util/outfile (what each kind of path becomes, hooks, killed writers), util/json (escapes
 * by RFC 8259), the skeleton's JSON name, and OBJ under failing allocations: every write
 * either fails with nothing on disk or gives the same bytes as a write that had memory. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include "unit.h"
#include "mesh_fixtures.h"
#include "sylva/skeleton.h"
#include "util/json.h"
#include "util/outfile.h"

/* ---- failing allocations: glibc lets a program replace malloc (not under ASan) ---- */
#if defined(__SANITIZE_ADDRESS__) /* gcc's word for ASan; clang's is __has_feature */
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif
#if defined(UNDER_ASAN)
#define FAULTS 0
#else
#define FAULTS 1
extern void *__libc_malloc(size_t), *__libc_calloc(size_t, size_t), *__libc_realloc(void *, size_t);
extern void __libc_free(void *);
static long fault_at = -1, allocations; /* fail the fault_at-th allocation from now */
static bool fault(void) { return fault_at >= 0 && allocations++ == fault_at; }
void *malloc(size_t n) { return fault() ? NULL : __libc_malloc(n); }
void *calloc(size_t n, size_t k) { return fault() ? NULL : __libc_calloc(n, k); }
void *realloc(void *p, size_t n) { return fault() ? NULL : __libc_realloc(p, n); }
void free(void *p) { __libc_free(p); }
#endif

typedef struct Dir {
    char path[64];
} Dir;

static Dir make_dir(void) {
    Dir d;
    snprintf(d.path, sizeof d.path, "/tmp/sylva-test-out-XXXXXX");
    assert_non_null(mkdtemp(d.path));
    return d;
}

static char *at(const Dir *d, const char *name) {
    static char buf[4][256]; /* a few at once in one assertion */
    static int next;
    char *p = buf[next++ % 4];
    snprintf(p, 256, "%s/%s", d->path, name);
    return p;
}

/* The names in the directory, sorted and joined by spaces ("" when empty). */
static void listing(const Dir *d, char *out, size_t n) {
    struct dirent **list;
    int k = scandir(d->path, &list, NULL, alphasort);
    assert_true(k >= 0);
    out[0] = 0;
    for (int i = 0; i < k; i++) {
        if (list[i]->d_name[0] != '.') {
            if (out[0]) strncat(out, " ", n - strlen(out) - 1);
            strncat(out, list[i]->d_name, n - strlen(out) - 1);
        }
        free(list[i]);
    }
    free(list);
}

static void remove_dir(const Dir *d) {
    DIR *dir = opendir(d->path);
    struct dirent *e;
    char p[512];
    while (dir && (e = readdir(dir)))
        if (e->d_name[0] != '.') {
            snprintf(p, sizeof p, "%s/%s", d->path, e->d_name);
            unlink(p);
        }
    if (dir) closedir(dir);
    rmdir(d->path);
}

static void put(const char *path, const char *text) {
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static char *slurp(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = NULL;
    size_t n = 0;
    FILE *mem = open_memstream(&buf, &n);
    int c;
    while ((c = fgetc(f)) != EOF) fputc(c, mem);
    fclose(mem);
    fclose(f);
    if (len) *len = n;
    return buf;
}

static void assert_file(const char *path, const char *want) {
    char *got = slurp(path, NULL);
    assert_non_null(got);
    assert_string_equal(got, want);
    free(got);
}

static bool write_text(const char *path, const char *text, bool commit, const OutHooks *hooks, FILE *diag) {
    OutFile o;
    if (!outfile_open(&o, path, hooks, &(SylSink){syl_diagnostic_print, diag})) return false;
    fputs(text, o.f);
    return outfile_close(&o, commit, &(SylSink){syl_diagnostic_print, diag});
}

/* ---- outfile ---- */

static void new_file_mode_follows_umask(void **state) {
    Dir d = make_dir();
    mode_t old = umask(027);
    assert_true(write_text(at(&d, "a"), "one\n", true, NULL, stderr));
    umask(old);
    struct stat st;
    assert_int_equal(stat(at(&d, "a"), &st), 0);
    assert_int_equal(st.st_mode & 07777, 0640); /* 0666 & ~027, as creat gives */
    assert_file(at(&d, "a"), "one\n");
    char names[256];
    listing(&d, names, sizeof names);
    assert_string_equal(names, "a");
    remove_dir(&d);
}

static void existing_file_keeps_mode_and_old_content_on_discard(void **state) {
    Dir d = make_dir();
    put(at(&d, "a"), "old\n");
    chmod(at(&d, "a"), 0600);
    assert_true(write_text(at(&d, "a"), "new\n", false, NULL, stderr)); /* not committed */
    assert_file(at(&d, "a"), "old\n");
    assert_true(write_text(at(&d, "a"), "new\n", true, NULL, stderr));
    assert_file(at(&d, "a"), "new\n");
    struct stat st;
    stat(at(&d, "a"), &st);
    assert_int_equal(st.st_mode & 07777, 0600);
    char names[256];
    listing(&d, names, sizeof names);
    assert_string_equal(names, "a");
    remove_dir(&d);
}

static void symlinks_are_followed_and_kept(void **state) {
    Dir d = make_dir();
    put(at(&d, "real"), "old\n");
    assert_int_equal(symlink("real", at(&d, "link")), 0);
    assert_int_equal(symlink("link", at(&d, "link2")), 0); /* a chain */
    assert_int_equal(symlink("made", at(&d, "dangling")), 0);
    assert_true(write_text(at(&d, "link2"), "new\n", true, NULL, stderr));
    assert_true(write_text(at(&d, "dangling"), "made\n", true, NULL, stderr));
    struct stat st;
    assert_int_equal(lstat(at(&d, "link2"), &st), 0);
    assert_true(S_ISLNK(st.st_mode));
    assert_int_equal(lstat(at(&d, "dangling"), &st), 0);
    assert_true(S_ISLNK(st.st_mode));
    assert_file(at(&d, "real"), "new\n");
    assert_file(at(&d, "made"), "made\n");
    assert_int_equal(symlink("loop", at(&d, "loop")), 0);
    char *msg = NULL;
    size_t n;
    FILE *diag = open_memstream(&msg, &n);
    assert_false(write_text(at(&d, "loop"), "x", true, NULL, diag));
    fclose(diag);
    assert_non_null(strstr(msg, "Too many levels of symbolic links"));
    free(msg);
    remove_dir(&d);
}

static void hard_links_stay_linked(void **state) {
    Dir d = make_dir();
    put(at(&d, "a"), "old\n");
    assert_int_equal(link(at(&d, "a"), at(&d, "b")), 0);
    struct stat before, after;
    stat(at(&d, "a"), &before);
    assert_true(write_text(at(&d, "a"), "new content\n", true, NULL, stderr));
    stat(at(&d, "a"), &after);
    assert_int_equal(after.st_nlink, 2);
    assert_true(after.st_ino == before.st_ino);
    assert_file(at(&d, "b"), "new content\n");
    assert_true(write_text(at(&d, "b"), "x\n", true, NULL, stderr)); /* shorter: cut */
    assert_file(at(&d, "a"), "x\n");
    char names[256];
    listing(&d, names, sizeof names);
    assert_string_equal(names, "a b");
    remove_dir(&d);
}

static void fifo_is_written_through(void **state) {
    Dir d = make_dir();
    assert_int_equal(mkfifo(at(&d, "f"), 0600), 0);
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    pid_t pid = fork();
    if (pid == 0) { /* the reader: copy the FIFO into the pipe */
        close(fds[0]);
        int in = open(at(&d, "f"), O_RDONLY);
        char buf[256];
        ssize_t n;
        while ((n = read(in, buf, sizeof buf)) > 0)
            if (write(fds[1], buf, (size_t)n) != n) _exit(1);
        _exit(0);
    }
    close(fds[1]);
    assert_true(write_text(at(&d, "f"), "through\n", true, NULL, stderr));
    char got[64] = {0};
    ssize_t n = read(fds[0], got, sizeof got - 1);
    assert_true(n > 0);
    int status;
    waitpid(pid, &status, 0);
    assert_string_equal(got, "through\n");
    struct stat st;
    assert_int_equal(lstat(at(&d, "f"), &st), 0);
    assert_true(S_ISFIFO(st.st_mode));
    close(fds[0]);
    remove_dir(&d);
}

/* As root, a node of our own: a broken writer could rename over the system's /dev/full. */
static void full_device_names_file_and_reason(void **state) {
    Dir d = make_dir();
    const char *full = "/dev/full";
    if (geteuid() == 0) {
        if (mknod(at(&d, "full"), S_IFCHR | 0666, makedev(1, 7))) {
            remove_dir(&d);
            skip();
        }
        full = at(&d, "full");
    }
    char *msg = NULL, want[256];
    size_t n;
    FILE *diag = open_memstream(&msg, &n);
    char big[100000];
    memset(big, 'x', sizeof big - 1);
    big[sizeof big - 1] = 0;
    assert_false(write_text(full, big, true, NULL, diag));
    fclose(diag);
    snprintf(want, sizeof want, "sylva: error: cannot write '%s': No space left on device\n", full);
    assert_string_equal(msg, want);
    free(msg);
    struct stat st;
    assert_int_equal(stat(full, &st), 0);
    assert_true(S_ISCHR(st.st_mode));
    remove_dir(&d);
}

typedef struct Seen {
    char created[256], gone[256];
    bool existed_at_create;
} Seen;
static void seen_created(void *ctx, const char *tmp) {
    Seen *s = ctx;
    snprintf(s->created, sizeof s->created, "%s", tmp);
    s->existed_at_create = access(tmp, F_OK) == 0;
}
static void seen_gone(void *ctx, const char *tmp) {
    Seen *s = ctx;
    snprintf(s->gone, sizeof s->gone, "%s", tmp);
}

static void hooks_see_the_named_temporary_file(void **state) {
    Dir d = make_dir();
    Seen seen = {0};
    OutHooks hooks = {seen_created, seen_gone, &seen};
    OutFile o;
    assert_true(outfile_open(&o, at(&d, "a"), &hooks, &(SylSink){syl_diagnostic_print, stderr}));
    assert_true(seen.created[0] && !seen.existed_at_create); /* told before it exists */
    assert_int_equal(access(seen.created, F_OK), 0);
    fputs("x\n", o.f);
    assert_true(outfile_close(&o, false, &(SylSink){syl_diagnostic_print, stderr}));
    assert_string_equal(seen.gone, seen.created);
    char names[256];
    listing(&d, names, sizeof names);
    assert_string_equal(names, ""); /* discarded: nothing */
    remove_dir(&d);
}

/* A writer killed half-way (SIGKILL: no handler can run) leaves nothing: its temporary
 * file has no name. */
static void killed_writer_leaves_nothing(void **state) {
    Dir d = make_dir();
    put(at(&d, "keep"), "old\n");
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    pid_t pid = fork();
    if (pid == 0) {
        OutFile o;
        if (!outfile_open(&o, at(&d, "keep"), NULL, NULL)) _exit(1);
        fputs("half", o.f);
        fflush(o.f);
        if (write(fds[1], "x", 1) != 1) _exit(1);
        pause();
        _exit(2);
    }
    char c;
    assert_int_equal(read(fds[0], &c, 1), 1);
    kill(pid, SIGKILL);
    int status;
    waitpid(pid, &status, 0);
    assert_true(WIFSIGNALED(status));
    char names[256];
    listing(&d, names, sizeof names);
    assert_string_equal(names, "keep");
    assert_file(at(&d, "keep"), "old\n");
    close(fds[0]);
    close(fds[1]);
    remove_dir(&d);
}

/* ---- JSON ---- */

static void json_escapes_by_the_rfc(void **state) {
    char *out = NULL;
    size_t n;
    FILE *f = open_memstream(&out, &n);
    /* quote, backslash, newline, U+0001, a stray byte, a truncated sequence, é and € as UTF-8 */
    json_string_file(f, "a\"b\\c\n\x01\xff\xe2\x82 \xc3\xa9\xe2\x82\xac/");
    fclose(f);
    assert_string_equal(out, "\"a\\\"b\\\\c\\u000a\\u0001\\ufffd\\ufffd\\ufffd \xc3\xa9\xe2\x82\xac/\"");
    free(out);
}

static void skeleton_json_escapes_the_name(void **state) {
    SylSkeleton *s = syl_skeleton_new("tree \"one\"\n\\");
    char *out = NULL;
    size_t n;
    FILE *f = open_memstream(&out, &n);
    assert_int_equal(syl_skeleton_write_json(s, f), SYL_OK);
    fclose(f);
    const char *want = "{\"name\":\"tree \\\"one\\\"\\u000a\\\\\",\"nodes\":[";
    assert_true(!strncmp(out, want, strlen(want)));
    free(out);
    syl_skeleton_free(s);
}

/* ---- OBJ when allocations fail ---- */

#if FAULTS
static SylMesh *leafy_mesh(bool leaf) {
    SylSkeleton *s = fx_tree(3, 1);
    SylOrgan o = fx_organ(SYL_KIND_LEAF, 0, 2, 0, 0.4f, 1);
    if (leaf) syl_skeleton_add_organ(s, &o);
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(s, NULL, &m), SYL_OK);
    syl_skeleton_free(s);
    return m;
}
#endif

/* Write m as name through write with the k-th allocation failing, for k = 0, 1, ... until
 * none fails: each run fails with a message, status 3 or 4 and neither name nor mtl (when
 * given) nor a temporary file on disk, or writes the same files as a run with memory. */
static void under_failing_allocations(int (*write)(const SylMesh *, const char *, const SylSink *), const char *name,
                                      const char *mtl) {
#if FAULTS
    SylMesh *m = leafy_mesh(mtl != NULL); /* two textures for OBJ; one is enough for GLB */
    Dir ref = make_dir(), d = make_dir();
    assert_int_equal(write(m, at(&ref, name), &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    char ref_names[512];
    listing(&ref, ref_names, sizeof ref_names);
    int failed = 0;
    for (long k = 0;; k++) {
        char *msg = NULL;
        size_t n;
        FILE *diag = open_memstream(&msg, &n);
        fflush(diag);
        allocations = 0;
        fault_at = k;
        int st = write(m, at(&d, name), &(SylSink){syl_diagnostic_print, diag});
        fault_at = -1;
        bool hit = allocations > k;
        fclose(diag);
        char names[512];
        listing(&d, names, sizeof names);
        if (st) {
            failed++;
            if (!msg || !strstr(msg, "sylva: error: ")) fprintf(stderr, "allocation %ld: status %d, silent\n", k, st);
            assert_true(hit);
            assert_true(st == SYL_ELIMIT || st == SYL_EIO);
            assert_true(msg && strstr(msg, "sylva: error: ")); /* every failure says why */
            assert_null(strstr(names, name));
            if (mtl) assert_null(strstr(names, mtl));
            assert_null(strstr(names, ".tmp"));
        } else { /* done with less memory (stdio unbuffered, say): the same files */
            assert_string_equal(names, ref_names);
            for (char *p = names, *e; *p; p = e + (*e != 0)) {
                e = p + strcspn(p, " ");
                char file[64];
                snprintf(file, sizeof file, "%.*s", (int)(e - p), p);
                size_t l1, l2;
                char *a = slurp(at(&ref, file), &l1), *b = slurp(at(&d, file), &l2);
                if (!(l1 == l2 && !memcmp(a, b, l1))) fprintf(stderr, "allocation %ld: %s differs\n", k, file);
                assert_true(l1 == l2 && !memcmp(a, b, l1));
                free(a);
                free(b);
            }
        }
        free(msg);
        remove_dir(&d);
        assert_non_null(mkdtemp(strcpy(d.path, "/tmp/sylva-test-out-XXXXXX")));
        if (!hit) break;
    }
    assert_true(failed > 0);
    remove_dir(&ref);
    remove_dir(&d);
    syl_mesh_free(m);
#else
    (void)write, (void)name, (void)mtl;
    skip();
#endif
}

static void obj_under_failing_allocations(void **state) { under_failing_allocations(syl_mesh_write_obj, "t.obj", "t.mtl"); }
static void ply_under_failing_allocations(void **state) { under_failing_allocations(syl_mesh_write_ply, "t.ply", NULL); }
static void glb_under_failing_allocations(void **state) { under_failing_allocations(syl_mesh_write_glb, "t.glb", NULL); }

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(new_file_mode_follows_umask),
        cmocka_unit_test(existing_file_keeps_mode_and_old_content_on_discard),
        cmocka_unit_test(symlinks_are_followed_and_kept),
        cmocka_unit_test(hard_links_stay_linked),
        cmocka_unit_test(fifo_is_written_through),
        cmocka_unit_test(full_device_names_file_and_reason),
        cmocka_unit_test(hooks_see_the_named_temporary_file),
        cmocka_unit_test(killed_writer_leaves_nothing),
        cmocka_unit_test(json_escapes_by_the_rfc),
        cmocka_unit_test(skeleton_json_escapes_the_name),
        cmocka_unit_test(obj_under_failing_allocations),
        cmocka_unit_test(ply_under_failing_allocations),
        cmocka_unit_test(glb_under_failing_allocations),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
