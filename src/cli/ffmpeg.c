/* The pipe to Debian's ffmpeg for `sylva animate`: raw RGB frames in on a socket (a write
 * to an ffmpeg that has stopped fails with EPIPE instead of raising SIGPIPE), an MP4 or a
 * GIF out; started with posix_spawnp, no shell, its exit status checked. */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli/animate.h"
#include "cli/cli.h"
#include "cli/testfaults.h"

extern char **environ;

static atomic_int child_pid;
/* 0; SPAWNING while ffmpeg starts; or the signal that came then, which spawned() acts on */
enum { SPAWNING = -1 };
static atomic_int spawn_state;
static void (*stop_on_signal)(int sig);

void cli_child_on_signal(void (*stop)(int sig)) { stop_on_signal = stop; }

static void spawned(int pid) {
    cli_child_started(pid);
    int sig = atomic_exchange(&spawn_state, 0);
    if (sig > 0 && stop_on_signal) stop_on_signal(sig);
    else if (sig > 0) raise(sig);
}

bool cli_encode_start(Encoder *e, EncodeFormat f, int width, int height, int fps, const char *path, int out_fd) {
    memset(e, 0, sizeof *e);
    e->in = -1;
    char size[32], rate[16], target[4200];
    snprintf(size, sizeof size, "%dx%d", width, height);
    snprintf(rate, sizeof rate, "%d", fps);
    /* file: keeps a name with a colon from being read as a protocol */
    if (path) snprintf(target, sizeof target, "file:%s", path);
    else snprintf(target, sizeof target, "pipe:1");
    const char *argv[40];
    int n = 0;
    const char *head[] = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24",
                          "-video_size", size, "-framerate", rate, "-i", "pipe:0"};
    for (size_t i = 0; i < sizeof head / sizeof *head; i++) argv[n++] = head[i];
    if (f == ENCODE_MP4) {
        const char *mp4[] = {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "20", "-movflags",
                             /* a stream cannot be rewound to write the index at the end */
                             path ? "+faststart" : "frag_keyframe+empty_moov", "-f", "mp4"};
        for (size_t i = 0; i < sizeof mp4 / sizeof *mp4; i++) argv[n++] = mp4[i];
    } else {
        /* a palette per frame (stats_mode=single, new=1): one for the whole animation would make
         * ffmpeg hold every frame until the last (1000 frames of 1024²: 7 GB) */
        const char *gif[] = {"-filter_complex",
                             "[0:v]split[a][b];[a]palettegen=stats_mode=single[p];[b][p]paletteuse=new=1", "-f", "gif"};
        for (size_t i = 0; i < sizeof gif / sizeof *gif; i++) argv[n++] = gif[i];
    }
    argv[n++] = "-y";
    argv[n++] = target;
    argv[n] = NULL;

    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv)) {
        fprintf(stderr, "sylva: error: cannot make a pipe to ffmpeg: %s\n", strerror(errno));
        return false;
    }
    shutdown(sv[0], SHUT_WR); /* ffmpeg only reads */
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, sv[0], 0);
    if (!path) posix_spawn_file_actions_adddup2(&fa, out_fd, 1);
    else posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    /* A signal between ffmpeg's start and its pid noted (main.c) would remove the temporary
     * file while ffmpeg goes on to write it: such a signal waits until the pid is noted. */
    atomic_store(&spawn_state, SPAWNING);
    int err = posix_spawnp(&e->pid, "ffmpeg", &fa, NULL, (char *const *)argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(sv[0]);
    cli_test_pause_spawn();
    if (err) {
        spawned(0);
        close(sv[1]);
        if (err == ENOENT)
            fprintf(stderr, "sylva: error: ffmpeg is not on PATH: install it (apt-get install ffmpeg, or make "
                            "deps), or write PNG frames with -o DIR/\n");
        else fprintf(stderr, "sylva: error: cannot run ffmpeg: %s\n", strerror(err));
        return false;
    }
    e->in = sv[1];
    spawned(e->pid); /* a signal now stops it before removing the file it writes */
    return true;
}

void cli_child_started(int pid) { atomic_store(&child_pid, pid); }
bool cli_child_defer(int sig) {
    int spawning = SPAWNING;
    return atomic_compare_exchange_strong(&spawn_state, &spawning, sig);
}
void cli_child_gone(void) { atomic_store(&child_pid, 0); }
int cli_child_take(void) { return atomic_exchange(&child_pid, 0); }

bool cli_encode_frame(Encoder *e, const uint8_t *rgb, size_t bytes) {
    while (bytes && !e->broken) {
        ssize_t w = send(e->in, rgb, bytes, MSG_NOSIGNAL);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) e->broken = true;
        else rgb += w, bytes -= (size_t)w;
    }
    return !e->broken;
}

bool cli_encode_finish(Encoder *e) {
    if (e->in >= 0) close(e->in);
    e->in = -1;
    int ws;
    pid_t r;
    while ((r = waitpid(e->pid, &ws, 0)) < 0 && errno == EINTR) {
    }
    cli_child_gone();
    if (r < 0) {
        fprintf(stderr, "sylva: error: lost ffmpeg: %s\n", strerror(errno));
        return false;
    }
    if (WIFEXITED(ws) && WEXITSTATUS(ws) == 0) {
        if (!e->broken) return true;
        fprintf(stderr, "sylva: error: ffmpeg stopped reading the frames\n");
    } else if (WIFEXITED(ws)) fprintf(stderr, "sylva: error: ffmpeg failed (exit status %d)\n", WEXITSTATUS(ws));
    else if (WIFSIGNALED(ws)) fprintf(stderr, "sylva: error: ffmpeg was killed by signal %d\n", WTERMSIG(ws));
    return false;
}
