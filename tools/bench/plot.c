/* SPDX-License-Identifier: MIT */
/* plot — line plots onto an RGB canvas with a built-in 5x7 font. See plot.h. */
#include "bench/plot.h"
#include "formats/image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 5x7 glyphs for ASCII 32..126, one byte per row, top row first; bit 4 is the leftmost
 * column, bit 0 the rightmost. */
/* clang-format off: a glyph table, two glyphs a row */
static const unsigned char font5x7[95][7] = {
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00},
    {0x04, 0x04, 0x04, 0x04, 0x04, 0x00, 0x04}, /*   ! */
    {0x0A, 0x0A, 0x00, 0x00, 0x00, 0x00, 0x00},
    {0x0A, 0x0A, 0x1F, 0x0A, 0x1F, 0x0A, 0x0A}, /* " # */
    {0x04, 0x0F, 0x14, 0x0E, 0x05, 0x1E, 0x04},
    {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}, /* $ % */
    {0x08, 0x14, 0x14, 0x08, 0x15, 0x12, 0x0D},
    {0x04, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00}, /* & ' */
    {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02},
    {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}, /* ( ) */
    {0x00, 0x04, 0x15, 0x0E, 0x15, 0x04, 0x00},
    {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}, /* * + */
    {0x00, 0x00, 0x00, 0x00, 0x06, 0x04, 0x08},
    {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}, /* , - */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C},
    {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}, /* . / */
    {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E},
    {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}, /* 0 1 */
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F},
    {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}, /* 2 3 */
    {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02},
    {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}, /* 4 5 */
    {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E},
    {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}, /* 6 7 */
    {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E},
    {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}, /* 8 9 */
    {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00},
    {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x04, 0x08}, /* : ; */
    {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02},
    {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}, /* < = */
    {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08},
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04}, /* > ? */
    {0x0E, 0x11, 0x01, 0x0D, 0x15, 0x15, 0x0E},
    {0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11}, /* @ A */
    {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E},
    {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}, /* B C */
    {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C},
    {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}, /* D E */
    {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}, /* F G */
    {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11},
    {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}, /* H I */
    {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C},
    {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}, /* J K */
    {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F},
    {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}, /* L M */
    {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11},
    {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, /* N O */
    {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}, /* P Q */
    {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11},
    {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}, /* R S */
    {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04},
    {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, /* T U */
    {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04},
    {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}, /* V W */
    {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11},
    {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}, /* X Y */
    {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F},
    {0x0E, 0x08, 0x08, 0x08, 0x08, 0x08, 0x0E}, /* Z [ */
    {0x00, 0x10, 0x08, 0x04, 0x02, 0x01, 0x00},
    {0x0E, 0x02, 0x02, 0x02, 0x02, 0x02, 0x0E}, /* \ ] */
    {0x04, 0x0A, 0x11, 0x00, 0x00, 0x00, 0x00},
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}, /* ^ _ */
    {0x08, 0x04, 0x02, 0x00, 0x00, 0x00, 0x00},
    {0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F}, /* ` a */
    {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E},
    {0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E}, /* b c */
    {0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F},
    {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}, /* d e */
    {0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08},
    {0x00, 0x0F, 0x11, 0x11, 0x0F, 0x01, 0x0E}, /* f g */
    {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11},
    {0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E}, /* h i */
    {0x02, 0x00, 0x06, 0x02, 0x02, 0x12, 0x0C},
    {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}, /* j k */
    {0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E},
    {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}, /* l m */
    {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11},
    {0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E}, /* n o */
    {0x00, 0x00, 0x1E, 0x11, 0x1E, 0x10, 0x10},
    {0x00, 0x00, 0x0D, 0x13, 0x0F, 0x01, 0x01}, /* p q */
    {0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10},
    {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}, /* r s */
    {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06},
    {0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D}, /* t u */
    {0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04},
    {0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A}, /* v w */
    {0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11},
    {0x00, 0x00, 0x11, 0x11, 0x0F, 0x01, 0x0E}, /* x y */
    {0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F},
    {0x02, 0x04, 0x04, 0x08, 0x04, 0x04, 0x02}, /* z { */
    {0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04},
    {0x08, 0x04, 0x04, 0x02, 0x04, 0x04, 0x08}, /* | } */
    {0x00, 0x00, 0x08, 0x15, 0x02, 0x00, 0x00}, /* ~   */
};
/* clang-format on */

static const unsigned char BLACK[3] = {0, 0, 0}, WHITE[3] = {255, 255, 255},
                           GRID[3] = {225, 225, 225};

enum { MAX_TEXT = 200, MAX_TICKS = 60 };

/* Canvas with an inclusive clip rectangle: every write goes through put(). */
typedef struct {
    unsigned char *p;
    int w, h, cx0, cy0, cx1, cy1;
} canvas;
typedef struct {
    int x0, y0, x1, y1;
} rect;
/* lo..hi is the drawn range in axis space (log10 of the value on a log axis); ticks are
 * the multiples of step inside it. */
typedef struct {
    double lo, hi, step;
    int log, prec;
} axis;

static void put(const canvas *c, int x, int y, const unsigned char col[3])
{
    if (x < c->cx0 || x > c->cx1 || y < c->cy0 || y > c->cy1) return;
    memcpy(c->p + ((size_t)y * (size_t)c->w + (size_t)x) * 3, col, 3);
}

static void fill(const canvas *c, int x0, int y0, int x1, int y1, const unsigned char col[3])
{
    int x, y;
    x0 = x0 < c->cx0 ? c->cx0 : x0;
    y0 = y0 < c->cy0 ? c->cy0 : y0;
    x1 = x1 > c->cx1 ? c->cx1 : x1;
    y1 = y1 > c->cy1 ? c->cy1 : y1;
    for (y = y0; y <= y1; y++)
        for (x = x0; x <= x1; x++) put(c, x, y, col);
}

static void outline(const canvas *c, rect r, const unsigned char col[3])
{
    fill(c, r.x0, r.y0, r.x1, r.y0, col);
    fill(c, r.x0, r.y1, r.x1, r.y1, col);
    fill(c, r.x0, r.y0, r.x0, r.y1, col);
    fill(c, r.x1, r.y0, r.x1, r.y1, col);
}

static int text_len(const char *s)
{
    size_t n = s ? strlen(s) : 0;
    return n > MAX_TEXT ? MAX_TEXT : (int)n;
}

/* Width in pixels of s at a scale: 6-pixel cells without the trailing gap. */
static int text_w(const char *s, int scale)
{
    int n = text_len(s);
    return n ? (n * 6 - 1) * scale : 0;
}

/* Draws s from (x, y): horizontally with (x, y) the top-left corner, or, when vertical,
 * rotated a quarter turn anticlockwise, reading upwards from the bottom-left (x, y). */
static void draw_text(const canvas *c, int x, int y, const char *s, int scale,
                      const unsigned char col[3], int vertical)
{
    int i, n = text_len(s), gx, gy;
    for (i = 0; i < n; i++) {
        int ch = (unsigned char)s[i];
        const unsigned char *g = font5x7[(ch >= 32 && ch <= 126 ? ch : '?') - 32];
        int ox = vertical ? x : x + i * 6 * scale, oy = vertical ? y - i * 6 * scale : y;
        for (gy = 0; gy < 7; gy++)
            for (gx = 0; gx < 5; gx++) {
                if (!(g[gy] & (0x10 >> gx))) continue;
                if (vertical)
                    fill(c, ox + gy * scale, oy - (gx + 1) * scale + 1, ox + (gy + 1) * scale - 1,
                         oy - gx * scale, col);
                else
                    fill(c, ox + gx * scale, oy + gy * scale, ox + (gx + 1) * scale - 1,
                         oy + (gy + 1) * scale - 1, col);
            }
    }
}

/* Bresenham with a square brush of lw pixels centred on the line. */
static void line(const canvas *c, int x0, int y0, int x1, int y1, int lw,
                 const unsigned char col[3])
{
    int dx = abs(x1 - x0), dy = -abs(y1 - y0), sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int e = dx + dy, e2, h = lw / 2;
    for (;;) {
        fill(c, x0 - h, y0 - h, x0 - h + lw - 1, y0 - h + lw - 1, col);
        if (x0 == x1 && y0 == y1) break;
        e2 = 2 * e; /* both decisions use the error from before this step */
        if (e2 >= dy) {
            e += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            e += dx;
            y0 += sy;
        }
    }
}

/* ---- data and axes ---- */

/* V on an axis, log10 of it on a log axis (LOG); 0 when it must be skipped: not
 * finite, beyond 1e300 (so that ranges and tick arithmetic cannot overflow), or not
 * above 0 on a log axis. */
static int axis_value(double v, int log, double *out)
{
    if (!isfinite(v) || fabs(v) > 1e300) return 0;
    if (log) {
        if (!(v > 0.0)) return 0;
        v = log10(v);
    }
    *out = v;
    return 1;
}

/* Point i of s in axis space (LOG_X, LOG_Y: log axes); 0 when it must be skipped. */
static int point(const plot_series *s, int i, int log_x, int log_y, double *x, double *y)
{
    return axis_value(s->x ? s->x[i] : (double)i, log_x, x) && axis_value(s->y[i], log_y, y);
}

/* Data bounds over all drawable points; lo > hi is left when there are none. */
static void data_range(const plot_series *s, int ns, int log_x, int log_y, double bx[2],
                       double by[2])
{
    int k, i;
    double x, y;
    bx[0] = by[0] = HUGE_VAL;
    bx[1] = by[1] = -HUGE_VAL;
    for (k = 0; k < ns; k++)
        for (i = 0; i < s[k].n; i++)
            if (point(&s[k], i, log_x, log_y, &x, &y)) {
                bx[0] = fmin(bx[0], x), bx[1] = fmax(bx[1], x);
                by[0] = fmin(by[0], y), by[1] = fmax(by[1], y);
            }
}

/* 1, 2 or 5 times a power of ten, giving about five intervals over range (> 0). */
static double nice_step(double range)
{
    double raw = range / 5.0, e = pow(10.0, floor(log10(raw))), f = raw / e;
    return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * e;
}

/* Fits an axis to the data bounds: widens empty and zero-width ranges, then rounds the
 * ends out to whole steps (whole decades on a log axis). */
static void axis_fit(axis *a, double lo, double hi, int log)
{
    double mag;
    if (!(lo <= hi)) lo = 0.0, hi = 1.0;
    if (log) {
        lo = floor(lo), hi = ceil(hi);
        if (hi == lo) lo -= 1.0, hi += 1.0;
        a->step = ceil((hi - lo) / 10.0);
    } else {
        mag = fmax(fabs(lo), fabs(hi));
        if (hi - lo <= 1e-12 * mag || hi - lo < 1e-200) {
            double mid = 0.5 * (lo + hi), d = fabs(mid) > 1e-200 ? 0.1 * fabs(mid) : 1.0;
            lo = mid - d, hi = mid + d;
        }
        a->step = nice_step(hi - lo);
    }
    a->lo = floor(lo / a->step) * a->step;
    a->hi = ceil(hi / a->step) * a->step;
    a->log = log;
    /* Enough significant digits that neighbouring tick labels differ. */
    mag = fmax(fabs(a->lo), fabs(a->hi)) / a->step;
    a->prec = mag > 1e5 ? (int)fmin(15.0, ceil(log10(mag)) + 2.0) : 6;
}

/* Tick indices: ticks are i * step for i0 <= i <= i1, at most MAX_TICKS of them. */
static int axis_ticks(const axis *a, long long *i0)
{
    double f0 = ceil(a->lo / a->step - 1e-9), f1 = floor(a->hi / a->step + 1e-9);
    if (!(f0 > -1e15 && f1 < 1e15 && f1 >= f0)) return 0;
    *i0 = (long long)f0;
    return f1 - f0 + 1 > MAX_TICKS ? MAX_TICKS : (int)(f1 - f0) + 1;
}

static void tick_label(const axis *a, long long i, char *buf, size_t len)
{
    double v = (double)i * a->step;
    snprintf(buf, len, "%.*g", a->prec, a->log ? pow(10.0, v) : v);
}

/* Axis-space value to pixel: p0 is the pixel of a->lo, p1 that of a->hi. */
static int to_px(const axis *a, double v, int p0, int p1)
{
    double p = p0 + (v - a->lo) / (a->hi - a->lo) * (p1 - p0);
    p = p < -1e6 ? -1e6 : p > 1e6 ? 1e6 : p; /* keeps the int conversion defined */
    return (int)floor(p + 0.5);
}

static int max_label_w(const axis *a, int scale)
{
    long long i0 = 0;
    int k, n = axis_ticks(a, &i0), m = 0, tw;
    char buf[40];
    for (k = 0; k < n; k++) {
        tick_label(a, i0 + k, buf, sizeof buf);
        tw = text_w(buf, scale);
        m = tw > m ? tw : m;
    }
    return m;
}

/* ---- layout and drawing ---- */

/* Plot area inside the margins that the texts and tick labels need. */
static rect layout(int w, int h, int s, const plot_opts *o, const axis *ax, const axis *ay)
{
    rect r;
    int xl = max_label_w(ax, s) / 2 + 3 * s;
    r.x0 = 4 * s + (text_len(o->ylabel) ? 12 * s : 0) + max_label_w(ay, s) + 7 * s;
    r.y0 = text_len(o->title) ? 28 * s : 10 * s;
    r.x1 = w - 1 - (xl > 10 * s ? xl : 10 * s);
    r.y1 = h - 1 - (19 * s + (text_len(o->xlabel) ? 13 * s : 0));
    r.x1 = r.x1 > r.x0 ? r.x1 : r.x0 + 1; /* tiny canvases: keep the mapping sane */
    r.y1 = r.y1 > r.y0 ? r.y1 : r.y0 + 1;
    return r;
}

/* Grid lines, tick marks and tick labels of both axes. */
static void draw_ticks(const canvas *c, rect r, int s, const axis *ax, const axis *ay)
{
    long long i0 = 0;
    int k, n, p;
    char buf[40];
    for (k = 0, n = axis_ticks(ax, &i0); k < n; k++) {
        p = to_px(ax, (double)(i0 + k) * ax->step, r.x0, r.x1);
        fill(c, p, r.y0, p, r.y1, GRID);
        fill(c, p, r.y1, p, r.y1 + 4 * s, BLACK);
        tick_label(ax, i0 + k, buf, sizeof buf);
        draw_text(c, p - text_w(buf, s) / 2, r.y1 + 7 * s, buf, s, BLACK, 0);
    }
    for (k = 0, n = axis_ticks(ay, &i0); k < n; k++) {
        p = to_px(ay, (double)(i0 + k) * ay->step, r.y1, r.y0);
        fill(c, r.x0, p, r.x1, p, GRID);
        fill(c, r.x0 - 4 * s, p, r.x0, p, BLACK);
        tick_label(ay, i0 + k, buf, sizeof buf);
        draw_text(c, r.x0 - 7 * s - text_w(buf, s), p - 3 * s, buf, s, BLACK, 0);
    }
}

/* The curves, clipped to the plot area. A run of valid points is one polyline; a point
 * after a skipped one starts a new run with a dot, so isolated points stay visible. */
static void draw_series(canvas *c, rect r, int s, const plot_series *sr, int ns, const axis *ax,
                        const axis *ay)
{
    int k, i, px = 0, py = 0, qx, qy, run;
    double x, y;
    /* Clip to the plot area, which on tiny canvases may stick out of the canvas. */
    c->cx0 = r.x0 > 0 ? r.x0 : 0, c->cy0 = r.y0 > 0 ? r.y0 : 0;
    c->cx1 = r.x1 < c->w - 1 ? r.x1 : c->w - 1, c->cy1 = r.y1 < c->h - 1 ? r.y1 : c->h - 1;
    for (k = 0; k < ns; k++)
        for (i = 0, run = 0; i < sr[k].n; i++) {
            if (!point(&sr[k], i, ax->log, ay->log, &x, &y)) {
                run = 0;
                continue;
            }
            qx = to_px(ax, x, r.x0, r.x1);
            qy = to_px(ay, y, r.y1, r.y0);
            line(c, run ? px : qx, run ? py : qy, qx, qy, s + 1, sr[k].rgb);
            px = qx, py = qy, run = 1;
        }
    c->cx0 = c->cy0 = 0, c->cx1 = c->w - 1, c->cy1 = c->h - 1;
}

static int points_in(rect b, const plot_series *sr, int ns, rect r, const axis *ax, const axis *ay)
{
    int k, i, n = 0, qx, qy;
    double x, y;
    for (k = 0; k < ns; k++)
        for (i = 0; i < sr[k].n; i++)
            if (point(&sr[k], i, ax->log, ay->log, &x, &y)) {
                qx = to_px(ax, x, r.x0, r.x1);
                qy = to_px(ay, y, r.y1, r.y0);
                n += qx >= b.x0 && qx <= b.x1 && qy >= b.y0 && qy <= b.y1;
            }
    return n;
}

/* Legend box in the corner of the plot area that covers the fewest data points
 * (top-right preferred on ties): a coloured sample line and the label per series. */
static void draw_legend(const canvas *c, rect r, int s, const plot_series *sr, int ns,
                        const axis *ax, const axis *ay)
{
    int k, n = 0, tw = 0, bw, bh, best = -1, bestn = 0, cnt, y;
    rect b = r, cand;
    for (k = 0; k < ns; k++)
        if (text_len(sr[k].label)) {
            n++;
            tw = text_w(sr[k].label, s) > tw ? text_w(sr[k].label, s) : tw;
        }
    if (!n) return;
    bw = 6 * s + 16 * s + 5 * s + tw + 6 * s;
    bh = n * 10 * s + 5 * s;
    for (k = 0; k < 4; k++) {
        cand.x0 = (k & 1) ? r.x0 + 6 * s : r.x1 - 6 * s - bw;
        cand.y0 = (k & 2) ? r.y1 - 6 * s - bh : r.y0 + 6 * s;
        cand.x1 = cand.x0 + bw, cand.y1 = cand.y0 + bh;
        cnt = points_in(cand, sr, ns, r, ax, ay);
        if (best < 0 || cnt < bestn) best = k, bestn = cnt, b = cand;
    }
    fill(c, b.x0, b.y0, b.x1, b.y1, WHITE);
    outline(c, b, BLACK);
    for (k = 0, y = b.y0 + 6 * s; k < ns; k++) {
        if (!text_len(sr[k].label)) continue;
        fill(c, b.x0 + 6 * s, y + 3 * s - s / 2, b.x0 + 22 * s - 1, y + 3 * s - s / 2 + s,
             sr[k].rgb);
        draw_text(c, b.x0 + 27 * s, y, sr[k].label, s, BLACK, 0);
        y += 10 * s;
    }
}

static void draw_labels(const canvas *c, rect r, int s, const plot_opts *o)
{
    int ts = text_w(o->title, 2 * s) <= c->w - 8 * s ? 2 * s : s;
    draw_text(c, (c->w - text_w(o->title, ts)) / 2, 6 * s + (2 * s - ts) * 7 / 2, o->title, ts,
              BLACK, 0);
    draw_text(c, (r.x0 + r.x1 - text_w(o->xlabel, s)) / 2, r.y1 + 20 * s, o->xlabel, s, BLACK, 0);
    draw_text(c, 4 * s, (r.y0 + r.y1 + text_w(o->ylabel, s)) / 2, o->ylabel, s, BLACK, 1);
}

int plot_text(unsigned char *rgb, int w, int h, int x, int y, const char *s, int scale,
              const unsigned char colour[3])
{
    canvas c;
    if (!rgb || w < 1 || h < 1 || scale < 1 || !colour) return 0;
    c.p = rgb, c.w = w, c.h = h, c.cx0 = c.cy0 = 0, c.cx1 = w - 1, c.cy1 = h - 1;
    draw_text(&c, x, y, s, scale, colour, 0);
    return text_len(s) * 6 * scale;
}

static int args_ok(const unsigned char *rgb, int w, int h, const plot_series *sr, int ns)
{
    int k;
    if (!rgb || w < 1 || h < 1 || ns < 0 || (ns > 0 && !sr)) return 0;
    for (k = 0; k < ns; k++)
        if (sr[k].n < 0 || (sr[k].n > 0 && !sr[k].y)) return 0;
    return 1;
}

int plot_render(unsigned char *rgb, int w, int h, const plot_series *series, int nseries,
                const plot_opts *opts)
{
    static const plot_opts none;
    canvas c;
    axis ax, ay;
    rect r;
    double bx[2], by[2];
    int s;
    if (!args_ok(rgb, w, h, series, nseries)) return -1;
    opts = opts ? opts : &none;
    s = w / 640 < h / 480 ? w / 640 : h / 480; /* text and line scale grows with the canvas */
    s = s < 1 ? 1 : s;
    c.p = rgb, c.w = w, c.h = h, c.cx0 = c.cy0 = 0, c.cx1 = w - 1, c.cy1 = h - 1;
    memset(rgb, 255, (size_t)w * (size_t)h * 3);
    data_range(series, nseries, opts->log_x != 0, opts->log_y != 0, bx, by);
    axis_fit(&ax, bx[0], bx[1], opts->log_x != 0);
    axis_fit(&ay, by[0], by[1], opts->log_y != 0);
    r = layout(w, h, s, opts, &ax, &ay);
    draw_ticks(&c, r, s, &ax, &ay);
    draw_series(&c, r, s, series, nseries, &ax, &ay);
    outline(&c, r, BLACK);
    draw_legend(&c, r, s, series, nseries, &ax, &ay);
    draw_labels(&c, r, s, opts);
    return 0;
}

int plot_write(const char *path, const plot_series *series, int nseries, const plot_opts *opts,
               char *err, size_t errlen)
{
    int w = opts && opts->width > 0 ? opts->width : 640,
        h = opts && opts->height > 0 ? opts->height : 480, rc;
    unsigned char *rgb;
    if (w > IMG_MAX_DIM || h > IMG_MAX_DIM || !(rgb = malloc((size_t)w * (size_t)h * 3))) {
        if (err && errlen)
            snprintf(err, errlen, "%s: %s", path ? path : "(null)",
                     w > IMG_MAX_DIM || h > IMG_MAX_DIM ? "plot size too large" : "out of memory");
        return -1;
    }
    if (plot_render(rgb, w, h, series, nseries, opts) != 0) {
        free(rgb);
        if (err && errlen) snprintf(err, errlen, "%s: invalid plot series", path ? path : "(null)");
        return -1;
    }
    rc = img_write(path, rgb, w, h, err, errlen);
    free(rgb);
    return rc;
}
