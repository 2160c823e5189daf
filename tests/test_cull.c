/* SPDX-License-Identifier: MIT */
/* Culled gathers (lib/cull.c) in both builds: through the hierarchy a gather draws the
 * same pixels as drawing every surface, bit for bit (its E, its probe's nine values,
 * and the last face's depth and item buffers), on seven scenes: a Cornell box, a box
 * of boxes, coplanar overlapping quads (ties of equal depth), gather points on a
 * surface, one surface alone, a grid of rooms, and a field of slivers under a pixel
 * (boxes tested pixel by pixel, ties among them). The buffer sizes are exact, and bad buffers are refused.
 * Shots through the hierarchy (rad_shoot_cull) leave the same solution, bit for bit,
 * shot by shot or in batches, and the same form factors (rad_form_factors).
 *
 * This file is compiled twice (Makefile: tests/float/test_cull.o): with RAD_FLOAT=1
 * it defines the *_float functions, without it the *_fixed ones and the tests. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "check.h"
#include "rad/rad.h"
#if RAD_FLOAT
#include "host/float_names.h" /* sc_ names for the twin's scf_ (host_gathers) */
#endif
#include "host/scene.h"

#if RAD_FLOAT
#define TW(name) name##_float
#else
#define TW(name) name##_fixed
#endif

/* What one scene's comparisons found. */
typedef struct {
    long gathers, probes;   /* compared */
    long differ;            /* gathers or probes whose values or buffers differ */
    long first;             /* the first that differs (-1: none) */
    unsigned long calls[2]; /* raster calls: every surface drawn, culled */
    unsigned surfaces;
} cres;

/* Sizes and errors: what each call returned. */
typedef struct {
    int built, short_build, misaligned, early, short_work, exact_work, odd_work, other_scene;
    int guard_ok;
    unsigned surfaces;
} csizes;

/* What solving a scene with and without the hierarchy found. */
typedef struct {
    long shots[2];          /* shots done: drawing all, culled */
    long differ;            /* elements or patches whose values differ at the end */
    long ff_differ;         /* form factors (rad_form_factors) that differ */
    long waits;             /* culled solve's shots drawn in full after a cube that did not pay */
    unsigned long calls[2]; /* raster calls: every surface drawn, culled */
    unsigned surfaces, elements;
} sres;

#define DECLARE(B)                                          \
    int scene_cull_##B(int scene, int res, cres *r);        \
    int shots_cull_##B(int scene, unsigned batch, sres *r); \
    int sizes_cull_##B(csizes *z);                          \
    int host_gathers_##B(const sc_poly *p, int n, long *failed, long *differ)
DECLARE(fixed);
DECLARE(float);
#undef DECLARE

enum { CORNELL, BOXES, COPLANAR, ON_SURFACE, ONE, ROOMS, FIELD, NSCENES };

#define NS   5400
#define NP   6000
#define NE   24000
#define NV   48000
#define RMAX 64

typedef struct {
    rad_surface_t surf[NS];
    rad_patch_t patch[NP];
    rad_element_t elem[NE];
    rad_vec3_t vert[NV];
    unsigned char work[RAD_WORK_BYTES(32, RAD_PIXELS_ALL(32), NV)];
    unsigned char gwork[2][RAD_GATHER_SH_BYTES(RMAX)];
    unsigned char cwork[RAD_GATHER_CULL_BYTES(RMAX, NS) + 16];
    uint32_t cull[(RAD_CULL_BYTES(NS) + 16) / 4];
    rad_scene_t s;
} world_t;

static rad_vec3_t vec(double x, double y, double z)
{
    rad_vec3_t v;
    v.x = RAD_REAL(x);
    v.y = RAD_REAL(y);
    v.z = RAD_REAL(z);
    return v;
}

static world_t *world_new(double element)
{
    world_t *w = calloc(1, sizeof *w);
    rad_pools_t p;
    rad_config_t c;
    if (!w) return NULL;
    p.surfaces = w->surf;
    p.max_surfaces = NS;
    p.patches = w->patch;
    p.max_patches = NP;
    p.elements = w->elem;
    p.max_elements = NE;
    p.vertices = w->vert;
    p.max_vertices = NV;
    p.work = w->work;
    p.work_bytes = sizeof w->work;
    memset(&c, 0, sizeof c);
    c.max_patch = RAD_REAL(2 * element);
    c.max_element = RAD_REAL(element);
    c.res = 32;
    if (rad_init(&w->s, &p, &c) != RAD_OK) {
        free(w);
        return NULL;
    }
    return w;
}

/* A quad with corners P + U, P + U + V, ... counter-clockwise seen from the side its
 * normal U x V points to: corners P, P + U, P + U + V, P + V. */
static int quad(world_t *w, const double *p, const double *u, const double *v, double rho,
                double emit)
{
    rad_vec3_t c[4];
    rad_rgb_t r, e;
    r.r = RAD_REAL(rho);
    r.g = RAD_REAL(rho * 0.8);
    r.b = RAD_REAL(rho * 0.6);
    e.r = e.g = e.b = RAD_REAL(emit);
    c[0] = vec(p[0], p[1], p[2]);
    c[1] = vec(p[0] + u[0], p[1] + u[1], p[2] + u[2]);
    c[2] = vec(p[0] + u[0] + v[0], p[1] + u[1] + v[1], p[2] + u[2] + v[2]);
    c[3] = vec(p[0] + v[0], p[1] + v[1], p[2] + v[2]);
    return rad_add_polygon(&w->s, c, 4, &r, emit > 0 ? &e : NULL) < 0 ? -1 : 0;
}

/* The six faces of the box at P with edges E, facing out (IN: facing in). */
static int box(world_t *w, const double *p, const double *e, int in, double rho)
{
    int a, k;
    for (a = 0; a < 3; a++)
        for (k = 0; k < 2; k++) {
            double o[3] = {p[0], p[1], p[2]}, u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
            int b = (a + 1) % 3, c = (a + 2) % 3, flip = (k == 0) != (in != 0);
            o[a] += k * e[a];
            u[flip ? c : b] = e[flip ? c : b];
            v[flip ? b : c] = e[flip ? b : c];
            if (quad(w, o, u, v, rho, 0) < 0) return -1;
        }
    return 0;
}

/* The Cornell box: a room 0..10, a light under the ceiling, two blocks turned. */
static int cornell(world_t *w)
{
    static const double room[3] = {0, 0, 0}, size[3] = {10, 10, 10};
    static const double lp[3] = {4, 4, 9.9}, lu[3] = {2, 0, 0}, lv[3] = {0, -2, 0};
    double blk[2][3] = {{2.5, 2.5, 0}, {6, 5.5, 0}}, h[2] = {3, 6};
    int b, s;
    if (box(w, room, size, 1, 0.6) < 0 || quad(w, lp, lu, lv, 0.3, 8) < 0) return -1;
    for (b = 0; b < 2; b++) /* four sides turned by atan(1/3), and a top */
        for (s = 0; s < 4; s++) {
            static const double dir[4][2] = {{3, 1}, {-1, 3}, {-3, -1}, {1, -3}};
            double o[3], u[3], v[3] = {0, 0, 0}, c = 0;
            int k;
            o[0] = blk[b][0];
            o[1] = blk[b][1];
            o[2] = 0;
            for (k = 0; k < s; k++) {
                o[0] += dir[k][0] * 0.6;
                o[1] += dir[k][1] * 0.6;
            }
            u[0] = dir[s][0] * 0.6;
            u[1] = dir[s][1] * 0.6;
            u[2] = 0;
            v[2] = h[b];
            if (quad(w, o, u, v, 0.5, 0) < 0) return -1;
            (void)c;
        }
    for (b = 0; b < 2; b++) {
        double o[3] = {blk[b][0], blk[b][1], h[b]}, u[3] = {1.8, 0.6, 0}, v[3] = {-0.6, 1.8, 0};
        if (quad(w, o, u, v, 0.5, 0) < 0) return -1;
    }
    return 0;
}

/* A room 0..16 around a 4 x 4 x 2 grid of cubes, a light in the ceiling. */
static int boxes(world_t *w)
{
    static const double room[3] = {0, 0, 0}, size[3] = {16, 16, 16}, edge[3] = {1.5, 1.5, 1.5};
    static const double lp[3] = {6, 6, 15.9}, lu[3] = {4, 0, 0}, lv[3] = {0, -4, 0};
    int i, j, k;
    if (box(w, room, size, 1, 0.5) < 0 || quad(w, lp, lu, lv, 0.2, 6) < 0) return -1;
    for (k = 0; k < 2; k++)
        for (j = 0; j < 4; j++)
            for (i = 0; i < 4; i++) {
                double p[3] = {1.5 + 3.6 * i, 1.5 + 3.6 * j, 2 + 6 * k};
                if (box(w, p, edge, 0, 0.3 + 0.1 * ((i + j + k) % 4)) < 0) return -1;
            }
    return 0;
}

/* Overlapping quads on the floor z = 0 of a room, added far from their neighbours in
 * the surfaces' order, some exactly on top of each other: equal depths, many ties. */
static int coplanar(world_t *w)
{
    static const double room[3] = {-1, -1, 0}, size[3] = {14, 14, 8};
    static const double lp[3] = {4, 4, 7.9}, lu[3] = {4, 0, 0}, lv[3] = {0, -4, 0};
    int k;
    if (box(w, room, size, 1, 0.5) < 0 || quad(w, lp, lu, lv, 0.2, 6) < 0) return -1;
    for (k = 0; k < 24; k++) {
        int m = (k * 7) % 24; /* 0, 7, 14, 21, 4, ...: neighbours far apart in order */
        double p[3] = {(m % 6) * 2.0, (m / 6) * 2.5, 0}, u[3] = {3, 0, 0}, v[3] = {0, 3, 0};
        if (quad(w, p, u, v, 0.1 + 0.03 * k, 0) < 0) return -1;
        if (k % 3 == 0 && quad(w, p, u, v, 0.9 - 0.03 * k, 0) < 0) return -1; /* the same again */
    }
    return 0;
}

/* A SIDE x SIDE grid of closed rooms 4 x 4 x 3 with a cube and a lamp each (13
 * surfaces a room), PX apart along x (at 4 the neighbours' walls lie in one plane back
 * to back: equal depths, a wall's face against the next room's back), 4.5 along y. From inside
 * a room all else is hidden, but what touches its walls' planes (the floors and walls
 * of the rooms along x). */
static int rooms_grid(world_t *w, int side, double px)
{
    static const double size[3] = {4, 4, 3}, edge[3] = {1, 1, 1}, lu[3] = {1, 0, 0},
                        lv[3] = {0, -1, 0};
    int i, j;
    for (j = 0; j < side; j++)
        for (i = 0; i < side; i++) {
            double room[3] = {px * i, 4.5 * j, 0},
                   cube[3] = {px * i + 1 + 0.5 * j, 4.5 * j + 1.5, 0};
            double lp[3] = {px * i + 1.5, 4.5 * j + 2.5, 2.95};
            if (box(w, room, size, 1, 0.5) < 0 || box(w, cube, edge, 0, 0.4) < 0 ||
                quad(w, lp, lu, lv, 0.2, 5) < 0)
                return -1;
        }
    return 0;
}

static int rooms(world_t *w)
{
    return rooms_grid(w, 3, 4.0);
}

/* A room 0..12 and 20 x 20 slivers standing on its floor, each 0.06 wide and 0.3 tall,
 * turned and leaning (their boxes wider than they are), every fourth twice over (equal
 * depths): from a few units away each is under a pixel at res 32 (2.8 degrees). */
static int field(world_t *w)
{
    static const double room[3] = {0, 0, 0}, size[3] = {12, 12, 12};
    static const double lp[3] = {5, 5, 11.9}, lu[3] = {2, 0, 0}, lv[3] = {0, -2, 0};
    int i, j;
    if (box(w, room, size, 1, 0.5) < 0 || quad(w, lp, lu, lv, 0.2, 6) < 0) return -1;
    for (j = 0; j < 20; j++)
        for (i = 0; i < 20; i++) {
            double t = 0.37 * (i * 20 + j), c = 0.03 * cos(t), sn = 0.03 * sin(t);
            double p[3] = {1 + 0.5 * i + 0.1 * (j % 3), 1 + 0.5 * j, 0.1 * ((i * j) % 5)};
            double u[3] = {c, sn, 0}, v[3] = {-sn / 3, c / 3, 0.1};
            if (quad(w, p, u, v, 0.2 + 0.02 * (j % 30), 0) < 0) return -1;
            if ((i + j) % 4 == 0 && quad(w, p, u, v, 0.7, 0) < 0) return -1;
        }
    return 0;
}

/* One surface: a glowing square. */
static int one(world_t *w)
{
    static const double p[3] = {0, 0, 0}, u[3] = {4, 0, 0}, v[3] = {0, 4, 0};
    return quad(w, p, u, v, 0.5, 4);
}

/* Gather points of scene SCENE: K-th of N, a point and normal. */
static void point_of(int scene, int k, int n, double *p, double *nrm)
{
    /* a fixed low-discrepancy walk through the room */
    double a = (k * 0.618034) - (int)(k * 0.618034), b = (k * 0.754878) - (int)(k * 0.754878);
    double c = (k * 0.569840) - (int)(k * 0.569840);
    double ext = scene == BOXES                                          ? 16
                 : scene == COPLANAR || scene == ROOMS || scene == FIELD ? 12
                                                                         : 10;
    p[0] = 0.3 + a * (ext - 0.6);
    p[1] = 0.3 + b * (ext - 0.6);
    p[2] = 0.3 + c * ((scene == ROOMS ? 3 : ext) - 0.6);
    nrm[0] = (k % 5) - 2.0;
    nrm[1] = ((k / 5) % 3) - 1.0;
    nrm[2] = (k % 2) ? 1.0 : -0.7;
    if (scene == COPLANAR && k % 2) { /* over the floor, looking down and around */
        p[2] = 0.05 + c;
        nrm[0] = 0.1;
        nrm[1] = -0.2;
        nrm[2] = -1;
    }
    if (scene == ONE) { /* in front of it and behind it */
        p[0] = -2 + 8 * a;
        p[1] = -2 + 8 * b;
        p[2] = (k % 2 ? 1 : -1) * (0.1 + 3 * c);
    }
    (void)n;
}

/* Whether the two gatherers' last faces hold the same depths and items. */
static int same_face(const rad_gather_t *g, const rad_gather_t *h)
{
    size_t px = (size_t)g->res * g->res;
    return !memcmp(g->zbuf, h->zbuf, px * sizeof *g->zbuf) &&
           !memcmp(g->ibuf, h->ibuf, px * sizeof *g->ibuf);
}

/* Gathers plain (G) and culled (H) alike; counts into R whether they differ. */
static void compare(world_t *w, rad_gather_t *g, rad_gather_t *h, const rad_vec3_t *p,
                    const rad_vec3_t *n, uint32_t skip, cres *r)
{
    rad_rgb_t a[9], b[9];
    int ra, rb, same;
    memset(a, 0, sizeof a);
    memset(b, 0, sizeof b);
    if (n) {
        ra = rad_gather(&w->s, g, p, n, skip, RAD_SHADE_AMBIENT, a);
        rb = rad_gather(&w->s, h, p, n, skip, RAD_SHADE_AMBIENT, b);
    } else {
        ra = rad_gather_sh(&w->s, g, p, skip, RAD_SHADE_AMBIENT, a);
        rb = rad_gather_sh(&w->s, h, p, skip, RAD_SHADE_AMBIENT, b);
    }
    same = ra == RAD_OK && rb == RAD_OK && !memcmp(a, b, sizeof a) && same_face(g, h);
    if (!same && r->first < 0) r->first = r->gathers + r->probes;
    r->differ += !same;
    if (n)
        r->gathers++;
    else
        r->probes++;
}

int TW(scene_cull)(int scene, int res, cres *r)
{
    world_t *w = world_new(scene == ONE ? 1 : 2);
    rad_gather_t g[2], h[2];
    int k, rc = -1, t;
    memset(r, 0, sizeof *r);
    r->first = -1;
    if (!w) return -1;
    if ((scene == CORNELL || scene == ON_SURFACE ? cornell(w)
         : scene == BOXES                        ? boxes(w)
         : scene == COPLANAR                     ? coplanar(w)
         : scene == ROOMS                        ? rooms(w)
         : scene == FIELD                        ? field(w)
                                                 : one(w)) < 0)
        goto out;
    if (rad_shoot(&w->s, 30, 0) < 0) goto out;
    r->surfaces = w->s.n_surfaces;
    if (rad_cull_build(&w->s, w->cull, sizeof w->cull) != (int)(2 * w->s.n_surfaces - 1)) goto out;
    for (t = 0; t < 2; t++) { /* hemisphere gatherers, then sphere ones */
        unsigned fl = t ? RAD_GATHER_SH : 0u;
        if (rad_gather_init(&g[t], (unsigned)res, fl, w->gwork[0], sizeof w->gwork[0]) != RAD_OK ||
            rad_gather_init(&h[t], (unsigned)res, fl, w->gwork[1], sizeof w->gwork[1]) != RAD_OK ||
            rad_gather_cull(&h[t], w->cull, w->cwork, sizeof w->cwork) != RAD_OK)
            goto out;
        for (k = 0; k < 40; k++) {
            double p[3], n[3];
            rad_vec3_t pv, nv;
            uint32_t skip = RAD_INDEX_NONE;
            point_of(scene, k, 40, p, n);
            if (scene == ON_SURFACE) {
                /* on the wall x = 0 (surface 0) or the floor z = 0 (surface 4), the
                 * surface skipped or (edge on) drawn */
                int wall = k % 2;
                p[wall ? 0 : 2] = 0;
                n[0] = wall ? 1 : 0.05 * (k % 3);
                n[1] = 0.1;
                n[2] = wall ? 0.05 * (k % 3) : 1;
                skip = k % 4 < 2 ? (wall ? 0u : 4u) : RAD_INDEX_NONE;
            }
            pv = vec(p[0], p[1], p[2]);
            nv = vec(n[0], n[1], n[2]);
            g[t].turn = h[t].turn = (uint32_t)k;
            compare(w, &g[t], &h[t], &pv, t ? NULL : &nv, skip, r);
        }
        r->calls[0] += g[t].stats.raster_calls;
        r->calls[1] += h[t].stats.raster_calls;
    }
    rc = 0;
out:
    free(w);
    return rc;
}

#define SHOTS 120

/* Shots of scene SCENE on W (BATCH 0: rad_shoot one at a time, else batches of BATCH
 * rendered in order); the shots done, counting into *WAITS those drawn in full while
 * the hierarchy waits (cull_wait). */
static long shots_of(world_t *w, unsigned batch, unsigned char *bufs, long *waits)
{
    uint32_t patches[RAD_BATCH_MAX];
    size_t bytes = RAD_BATCH_BYTES(32, NE);
    void *b[RAD_BATCH_MAX];
    long done = 0;
    unsigned k;
    for (k = 0; k < RAD_BATCH_MAX; k++) b[k] = bufs + k * bytes;
    while (done < SHOTS) {
        int n;
        *waits += w->s.cull_wait > 0;
        if (!batch) {
            if ((n = rad_shoot(&w->s, 1, 0)) <= 0) break;
        } else {
            if ((n = rad_batch_begin(&w->s, 0, batch, patches)) <= 0) break;
            for (k = 0; k < (unsigned)n; k++)
                if (rad_batch_render(&w->s, patches[k], k, b[k], bytes) < 0) return -1;
            if ((n = rad_batch_end(&w->s, b, (unsigned)n)) <= 0) break;
        }
        done += n;
    }
    return done;
}

int TW(shots_cull)(int scene, unsigned batch, sres *r)
{
    world_t *w[2] = {world_new(scene == ROOMS ? 2 : 1), world_new(scene == ROOMS ? 2 : 1)};
    unsigned char *bufs = malloc(RAD_BATCH_MAX * RAD_BATCH_BYTES(32, NE));
    rad_ff_t *ff[2] = {malloc(NE * sizeof(rad_ff_t)), malloc(NE * sizeof(rad_ff_t))};
    long waits = 0;
    uint32_t e, p;
    int k, rc = -1;
    memset(r, 0, sizeof *r);
    if (!w[0] || !w[1] || !bufs || !ff[0] || !ff[1]) goto out;
    for (k = 0; k < 2; k++) {
        world_t *v = w[k];
        if ((scene == CORNELL ? cornell(v)
             : scene == ROOMS ? rooms_grid(v, 20, 4.5)
                              : field(v)) < 0 ||
            rad_shoot(&v->s, 1, 0) != 1) /* the geometry frozen */
            goto out;
        if (k && (rad_cull_build(&v->s, v->cull, sizeof v->cull) < 0 ||
                  rad_shoot_cull(&v->s, v->cull) != RAD_OK))
            goto out;
        r->shots[k] = shots_of(v, batch, bufs, k ? &r->waits : &waits);
        r->calls[k] = v->s.stats.raster_calls;
    }
    r->surfaces = w[0]->s.n_surfaces;
    r->elements = w[0]->s.n_elements;
    for (e = 0; e < w[0]->s.n_elements; e++)
        r->differ += memcmp(&w[0]->elem[e].radiosity, &w[1]->elem[e].radiosity,
                            sizeof w[0]->elem[e].radiosity) != 0;
    for (p = 0; p < w[0]->s.n_patches; p++)
        r->differ +=
            memcmp(w[0]->patch[p].unshot, w[1]->patch[p].unshot, sizeof w[0]->patch[p].unshot) != 0;
    for (p = 0; p < w[0]->s.n_patches; p += w[0]->s.n_patches / 40u + 1u) {
        if (rad_form_factors(&w[0]->s, p, ff[0]) < 0 || rad_form_factors(&w[1]->s, p, ff[1]) < 0)
            goto out;
        for (e = 0; e < w[0]->s.n_elements; e++)
            r->ff_differ += memcmp(&ff[0][e], &ff[1][e], sizeof ff[0][e]) != 0;
    }
    rc = 0;
out:
    free(w[0]);
    free(w[1]);
    free(bufs);
    free(ff[0]);
    free(ff[1]);
    return rc;
}

int TW(sizes_cull)(csizes *z)
{
    world_t *w = world_new(2), *v = world_new(2);
    unsigned char *buf = (unsigned char *)w->cull, *cw = w->cwork;
    size_t need, i, cneed;
    rad_gather_t g;
    rad_vec3_t p = vec(5, 5, 5), n = vec(0, 0, 1);
    rad_rgb_t out;
    int rc = -1;
    memset(z, 0, sizeof *z);
    if (!w || !v || cornell(w) < 0 || cornell(v) < 0 ||
        quad(v, (const double[3]){1, 1, 1}, (const double[3]){1, 0, 0}, (const double[3]){0, 1, 0},
             0.5, 0) < 0)
        goto out;
    z->early = rad_cull_build(&w->s, buf, sizeof w->cull);
    if (rad_shoot(&w->s, 5, 0) < 0 || rad_shoot(&v->s, 5, 0) < 0) goto out;
    z->surfaces = w->s.n_surfaces;
    need = RAD_CULL_BYTES(w->s.n_surfaces);
    memset(buf, 0xA5, sizeof w->cull);
    z->short_build = rad_cull_build(&w->s, buf, need - 1);
    z->misaligned = rad_cull_build(&w->s, buf + 2, need);
    z->built = rad_cull_build(&w->s, buf, need);
    z->guard_ok = 1;
    for (i = need; i < sizeof w->cull; i++) z->guard_ok &= buf[i] == 0xA5;
    if (rad_gather_init(&g, 16, 0, w->gwork[0], sizeof w->gwork[0]) != RAD_OK) goto out;
    /* the work may start anywhere: at 1 past a multiple of 4 it needs all the macro's bytes */
    cneed = RAD_GATHER_CULL_BYTES(16, w->s.n_surfaces);
    cw += (4u - ((uintptr_t)cw & 3u)) % 4u + 1u;
    z->short_work = rad_gather_cull(&g, buf, cw, cneed - 1);
    z->exact_work = rad_gather_cull(&g, buf, cw, cneed);
    memset(cw + cneed, 0x5A, 8);
    if (rad_gather(&w->s, &g, &p, &n, RAD_INDEX_NONE, 0, &out) != RAD_OK) z->exact_work = -100;
    for (i = cneed; i < cneed + 8; i++) z->guard_ok &= cw[i] == 0x5A;
    z->odd_work = rad_gather_cull(&g, cw, cw, cneed); /* not a hierarchy */
    /* the hierarchy of W on V, which has one surface more */
    if (rad_gather_init(&g, 16, 0, v->gwork[0], sizeof v->gwork[0]) != RAD_OK ||
        rad_gather_cull(&g, buf, v->cwork, sizeof v->cwork) != RAD_OK)
        goto out;
    z->other_scene = rad_gather(&v->s, &g, &p, &n, RAD_INDEX_NONE, 0, &out);
    rc = 0;
out:
    free(w);
    free(v);
    return rc;
}

/* The host's gatherers (tools/host/scene.c) over polygons P: 30 gathers through the
 * hierarchy and drawing every surface; counts calls FAILED and values that DIFFER.
 * Returns 0, or -1 when the scene cannot be made. */
int TW(host_gathers)(const sc_poly *p, int n, long *failed, long *differ)
{
    char err[256];
    sc_opts o;
    sc_solver *s;
    sc_gatherer *g = NULL;
    int k;
    memset(&o, 0, sizeof o);
    o.max_element = 2;
    o.res = 32;
    *failed = *differ = 0;
    s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    if (!s || sc_solve(s, 20, 0, NULL, NULL) < 0 || !(g = sc_gatherer_new(s, 32, 0))) {
        sc_destroy(s);
        return -1;
    }
    for (k = 0; k < 30; k++) {
        double pt[3] = {0.5 + 0.5 * k, 0.3 + 0.45 * k, 15.5 - 0.5 * k},
               nrm[3] = {k % 3 - 1.0, 1, 0.3};
        double a[3], c[3];
        *failed += sc_gatherer_cull(g, 0) != 0 || sc_gather(g, pt, nrm, 1, a) != 0;
        *failed += sc_gatherer_cull(g, 1) != 0 || sc_gather(g, pt, nrm, 1, c) != 0;
        *differ += memcmp(a, c, sizeof a) != 0;
    }
    sc_gatherer_free(g);
    sc_destroy(s);
    return 0;
}

#if !RAD_FLOAT
/* ---- the tests (fixed half) --------------------------------------------------------- */

static const char *const names[NSCENES] = {"Cornell box",        "box of boxes", "coplanar ties",
                                           "points on surfaces", "one surface",  "grid of rooms",
                                           "field of slivers"};

/* Scene SCENE at RES in both builds: every gather the same culled; returns the raster
 * calls (all drawn, culled) of the fixed build. */
static void check_scene_calls(int scene, int res, unsigned long *calls)
{
    int b;
    for (b = 0; b < 2; b++) {
        cres r;
        int rc = b ? scene_cull_float(scene, res, &r) : scene_cull_fixed(scene, res, &r);
        const char *build = b ? "float" : "fixed";
        if (rc != 0) fail_msg("%s %s: the scene or its hierarchy failed", build, names[scene]);
        if (r.differ != 0)
            fail_msg("%s %s res %d: %ld of %ld gathers and %ld probes differ culled (first: %ld)",
                     build, names[scene], res, r.differ, r.gathers, r.probes, r.first);
        print_message("%s %s (%u surfaces) res %d: %ld gathers, %ld probes the same; raster calls "
                      "%lu all, %lu culled\n",
                      build, names[scene], r.surfaces, res, r.gathers, r.probes, r.calls[0],
                      r.calls[1]);
        if (b == 0 && calls) memcpy(calls, r.calls, sizeof r.calls);
    }
}

static void check_scene(int scene, int res)
{
    check_scene_calls(scene, res, NULL);
}

static void test_cornell(void **st)
{
    (void)st;
    check_scene(CORNELL, 32);
    check_scene(CORNELL, 64);
}

static void test_boxes(void **st)
{
    (void)st;
    check_scene(BOXES, 32);
}

static void test_coplanar(void **st)
{
    (void)st;
    check_scene(COPLANAR, 32);
}

static void test_on_surface(void **st)
{
    (void)st;
    check_scene(ON_SURFACE, 16);
}

static void test_one(void **st)
{
    (void)st;
    check_scene(ONE, 16);
}

/* In closed rooms culling hides most surfaces: the culled gathers draw the surfaces
 * they keep, then again those left nearest at a pixel, and still fewer polygons than
 * drawing all once (measured: 0.60 times as many; 0.86 when every kept surface was
 * drawn twice; with points in the gaps between rooms, where nothing is hidden). */
static void test_rooms(void **st)
{
    unsigned long calls[2];
    (void)st;
    check_scene_calls(ROOMS, 32, calls);
    if (calls[1] >= calls[0])
        fail_msg(
            "grid of rooms: %lu raster calls culled, not below %lu drawing all: nothing hidden",
            calls[1], calls[0]);
}

/* Slivers under a pixel in an open field: their boxes are tested pixel by pixel, and
 * most of them hide behind nearer ones or meet no pixel's centre, so the culled
 * gathers make fewer raster calls than drawing every surface once (measured: 12,207
 * against 19,780; tiles alone, which fail wherever a tile shows nothing, drew every
 * surface twice: 39,560). */
static void test_field(void **st)
{
    unsigned long calls[2];
    (void)st;
    check_scene_calls(FIELD, 16, calls);
    if (calls[1] >= calls[0])
        fail_msg("field of slivers: %lu raster calls culled, not below %lu drawing all", calls[1],
                 calls[0]);
}

/* Shots through the hierarchy, one at a time and in batches of 4, in both builds: the
 * same element radiosity and unshot power after SHOTS shots, and the same form factors.
 * The culling is used (the raster calls differ) and, where it does not pay (an open
 * Cornell box, where a cube tests more nodes than a third of the surfaces), shots wait
 * drawing every surface; in 20 x 20 closed rooms (5,200 surfaces; a cube tests 500 to
 * 900 nodes whatever their count) it draws fewer polygons and no shot waits. */
static void check_shots(int scene)
{
    int b, batch;
    for (b = 0; b < 2; b++)
        for (batch = 0; batch <= 4; batch += 4) {
            sres r;
            const char *build = b ? "float" : "fixed";
            int rc = b ? shots_cull_float(scene, (unsigned)batch, &r)
                       : shots_cull_fixed(scene, (unsigned)batch, &r);
            if (rc != 0) fail_msg("%s %s: the scene or its hierarchy failed", build, names[scene]);
            print_message("%s %s (%u surfaces, %u elements) batch %d: %ld and %ld shots, %ld "
                          "values and %ld form factors differ; raster calls %lu all, %lu culled, "
                          "%ld shots waited\n",
                          build, names[scene], r.surfaces, r.elements, batch, r.shots[0],
                          r.shots[1], r.differ, r.ff_differ, r.calls[0], r.calls[1], r.waits);
            if (r.shots[0] != SHOTS || r.shots[1] != SHOTS || r.differ || r.ff_differ)
                fail_msg("%s %s batch %d: %ld and %ld shots (expected %d each), %ld values and "
                         "%ld form factors differ culled (expected 0)",
                         build, names[scene], batch, r.shots[0], r.shots[1], SHOTS, r.differ,
                         r.ff_differ);
            if (r.calls[1] == r.calls[0])
                fail_msg("%s %s batch %d: %lu raster calls either way: the hierarchy unused", build,
                         names[scene], batch, r.calls[0]);
            if (scene == ROOMS && (r.calls[1] >= r.calls[0] || r.waits > 0))
                fail_msg("%s %s batch %d: %lu raster calls culled against %lu, %ld shots waited "
                         "(expected fewer calls, none waiting)",
                         build, names[scene], batch, r.calls[1], r.calls[0], r.waits);
            if (scene == CORNELL && r.waits == 0)
                fail_msg("%s %s batch %d: no shot waited where the hierarchy hides little", build,
                         names[scene], batch);
        }
}

static void test_shots(void **st)
{
    (void)st;
    check_shots(CORNELL);
    check_shots(ROOMS);
    check_shots(FIELD);
}

static void test_sizes(void **st)
{
    int b;
    (void)st;
    for (b = 0; b < 2; b++) {
        csizes z;
        const char *build = b ? "float" : "fixed";
        if ((b ? sizes_cull_float(&z) : sizes_cull_fixed(&z)) != 0)
            fail_msg("%s: setup failed", build);
        if (z.early != RAD_ERR_STATE)
            fail_msg("%s: built before the geometry froze: %d", build, z.early);
        if (z.short_build != RAD_ERR_WORK)
            fail_msg("%s: RAD_CULL_BYTES - 1 gave %d, not RAD_ERR_WORK", build, z.short_build);
        if (z.misaligned != RAD_ERR_ALIGN)
            fail_msg("%s: a misaligned buffer gave %d", build, z.misaligned);
        if (z.built != (int)(2 * z.surfaces - 1))
            fail_msg("%s: RAD_CULL_BYTES exactly gave %d, not %u nodes", build, z.built,
                     2 * z.surfaces - 1);
        if (!z.guard_ok) fail_msg("%s: bytes past a buffer's size were written", build);
        if (z.short_work != RAD_ERR_WORK)
            fail_msg("%s: RAD_GATHER_CULL_BYTES - 1 gave %d, not RAD_ERR_WORK", build,
                     z.short_work);
        if (z.exact_work != RAD_OK)
            fail_msg("%s: RAD_GATHER_CULL_BYTES exactly gave %d", build, z.exact_work);
        if (z.odd_work != RAD_ERR_ARG)
            fail_msg("%s: a buffer that is no hierarchy gave %d", build, z.odd_work);
        if (z.other_scene != RAD_ERR_STATE)
            fail_msg("%s: another scene's hierarchy gave %d, not RAD_ERR_STATE", build,
                     z.other_scene);
    }
}

/* A quad of sc_poly P[N] at (X0, Y0, Z0) spanning DU, DV along the axes after AX,
 * turned over when FLIP; returns N + 1. */
static int host_poly(sc_poly *p, int n, double x0, double y0, double z0, int ax, double du,
                     double dv, int flip, double rho, double emit)
{
    int u = (ax + 1) % 3, v = (ax + 2) % 3, k;
    static const int cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
    memset(&p[n], 0, sizeof p[n]);
    for (k = 0; k < 4; k++) {
        int kk = flip ? 3 - k : k;
        p[n].v[k][0] = x0;
        p[n].v[k][1] = y0;
        p[n].v[k][2] = z0;
        p[n].v[k][u] += cu[kk] * du;
        p[n].v[k][v] += cv[kk] * dv;
    }
    p[n].n = 4;
    p[n].rho[0] = p[n].rho[1] = p[n].rho[2] = rho;
    p[n].emit[0] = p[n].emit[1] = p[n].emit[2] = emit;
    p[n].tag = n;
    return n + 1;
}

/* The six faces of the cube at (X, Y, Z) of edge E facing out (IN: in) into P at N. */
static int host_cube(sc_poly *p, int n, double x, double y, double z, double e, int in, double rho)
{
    int ax;
    for (ax = 0; ax < 3; ax++) {
        double o[3] = {x, y, z};
        n = host_poly(p, n, o[0], o[1], o[2], ax, e, e, !in, rho, 0);
        o[ax] += e;
        n = host_poly(p, n, o[0], o[1], o[2], ax, e, e, in, rho, 0);
    }
    return n;
}

/* The host's gatherers: a room of 4 x 4 x 2 cubes (199 polygons) gathered at 30
 * points through the hierarchy and drawing every surface, in both builds: the same
 * doubles. */
static void test_host(void **st)
{
    sc_poly *p = calloc(256, sizeof *p);
    int n = 0, i, j, k, b;
    (void)st;
    if (!p) fail_msg("out of memory");
    n = host_cube(p, n, 0, 0, 0, 16, 1, 0.5);
    n = host_poly(p, n, 6, 15.9, 6, 1, 4, 4, 1, 0.2, 6); /* the lamp, facing down */
    for (k = 0; k < 2; k++)
        for (j = 0; j < 4; j++)
            for (i = 0; i < 4; i++)
                n = host_cube(p, n, 1.5 + 3.6 * i, 2 + 6 * k, 1.5 + 3.6 * j, 1.5, 0, 0.4);
    for (b = 0; b < 2; b++) {
        long failed, differ;
        int rc = b ? host_gathers_float(p, n, &failed, &differ)
                   : host_gathers_fixed(p, n, &failed, &differ);
        if (rc != 0) fail_msg("%s host: the scene failed", b ? "float" : "fixed");
        if (failed || differ)
            fail_msg("%s host, %d polygons: %ld calls failed, %ld of 30 gathers differ culled",
                     b ? "float" : "fixed", n, failed, differ);
    }
    free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cornell),  cmocka_unit_test(test_boxes),
        cmocka_unit_test(test_coplanar), cmocka_unit_test(test_on_surface),
        cmocka_unit_test(test_one),      cmocka_unit_test(test_rooms),
        cmocka_unit_test(test_field),    cmocka_unit_test(test_shots),
        cmocka_unit_test(test_sizes),    cmocka_unit_test(test_host),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
#endif
