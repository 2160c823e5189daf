/* SPDX-License-Identifier: MIT */
/* rad — analytic references (see reference.h), written independently of the core. */
#include "reference/reference.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Lambert's sum over P's edges: sum of theta_i unit(R_i x R_i+1), per axis, into S. */
static void lambert_sum(const sc_poly *p, double *s)
{
    int i, k;
    s[0] = s[1] = s[2] = 0;
    for (i = 0; i < p->n; i++) {
        const double *a = p->v[i], *b = p->v[(i + 1) % p->n];
        double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]};
        double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double th = acos((a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb));
        for (k = 0; k < 3; k++) s[k] += th * c[k] / lc;
    }
}

double ref_point_ff(const sc_poly *p)
{
    /* Lambert: F = 1/(2 pi) |sum of theta_i (n . unit(R_i x R_i+1))|, n = +z. */
    double s[3];
    lambert_sum(p, s);
    return fabs(s[2]) / (2 * 3.14159265358979323846);
}

void ref_point_vector(const sc_poly *p, double *phi)
{
    int k;
    lambert_sum(p, phi);
    for (k = 0; k < 3; k++) phi[k] *= 0.5;
    if (phi[2] < 0)
        for (k = 0; k < 3; k++) phi[k] = -phi[k];
}

sc_poly ref_quad(double ax, double ay, double az, double bx, double by, double bz, double cx,
                 double cy, double cz, double dx, double dy, double dz)
{
    sc_poly p;
    memset(&p, 0, sizeof p);
    p.n = 4;
    p.v[0][0] = ax;
    p.v[0][1] = ay;
    p.v[0][2] = az;
    p.v[1][0] = bx;
    p.v[1][1] = by;
    p.v[1][2] = bz;
    p.v[2][0] = cx;
    p.v[2][1] = cy;
    p.v[2][2] = cz;
    p.v[3][0] = dx;
    p.v[3][1] = dy;
    p.v[3][2] = dz;
    return p;
}

int ref_receiver(int k, sc_poly *p)
{
    const double s45 = sqrt(0.5);
    double *a, *b, *c, n[3];
    switch (k) {
    case 0:
        *p = ref_quad(-0.5, -0.5, 1, -0.5, 0.5, 1, 0.5, 0.5, 1, 0.5, -0.5, 1);
        break; /* parallel, centred */
    case 1:
        *p = ref_quad(0.3, -0.2, 1, 0.3, 0.8, 1, 1.3, 0.8, 1, 1.3, -0.2, 1);
        break; /* parallel, offset */
    case 2:
        *p = ref_quad(0.6, -0.5, 0.1, 0.6, 0.5, 0.1, 0.6, 0.5, 1.1, 0.6, -0.5, 1.1);
        break; /* perpendicular */
    case 3:
        *p = ref_quad(-0.5, -0.5, 0.8, -0.5 + s45, -0.5, 0.8 + s45, -0.5 + s45, 0.5, 0.8 + s45,
                      -0.5, 0.5, 0.8);
        break; /* tilted 45 deg */
    case 4:
        *p = ref_quad(-1, -1, 0.5, -1, 1, 0.5, 1, 1, 0.5, 1, -1, 0.5);
        break; /* large, all faces */
    case 5:
        *p = ref_quad(1.5, -1, 0.02, 1.5, 1, 0.02, 1.5, 1, 0.6, 1.5, -1, 0.6);
        break; /* grazing */
    case 6:    /* tilted triangle */
        *p = ref_quad(-0.4, 0.2, 0.7, 0.6, -0.3, 1.0, 0.1, 0.7, 1.2, 0, 0, 0);
        p->n = 3;
        break;
    default: return 0;
    }
    /* Face the origin: reverse the winding if the normal points away. */
    a = p->v[0];
    b = p->v[1];
    c = p->v[2];
    n[0] = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]);
    n[1] = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]);
    n[2] = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (n[0] * a[0] + n[1] * a[1] + n[2] * a[2] > 0) {
        sc_poly r = *p;
        int i;
        for (i = 0; i < p->n; i++) memcpy(r.v[i], p->v[p->n - 1 - i], sizeof r.v[i]);
        *p = r;
    }
    p->tag = 1;
    return 1;
}

double ref_hemicube_ff(int k, int res, int twin, double *want)
{
    sc_poly p[2];
    sc_opts o = {0};
    sc_stats stt;
    char err[256];
    double sum = 0, *ff = NULL;
    int e;
    memset(p, 0, sizeof p);
    /* A shooter small enough to be a point, at the origin facing +z. */
    p[0] = ref_quad(-0.005, -0.005, 0, 0.005, -0.005, 0, 0.005, 0.005, 0, -0.005, 0.005, 0);
    if (!ref_receiver(k, &p[1])) return -1;
    *want = ref_point_ff(&p[1]);
    o.res = res;
    if (twin) {
        scf_solver *s = scf_create(p, 2, &o, NULL, NULL, err, sizeof err);
        if (!s) return -1;
        scf_get_stats(s, &stt);
        ff = calloc((size_t)stt.elements, sizeof *ff);
        if (ff && scf_form_factors(s, 0, ff) == 0)
            for (e = 0; e < stt.elements; e++)
                if (scf_element_tag(s, e) == 1) sum += ff[e];
        scf_destroy(s);
    } else {
        sc_solver *s = sc_create(p, 2, &o, NULL, NULL, err, sizeof err);
        if (!s) return -1;
        sc_get_stats(s, &stt);
        ff = calloc((size_t)stt.elements, sizeof *ff);
        if (ff && sc_form_factors(s, 0, ff) == 0)
            for (e = 0; e < stt.elements; e++)
                if (sc_element_tag(s, e) == 1) sum += ff[e];
        sc_destroy(s);
    }
    if (!ff) return -1;
    free(ff);
    return sum;
}

int ref_rgb_diff(const double *x, const double *ref, int n, double *worst, double *rms)
{
    double top = 0, s2 = 0;
    int i, m = 0;
    for (i = 0; i < 3 * n; i++)
        if (ref[i] > top) top = ref[i];
    *worst = 0;
    for (i = 0; i < 3 * n; i++) {
        double d;
        if (ref[i] < 0.01 * top) continue;
        d = fabs(x[i] / ref[i] - 1);
        if (d > *worst) *worst = d;
        s2 += d * d;
        m++;
    }
    *rms = m ? sqrt(s2 / m) : 0;
    return m;
}

/* The displayed radiosities of the N elements of FX, or of the twin FL when FX is NULL. */
static double *rgb_of(sc_solver *fx, scf_solver *fl, int n)
{
    double *v = malloc((size_t)(n > 0 ? n : 1) * 3 * sizeof *v);
    int e;
    if (!v) return NULL;
    for (e = 0; e < n; e++) {
        if (fx)
            sc_element_rgb(fx, e, 1, v + 3 * e);
        else
            scf_element_rgb(fl, e, 1, v + 3 * e);
    }
    return v;
}

/* X against the fixed solver RFX, or the twin RFL when RFX is NULL. */
static int diff_of(sc_solver *x, sc_solver *rfx, scf_solver *rfl, double *worst, double *rms)
{
    sc_stats st;
    double *a, *b;
    int m = -1;
    sc_get_stats(x, &st);
    a = rgb_of(x, NULL, st.elements);
    b = rgb_of(rfx, rfl, st.elements);
    if (a && b) m = ref_rgb_diff(a, b, st.elements, worst, rms);
    free(a);
    free(b);
    return m;
}

int ref_twin_diff(sc_solver *fx, scf_solver *fl, double *worst, double *rms)
{
    return diff_of(fx, NULL, fl, worst, rms);
}

int ref_solution_diff(sc_solver *x, sc_solver *ref, double *worst, double *rms)
{
    return diff_of(x, ref, NULL, worst, rms);
}
