/* The library's pictures through the public API (sylva/ecosystem.h, sylva/terrain.h): an
 * ecosystem's snapshot map and its terrain's slope in colour, drawn by an embedding program
 * as `sylva ecosystem` and `sylva terrain --maps` draw map-YEAR.png and slope-colour.png.
 *   pictures MODEL.syl PLANTS.csv MAP.png SLOPE.png   prints "map W H", "slope W H",
 *                                                      "status N" */
#include <stdio.h>
#include <stdlib.h>

#include <sylva/ecosystem.h>
#include <sylva/texture.h>

int main(int argc, char **argv) {
    if (argc != 5) return 2;
    int st;
    SylProgram *p = syl_compile(argv[1], NULL, 0, &(SylCompileOptions){.diag = stdout, .validate = syl_validate}, &st);
    static SylEcoModel m; /* large: off the stack */
    SylTerrain *t = NULL;
    SylEcoPlant *plants = NULL;
    size_t n = 0;
    SylPicture map = {0}, slope = {0};
    if (p) st = syl_ecosystem_load(p, &(SylEcoOptions){.diag = stdout}, &m, &t);
    if (!st) st = syl_ecosystem_table_read(argv[2], &m, t, &plants, &n, &(SylSink){syl_diagnostic_print, stdout});
    if (!st) st = syl_ecosystem_draw_map(&m, t, plants, n, &(SylMapOptions){0}, &map);
    if (!st) st = syl_png_write(argv[3], map.rgb, map.width, map.height, &(SylSink){syl_diagnostic_print, stdout});
    if (!st) st = syl_terrain_draw_colour_map(t, SYL_TERRAIN_SLOPE, NULL, &slope);
    if (!st) st = syl_png_write(argv[4], slope.rgb, slope.width, slope.height, &(SylSink){syl_diagnostic_print, stdout});
    printf("map %d %d\nslope %d %d\nstatus %d\n", map.width, map.height, slope.width, slope.height, st);
    syl_picture_free(&map), syl_picture_free(&slope);
    free(plants);
    syl_terrain_free(t);
    syl_program_free(p);
    return 0;
}
