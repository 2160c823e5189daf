/* SPDX-License-Identifier: MIT */
/* sky_map — an equirectangular map as the core's sky dome of suns. See sky_map.h. */
#include "host/sky_map.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

int sky_map_bands(int dirs)
{
    int n = dirs > 0 ? dirs : SKY_MAP_DEFAULT_DIRS, m = 1;
    while (3 * (m + 1) * (m + 1) <= n) m++;
    return m;
}

/* The map's light over zenith angles T0..T1 and the map's U range U0..U1 (of width at
 * most 1; either end may lie outside 0..1: the map wraps) per channel into V: the sum
 * over pixels of L times the integral of w dw over the pixel's part of the range, for
 * w = (sin t cos a, cos t, sin t sin a), dw = sin t dt da (a = 2 pi (u - 1/2)): the
 * integrals of sin^2 t (t / 2 - sin 2t / 4) and of sin t cos t (sin^2 t / 2) over the
 * row's part times those of cos a, 1 and sin a over the column's part. COLUMN holds
 * sin and cos of a at the W + 1 column edges. */
static void cell_light(const float *rgb, int w, int h, const double (*column)[2], double t0,
                       double t1, double u0, double u1, double v[3][3])
{
    int y, c;
    const int y0 = (int)floor(t0 / PI * h), y1 = (int)ceil(t1 / PI * h);
    const long x0 = (long)floor(u0 * w), x1 = (long)ceil(u1 * w);
    const double e0[2] = {sin(2 * PI * (u0 - 0.5)), cos(2 * PI * (u0 - 0.5))};
    const double e1[2] = {sin(2 * PI * (u1 - 0.5)), cos(2 * PI * (u1 - 0.5))};
    memset(v, 0, 9 * sizeof v[0][0]);
    for (y = y0 < 0 ? 0 : y0; y < y1 && y < h; y++) {
        const double ta = fmax(t0, PI * y / h), tb = fmin(t1, PI * (y + 1) / h);
        const double s2 = (tb - ta) / 2 - (sin(2 * tb) - sin(2 * ta)) / 4;
        const double sc = (sin(tb) * sin(tb) - sin(ta) * sin(ta)) / 2;
        double row[3][3] = {
            {0}}; /* per channel: the sums over columns of L d(sin a), L da, L -d(cos a) */
        long xu;
        if (!(tb > ta)) continue;
        for (xu = x0; xu < x1; xu++) {
            const long x = ((xu % w) + w) % w;
            const float *p = rgb + 3 * ((size_t)y * (size_t)w + (size_t)x);
            const int first = xu == x0 && u0 > (double)xu / w,
                      last = xu == x1 - 1 && u1 < (double)(xu + 1) / w;
            const double *sa = first ? e0 : column[x], *sb = last ? e1 : column[x + 1];
            const double da = 2 * PI * (fmin(u1, (double)(xu + 1) / w) - fmax(u0, (double)xu / w));
            if (p[0] == 0 && p[1] == 0 && p[2] == 0) continue;
            for (c = 0; c < 3; c++) {
                row[c][0] += p[c] * (sb[0] - sa[0]);
                row[c][1] += p[c] * da;
                row[c][2] += p[c] * (sa[1] - sb[1]);
            }
        }
        for (c = 0; c < 3; c++) {
            v[c][0] += s2 * row[c][0];
            v[c][1] += sc * row[c][1];
            v[c][2] += s2 * row[c][2];
        }
    }
}

int sky_map_suns(const float *rgb, int w, int h, double scale, int dirs, sky_sun *suns)
{
    /* The core's cell at azimuth psi from f0 toward f1 lies along cos psi f0 + sin psi f1
     * = (-cos(psi - psi0), 0, sin(psi - psi0)) with cos psi0 = 0.8, sin psi0 = 0.6: at
     * the map's azimuth a = pi + psi0 - psi, so the cell psi_j..psi_j+1 is the map's
     * a from pi + psi0 - psi_j+1, turning the other way. */
    const double psi0 = atan2(0.6, 0.8);
    const int m = sky_map_bands(dirs);
    double(*column)[2] = malloc(((size_t)w + 1) * sizeof *column);
    int i, j, c, n = 0;
    if (!column) return -1;
    for (i = 0; i <= w; i++) {
        column[i][0] = sin(2 * PI * ((double)i / w - 0.5));
        column[i][1] = cos(2 * PI * ((double)i / w - 0.5));
    }
    for (i = 0; i < m; i++) {
        const int cells = 3 * (2 * i + 1);
        const double t0 = asin((double)i / m), t1 = i + 1 == m ? PI / 2 : asin((double)(i + 1) / m);
        for (j = 0; j < cells; j++) {
            const double a0 = PI + psi0 - 2 * PI * (j + 1) / cells;
            const double u0 = a0 / (2 * PI) + 0.5;
            double v[3][3], g[3], len, cosine;
            cell_light(rgb, w, h, (const double(*)[2])column, t0, t1, u0, u0 + 1.0 / cells, v);
            for (c = 0; c < 3; c++) g[c] = v[0][c] + v[1][c] + v[2][c];
            len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
            if (!(len > 0) || !(g[1] > 0)) continue;
            cosine = g[1] / len;
            for (c = 0; c < 3; c++) {
                suns[n].dir[c] = -g[c] / len;
                suns[n].e[c] = scale * v[c][1] / cosine;
            }
            n++;
        }
    }
    free(column);
    return n;
}
