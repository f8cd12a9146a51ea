/* sylva animate: growth as a picture sequence — an L-system's derivation steps, a grown
 * plant's years, a strands tree's ages — the camera pulling back from the first frame's plant
 * to the last frame's (framing.c), written as PNG frames or encoded by ffmpeg into an MP4 or
 * a GIF. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/animate.h"
#include "cli/cli.h"
#include "util/outgroup.h"

int cmd_animate(int argc, char **argv);

const CliCommand cli_animate_command = {
    .name = "animate",
    .what = "render growth as PNG frames, an MP4 or a GIF",
    .run = cmd_animate,
    .usage = "sylva animate FILE[:Model] -o OUT.mp4|OUT.gif|DIR/ [options]",
    .about = "Render a model's growth frame by frame: an L-system's derivation steps 0 to n (derived\n"
             "once, each step drawn and meshed), a grow block's or a scene's years 1 to N (grown\n"
             "again to each year), a strands block's ages 1/N to 1. The first frame is framed to its\n"
             "own plant and the last to the last frame's; between them the camera pulls back\n"
             "steadily, so a seedling is readable and the grown plant fills the last frame.\n"
             "An MP4 (H.264, yuv420p) or a GIF is encoded by ffmpeg, which must be on PATH; a\n"
             "directory gets frame_0000.png, frame_0001.png ... and needs no ffmpeg. The frames\n"
             "never depend on the number of threads.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUTPUT,
         .help = "OUT.mp4, OUT.gif, or a directory (named with a final / or\n"
                 "existing; made if missing) for PNG frames"},
        {.option = CLI_OPT_SIZE, .help = "frame size in pixels (default 512x512; even for an MP4)"},
        {.option = CLI_OPT_FPS},
        {.option = CLI_OPT_FRAMES_PER_STEP},
        {.option = CLI_OPT_STEPS, .help = "draw the step (year, age) number in the top left corner"},
        {.option = CLI_OPT_VIEW},
        {.option = CLI_OPT_SAMPLES},
        {.option = CLI_OPT_AO},
        {.option = CLI_OPT_NO_SHADOWS},
        {.option = CLI_OPT_STATS, .help = "print the pictures rendered, frames written, times and\n"
                 "pictures per second to stderr"},
        {.option = CLI_OPT_DERIVE,
         .help = "the last step (grow blocks and scenes: year; strands: the number\n"
                 "of ages, default 10); default: the model's `derive` or `years`"},
        {.option = CLI_OPT_SEED},
        {.option = CLI_OPT_SET},
        {.option = CLI_OPT_ALLOW_PATH},
        {.option = CLI_OPT_THREADS},
        {.group = cli_limits},
        {.group = cli_grow_limits},
        {0},
    },
    .epilogue = "\nA progress bar is shown on stderr when it is a terminal and the work takes more than a\n"
                "second. Without ffmpeg, an MP4 or a GIF is an I/O error (exit code 4); so is ffmpeg\n"
                "failing. Nothing is left at OUT when it fails: the video is written to a temporary\n"
                "file and renamed, and a directory keeps what it held: the frames this run wrote are\n"
                "removed, and those it replaced are put back.\n\n" CLI_EXIT_CODES,
    .args_error = "expects one model file",
};

typedef enum { OUT_FRAMES, OUT_MP4, OUT_GIF } OutKind;

static bool ends_with(const char *s, const char *tail) {
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && !strcmp(s + n - m, tail);
}

/* What OUT names: a directory (a final / or one that exists), .mp4 or .gif. */
static bool out_kind(const char *out, OutKind *kind) {
    struct stat st;
    if (ends_with(out, "/") || (!stat(out, &st) && S_ISDIR(st.st_mode))) *kind = OUT_FRAMES;
    else if (ends_with(out, ".mp4") || ends_with(out, ".MP4")) *kind = OUT_MP4;
    else if (ends_with(out, ".gif") || ends_with(out, ".GIF")) *kind = OUT_GIF;
    else {
        fprintf(stderr, "sylva: error: -o '%s': expects a name ending in .mp4 or .gif, or a directory for PNG "
                        "frames (ending in /)\n", out);
        return false;
    }
    return true;
}

static bool on_path(const char *name) {
    const char *path = getenv("PATH");
    if (!path) path = "/usr/bin:/bin";
    while (*path) {
        size_t n = strcspn(path, ":");
        char full[4200];
        snprintf(full, sizeof full, "%.*s/%s", (int)(n ? n : 1), n ? path : ".", name);
        if (!access(full, X_OK)) return true;
        path += n + (path[n] == ':');
    }
    return false;
}

/* Where the frames go: PNG files in a directory, or ffmpeg writing the output file. */
typedef struct Sink {
    OutKind kind;
    const char *out;
    char *dir;          /* OUT_FRAMES: without the final / */
    bool made_dir;      /* this run made it: removed again on failure */
    int written;        /* frame files written */
    OutGroup frames;    /* what was at their paths: put back when a later frame fails */
    OutFile file;       /* OUT_MP4, OUT_GIF */
    bool file_open;
    Encoder enc;
    bool enc_started;
} Sink;

static int sink_open(Sink *s, int width, int height, int fps) {
    if (s->kind == OUT_FRAMES) {
        s->dir = strdup(s->out);
        if (!s->dir) return SYL_ELIMIT;
        size_t n = strlen(s->dir);
        while (n > 1 && s->dir[n - 1] == '/') s->dir[--n] = 0;
        if (!mkdir(s->dir, 0777)) s->made_dir = true;
        else if (errno != EEXIST) {
            fprintf(stderr, "sylva: error: cannot write '%s': %s\n", s->out, strerror(errno));
            return SYL_EIO;
        }
        struct stat st;
        if (stat(s->dir, &st) || !S_ISDIR(st.st_mode)) {
            fprintf(stderr, "sylva: error: cannot write '%s': not a directory\n", s->out);
            return SYL_EIO;
        }
        if (access(s->dir, W_OK | X_OK)) {
            fprintf(stderr, "sylva: error: cannot write '%s': %s\n", s->out, strerror(errno));
            return SYL_EIO;
        }
        return SYL_OK;
    }
    if (!out_open(&s->file, s->out)) return SYL_EIO;
    s->file_open = true;
    /* a regular file is written by ffmpeg under its temporary name, so that an MP4's index
     * can go at the front; anything else is streamed through */
    const char *path = s->file.how == OUTFILE_TEMP ? s->file.tmp : NULL;
    if (s->file.how == OUTFILE_TEMP && !path) {
        fprintf(stderr, "sylva: error: cannot write '%s': no temporary file to give ffmpeg\n", s->out);
        return SYL_EIO;
    }
    fflush(s->file.f);
    if (!cli_encode_start(&s->enc, s->kind == OUT_MP4 ? ENCODE_MP4 : ENCODE_GIF, width, height, fps, path,
                          s->file.fd))
        return SYL_EIO;
    s->enc_started = true;
    return SYL_OK;
}

static int sink_frame(Sink *s, const uint8_t *rgb, int width, int height) {
    if (s->kind != OUT_FRAMES) {
        if (cli_encode_frame(&s->enc, rgb, (size_t)width * height * 3)) return SYL_OK;
        return SYL_EIO; /* ffmpeg stopped: its exit status tells why (sink_close) */
    }
    char *path = malloc(strlen(s->dir) + 32);
    if (!path) return SYL_ELIMIT;
    sprintf(path, "%s/frame_%04d.png", s->dir, s->written);
    int st = outgroup_add(&s->frames, path, &cli_sink) ? syl_png_write(path, rgb, width, height, &cli_sink) : SYL_EIO;
    free(path);
    if (!st) s->written++;
    return st;
}

/* Finish: on success put the output in place; otherwise leave nothing this run wrote. */
static int sink_close(Sink *s, int status) {
    if (s->enc_started && !cli_encode_finish(&s->enc) && !status) status = SYL_EIO;
    if (s->file_open) status = out_close(&s->file, status);
    if (status) outgroup_undo(&s->frames); /* the user's frames as they were */
    else outgroup_commit(&s->frames);
    if (s->kind == OUT_FRAMES && status && s->made_dir) rmdir(s->dir);
    free(s->dir);
    return status;
}

int cmd_animate(int argc, char **argv) {
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylRenderOptions ro = {.diag = stderr, .view = SYL_VIEW_AUTO};
    CliArgs a = {.m = &m, .d = &d, .ro = &ro, .fps = 4, .frames_per_step = 1};
    int done = cli_parse(&cli_animate_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    if (!a.output) {
        fprintf(stderr, "sylva: error: animate needs -o OUT.mp4, OUT.gif or DIR/\n");
        return SYL_EUSAGE;
    }
    Sink sink = {.out = a.output};
    if (!out_kind(a.output, &sink.kind)) return SYL_EUSAGE;
    int w = ro.width ? ro.width : 512, h = ro.height ? ro.height : 512;
    ro.width = w, ro.height = h;
    if (sink.kind == OUT_MP4 && (w % 2 || h % 2)) {
        fprintf(stderr, "sylva: error: an MP4 (yuv420p) needs an even width and height, not %dx%d\n", w, h);
        return SYL_EUSAGE;
    }
    if (sink.kind != OUT_FRAMES && !on_path("ffmpeg")) { /* before any work */
        fprintf(stderr, "sylva: error: ffmpeg is not on PATH: install it (apt-get install ffmpeg, or make deps), "
                        "or write PNG frames with -o DIR/\n");
        return SYL_EIO;
    }
    cli_model_spec(&m, a.files[0]);
    ro.threads = d.threads;

    double t0 = cli_now();
    int status;
    SylProgram *p = cli_compile(&m, SYL_WARN_MISTAKES | SYL_WARN_DRAWS, &status);
    if (!p) return status;
    SylBudget *budget = syl_budget_new(d.max_memory);
    SylMeshOptions mo = {.threads = d.threads, .diag = stderr, .budget = budget};
    ro.budget = budget;
    Progress bar;
    cli_progress_start(&bar, "growing");
    SylPlantOptions po = {.use_steps = d.steps >= 0, .steps = d.steps, .use_seed = d.use_seed, .seed = d.seed,
                          .threads = d.threads, .max_modules = d.max_modules, .max_memory = d.max_memory,
                          .max_work = d.max_work, .max_metamers = m.max_metamers, .max_buds = m.max_buds,
                          .budget = budget, .drop_string = 1, .scene = !m.model, .mesh = &mo, .diag = stderr,
                          .progress = cli_progress, .user = &bar};
    SylGrowth *g = NULL;
    SylPlant last = {0}, frame = {0};
    uint8_t *rgb = NULL;
    status = syl_growth_new(p, &po, &g);
    cli_progress(&bar, 1);
    double build_s = cli_now() - t0, render_s = 0;
    int n = status ? 0 : syl_growth_count(g);
    /* the last frame first: the box every frame's camera moves toward */
    if (!status) status = syl_growth_build(g, n - 1, &last);
    build_s = cli_now() - t0;
    if (!status && !(rgb = malloc((size_t)w * h * 3))) {
        fprintf(stderr, "sylva: error: out of memory for a %dx%d frame\n", w, h);
        status = SYL_ELIMIT;
    }
    if (!status) status = sink_open(&sink, w, h, a.fps);
    Progress rbar;
    cli_progress_start(&rbar, "rendering");
    for (int k = 0; k < n && !status; k++) {
        const SylPlant *pl = &last;
        double r0 = cli_now();
        if (k < n - 1) {
            status = syl_growth_build(g, k, &frame);
            pl = &frame;
            build_s += cli_now() - r0;
            r0 = cli_now();
        }
        CliFrameBox box;
        if (!status) {
            cli_frame_box(pl->mesh, last.mesh, n > 1 ? (double)k / (n - 1) : 1, &box);
            ro.frame = &box.mesh;
            status = syl_render_draw_mesh(pl->mesh, &ro, rgb);
        }
        render_s += cli_now() - r0;
        if (!status && a.steps) cli_label_draw(rgb, w, h, syl_growth_label(g, k), NULL, NULL);
        for (int r = 0; r < a.frames_per_step && !status; r++) status = sink_frame(&sink, rgb, w, h);
        syl_plant_free(&frame);
        cli_progress(&rbar, (double)(k + 1) / n);
    }
    status = sink_close(&sink, status);
    double t2 = cli_now();
    if (!status && a.stats) {
        int frames = n * a.frames_per_step;
        fprintf(stderr, "pictures: %d\nframes: %d\nsize: %dx%d\nbuild time: %.6f s\nrender time: %.6f s\n", n,
                frames, w, h, build_s, render_s);
        fprintf(stderr, "total time: %.6f s\npictures per second: %.3f\npeak memory: %.2f MB\n", t2 - t0,
                n / (t2 - t0), cli_peak_mb());
    }
    free(rgb);
    syl_plant_free(&last);
    syl_growth_free(g);
    syl_program_free(p);
    syl_budget_free(budget);
    return status;
}
