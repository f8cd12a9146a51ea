/* The step number on a frame of `sylva animate`: a 5 x 7 bitmap of the digits, so that the
 * overlay needs no font and looks the same in PNG frames and in videos. */
#include <stdio.h>
#include <string.h>

#include "cli/animate.h"

/* Rows top to bottom, bit 4 the leftmost column. */
static const uint8_t digits[10][7] = {
    {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}, {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e},
    {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}, {0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e},
    {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}, {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e},
    {0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e}, {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
    {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}, {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c},
};

void cli_label_draw(uint8_t *rgb, int width, int height, int number, int *box_w, int *box_h) {
    char text[16];
    int n = snprintf(text, sizeof text, "%d", number < 0 ? 0 : number);
    int s = height / 120 > 1 ? height / 120 : 1; /* pixels per bitmap dot */
    /* the box: one dot of margin around the digits, a dot between them */
    int bw = (n * 6 + 1) * s, bh = 9 * s;
    if (bw > width) bw = width;
    if (bh > height) bh = height;
    for (int y = 0; y < bh; y++)
        for (int x = 0; x < bw; x++) memset(rgb + 3 * ((size_t)y * width + x), 24, 3);
    for (int i = 0; i < n; i++) {
        const uint8_t *g = digits[text[i] - '0'];
        for (int r = 0; r < 7; r++)
            for (int c = 0; c < 5; c++) {
                if (!(g[r] >> (4 - c) & 1)) continue;
                for (int dy = 0; dy < s; dy++)
                    for (int dx = 0; dx < s; dx++) {
                        int x = (1 + i * 6 + c) * s + dx, y = (1 + r) * s + dy;
                        if (x < bw && y < bh) memset(rgb + 3 * ((size_t)y * width + x), 255, 3);
                    }
            }
    }
    if (box_w) *box_w = bw;
    if (box_h) *box_h = bh;
}
