/* SPDX-License-Identifier: MIT */
/* rad_cli's bake step: --lightmap (tools/bake/lightmap.h) and --probes / --probe-file
 * (tools/bake/probes.h), gathered from the solution through the glue's sc_gather. */
#include "cli.h"

#include <stdlib.h>
#include <string.h>

#include "bake/lightmap.h"
#include "bake/probes.h"
#include "host/clock.h"
#include "host/gltf_export.h"
#include "host/obj_polys.h"

#define GATHER_RES 32 /* the gathers' resolution without --gather: 0.84% from Lambert at 64 (tests/test_bake.c) */

typedef struct {
    sc_gatherer *g;
    int ambient;
    long gathers;
} gather_ctx;

static int lm_gather(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    gather_ctx *c = ctx;
    c->gathers++;
    return sc_gather(c->g, p, n, c->ambient, rgb);
}

static int pr_gather(void *ctx, const double p[3], double sh[9][3])
{
    gather_ctx *c = ctx;
    c->gathers++;
    return sc_gather_sh(c->g, p, c->ambient, sh);
}

struct bake_state {
    sc_poly *polys;
    int n;
    lm_atlas atlas;
    int has_atlas;
};

char *probes_output(const char *scene)
{
    char *png = default_output(scene), *out = png ? malloc(strlen(png) + 9) : NULL;
    if (out) {
        memcpy(out, png, strlen(png) - 4);
        strcpy(out + strlen(png) - 4, ".probes.json");
    }
    free(png);
    return out;
}

typedef struct {
    lm_atlas *a;
    int ambient;
    long *gathers; /* per thread */
} texel_job;

static int texel_rows(void *ctx, sc_gatherer *g, int first, int step)
{
    texel_job *j = ctx;
    gather_ctx c = {g, j->ambient, 0};
    int rc = lm_gather_rows(j->a, first, step, lm_gather, &c);
    j->gathers[first] = c.gathers;
    return rc;
}

/* The texels pass by pass (lm_plan), each pass's on N threads (--threads), each with a
 * gatherer of its own, by rows: the same bits as one. 0, or -1 (a gather failed, no
 * memory, no thread). */
static int gather_texels(run_t *r, lm_atlas *a, int n, int res, long *gathers)
{
    texel_job j = {a, r->ambient, calloc((size_t)n, sizeof(long))};
    int i, rc = j.gathers ? 0 : -1;
    while (rc == 0 && lm_plan(a) > 0) {
        rc = sc_gather_split(r->s, res, n, texel_rows, &j);
        for (i = 0; i < n; i++) *gathers += j.gathers[i];
    }
    free(j.gathers);
    return rc;
}

static int bake_lightmap(run_t *r, lm_atlas *a, int res)
{
    const opts_t *o = r->o;
    char err[1024];
    double t0 = host_now();
    long gathers = 0;
    int rc = gather_texels(r, a, o->threads > 1 ? o->threads : 1, res, &gathers);
    if (rc == 0) rc = lm_dilate(a);
    if (rc < 0) snprintf(err, sizeof err, "%s: a texel cannot be gathered (or no memory for the bake)", o->lightmap);
    else rc = lm_write(a, o->lightmap, o->exposure, err, sizeof err);
    if (rc < 0) fprintf(stderr, PROG ": %s\n", err);
    else if (o->stats)
        printf("lightmap: %dx%d texels, %d charts, texel %.6g, %ld gathers at res %d (%d passes, tolerance %g) on %d "
               "threads, %.2f s\n", a->size, a->size, a->ncharts, a->texel, gathers, res, a->pass - 1, a->tol,
               o->threads > 1 ? o->threads : 1, host_now() - t0);
    return rc;
}

static int bake_probes(run_t *r, const sc_poly *polys, int n, gather_ctx *c)
{
    const opts_t *o = r->o;
    char err[1024] = "";
    int np = o->probes ? o->probe_dims[0] * o->probe_dims[1] * o->probe_dims[2] : 0, rc = -1;
    double *pts = o->probes ? pr_grid_points(polys, n, o->probe_dims) : pr_read_points(o->probe_file, &np, err, sizeof err);
    pr_probe *pr = pts ? malloc((size_t)np * sizeof *pr) : NULL;
    if (pr && pr_bake(polys, n, pts, np, pr_gather, c, pr, err, sizeof err) == 0)
        rc = pr_write_json(o->probes_out, pr, np, o->probes ? o->probe_dims : NULL, err, sizeof err);
    if (rc < 0) fprintf(stderr, PROG ": %s\n", *err ? err : "out of memory for the probes");
    free(pts);
    free(pr);
    return rc;
}

int bake_prepare(run_t *r)
{
    const opts_t *o = r->o;
    lm_opts lo = {o->lightmap_size ? o->lightmap_size : 512, 0.0, 0, o->lightmap_tol};
    char err[1024];
    struct bake_state *b;
    if (!o->lightmap && !o->probes && !o->probe_file) return 0;
    b = r->bake = calloc(1, sizeof *b);
    if (b) b->polys = obj_to_polys(&r->sc, &b->n, NULL, NULL); /* warned of when built */
    if (!b || !b->polys) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    if (o->lightmap && lm_build(&b->atlas, b->polys, b->n, &lo, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s: %s\n", o->lightmap, err);
        return -1;
    }
    b->has_atlas = o->lightmap != NULL;
    return 0;
}

int bake_step(run_t *r)
{
    const opts_t *o = r->o;
    struct bake_state *b = r->bake;
    int rc = 0, res = o->gather_res ? o->gather_res : GATHER_RES;
    gather_ctx c = {NULL, r->ambient, 0};
    if (!b) return 0;
    if (b->has_atlas) rc = bake_lightmap(r, &b->atlas, res);
    if (rc == 0 && (o->probes || o->probe_file)) {
        c.g = sc_gatherer_new(r->s, res, 1);
        rc = c.g ? bake_probes(r, b->polys, b->n, &c) : -1;
        if (!c.g) fprintf(stderr, PROG ": out of memory for a gather of resolution %d\n", res);
        sc_gatherer_free(c.g);
    }
    return rc;
}

int bake_export_gltf(run_t *r, gltf_warn_fn warn)
{
    if (!r->o->gltf || !r->bake || !r->bake->has_atlas) return 0;
    return write_gltf(r, &r->bake->atlas, warn);
}

void bake_free(run_t *r)
{
    if (!r->bake) return;
    if (r->bake->has_atlas) lm_free(&r->bake->atlas);
    free(r->bake->polys);
    free(r->bake);
    r->bake = NULL;
}
