/* Words in pictures: a 5 x 7 bitmap font (util/font.c) drawn into RGB pictures, rows top down. */
#ifndef SYL_UTIL_FONT_H
#define SYL_UTIL_FONT_H
#include <stdint.h>

/* The 7 rows of a character (bit 4 the leftmost of 5 columns); a blank for one it lacks. */
const uint8_t *font_glyph(char c);
/* Pixels a text takes across at scale pixels a dot: 6 dots a character, less the last gap;
 * 7 dots high. */
int font_text_width(const char *text, int scale);
/* The text's dots in colour, its top left at (x, y); what falls outside is clipped. */
void font_text_draw(uint8_t *rgb, int width, int height, int x, int y, const char *text, int scale,
                   const uint8_t colour[3]);
void font_fill_rect(uint8_t *rgb, int width, int height, int x0, int y0, int w, int h, const uint8_t colour[3]);

#endif
