/* The pieces of `sylva animate` (cmd_animate.c): the step number drawn on a frame, and the
 * pipe to ffmpeg that encodes the frames. */
#ifndef SYL_CLI_ANIMATE_H
#define SYL_CLI_ANIMATE_H
#include <stdbool.h>
#include <stdint.h>
#include <sys/types.h>

#include "sylva/mesh.h"

/* Draw number in the top left corner of a width x height RGB picture: white digits on a dark
 * box, scaled with the picture's height. The box is all it changes: *box_w x *box_h pixels
 * from (0, 0), which it returns when not NULL. */
void cli_label_draw(uint8_t *rgb, int width, int height, int number, int *box_w, int *box_h);

/* The box frame number t (0 the first, 1 the last) is framed to: from the frame's own plant
 * toward the last frame's, as a mesh of its 8 corners for SylRenderOptions.frame. */
typedef struct CliFrameBox {
    float corners[8][3];
    SylMesh mesh;
} CliFrameBox;
void cli_frame_box(const SylMesh *own, const SylMesh *last, double t, CliFrameBox *box);

/* ffmpeg reading raw RGB frames on a pipe and writing an MP4 (H.264, yuv420p) or a GIF (one
 * palette for the whole animation). */
typedef struct Encoder {
    pid_t pid;
    int in;          /* the frames go here */
    bool broken;     /* a write failed: ffmpeg stopped reading */
} Encoder;
typedef enum { ENCODE_MP4, ENCODE_GIF } EncodeFormat;

/* Start ffmpeg (found on PATH) writing to the file path (seekable) or, when path is NULL, to
 * out_fd (written through, an MP4 then fragmented). false, reported, when it cannot start. */
bool cli_encode_start(Encoder *e, EncodeFormat f, int width, int height, int fps, const char *path, int out_fd);
bool cli_encode_frame(Encoder *e, const uint8_t *rgb, size_t bytes); /* false once ffmpeg is gone */
/* Close the pipe and wait: true when ffmpeg exited with 0 (otherwise reported). */
bool cli_encode_finish(Encoder *e);

#endif
