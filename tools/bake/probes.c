/* SPDX-License-Identifier: MIT */
/* probes — light probes in spherical harmonics, as JSON. See probes.h. */
#include "bake/probes.h"

#include "host/geom.h"
#include "formats/file_io.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RAYS 26

int pr_parse_grid(const char *text, int dims[3], char *err, size_t errlen)
{
    char tail;
    int k;
    if (!text || sscanf(text, "%d,%d,%d%c", &dims[0], &dims[1], &dims[2], &tail) != 3) {
        snprintf(err, errlen, "probes: '%s' is not NX,NY,NZ", text ? text : "");
        return -1;
    }
    for (k = 0; k < 3; k++)
        if (dims[k] < 1 || dims[k] > PR_MAX_GRID) {
            snprintf(err, errlen, "probes: a grid of %d along an axis is outside 1..%d", dims[k],
                     PR_MAX_GRID);
            return -1;
        }
    if ((long)dims[0] * dims[1] * dims[2] > PR_MAX_PROBES) {
        snprintf(err, errlen, "probes: a grid of %ld probes is above %d",
                 (long)dims[0] * dims[1] * dims[2], PR_MAX_PROBES);
        return -1;
    }
    return 0;
}

double *pr_grid_points(const sc_poly *polys, int n, const int dims[3])
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    size_t count = (size_t)dims[0] * dims[1] * dims[2], m = 0;
    double *pts = malloc(3 * count * sizeof *pts);
    int i, k, a, x, y, z;
    if (!pts) return NULL;
    for (i = 0; i < n; i++)
        for (k = 0; k < polys[i].n; k++)
            for (a = 0; a < 3; a++) {
                lo[a] = fmin(lo[a], polys[i].v[k][a]);
                hi[a] = fmax(hi[a], polys[i].v[k][a]);
            }
    for (z = 0; z < dims[2]; z++)
        for (y = 0; y < dims[1]; y++)
            for (x = 0; x < dims[0]; x++, m++) {
                int c[3] = {x, y, z};
                for (a = 0; a < 3; a++)
                    pts[3 * m + a] = lo[a] + (c[a] + 0.5) * (hi[a] - lo[a]) / dims[a];
            }
    return pts;
}

/* One line's point: 1 a point, 0 nothing (blank, comment), -1 malformed. */
static int parse_line(const char *s, double *p)
{
    char *end;
    int k;
    while (*s == ' ' || *s == '\t' || *s == '\r') s++;
    if (!*s || *s == '#') return 0;
    for (k = 0; k < 3; k++) {
        errno = 0;
        p[k] = strtod(s, &end);
        if (end == s || errno || !isfinite(p[k])) return -1;
        s = end;
    }
    while (*s == ' ' || *s == '\t' || *s == '\r') s++;
    return *s ? -1 : 1;
}

double *pr_read_points(const char *path, int *n, char *err, size_t errlen)
{
    char *data, *line, *next;
    size_t size;
    double *pts = NULL;
    int cap = 0, line_no = 0, rc = 0;
    *n = 0;
    if (fio_read_all(path, FIO_LIMIT_TEXT, &data, &size, err, errlen) != 0) return NULL;
    for (line = data; rc == 0 && line; line = next) {
        double p[3];
        int got;
        next = strchr(line, '\n');
        if (next) *next++ = '\0';
        line_no++;
        if ((got = parse_line(line, p)) < 0) {
            snprintf(err, errlen, "%s:%d: a probe is three numbers, X Y Z", path, line_no);
            rc = -1;
        } else if (got && *n == PR_MAX_PROBES) {
            snprintf(err, errlen, "%s:%d: more than %d probes", path, line_no, PR_MAX_PROBES);
            rc = -1;
        } else if (got) {
            if (*n == cap) {
                double *q = realloc(pts, (size_t)(cap = cap ? 2 * cap : 64) * 3 * sizeof *q);
                if (!q) {
                    snprintf(err, errlen, "%s: out of memory", path);
                    rc = -1;
                    break;
                }
                pts = q;
            }
            memcpy(&pts[3 * (*n)++], p, sizeof p);
        }
    }
    free(data);
    if (rc == 0 && *n == 0) {
        snprintf(err, errlen, "%s: no probes in the file", path);
        rc = -1;
    }
    if (rc != 0) {
        free(pts);
        *n = 0;
        return NULL;
    }
    return pts;
}

/* The 26 directions, turned (see probes.h). */
static void ray_dirs(double d[RAYS][3])
{
    static const double rot[3][3] = {{1, 2, 2}, {2, 1, -2}, {-2, 2, -1}};
    int x, y, z, m = 0, a;
    for (z = -1; z <= 1; z++)
        for (y = -1; y <= 1; y++)
            for (x = -1; x <= 1; x++) {
                double v[3] = {x, y, z};
                if (!x && !y && !z) continue;
                for (a = 0; a < 3; a++) d[m][a] = geom_dot(rot[a], v) / 3.0;
                geom_normalize(d[m++]);
            }
}

static double back_fraction(const void *grid, const sc_poly *polys, const double *p,
                            double d[RAYS][3])
{
    int j, backs = 0;
    for (j = 0; j < RAYS; j++) {
        int back = 0;
        if (geom_grid_ray(grid, polys, p, d[j], HUGE_VAL, &back) < HUGE_VAL && back) backs++;
    }
    return (double)backs / RAYS;
}

int pr_bake(const sc_poly *polys, int npolys, const double *pts, int n, pr_gather_fn fn, void *ctx,
            pr_probe *out, char *err, size_t errlen)
{
    double extent, d[RAYS][3];
    geom_poly *g = geom_polys(polys, npolys, &extent);
    void *grid = g ? geom_grid_new(polys, g, npolys) : NULL;
    int i, rc = 0;
    free(g);
    if (!grid) {
        snprintf(err, errlen, "out of memory for %d probes", n);
        return -1;
    }
    ray_dirs(d);
    for (i = 0; rc == 0 && i < n; i++) {
        memcpy(out[i].p, &pts[3 * i], sizeof out[i].p);
        out[i].back = back_fraction(grid, polys, out[i].p, d);
        out[i].inside = out[i].back > 0.5;
        if (fn(ctx, out[i].p, out[i].sh) != 0) {
            snprintf(err, errlen,
                     "probe %d at (%g, %g, %g) cannot be gathered (outside the scene's frame?)", i,
                     out[i].p[0], out[i].p[1], out[i].p[2]);
            rc = -1;
        }
    }
    geom_grid_free(grid);
    return rc;
}

static void write_probe(FILE *fp, const pr_probe *p, int last)
{
    int k;
    fprintf(fp, "    {\"p\": [%.9g, %.9g, %.9g], \"inside\": %s, \"back\": %.4g, \"sh\": [",
            p->p[0], p->p[1], p->p[2], p->inside ? "true" : "false", p->back);
    for (k = 0; k < 9; k++)
        fprintf(fp, "[%.9g, %.9g, %.9g]%s", p->sh[k][0], p->sh[k][1], p->sh[k][2],
                k < 8 ? ", " : "");
    fprintf(fp, "]}%s\n", last ? "" : ",");
}

int pr_write_json(const char *path, const pr_probe *pr, int n, const int *dims, char *err,
                  size_t errlen)
{
    fio_out *o = fio_out_open(path, err, errlen);
    FILE *fp;
    int i;
    if (!o) return -1;
    fp = fio_out_stream(o);
    fprintf(fp, "{\n  \"format\": \"rad-probes-1\",\n");
    fprintf(fp, "  \"sh_order\": [\"Y00\", \"Y1-1 (y)\", \"Y10 (z)\", \"Y11 (x)\", \"Y2-2 (xy)\", "
                "\"Y2-1 (yz)\", "
                "\"Y20 (3z^2-1)\", \"Y21 (xz)\", \"Y22 (x^2-y^2)\"],\n");
    if (dims)
        fprintf(fp, "  \"grid\": [%d, %d, %d],\n", dims[0], dims[1], dims[2]);
    else
        fprintf(fp, "  \"grid\": null,\n");
    fprintf(fp, "  \"probes\": [\n");
    for (i = 0; i < n; i++) write_probe(fp, &pr[i], i == n - 1);
    fprintf(fp, "  ]\n}\n");
    return fio_out_commit(o, err, errlen);
}
