/* SPDX-License-Identifier: MIT */
/* sky_map — an equirectangular map as the core's sky dome of suns. See sky_map.h. */
#include "host/sky_map.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

int sky_map_bands(int dirs)
{
    int n = dirs > 0 ? dirs : SKY_MAP_DEFAULT_DIRS, m = 1;
    while (3 * (m + 1) * (m + 1) <= n) m++;
    return m;
}

/* The integral of w dw over zenith angles T0..T1 and map azimuths A0..A1, for
 * w = (sin t cos a, cos t, sin t sin a), dw = sin t dt da: the integrals of sin^2 t
 * (t / 2 - sin 2t / 4) and of sin t cos t (sin^2 t / 2) times those of cos a, 1, sin a. */
static void patch(double t0, double t1, double a0, double a1, double out[3])
{
    const double s2 = (t1 - t0) / 2 - (sin(2 * t1) - sin(2 * t0)) / 4;
    const double sc = (sin(t1) * sin(t1) - sin(t0) * sin(t0)) / 2;
    out[0] = s2 * (sin(a1) - sin(a0));
    out[1] = sc * (a1 - a0);
    out[2] = s2 * (cos(a0) - cos(a1));
}

/* The map's light over zenith angles T0..T1 and the map's U range U0..U1 (of width at
 * most 1, either end may lie outside 0..1: the map wraps) per channel into V. */
static void cell_light(const float *rgb, int w, int h, double t0, double t1, double u0, double u1, double v[3][3])
{
    int y, c, k;
    const int y0 = (int)floor(t0 / PI * h), y1 = (int)ceil(t1 / PI * h);
    const long x0 = (long)floor(u0 * w), x1 = (long)ceil(u1 * w);
    memset(v, 0, 9 * sizeof v[0][0]);
    for (y = y0 < 0 ? 0 : y0; y < y1 && y < h; y++) {
        const double ta = fmax(t0, PI * y / h), tb = fmin(t1, PI * (y + 1) / h);
        long xu;
        if (!(tb > ta)) continue;
        for (xu = x0; xu < x1; xu++) {
            const double ua = fmax(u0, (double)xu / w), ub = fmin(u1, (double)(xu + 1) / w);
            const float *p = rgb + 3 * ((size_t)y * (size_t)w + (size_t)(((xu % w) + w) % w));
            double q[3];
            if (!(ub > ua) || (p[0] == 0 && p[1] == 0 && p[2] == 0)) continue;
            patch(ta, tb, 2 * PI * (ua - 0.5), 2 * PI * (ub - 0.5), q);
            for (c = 0; c < 3; c++)
                for (k = 0; k < 3; k++) v[c][k] += p[c] * q[k];
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
    int i, j, c, n = 0;
    for (i = 0; i < m; i++) {
        const int cells = 3 * (2 * i + 1);
        const double t0 = asin((double)i / m), t1 = i + 1 == m ? PI / 2 : asin((double)(i + 1) / m);
        for (j = 0; j < cells; j++) {
            const double a0 = PI + psi0 - 2 * PI * (j + 1) / cells;
            const double u0 = a0 / (2 * PI) + 0.5;
            double v[3][3], g[3], len, cosine;
            cell_light(rgb, w, h, t0, t1, u0, u0 + 1.0 / cells, v);
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
    return n;
}
