/* SPDX-License-Identifier: MIT */
/* rad host glue (see scene.h): relighting: new reflectances, emissions and light intensities; kept solutions mixed. Compiled once per build of the core. */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "host/scene_impl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int sc_set_surfaces(sc_solver *h, sc_tag_match_fn match, void *ctx, const double *rho,
                    const double *emit, char *err, size_t errlen)
{
    rad_rgb_t r;
    uint32_t i;
    int n = 0, k, rc;
    for (k = 0; k < 3; k++)
        if ((rho && !(rho[k] >= 0 && rho[k] <= 1e30)) ||
            (emit && !(emit[k] >= 0 && emit[k] <= 1e30))) {
            snprintf(err, errlen, "reflectance and emission must be finite and >= 0");
            return -1;
        }
    if (rho) {
        r.r = sc__rho_ch(h, rho[0]);
        r.g = sc__rho_ch(h, rho[1]);
        r.b = sc__rho_ch(h, rho[2]);
    }
    for (i = 0; emit && (emit[0] > 0 || emit[1] > 0 || emit[2] > 0) && i < h->s.n_surfaces; i++)
        if ((h->tiny[i] & 2) && match(ctx, h->tags[i])) {
            snprintf(err, errlen,
                     "surface %u (tag %d) is one of a group of faces below the core's precision, "
                     "shot together, which cannot emit",
                     i, h->tags[i]);
            return -1;
        }
    for (i = 0; i < h->s.n_surfaces; i++) {
        if (!match(ctx, h->tags[i])) continue;
        if (rho && (rc = rad_set_surface(&h->s, i, &r, NULL)) < 0) {
            snprintf(err, errlen, "surface %u: %s", i, rad_strerror(rc));
            return -1;
        }
        if (emit) memcpy(&h->emit[3 * i], emit, 3 * sizeof *emit);
        n++;
    }
    sc_restart(h);
    return n;
}

/* Emissions to the core at a scale that maps the brightest to CORE_EMIT_PEAK, as at
 * create: a relit scene (or one light group alone) keeps the core's full precision
 * however dim it is. Results map back through the same scale. */
void sc_restart(sc_solver *h)
{
    double peak = 0;
    uint32_t i;
    int k;
    free(h->soft_base); /* sc_solve_lights's, of the solution before */
    h->soft_base = NULL;
    for (i = 0; i < 3u * h->s.n_surfaces; i++)
        if (h->emit[i] > peak) peak = h->emit[i];
    for (k = 0; k < h->nlights; k++) peak = fmax(peak, sc__light_peak(h, &h->src[k]));
    if (peak > 0) {
        h->epeak = peak;
        h->escale = CORE_EMIT_PEAK / peak;
    }
    for (i = 0; i < h->s.n_surfaces; i++) {
        rad_rgb_t e;
        e.r = sc__emit_ch(h, h->emit[3 * i]);
        e.g = sc__emit_ch(h, h->emit[3 * i + 1]);
        e.b = sc__emit_ch(h, h->emit[3 * i + 2]);
        rad_set_surface(&h->s, i, NULL, &e); /* in range by construction */
    }
    rad_restart(&h->s);
    for (k = 0; k < h->nlights; k++) { /* after the restart: always taken */
        rad_light_t c;
        sc__light_to_core(h, &h->src[k], h->light_res, &c);
        rad_set_light(&h->s, (uint32_t)k, &c); /* in range by construction */
    }
    h->mixed = 0;
}

int sc_set_light(sc_solver *h, int i, const double *rgb, const double *horizon, char *err,
                 size_t errlen)
{
    int k;
    if (i < 0 || i >= h->nlights) {
        snprintf(err, errlen, "no light %d (the scene has %d)", i + 1, h->nlights);
        return -1;
    }
    for (k = 0; k < 3; k++)
        if ((rgb && !(rgb[k] >= 0 && rgb[k] <= 1e30)) ||
            (horizon && !(horizon[k] >= 0 && horizon[k] <= 1e30))) {
            snprintf(err, errlen, "light %d: intensities must be finite and >= 0", i + 1);
            return -1;
        }
    if (rgb) memcpy(h->src[i].rgb, rgb, sizeof h->src[i].rgb);
    if (horizon) memcpy(h->src[i].horizon, horizon, sizeof h->src[i].horizon);
    sc_restart(h);
    return 0;
}

struct sc_solution {
    uint32_t n;
    double escale;    /* the scale its radiosities are in */
    sc_light *lights; /* the lights it was solved with (caller units), h->nlights */
    rad_rgb_t rgb[1]; /* n entries, core units */
};

sc_solution *sc_keep(sc_solver *h, int ambient)
{
    uint32_t n = h->s.n_elements;
    struct sc_solution *k = malloc(sizeof *k + (n ? n - 1u : 0u) * sizeof k->rgb[0]);
    if (!k) return NULL;
    k->lights = NULL;
    if (h->nlights) {
        if (!(k->lights = malloc((size_t)h->nlights * sizeof *k->lights))) {
            free(k);
            return NULL;
        }
        memcpy(k->lights, h->src, (size_t)h->nlights * sizeof *k->lights);
    }
    k->n = n;
    k->escale = h->escale;
    rad_shade_elements(&h->s, sc__shade_flags(h, ambient), k->rgb, n);
    return k;
}

void sc_solution_free(sc_solution *k)
{
    if (k) free(k->lights);
    free(k);
}

/* The lights as the mix has them, for gathers (which add their direct light): light
 * I's intensities the groups' sum of INTENSITY[g] times theirs, in the core at the
 * mix's scale. The core's copy alone: the next solve restarts from h->src. */
static void mix_lights(sc_solver *h, sc_solution *const *groups, const double (*intensity)[3],
                       int n)
{
    int i, g, c;
    for (i = 0; i < h->nlights; i++) {
        sc_light l = h->src[i];
        for (c = 0; c < 3; c++) {
            l.rgb[c] = l.horizon[c] = 0;
            for (g = 0; g < n; g++) {
                l.rgb[c] += intensity[g][c] * groups[g]->lights[i].rgb[c];
                l.horizon[c] += intensity[g][c] * groups[g]->lights[i].horizon[c];
            }
        }
        sc__light_to_core(h, &l, h->light_res, &h->lights[i]);
    }
}

int sc_mix(sc_solver *h, sc_solution *const *groups, const double (*intensity)[3], int n, char *err,
           size_t errlen)
{
    uint32_t ne = h->s.n_elements, e;
    double *out = malloc((ne ? ne : 1u) * 3u * sizeof *out), top = 0, scale, shift;
    int i, c;
    if (!out) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (i = 0; i < n; i++) {
        for (c = 0; c < 3; c++)
            if (!(intensity[i][c] >= 0 && intensity[i][c] <= 1e30)) {
                snprintf(err, errlen, "intensity %g is not a finite number >= 0", intensity[i][c]);
                free(out);
                return -1;
            }
        if (!groups[i] || groups[i]->n != ne) {
            snprintf(err, errlen, "a solution of another scene");
            free(out);
            return -1;
        }
    }
    /* In double, in caller units: each solution has its own scale (its brightest
     * emitter at the core's peak), and no intensity is rounded to Q16.16. */
    for (e = 0; e < ne; e++) {
        double v[3] = {0, 0, 0};
        for (i = 0; i < n; i++) {
            const rad_rgb_t *g = &groups[i]->rgb[e];
            v[0] += intensity[i][0] * RAD_TO_DOUBLE(g->r) / groups[i]->escale;
            v[1] += intensity[i][1] * RAD_TO_DOUBLE(g->g) / groups[i]->escale;
            v[2] += intensity[i][2] * RAD_TO_DOUBLE(g->b) / groups[i]->escale;
        }
        for (c = 0; c < 3; c++) {
            out[3 * e + c] = v[c];
            if (v[c] > top) top = v[c];
        }
    }
    /* Back into the core (it shades and renders) at the scale the scene was built with,
     * or lower if the mix is brighter than the core's radiosity range takes. The
     * elements' radiosities are in the core's scale, the caller's times 2^power_shift
     * (the last solve's: 0 when an emission is the brightest, more when a light's
     * irradiance on the surfaces, rad.h: Scale, is the core's peak). */
    shift = ldexp(1.0, h->s.power_shift);
    scale = h->escale0;
    if (!isfinite(scale) || top * scale * shift > 16384.0)
        scale = top > 0 ? 16384.0 / (top * shift) : 1.0;
    h->escale = scale;
    for (e = 0; e < ne; e++) {
        rad_rgb_t *b = &h->pools.elements[e].radiosity;
        b->r = RAD_REAL(out[3 * e] * scale * shift);
        b->g = RAD_REAL(out[3 * e + 1] * scale * shift);
        b->b = RAD_REAL(out[3 * e + 2] * scale * shift);
    }
    /* rad_element_t.radiosity is the caller's pools' memory, which the glue owns; the
     * core's emissions still stand at the last solve's scale: solving again restarts. */
    mix_lights(h, groups, intensity, n);
    h->mixed = 1;
    free(out);
    return 0;
}
