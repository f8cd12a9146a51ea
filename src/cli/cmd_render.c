/* sylva render: derive a model, draw it, mesh it and ray-trace a PNG picture. */
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "render/render_internal.h"
#include "sylva/mesh.h"
#include "sylva/render.h"

static const char usage[] =
    "usage: sylva render FILE[:Model] [-o OUT.png] [options]\n"
    "\n"
    "Derive the model, draw it with the 3D turtle, mesh it and ray-trace a picture: sunlight\n"
    "with shadows, sky light with ambient occlusion, a grass ground, procedural bark, leaf\n"
    "and flower textures, the camera framed so the plant fills about 80% of the picture.\n"
    "The picture never depends on the number of threads.\n"
    "\n"
    "  -o, --output FILE     the PNG file (default: the model's name with .png, in the\n"
    "                        current directory; - is standard output)\n"
    "  --view V              iso (default: from 35 degrees up, 45 around), front (looking\n"
    "                        along -Z), side (along -X) or top (down from +Y)\n"
    "  --size WxH            picture size in pixels, 1 to 16384 each (default 1024x1024)\n"
    "  --samples N           anti-aliasing samples per pixel, 1 to 64 (default 4)\n"
    "  --ao N                ambient occlusion rays per pixel, 0 (none) to 64 (default 8)\n"
    "  --no-shadows          no sun shadows\n"
    "  --stats               print counts and times to stderr\n"
    CLI_DERIVE_HELP
    "\n"
    "A progress bar is shown on stderr when it is a terminal and the picture takes more than\n"
    "a second.\n"
    "\n"
    "Exit codes: 0 ok, 1 the model is wrong, 2 bad command line, 3 limit hit, 4 I/O error.\n";

enum { OPT_VIEW = 1000, OPT_SIZE, OPT_SAMPLES, OPT_AO, OPT_NO_SHADOWS, OPT_STATS, OPT_SYNTHETIC };

static bool parse_view(const char *arg, SylView *v) {
    static const char *const names[] = {"iso", "front", "side", "top"};
    for (int i = 0; i < 4; i++)
        if (!strcmp(arg, names[i])) {
            *v = (SylView)i;
            return true;
        }
    fprintf(stderr, "sylva: error: --view expects iso, front, side or top, not '%s'\n", arg);
    return false;
}

static bool parse_size(const char *arg, int *w, int *h) {
    char *end;
    long a = strtol(arg, &end, 10), b = a;
    if (end != arg && (*end == 'x' || *end == 'X')) {
        const char *s = end + 1;
        b = strtol(s, &end, 10);
        if (end == s) b = 0;
    }
    if (end == arg || *end || a < 1 || b < 1 || a > 16384 || b > 16384) {
        fprintf(stderr, "sylva: error: --size expects WIDTHxHEIGHT, each from 1 to 16384, not '%s'\n", arg);
        return false;
    }
    *w = (int)a;
    *h = (int)b;
    return true;
}

/* The progress bar: drawn on stderr once the picture has taken a second. */
typedef struct Progress {
    double start, last;
    bool shown;
} Progress;

static void progress(void *user, double fraction) {
    Progress *p = user;
    double now = cli_now();
    if (fraction < 1 && (now - p->start < 1.0 || now - p->last < 0.1)) return;
    if (fraction >= 1 && !p->shown) return;
    p->last = now;
    p->shown = true;
    enum { WIDTH = 40 };
    char bar[WIDTH + 1];
    int fill = (int)(fraction * WIDTH + 0.5);
    for (int i = 0; i < WIDTH; i++) bar[i] = i < fill ? '#' : '.';
    bar[WIDTH] = 0;
    fprintf(stderr, "\rrendering [%s] %3d%%", bar, (int)(fraction * 100 + 0.5));
    if (fraction >= 1) fputs("\r\033[K", stderr);
    fflush(stderr);
}

/* The default output: the model's name (or the file's, without its extension) + .png. */
static char *default_output(const ModelArgs *m) {
    const char *name = m->model;
    size_t len;
    if (name) len = strlen(name);
    else {
        const char *slash = strrchr(m->path, '/');
        name = slash ? slash + 1 : m->path;
        if (!strcmp(name, "-") || !*name) name = "plant";
        const char *dot = strrchr(name, '.');
        len = dot && dot != name ? (size_t)(dot - name) : strlen(name);
    }
    char *out = malloc(len + 5);
    if (out) {
        memcpy(out, name, len);
        memcpy(out + len, ".png", 5);
    }
    return out;
}

int cmd_render(int argc, char **argv) {
    static const struct option opts[] = {
        CLI_DERIVE_OPTIONS,
        {"output", required_argument, 0, 'o'},        {"view", required_argument, 0, OPT_VIEW},
        {"size", required_argument, 0, OPT_SIZE},      {"samples", required_argument, 0, OPT_SAMPLES},
        {"ao", required_argument, 0, OPT_AO},          {"no-shadows", no_argument, 0, OPT_NO_SHADOWS},
        {"stats", no_argument, 0, OPT_STATS},          {"synthetic", required_argument, 0, OPT_SYNTHETIC},
        {"help", no_argument, 0, 'h'},                 {0, 0, 0, 0},
    };
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylRenderOptions ro = {.diag = stderr};
    const char *output = NULL;
    bool stats = false;
    long synthetic = 0; /* hidden: render a synthetic tree of about N triangles (benchmarks) */
    double v;
    int c;
    optind = 1;
    while ((c = getopt_long(argc, argv, CLI_DERIVE_SHORT "o:h", opts, NULL)) != -1) {
        int done = cli_derive_option(c, optarg, &m, &d);
        if (done < 0) return SYL_EUSAGE;
        if (done) continue;
        switch (c) {
        case 'o': output = optarg; break;
        case OPT_VIEW:
            if (!parse_view(optarg, &ro.view)) return SYL_EUSAGE;
            break;
        case OPT_SIZE:
            if (!parse_size(optarg, &ro.width, &ro.height)) return SYL_EUSAGE;
            break;
        case OPT_SAMPLES:
            if (!cli_integer("--samples", optarg, 1, 64, &v)) return SYL_EUSAGE;
            ro.samples = (int)v;
            break;
        case OPT_AO:
            if (!cli_integer("--ao", optarg, 0, 64, &v)) return SYL_EUSAGE;
            ro.ao_samples = v > 0 ? (int)v : -1;
            break;
        case OPT_NO_SHADOWS: ro.shadows = -1; break;
        case OPT_STATS: stats = true; break;
        case OPT_SYNTHETIC:
            if (!cli_integer("--synthetic", optarg, 500, 1e8, &v)) return SYL_EUSAGE;
            synthetic = (long)v;
            break;
        case 'h': fputs(usage, stdout); return SYL_OK;
        default: fputs(usage, stderr); return SYL_EUSAGE;
        }
    }
    if (optind != argc - (synthetic ? 0 : 1)) {
        fprintf(stderr, "sylva render: expects one model file\n%s", usage);
        return SYL_EUSAGE;
    }
    ro.threads = d.threads;
    int status = SYL_OK;
    SylMesh *mesh = NULL;
    SylSkeleton *sk = NULL;
    size_t modules = 0;
    double t0 = cli_now(), t1 = t0, t2 = t0, t3 = t0;
    char *out_path = NULL;
    if (synthetic) {
        mesh = synth_tree(synthetic);
        if (!mesh) {
            fprintf(stderr, "sylva: error: out of memory\n");
            return SYL_ELIMIT;
        }
        t3 = cli_now();
        out_path = strdup(output ? output : "synthetic.png");
    } else {
        cli_model_spec(&m, argv[optind]);
        out_path = output ? strdup(output) : default_output(&m);
        SylProgram *p;
        SylString *s;
        status = cli_derive_interpreted(&m, &d, &p, &s);
        if (status) {
            free(out_path);
            return status;
        }
        t1 = cli_now();
        SylTurtleOptions topt = {.diag = stderr};
        status = syl_turtle(p, s, &topt, &sk);
        modules = syl_string_length(s);
        syl_string_free(s);
        syl_program_free(p);
        t2 = cli_now();
        SylMeshOptions mo = {.threads = d.threads, .diag = stderr};
        if (!status) status = syl_mesh_build(sk, &mo, &mesh);
        t3 = cli_now();
    }
    if (!out_path && !status) {
        fprintf(stderr, "sylva: error: out of memory\n");
        status = SYL_ELIMIT;
    }
    Progress prog = {.start = cli_now()};
    if (isatty(2)) {
        ro.progress = progress;
        ro.user = &prog;
    }
    double t4 = t3, t5 = t3;
    if (!status) {
        int w = ro.width ? ro.width : 1024, h = ro.height ? ro.height : 1024;
        uint8_t *rgb = malloc((size_t)w * (size_t)h * 3);
        if (!rgb) {
            fprintf(stderr, "sylva: error: out of memory for a %dx%d picture\n", w, h);
            status = SYL_ELIMIT;
        } else {
            t4 = cli_now();
            status = syl_render(mesh, &ro, rgb);
            t5 = cli_now();
            if (!status) status = syl_write_png(out_path, rgb, w, h, stderr);
            free(rgb);
        }
    }
    double t6 = cli_now();
    if (!status && stats) {
        if (!synthetic)
            fprintf(stderr, "modules: %zu\nderive time: %.6f s\nturtle time: %.6f s\nmesh time: %.6f s\n", modules,
                    t1 - t0, t2 - t1, t3 - t2);
        fprintf(stderr, "vertices: %zu\ntriangles: %zu\n", mesh->nverts, mesh->nidx / 3);
        fprintf(stderr, "render time: %.6f s\nwrite time: %.6f s\npeak memory: %.2f MB\n", t5 - t4, t6 - t5,
                cli_peak_mb());
    }
    free(out_path);
    if (synthetic) synth_free(mesh);
    else syl_mesh_free(mesh);
    syl_skeleton_free(sk);
    return status;
}
