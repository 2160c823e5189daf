/* rad host glue (see scene.h): compiled once per build of the core. */
#include "scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rad/rad.h"

#if RAD_FLOAT
#define SC(x) scf_##x
#else
#define SC(x) sc_##x
#endif

#define CORE_HALF_EXTENT 32.0   /* scene scaled into +-32: half the core's range */
#define CORE_EMIT_PEAK 256.0    /* brightest emission channel, well inside 4096 */
#define RHO_MAX (65535.0 / 65536.0)

struct SC(solver) {
    rad_scene_t s;
    rad_pools_t pools;
    int *tags;                  /* per surface */
    double scale, off[3], escale;
    int skipped, split, clamped;
};

typedef struct {
    sc_warn_fn warn;
    void *ctx;
    int seen, emitted;          /* warnings met in this attempt, already reported */
} warner_t;

static void warnf(warner_t *w, int tag, const char *msg, int code)
{
    char buf[160];
    if (w->seen++ < w->emitted || !w->warn) return;
    snprintf(buf, sizeof buf, "%s (%s)", msg, rad_strerror(code));
    w->warn(w->ctx, tag, buf);
    w->emitted++;
}

static void free_pools(struct SC(solver) *h)
{
    free(h->pools.surfaces); free(h->pools.patches); free(h->pools.elements);
    free(h->pools.vertices); free(h->pools.work); free(h->tags);
    memset(&h->pools, 0, sizeof h->pools);
    h->tags = NULL;
}

static int alloc_pools(struct SC(solver) *h, long elements, int npolys, const rad_config_t *cfg)
{
    uint32_t nacc;
    rad_pools_t *p = &h->pools;
    size_t pixels;
    p->max_surfaces = (uint32_t)(2 * npolys + 1);
    p->max_elements = (uint32_t)elements;
    p->max_patches = (uint32_t)elements;
    p->max_vertices = (uint32_t)(3 * elements);
    nacc = p->max_vertices;
    pixels = cfg->band_rows ? (size_t)cfg->res * cfg->band_rows : RAD_PIXELS_ALL(cfg->res);
    p->work_bytes = RAD_WORK_BYTES(cfg->res, pixels, nacc);
    p->surfaces = calloc(p->max_surfaces, sizeof *p->surfaces);
    p->patches = calloc(p->max_patches, sizeof *p->patches);
    p->elements = calloc(p->max_elements, sizeof *p->elements);
    p->vertices = calloc(p->max_vertices, sizeof *p->vertices);
    p->work = malloc(p->work_bytes);
    h->tags = calloc(p->max_surfaces, sizeof *h->tags);
    return p->surfaces && p->patches && p->elements && p->vertices && p->work && h->tags;
}

static rad_real_t emit_ch(struct SC(solver) *h, double e)
{
    double v = e * h->escale;
    return RAD_REAL(v > 4096.0 ? 4096.0 : v);
}

static rad_real_t rho_ch(struct SC(solver) *h, double r)
{
    if (r >= 1.0) { h->clamped++; r = RHO_MAX; }
    return RAD_REAL(r);
}

static void to_core(const struct SC(solver) *h, const double *p, rad_vec3_t *v)
{
    v->x = RAD_REAL((p[0] - h->off[0]) * h->scale);
    v->y = RAD_REAL((p[1] - h->off[1]) * h->scale);
    v->z = RAD_REAL((p[2] - h->off[2]) * h->scale);
}

/* Adds one polygon; a quad the core refuses as non-planar is split in two. Returns
 * RAD_OK, RAD_ERR_FULL (grow and retry) or another error (fatal). */
static int add_poly(struct SC(solver) *h, const sc_poly *q, warner_t *w)
{
    rad_vec3_t v[4];
    rad_rgb_t rho, em;
    int i, rc;
    for (i = 0; i < q->n; i++) to_core(h, q->v[i], &v[i]);
    rho.r = rho_ch(h, q->rho[0]); rho.g = rho_ch(h, q->rho[1]); rho.b = rho_ch(h, q->rho[2]);
    em.r = emit_ch(h, q->emit[0]); em.g = emit_ch(h, q->emit[1]); em.b = emit_ch(h, q->emit[2]);
    rc = rad_add_polygon(&h->s, v, (unsigned)q->n, &rho, &em);
    if (rc >= 0) { h->tags[rc] = q->tag; return RAD_OK; }
    if (q->n == 4 && (rc == RAD_ERR_NONPLANAR || rc == RAD_ERR_DEGENERATE)) {
        rad_vec3_t t[3];
        int k;
        h->split++;
        for (k = 0; k < 2; k++) {
            t[0] = v[0]; t[1] = v[1 + k]; t[2] = v[2 + k];
            rc = rad_add_polygon(&h->s, t, 3, &rho, &em);
            if (rc >= 0) h->tags[rc] = q->tag;
            else if (rc == RAD_ERR_DEGENERATE) { h->skipped++; warnf(w, q->tag, "skipped a degenerate triangle of a split quad", rc); }
            else return rc;
        }
        return RAD_OK;
    }
    if (rc == RAD_ERR_DEGENERATE) {
        h->skipped++;
        warnf(w, q->tag, "skipped a degenerate polygon", rc);
        return RAD_OK;
    }
    return rc;
}

static int frame_scene(struct SC(solver) *h, const sc_poly *polys, int n, char *err, size_t errlen)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double half = 0.0, emax = 0.0;
    int i, k, a;
    for (i = 0; i < n; i++) {
        if (polys[i].n != 3 && polys[i].n != 4) {
            snprintf(err, errlen, "polygon %d has %d vertices (the core takes 3 or 4)", i, polys[i].n);
            return -1;
        }
        for (k = 0; k < polys[i].n; k++)
            for (a = 0; a < 3; a++) {
                double c = polys[i].v[k][a];
                if (!isfinite(c) || fabs(c) > 1e30) {
                    snprintf(err, errlen, "polygon %d has a coordinate that is not a finite number", i);
                    return -1;
                }
                if (c < lo[a]) lo[a] = c;
                if (c > hi[a]) hi[a] = c;
            }
        for (a = 0; a < 3; a++) {
            double e = polys[i].emit[a], r = polys[i].rho[a];
            if (!isfinite(e) || e < 0 || !isfinite(r) || r < 0) {
                snprintf(err, errlen, "polygon %d has a negative or non-finite reflectance or emission", i);
                return -1;
            }
            if (e > emax) emax = e;
        }
    }
    for (a = 0; a < 3; a++) {
        h->off[a] = 0.5 * (lo[a] + hi[a]);
        if (0.5 * (hi[a] - lo[a]) > half) half = 0.5 * (hi[a] - lo[a]);
    }
    if (!(half > 0.0) || !isfinite(half)) {
        snprintf(err, errlen, "the scene has no extent");
        return -1;
    }
    h->scale = CORE_HALF_EXTENT / half;
    h->escale = emax > 0.0 ? CORE_EMIT_PEAK / emax : 1.0;
    return 0;
}

/* A generous estimate of the elements the core will make (it grows if short). */
static long estimate_elements(const struct SC(solver) *h, const sc_poly *polys, int n, double me)
{
    double sum = 0.0;
    int i;
    for (i = 0; i < n; i++) {
        double l = 0.0;
        int k, a;
        for (k = 0; k < polys[i].n; k++) {
            double d = 0.0;
            for (a = 0; a < 3; a++) {
                double x = (polys[i].v[(k + 1) % polys[i].n][a] - polys[i].v[k][a]) * h->scale;
                d += x * x;
            }
            if (sqrt(d) > l) l = sqrt(d);
        }
        sum += 2.0 * (ceil(l / me) + 1.0) * (ceil(l / me) + 1.0);
    }
    return (long)(sum > 1024.0 ? sum : 1024.0);
}

SC(solver) *SC(create)(const sc_poly *polys, int n, const sc_opts *o, sc_warn_fn warn, void *ctx,
                       char *err, size_t errlen)
{
    static const sc_opts defaults = {0, 0, 0, 0, 0};
    struct SC(solver) *h = calloc(1, sizeof *h);
    rad_config_t cfg;
    long cap, limit;
    warner_t w;
    if (!o) o = &defaults;
    if (!h) { snprintf(err, errlen, "out of memory"); return NULL; }
    if (n <= 0) { snprintf(err, errlen, "the scene has no polygons"); free(h); return NULL; }
    if (frame_scene(h, polys, n, err, errlen) < 0) { free(h); return NULL; }
    memset(&cfg, 0, sizeof cfg);
    {
        double me = o->max_element > 0 ? o->max_element * h->scale : 2.0 * CORE_HALF_EXTENT / 24.0;
        double mp = o->max_patch > 0 ? o->max_patch * h->scale : 4.0 * me;
        if (me < 1.0 / 16.0 || me > 128.0 || mp < me || mp > 256.0) {
            snprintf(err, errlen, "element size %g / patch size %g out of range for this scene (element >= %g, patch >= element)",
                     me / h->scale, mp / h->scale, 1.0 / 16.0 / h->scale);
            free(h);
            return NULL;
        }
        cfg.max_element = RAD_REAL(me);
        cfg.max_patch = RAD_REAL(mp);
        cfg.res = (uint16_t)(o->res ? o->res : 64);
        cfg.band_rows = (uint16_t)o->band_rows;
        cap = estimate_elements(h, polys, n, me);
    }
    limit = o->max_elements > 0 ? o->max_elements : 4000000L;
    w.warn = warn; w.ctx = ctx; w.emitted = 0;
    for (;;) {
        int i, rc = RAD_OK;
        if (cap > limit) cap = limit;
        if (!alloc_pools(h, cap, n, &cfg)) { snprintf(err, errlen, "out of memory for %ld elements", cap); break; }
        rc = rad_init(&h->s, &h->pools, &cfg);
        if (rc < 0) { snprintf(err, errlen, "cannot set up the solver: %s", rad_strerror(rc)); break; }
        h->skipped = h->split = h->clamped = 0;
        w.seen = 0;
        for (i = 0; i < n && rc == RAD_OK; i++) rc = add_poly(h, &polys[i], &w);
        if (rc == RAD_OK) {
            if (h->s.n_elements == 0) { snprintf(err, errlen, "no polygon could be meshed"); break; }
            return h;
        }
        if (rc != RAD_ERR_FULL) {
            snprintf(err, errlen, "polygon %d (tag %d): %s", i - 1, polys[i - 1].tag, rad_strerror(rc));
            break;
        }
        free_pools(h);
        if (cap >= limit) {
            snprintf(err, errlen, "the scene needs more than %ld elements: raise the element size", limit);
            SC(destroy)(h);
            return NULL;
        }
        cap *= 2;
    }
    SC(destroy)(h);
    return NULL;
}

void SC(destroy)(SC(solver) *h)
{
    if (!h) return;
    free_pools(h);
    free(h);
}

int SC(solve)(SC(solver) *h, int max_shots, double tol, sc_progress_fn progress, void *ctx)
{
    int done = 0;
    rad_real_t t = RAD_REAL(tol);
    while (done < max_shots) {
        int k = rad_shoot(&h->s, progress ? 1u : (uint32_t)(max_shots - done), t);
        if (k <= 0) break;
        done += k;
        if (progress && progress(ctx, done, RAD_TO_DOUBLE(rad_unshot_fraction(&h->s)))) break;
    }
    return done;
}

void SC(get_stats)(SC(solver) *h, sc_stats *st)
{
    const rad_pools_t *p = &h->pools;
    memset(st, 0, sizeof *st);
    st->surfaces = (int)h->s.n_surfaces;
    st->patches = (int)h->s.n_patches;
    st->elements = (int)h->s.n_elements;
    st->vertices = (int)h->s.n_vertices;
    st->skipped = h->skipped;
    st->split = h->split;
    st->clamped = h->clamped;
    st->shots = (int)h->s.stats.shots;
    st->unshot = RAD_TO_DOUBLE(rad_unshot_fraction(&h->s));
    st->saturations = h->s.stats.saturations;
    st->raster_calls = h->s.stats.raster_calls;
    st->raster_pixels = h->s.stats.raster_pixels;
    st->pool_bytes = h->s.n_surfaces * sizeof *p->surfaces + h->s.n_patches * sizeof *p->patches +
                     h->s.n_elements * sizeof *p->elements + h->s.n_vertices * sizeof *p->vertices;
    st->work_bytes = RAD_WORK_BYTES(h->s.cfg.res, h->s.pass_pixels,
                                    h->s.n_elements > h->s.n_vertices ? h->s.n_elements : h->s.n_vertices);
}

static void rgb_out(const struct SC(solver) *h, const rad_rgb_t *c, double *o)
{
    o[0] = RAD_TO_DOUBLE(c->r) / h->escale;
    o[1] = RAD_TO_DOUBLE(c->g) / h->escale;
    o[2] = RAD_TO_DOUBLE(c->b) / h->escale;
}

void SC(element_rgb)(SC(solver) *h, int e, int ambient, double rgb[3])
{
    rad_rgb_t c = {0, 0, 0};
    rad_element_radiosity(&h->s, (uint32_t)e, ambient ? RAD_SHADE_AMBIENT : 0, &c);
    rgb_out(h, &c, rgb);
}

double SC(element_area)(SC(solver) *h, int e)
{
    return RAD_TO_DOUBLE(h->pools.elements[e].area) / (h->scale * h->scale);
}

void SC(vertex_pos)(SC(solver) *h, int v, double p[3])
{
    const rad_vec3_t *c = &h->pools.vertices[v];
    p[0] = RAD_TO_DOUBLE(c->x) / h->scale + h->off[0];
    p[1] = RAD_TO_DOUBLE(c->y) / h->scale + h->off[1];
    p[2] = RAD_TO_DOUBLE(c->z) / h->scale + h->off[2];
}

int SC(element_vertices)(SC(solver) *h, int e, int v[4])
{
    const rad_element_t *el = &h->pools.elements[e];
    int k, n = el->v[3] == RAD_INDEX_NONE ? 3 : 4;
    for (k = 0; k < n; k++) v[k] = (int)el->v[k];
    return n;
}

void SC(element_centroid)(SC(solver) *h, int e, double c[3])
{
    int v[4], n = SC(element_vertices)(h, e, v), k, a;
    c[0] = c[1] = c[2] = 0.0;
    for (k = 0; k < n; k++) {
        double p[3];
        SC(vertex_pos)(h, v[k], p);
        for (a = 0; a < 3; a++) c[a] += p[a] / n;
    }
}

int SC(element_tag)(SC(solver) *h, int e)
{
    return h->tags[h->pools.elements[e].surface];
}

static rad_rgb_t *shade_core(struct SC(solver) *h, int ambient)
{
    rad_rgb_t *v = malloc((h->s.n_vertices ? h->s.n_vertices : 1) * sizeof *v);
    if (v) rad_shade_vertices(&h->s, ambient ? RAD_SHADE_AMBIENT : 0, v, h->s.n_vertices);
    return v;
}

int SC(shade)(SC(solver) *h, int ambient, double *rgb)
{
    rad_rgb_t *v = shade_core(h, ambient);
    uint32_t i;
    if (!v) return -1;
    for (i = 0; i < h->s.n_vertices; i++) rgb_out(h, &v[i], &rgb[3 * i]);
    free(v);
    return 0;
}

int SC(render)(SC(solver) *h, const sc_camera *cam, int ambient, int w, int hgt, float *rgb,
               char *err, size_t errlen)
{
    rad_camera_t c;
    rad_rgb_t *v = shade_core(h, ambient), *fb = malloc((size_t)w * hgt * sizeof *fb);
    uint32_t *z = malloc((size_t)w * hgt * sizeof *z);
    int rc = -1;
    if (v && fb && z) {
        size_t i;
        to_core(h, cam->eye, &c.eye);
        to_core(h, cam->target, &c.target);
        c.up.x = RAD_REAL(cam->up[0]); c.up.y = RAD_REAL(cam->up[1]); c.up.z = RAD_REAL(cam->up[2]);
        c.tan_half_fov = RAD_REAL(tan(cam->fov_deg * 0.5 * 3.14159265358979323846 / 180.0));
        rc = rad_render(&h->s, v, &c, fb, z, (unsigned)w, (unsigned)hgt);
        if (rc < 0) snprintf(err, errlen, "cannot render this view: %s (camera too far, degenerate, or image too large)", rad_strerror(rc));
        for (i = 0; rc >= 0 && i < (size_t)w * hgt; i++) {
            double o[3];
            rgb_out(h, &fb[i], o);
            rgb[3 * i] = (float)o[0]; rgb[3 * i + 1] = (float)o[1]; rgb[3 * i + 2] = (float)o[2];
        }
    } else {
        snprintf(err, errlen, "out of memory for a %dx%d image", w, hgt);
    }
    free(v); free(fb); free(z);
    return rc < 0 ? -1 : 0;
}

int SC(form_factors)(SC(solver) *h, int p, double *ff)
{
    rad_ff_t *f = malloc((h->s.n_elements ? h->s.n_elements : 1) * sizeof *f);
    int rc, e;
    if (!f) return -1;
    rc = rad_form_factors(&h->s, (uint32_t)p, f);
    for (e = 0; rc >= 0 && e < rc; e++) ff[e] = RAD_FF_TO_DOUBLE(f[e]);
    free(f);
    return rc < 0 ? -1 : 0;
}

uint64_t SC(checksum)(SC(solver) *h)
{
    uint64_t x = 1469598103934665603ull;
    uint32_t e;
    for (e = 0; e < h->s.n_elements; e++) {
        const rad_rgb_t *c = &h->pools.elements[e].radiosity;
        unsigned char b[sizeof *c];
        size_t k;
        memcpy(b, c, sizeof b);
        for (k = 0; k < sizeof b; k++) { x ^= b[k]; x *= 1099511628211ull; }
    }
    return x;
}

void *SC(core)(SC(solver) *h) { return &h->s; }
