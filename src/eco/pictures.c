/* An ecosystem's pictures (sylva/ecosystem.h): a snapshot's top-down map, its plants as
 * discs in their species' colours over the terrain's hillshade, the tallest on top, with a
 * legend; and the SVG chart of each species' cover over the years. One palette for both. */
#include "util/lazy_xml.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/font.h"
#include "sylva/ecosystem.h"

static const uint8_t palette[][3] = {{46, 125, 50}, {230, 140, 30}, {30, 90, 160}, {170, 60, 150},
                                     {200, 50, 40}, {120, 170, 40}, {90, 60, 30}, {20, 160, 160}};
enum { NPAL = sizeof palette / sizeof palette[0] };

/* The species' colours and names in the top left corner, on a dark box. */
static void map_legend(const SylEcoModel *m, const SylPicture *pic) {
    static const uint8_t dark[3] = {24, 24, 24}, white[3] = {240, 240, 240};
    int s = pic->width >= 400 ? 2 : 1, line = 10 * s, wide = 0;
    for (int i = 0; i < m->nspecies; i++) {
        int tw = font_text_width(m->species[i].name, s);
        wide = tw > wide ? tw : wide;
    }
    font_fill_rect(pic->rgb, pic->width, pic->height, 0, 0, wide + 14 * s, m->nspecies * line + 4 * s, dark);
    for (int i = 0; i < m->nspecies; i++) {
        int y = 3 * s + i * line;
        font_fill_rect(pic->rgb, pic->width, pic->height, 3 * s, y, 7 * s, 7 * s, palette[i % NPAL]);
        font_text_draw(pic->rgb, pic->width, pic->height, 12 * s, y, m->species[i].name, s, white);
    }
}

static int by_height(const void *a, const void *b, void *plants) {
    const SylEcoPlant *p = (const SylEcoPlant *)plants + *(const uint32_t *)a,
                      *q = (const SylEcoPlant *)plants + *(const uint32_t *)b;
    if (p->height != q->height) return p->height < q->height ? -1 : 1;
    return p->id < q->id ? -1 : p->id > q->id;
}

int syl_ecosystem_draw_map(const SylEcoModel *m, const SylTerrain *t, const SylEcoPlant *plants, size_t n,
                           const SylMapOptions *o, SylPicture *out) {
    SylPicture pic = {0};
    int st = syl_terrain_draw_hillshade(t, o, &pic);
    uint32_t *order = st ? NULL : malloc((n ? n : 1) * sizeof *order); /* indices: no copy of the plants */
    if (!order) {
        syl_picture_free(&pic);
        *out = (SylPicture){0};
        return SYL_ELIMIT;
    }
    uint8_t *rgb = pic.rgb;
    int w = pic.width, h = pic.height;
    double scale = (double)w / t->nx / t->cell; /* pixels per metre */
    for (size_t j = 0; j < n; j++) order[j] = (uint32_t)j;
    qsort_r(order, n, sizeof *order, by_height, (void *)plants); /* the tallest drawn last, on top */
    for (size_t j = 0; j < n; j++) {
        const SylEcoPlant *p = &plants[order[j]];
        double rad = m->species[p->species].radius_ratio * p->height * scale;
        if (rad < 0.75) rad = 0.75;
        double cx = (p->x - t->x0) * scale, cz = (p->z - t->z0) * scale;
        const uint8_t *c = palette[p->species % NPAL];
        double dim = p->state == SYL_ECO_DOMINATED ? 0.6 : 1.0;
        for (int z = (int)floor(cz - rad); z <= (int)ceil(cz + rad); z++) {
            if (z < 0 || z >= h) continue;
            for (int x = (int)floor(cx - rad); x <= (int)ceil(cx + rad); x++) {
                if (x < 0 || x >= w) continue;
                double dx = x + 0.5 - cx, dz = z + 0.5 - cz, d2 = dx * dx + dz * dz;
                if (d2 > rad * rad) continue;
                double lit = dim * (1.05 - 0.35 * d2 / (rad * rad)); /* a rounded crown */
                uint8_t *px = rgb + 3 * ((size_t)z * w + x);
                for (int ch = 0; ch < 3; ch++) {
                    double v = c[ch] * lit;
                    px[ch] = (uint8_t)(v > 255 ? 255 : v);
                }
            }
        }
    }
    map_legend(m, &pic);
    free(order);
    *out = pic;
    return SYL_OK;
}

/* The chart: each species' cover (crown area / terrain area) over the years. */
int syl_ecosystem_draw_chart(const SylEcoModel *m, const SylEcoYear *years, int nyears, const SylChartOptions *o,
                             char **svg, size_t *len) {
    *svg = NULL, *len = 0;
    xmlBufferPtr buf = xmlBufferCreate();
    xmlTextWriterPtr w = buf ? xmlNewTextWriterMemory(buf, 0) : NULL;
    if (!w) {
        if (buf) xmlBufferFree(buf);
        return SYL_ELIMIT;
    }
    const double W = o && o->width > 0 ? o->width : 640, H = o && o->height > 0 ? o->height : 360, L = 60, R = 140, T = 20, B = 40;
    double top = 0;
    for (int y = 0; y < nyears; y++)
        for (int s = 0; s < m->nspecies; s++)
            if (years[y].cover[s] > top) top = years[y].cover[s];
    top = top > 0 ? ceil(top * 10) / 10 : 1;
    int last = nyears ? years[nyears - 1].year : 1;
    char v[64];
    xmlTextWriterSetIndent(w, 1);
    xmlTextWriterStartDocument(w, NULL, "UTF-8", NULL);
    xmlTextWriterStartElement(w, BAD_CAST "svg");
    xmlTextWriterWriteAttribute(w, BAD_CAST "xmlns", BAD_CAST "http://www.w3.org/2000/svg");
    snprintf(v, sizeof v, "%g", W);
    xmlTextWriterWriteAttribute(w, BAD_CAST "width", BAD_CAST v);
    snprintf(v, sizeof v, "%g", H);
    xmlTextWriterWriteAttribute(w, BAD_CAST "height", BAD_CAST v);
    xmlTextWriterWriteAttribute(w, BAD_CAST "font-family", BAD_CAST "sans-serif");
    xmlTextWriterWriteAttribute(w, BAD_CAST "font-size", BAD_CAST "12");
    xmlTextWriterStartElement(w, BAD_CAST "rect");
    xmlTextWriterWriteFormatAttribute(w, BAD_CAST "x", "%g", L);
    xmlTextWriterWriteFormatAttribute(w, BAD_CAST "y", "%g", T);
    xmlTextWriterWriteFormatAttribute(w, BAD_CAST "width", "%g", W - L - R);
    xmlTextWriterWriteFormatAttribute(w, BAD_CAST "height", "%g", H - T - B);
    xmlTextWriterWriteAttribute(w, BAD_CAST "fill", BAD_CAST "none");
    xmlTextWriterWriteAttribute(w, BAD_CAST "stroke", BAD_CAST "#444");
    xmlTextWriterEndElement(w);
    for (int i = 0; i <= 4; i++) { /* the axes' labels */
        xmlTextWriterStartElement(w, BAD_CAST "text");
        xmlTextWriterWriteFormatAttribute(w, BAD_CAST "x", "%g", L - 6);
        xmlTextWriterWriteFormatAttribute(w, BAD_CAST "y", "%.1f", H - B - (H - T - B) * i / 4 + 4);
        xmlTextWriterWriteAttribute(w, BAD_CAST "text-anchor", BAD_CAST "end");
        xmlTextWriterWriteFormatString(w, "%g%%", round(top * 100 * i / 4));
        xmlTextWriterEndElement(w);
        xmlTextWriterStartElement(w, BAD_CAST "text");
        xmlTextWriterWriteFormatAttribute(w, BAD_CAST "x", "%.1f", L + (W - L - R) * i / 4);
        xmlTextWriterWriteFormatAttribute(w, BAD_CAST "y", "%g", H - B + 16);
        xmlTextWriterWriteAttribute(w, BAD_CAST "text-anchor", BAD_CAST "middle");
        xmlTextWriterWriteFormatString(w, "%d", (int)round((double)last * i / 4));
        xmlTextWriterEndElement(w);
    }
    xmlTextWriterStartElement(w, BAD_CAST "text");
    xmlTextWriterWriteFormatAttribute(w, BAD_CAST "x", "%g", L + (W - L - R) / 2);
    xmlTextWriterWriteFormatAttribute(w, BAD_CAST "y", "%g", H - 6);
    xmlTextWriterWriteAttribute(w, BAD_CAST "text-anchor", BAD_CAST "middle");
    xmlTextWriterWriteString(w, BAD_CAST "year (cover: crown area / terrain area)");
    xmlTextWriterEndElement(w);
    for (int s = 0; s < m->nspecies; s++) {
        const uint8_t *c = palette[s % NPAL];
        char colour[16];
        snprintf(colour, sizeof colour, "#%02x%02x%02x", c[0], c[1], c[2]);
        xmlTextWriterStartElement(w, BAD_CAST "polyline");
        xmlTextWriterWriteAttribute(w, BAD_CAST "fill", BAD_CAST "none");
        xmlTextWriterWriteAttribute(w, BAD_CAST "stroke", BAD_CAST colour);
        xmlTextWriterWriteAttribute(w, BAD_CAST "stroke-width", BAD_CAST "2");
        xmlTextWriterStartAttribute(w, BAD_CAST "points");
        for (int y = 0; y < nyears; y++)
            xmlTextWriterWriteFormatString(w, "%s%.1f,%.1f", y ? " " : "",
                                           L + (W - L - R) * years[y].year / last,
                                           H - B - (H - T - B) * years[y].cover[s] / top);
        xmlTextWriterEndAttribute(w);
        xmlTextWriterEndElement(w);
        xmlTextWriterStartElement(w, BAD_CAST "text");
        xmlTextWriterWriteFormatAttribute(w, BAD_CAST "x", "%g", W - R + 10);
        xmlTextWriterWriteFormatAttribute(w, BAD_CAST "y", "%d", (int)T + 14 + 18 * s);
        xmlTextWriterWriteAttribute(w, BAD_CAST "fill", BAD_CAST colour);
        xmlTextWriterWriteString(w, BAD_CAST m->species[s].name);
        xmlTextWriterEndElement(w);
    }
    xmlTextWriterEndDocument(w);
    xmlFreeTextWriter(w);
    int st = SYL_OK;
    if (!(*svg = malloc((size_t)buf->use + 1))) st = SYL_ELIMIT;
    else memcpy(*svg, buf->content, (size_t)buf->use), (*svg)[buf->use] = 0, *len = (size_t)buf->use;
    xmlBufferFree(buf);
    return st;
}
