/* Mesh files: OBJ (read back), PLY (header and sizes), GLB (header, chunks, JSON), and
 * failures that leave nothing behind. */
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/glb.h"
#include "unit.h"
#include "mesh_fixtures.h"

/* A mesh with tubes, organs and a polygon in five materials. */
static SylMesh *sample_mesh(void) {
    SylSkeleton *s = fx_tree(4, 1);
    snprintf(s->name, sizeof s->name, "Sample \"tree\"");
    s->nodes[2].material = 3;
    SylOrgan leaf = fx_organ(SYL_KIND_LEAF, 0, 2, 0, 0.4f, 1), flower = fx_organ(SYL_KIND_FLOWER, 1, 2, 0, 0.3f, 2),
             ball = fx_organ(SYL_KIND_SPHERE, 0, 3, 1, 0.2f, 4);
    syl_skeleton_add_organ(s, &leaf);
    syl_skeleton_add_organ(s, &flower);
    syl_skeleton_add_organ(s, &ball);
    const float quad[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5f}, {0, 1, 0.5f}};
    syl_skeleton_add_polygon(s, quad, 4, -1, 1, 0);
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(s, NULL, &m), SYL_OK);
    syl_skeleton_free(s);
    assert_int_equal(m->ngroups, 5);
    return m;
}

typedef struct Dir {
    char path[64];
} Dir;

static Dir make_dir(void) {
    Dir d;
    snprintf(d.path, sizeof d.path, "/tmp/sylva-test-io-XXXXXX");
    assert_non_null(mkdtemp(d.path));
    return d;
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

/* Files in the directory, and whether any is a leftover temporary file. */
static int count_files(const Dir *d, bool *tmp) {
    DIR *dir = opendir(d->path);
    struct dirent *e;
    int n = 0;
    *tmp = false;
    while (dir && (e = readdir(dir)))
        if (e->d_name[0] != '.') {
            n++;
            if (strstr(e->d_name, ".tmp")) *tmp = true;
        }
    if (dir) closedir(dir);
    return n;
}

static char *slurp(const char *path, size_t *len) {
    char *text = syl_read_file(path, len);
    assert_non_null(text);
    return text;
}

static bool exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

/* ---- OBJ ---- */

static void obj_reads_back(void **state) {
    (void)state;
    SylMesh *m = sample_mesh();
    Dir d = make_dir();
    char path[256], mtl[256];
    snprintf(path, sizeof path, "%s/plant.obj", d.path);
    snprintf(mtl, sizeof mtl, "%s/plant.mtl", d.path);
    assert_int_equal(syl_mesh_write(m, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    size_t len;
    char *text = slurp(path, &len);
    size_t nv = 0, nvt = 0, nvn = 0, nf = 0;
    int usemtl = 0;
    bool mtllib = false;
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        if (!strncmp(line, "v ", 2)) {
            float x, y, z;
            assert_int_equal(sscanf(line + 2, "%f %f %f", &x, &y, &z), 3);
            assert_true(nv < m->nverts);
            const float *p = m->pos + 3 * nv;
            assert_near(x, p[0], 1e-6 + 1e-6 * fabs(p[0]));
            assert_near(y, p[1], 1e-6 + 1e-6 * fabs(p[1]));
            assert_near(z, p[2], 1e-6 + 1e-6 * fabs(p[2]));
            nv++;
        } else if (!strncmp(line, "vt ", 3)) {
            float u, v;
            assert_int_equal(sscanf(line + 3, "%f %f", &u, &v), 2);
            assert_near(u, m->uv[2 * nvt], 1e-5);
            assert_near(v, 1 - m->uv[2 * nvt + 1], 1e-5 + 1e-6 * fabs(v)); /* OBJ's v runs up */
            nvt++;
        } else if (!strncmp(line, "vn ", 3)) {
            nvn++;
        } else if (!strncmp(line, "f ", 2)) {
            unsigned a[3], b[3], c[3];
            assert_int_equal(sscanf(line + 2, "%u/%u/%u %u/%u/%u %u/%u/%u", &a[0], &b[0], &c[0], &a[1], &b[1], &c[1],
                                    &a[2], &b[2], &c[2]),
                             9);
            for (int k = 0; k < 3; k++) {
                assert_true(a[k] >= 1 && a[k] <= m->nverts);
                assert_true(a[k] == b[k] && a[k] == c[k]);
                assert_int_equal(a[k] - 1, m->idx[3 * nf + (size_t)k]);
            }
            nf++;
        } else if (!strncmp(line, "usemtl ", 7)) {
            usemtl++;
        } else if (!strcmp(line, "mtllib plant.mtl")) {
            mtllib = true;
        }
    }
    assert_int_equal(nv, m->nverts);
    assert_int_equal(nvt, m->nverts);
    assert_int_equal(nvn, m->nverts);
    assert_int_equal(nf, m->nidx / 3);
    assert_int_equal(usemtl, m->ngroups);
    assert_true(mtllib);
    free(text);
    /* the material library and its textures */
    text = slurp(mtl, &len);
    assert_int_equal(unit_occurrences(text, "newmtl "), m->ngroups);
    assert_contains(text, "newmtl bark0\n");
    assert_contains(text, "Kd 0.4000 0.2800 0.1800\n");
    assert_contains(text, "map_Kd plant_bark.png");
    assert_contains(text, "map_Kd plant_leaf.png");
    assert_contains(text, "map_Kd plant_flower.png");
    free(text);
    char tex[256];
    for (int k = 0; k < 3; k++) {
        static const char *const kinds[] = {"bark", "leaf", "flower"};
        snprintf(tex, sizeof tex, "%s/plant_%s.png", d.path, kinds[k]);
        assert_true(exists(tex));
    }
    bool tmp;
    assert_int_equal(count_files(&d, &tmp), 5);
    assert_false(tmp);
    remove_dir(&d);
    syl_mesh_free(m);
}

/* ---- PLY ---- */

static uint32_t le32(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float lef(const unsigned char *p) {
    uint32_t u = le32(p);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static void ply_header_and_sizes(void **state) {
    (void)state;
    SylMesh *m = sample_mesh();
    Dir d = make_dir();
    char path[256];
    snprintf(path, sizeof path, "%s/plant.ply", d.path);
    assert_int_equal(syl_mesh_write(m, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    size_t len;
    char *data = slurp(path, &len);
    char *end = strstr(data, "end_header\n");
    assert_non_null(end);
    size_t head = (size_t)(end - data) + strlen("end_header\n");
    assert_true(!strncmp(data, "ply\nformat binary_little_endian 1.0\n", 36));
    char want[128];
    snprintf(want, sizeof want, "element vertex %zu\n", m->nverts);
    assert_contains(data, want);
    snprintf(want, sizeof want, "element face %zu\n", m->nidx / 3);
    assert_contains(data, want);
    assert_contains(data, "property list uchar uint vertex_indices\nproperty uchar material_index\n");
    assert_int_equal(len, head + 32 * m->nverts + 14 * (m->nidx / 3));
    const unsigned char *v = (const unsigned char *)data + head;
    for (size_t i = 0; i < m->nverts; i += 101) {
        const unsigned char *p = v + 32 * i;
        for (int k = 0; k < 3; k++) assert_true(lef(p + 4 * k) == m->pos[3 * i + (size_t)k]);
        for (int k = 0; k < 3; k++) assert_true(lef(p + 12 + 4 * k) == m->nrm[3 * i + (size_t)k]);
        assert_true(lef(p + 24) == m->uv[2 * i]);
    }
    const unsigned char *f = v + 32 * m->nverts;
    for (int g = 0; g < m->ngroups; g++)
        for (uint32_t t = m->groups[g].first / 3; t < (m->groups[g].first + m->groups[g].count) / 3; t++) {
            const unsigned char *p = f + 14 * (size_t)t;
            assert_int_equal(p[0], 3);
            for (int k = 0; k < 3; k++) assert_int_equal(le32(p + 1 + 4 * k), m->idx[3 * t + (uint32_t)k]);
            assert_int_equal(p[13], m->groups[g].material);
        }
    free(data);
    remove_dir(&d);
    syl_mesh_free(m);
}

/* ---- GLB ---- */

/* A JSON syntax check: true when text[0..len) is one JSON value (and spaces). */
typedef struct Json {
    const char *p, *end;
} Json;

static void json_ws(Json *j) {
    while (j->p < j->end && (*j->p == ' ' || *j->p == '\n' || *j->p == '\t' || *j->p == '\r')) j->p++;
}

static bool json_value(Json *j, int depth);

static bool json_string(Json *j) {
    if (j->p >= j->end || *j->p != '"') return false;
    for (j->p++; j->p < j->end; j->p++) {
        if (*j->p == '"') {
            j->p++;
            return true;
        }
        if ((unsigned char)*j->p < 0x20) return false;
        if (*j->p == '\\') j->p++;
    }
    return false;
}

static bool json_value(Json *j, int depth) {
    if (depth > 64) return false;
    json_ws(j);
    if (j->p >= j->end) return false;
    char c = *j->p;
    if (c == '"') return json_string(j);
    if (c == '{' || c == '[') {
        char close = c == '{' ? '}' : ']';
        j->p++;
        json_ws(j);
        if (j->p < j->end && *j->p == close) return j->p++, true;
        for (;;) {
            if (c == '{') {
                json_ws(j);
                if (!json_string(j)) return false;
                json_ws(j);
                if (j->p >= j->end || *j->p++ != ':') return false;
            }
            if (!json_value(j, depth + 1)) return false;
            json_ws(j);
            if (j->p >= j->end) return false;
            if (*j->p == ',') {
                j->p++;
                continue;
            }
            return *j->p++ == close;
        }
    }
    if (!strncmp(j->p, "true", 4)) return j->p += 4, true;
    if (!strncmp(j->p, "false", 5)) return j->p += 5, true;
    if (!strncmp(j->p, "null", 4)) return j->p += 4, true;
    char *num_end;
    strtod(j->p, &num_end);
    if (num_end == j->p) return false;
    j->p = num_end;
    return true;
}

static bool json_ok(const char *text, size_t len) {
    Json j = {text, text + len};
    if (!json_value(&j, 0)) return false;
    json_ws(&j);
    return j.p == j.end;
}

/* Every "key":NUMBER in the JSON is a multiple of 4. */
static void assert_aligned(const char *json, const char *key) {
    for (const char *p = json; (p = strstr(p, key)); p += strlen(key)) {
        long v = strtol(p + strlen(key), NULL, 10);
        if (v % 4) fail_msg("%s%ld is not a multiple of 4", key, v);
    }
}

typedef struct Glb {
    unsigned char *data;
    size_t len;
    char *json; /* NUL-terminated copy */
    uint32_t json_len, bin_len;
    const unsigned char *bin;
} Glb;

static Glb read_glb(const char *path) {
    Glb g = {0};
    g.data = (unsigned char *)slurp(path, &g.len);
    assert_true(g.len >= 20);
    assert_int_equal(le32(g.data), 0x46546C67); /* "glTF" */
    assert_int_equal(le32(g.data + 4), 2);
    assert_int_equal(le32(g.data + 8), g.len);
    g.json_len = le32(g.data + 12);
    assert_int_equal(le32(g.data + 16), 0x4E4F534A); /* JSON */
    assert_int_equal(g.json_len % 4, 0);
    assert_true(20 + (size_t)g.json_len <= g.len);
    g.json = strndup((const char *)g.data + 20, g.json_len);
    assert_true(json_ok(g.json, g.json_len));
    size_t at = 20 + g.json_len;
    if (at < g.len) {
        assert_true(at + 8 <= g.len);
        g.bin_len = le32(g.data + at);
        assert_int_equal(le32(g.data + at + 4), 0x004E4942); /* BIN */
        assert_int_equal(g.bin_len % 4, 0);
        assert_int_equal(at + 8 + g.bin_len, g.len);
        g.bin = g.data + at + 8;
    }
    return g;
}

static void glb_structure(void **state) {
    (void)state;
    SylMesh *m = sample_mesh();
    Dir d = make_dir();
    char path[256], want[128];
    snprintf(path, sizeof path, "%s/plant.glb", d.path);
    assert_int_equal(syl_mesh_write(m, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    Glb g = read_glb(path);
    assert_non_null(g.bin);
    assert_contains(g.json, "\"asset\":{\"version\":\"2.0\",\"generator\":\"Sylva\"}");
    assert_contains(g.json, "\"nodes\":[{\"name\":\"Sample \\\"tree\\\"\",\"mesh\":0}]");
    snprintf(want, sizeof want, "\"buffers\":[{\"byteLength\":%u}]", g.bin_len);
    assert_contains(g.json, want);
    snprintf(want, sizeof want, "\"count\":%zu,\"type\":\"VEC3\"", m->nverts);
    assert_int_equal(unit_occurrences(g.json, want), 2); /* POSITION and NORMAL */
    assert_int_equal(unit_occurrences(g.json, "\"TEXCOORD_0\":2"), m->ngroups); /* one primitive per group */
    assert_int_equal(unit_occurrences(g.json, "\"baseColorFactor\""), m->ngroups);
    assert_int_equal(unit_occurrences(g.json, "\"mimeType\":\"image/png\""), 3); /* bark, leaf, flower */
    assert_contains(g.json, "\"min\":[");
    assert_aligned(g.json, "\"byteOffset\":");
    /* positions are the first buffer view */
    for (size_t i = 0; i < 3 * m->nverts; i += 37) assert_true(lef(g.bin + 4 * i) == m->pos[i]);
    free(g.json);
    free(g.data);
    bool tmp;
    assert_int_equal(count_files(&d, &tmp), 1);
    assert_false(tmp);
    /* an empty mesh: a scene with a node and nothing else */
    SylSkeleton *s = syl_skeleton_new("empty");
    SylMesh *e = NULL;
    assert_int_equal(syl_mesh_build(s, NULL, &e), SYL_OK);
    assert_int_equal(syl_mesh_write_glb(e, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    g = read_glb(path);
    assert_null(g.bin);
    assert_not_contains(g.json, "\"meshes\"");
    free(g.json);
    free(g.data);
    syl_mesh_free(e);
    syl_skeleton_free(s);
    remove_dir(&d);
    syl_mesh_free(m);
}

/* glb_primitives: above 65,535 vertices each group is cut into runs of its triangles, in
 * order, whose vertices lie in windows of at most 65,535; a triangle spanning more gives 32-bit
 * indices, one primitive a group. Only the indices matter: no attributes are made. */
static void glb_primitive_windows(void **state) {
    (void)state;
    enum { NV = 200000 };
    SylMesh m = {.nverts = NV, .ngroups = 2};
    SylMeshGroup groups[2];
    m.groups = groups;
    m.idx = malloc(3 * NV * sizeof *m.idx);
    for (uint32_t t = 0; t + 2 < NV; t++) /* a strip of triangles over every vertex, in two groups */
        m.idx[3 * t] = t, m.idx[3 * t + 1] = t + 1, m.idx[3 * t + 2] = t + 2;
    m.nidx = 3 * (NV - 2);
    groups[0] = (SylMeshGroup){0, 3 * 70000, 0}, groups[1] = (SylMeshGroup){3 * 70000, (uint32_t)m.nidx - 3 * 70000, 1};
    GlbPrims p;
    assert_true(glb_primitives(&m, &p));
    assert_true(p.split && !p.wide);
    size_t at = 0;
    for (size_t k = 0; k < p.n; k++) {
        const GlbPrim *q = &p.prim[k];
        assert_int_equal(q->first, at); /* in order, nothing left out */
        assert_true(q->count > 0 && q->count % 3 == 0 && q->nv <= 65535);
        assert_true(at >= groups[q->group].first && at + q->count <= groups[q->group].first + groups[q->group].count);
        for (size_t i = q->first; i < q->first + q->count; i++) assert_true(m.idx[i] >= q->lo && m.idx[i] < q->lo + q->nv);
        at += q->count;
    }
    assert_int_equal(at, m.nidx);
    assert_true(p.n >= 4 && p.n <= 5); /* 70,000 and 130,000 vertices: 2 and 2 or 3 windows */
    free(p.prim);
    m.idx[0] = 0, m.idx[1] = 1, m.idx[2] = NV - 1; /* one triangle too wide for a window */
    assert_true(glb_primitives(&m, &p));
    assert_true(p.wide && !p.split);
    assert_int_equal(p.n, 2);
    assert_int_equal(p.prim[1].first, groups[1].first);
    free(p.prim);
    m.nverts = 65535; /* at most 65,535 vertices: one primitive a group */
    m.nidx = 3 * 65533, groups[1].count = (uint32_t)m.nidx - groups[1].first;
    m.idx[2] = 2;
    assert_true(glb_primitives(&m, &p));
    assert_true(!p.split && !p.wide && p.n == 2);
    free(p.prim);
    free(m.idx);
}

static void failures_leave_nothing(void **state) {
    (void)state;
    SylMesh *m = sample_mesh();
    Dir d = make_dir();
    char path[256];
    char *diag = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&diag, &len);
    static const char *const names[] = {"no/such/dir/plant.glb", "no/such/dir/plant.obj", "no/such/dir/plant.ply"};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/%s", d.path, names[k]);
        assert_int_equal(syl_mesh_write(m, path, &(SylSink){syl_diagnostic_print, f}), SYL_EIO);
    }
    snprintf(path, sizeof path, "%s/plant.stl", d.path);
    assert_int_equal(syl_mesh_write(m, path, &(SylSink){syl_diagnostic_print, f}), SYL_EUSAGE);
    fclose(f);
    assert_contains(diag, "cannot write");
    assert_contains(diag, "cannot tell the format");
    free(diag);
    bool tmp;
    assert_int_equal(count_files(&d, &tmp), 0);
    remove_dir(&d);
    syl_mesh_free(m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(obj_reads_back),
        cmocka_unit_test(ply_header_and_sizes),
        cmocka_unit_test(glb_structure),
        cmocka_unit_test(glb_primitive_windows),
        cmocka_unit_test(failures_leave_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
