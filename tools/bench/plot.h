/* SPDX-License-Identifier: MIT */
/* plot — a tiny line-plot renderer (host tool) used by the benchmark to draw convergence
 * curves: white canvas, framed axes with ticks, numeric labels and a light grid, a title,
 * axis labels and a legend, in a built-in 5x7 bitmap font. Written with img_write.
 */
#ifndef RAD_TOOLS_PLOT_H
#define RAD_TOOLS_PLOT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One curve. x may be NULL: the point index 0..n-1 is used. Points with a non-finite
 * coordinate (or y <= 0 on a log axis) are skipped and break the line. label may be NULL
 * or "" (no legend entry). */
typedef struct {
    const char *label;
    const double *x;
    const double *y;
    int n;
    unsigned char rgb[3];
} plot_series;

/* Any string may be NULL. width/height are used by plot_write only; <= 0 means 640x480.
 * opts itself may be NULL (no texts, linear axes, default size). */
typedef struct {
    const char *title, *xlabel, *ylabel;
    int log_x, log_y; /* log10 x axis, y axis */
    int width, height;
} plot_opts;

/* Renders the series and writes the canvas with img_write (format by extension).
 * Returns 0 or -1 with a one-line "PATH: what is wrong" message in err. */
int plot_write(const char *path, const plot_series *series, int nseries, const plot_opts *opts,
               char *err, size_t errlen);

/* Same into a caller buffer (w*h*3 bytes, row 0 at the top), for tests. Text and lines are
 * clipped to the canvas, so any w, h >= 1 works. Returns 0, or -1 on bad arguments (NULL
 * rgb, w or h < 1, nseries < 0, series NULL with nseries > 0, n < 0, y NULL with n > 0). */
int plot_render(unsigned char *rgb, int w, int h, const plot_series *series, int nseries,
                const plot_opts *opts);

/* Draws ASCII text (5x7 glyphs in 6x8 cells, times scale >= 1) with its top-left corner at
 * (x, y), clipped to the canvas; bytes outside 32..126 draw as '?'. Returns the advance
 * in pixels. Exposed for labelling images in the other tools. */
int plot_text(unsigned char *rgb, int w, int h, int x, int y, const char *s, int scale,
              const unsigned char colour[3]);

#ifdef __cplusplus
}
#endif

#endif
