/* SPDX-License-Identifier: MIT */
/* rad_cli's bake step: --lightmap (tools/bake/lightmap.h) and --probes / --probe-file
 * (tools/bake/probes.h), gathered from the solution through the glue's sc_gather. */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/lightmap.h"
#include "bake/probes.h"
#include "formats/file_io.h"
#include "host/clock.h"
#include "bake/gltf_export.h"
#include "host/polys.h"
#include "progress.h"

/* A thread's gathers; PG (the calling thread's, else NULL) shows its count against
 * TOTAL, its own share of the stage, every PROGRESS_EVERY gathers. S and A: the solve
 * and the atlas, for the texels' sharp lights (lm_direct). */
typedef struct {
    sc_gatherer *g;
    int flags; /* SC_AMBIENT; SC_SKIES: a painted lightmap's skies per texel */
    long gathers;
    progress_t *pg;
    double total;
    const char *unit;
    sc_solver *s;
    lm_atlas *a;
} gather_ctx;

#define PROGRESS_EVERY 64

static void gathered(gather_ctx *c)
{
    char detail[96];
    if (++c->gathers % PROGRESS_EVERY || !c->pg) return;
    snprintf(detail, sizeof detail, "%ld of %.0f %s", c->gathers, c->total, c->unit);
    progress_update(c->pg, c->gathers / c->total, detail);
}

/* A texel's soft light: its sharp lights' direct light is lm_direct's, per texel. */
static int lm_gather(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    gather_ctx *c = ctx;
    gathered(c);
    return sc_gather(c->g, p, n, c->flags | SC_SOFT, rgb);
}

static int lm_direct(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    gather_ctx *c = ctx;
    gathered(c);
    return sc_direct(c->s, p, n, c->flags & SC_SKIES, lm_visible, c->a, rgb);
}

static int pr_gather(void *ctx, const double p[3], double sh[9][3])
{
    gather_ctx *c = ctx;
    gathered(c);
    return sc_gather_sh(c->g, p, c->flags & SC_AMBIENT, sh);
}

struct bake_state {
    sc_poly *polys;
    int n;
    lm_atlas atlas;
    int has_atlas;
    double *pts; /* the probes' points (grid or --probe-file), read before the solve */
    int npts;
};

char *cli_probes_output(const char *scene)
{
    char *png = cli_default_output(scene), *out = png ? malloc(strlen(png) + 9) : NULL;
    if (out) {
        memcpy(out, png, strlen(png) - 4);
        strcpy(out + strlen(png) - 4, ".probes.json");
    }
    free(png);
    return out;
}

typedef struct {
    sc_solver *s;
    lm_atlas *a;
    int flags;     /* gather_ctx's */
    long *gathers; /* per thread */
    progress_t *pg;
    double share; /* a thread's share of the pass's texels */
    int direct;   /* the sharp lights' pass (lm_direct_rows), not a gathering one */
} texel_job;

static int texel_rows(void *ctx, sc_gatherer *g, int first, int step)
{
    texel_job *j = ctx;
    gather_ctx c = {g, j->flags, 0, NULL, 0.0, "texels", j->s, j->a};
    int rc;
    if (first == 0) {
        c.pg = j->pg;
        c.total = j->share;
    }
    rc = j->direct ? lm_direct_rows(j->a, first, step, lm_direct, &c)
                   : lm_gather_rows(j->a, first, step, lm_gather, &c);
    j->gathers[first] = c.gathers;
    return rc;
}

/* Texels with a sample: what may be gathered. */
static long covered_texels(const lm_atlas *a)
{
    size_t i, t = (size_t)a->size * a->size;
    long n = 0;
    for (i = 0; i < t; i++) n += !isnan(a->sample[2 * i]);
    return n;
}

/* After the first pass, whose gathers took SECONDS each (wall, on --threads): a note
 * when the passes left may take long, naming the painted bake. */
static void long_bake_note(run_t *r, const lm_atlas *a, double seconds)
{
    long texels = lm_undecided(a);
    double left = seconds * (double)texels;
    if (left > LIGHTMAP_NOTE_SECONDS && !r->o->quiet)
        fprintf(stderr,
                PROG ": note: %s: the passes left may take up to %.0f minutes (%ld texels at "
                     "%.1f ms each, the first pass's rate); --lightmap-soft elements paints "
                     "the soft light from the solve in seconds, as a preview (docs/cli.md)\n",
                r->o->lightmap, left / 60.0, texels, 1e3 * seconds);
}

/* The texels pass by pass (lm_plan), each pass's on N threads (--threads), each with a
 * gatherer of its own, by rows: the same bits as one; each pass a stage of progress
 * (how many passes there will be depends on what they gather). 0, or -1 (a gather
 * failed, no memory, no thread). */
static int gather_texels(run_t *r, lm_atlas *a, int n, int res, long *gathers, double *t_direct)
{
    progress_t pg;
    texel_job j = {r->s,
                   a,
                   (r->ambient ? SC_AMBIENT : 0) | (a->painted ? SC_SKIES : 0),
                   calloc((size_t)n, sizeof(long)),
                   &pg,
                   0.0,
                   0};
    char what[64];
    long count;
    double t;
    int i, rc = j.gathers ? 0 : -1;
    while (rc == 0 && (count = lm_plan(a)) > 0) {
        snprintf(what, sizeof what, "lightmap pass %d", a->pass);
        progress_begin(&pg, what, r->o->quiet);
        j.share = (double)count / n;
        t = host_now();
        rc = sc_gather_split(r->s, res, n, texel_rows, &j);
        for (i = 0; i < n; i++) *gathers += j.gathers[i];
        progress_end(&pg);
        if (rc == 0 && a->pass == 1 && !a->painted) long_bake_note(r, a, (host_now() - t) / count);
    }
    t = host_now();
    if (rc == 0) { /* the sharp lights at every covered texel */
        progress_begin(&pg,
                       j.flags & SC_SKIES ? "lightmap: suns, skies, points and spots"
                                          : "lightmap: suns, points and spots",
                       r->o->quiet);
        j.direct = 1;
        j.share = (double)covered_texels(a) / n;
        rc = sc_gather_split(r->s, 8, n, texel_rows, &j);
        progress_end(&pg);
    }
    *t_direct = host_now() - t;
    free(j.gathers);
    return rc;
}

/* The soft light from the solve's elements (lm_paint); the texels on elements whose
 * light is not known are left to gather_texels. 0, or -1 out of memory. */
static int paint_texels(run_t *r, lm_atlas *a)
{
    long n, left;
    sc_soft_element *el = sc_soft_elements(r->s, r->ambient, &n);
    if (!el) return -1;
    left = lm_paint(a, el, n);
    free(el);
    if (left < 0) return -1;
    if (!r->o->quiet)
        fprintf(stderr, PROG ": lightmap: soft light from %ld elements; %ld texels to gather\n", n,
                left);
    return 0;
}

static int bake_lightmap(run_t *r, lm_atlas *a, int res)
{
    const opts_t *o = r->o;
    char err[1024];
    double t0 = host_now(), t_direct = 0.0;
    long gathers = 0, total = covered_texels(a);
    int rc;
    if (!o->quiet)
        fprintf(stderr,
                PROG ": lightmap: %d charts%s, %ld texels covered: at most %ld gathers at res %d\n",
                a->file_uv ? a->file_charts : a->ncharts, a->file_uv ? " (the file's UVs)" : "",
                total, total, res);
    if (o->lightmap_soft == LIGHTMAP_SOFT_ELEMENTS && !r->soft_kept && !o->quiet)
        fprintf(stderr,
                PROG ": warning: %s: --lightmap-soft elements needs a shooting solve (not stored "
                     "form factors nor relighting) with memory for its split: the texels are "
                     "gathered\n",
                o->lightmap);
    if (r->soft_kept && (rc = paint_texels(r, a)) < 0) {
        fprintf(stderr, PROG ": %s: out of memory for the lightmap's elements\n", o->lightmap);
        return -1;
    }
    rc = gather_texels(r, a, o->threads > 1 ? o->threads : 1, res, &gathers, &t_direct);
    if (rc == 0) rc = lm_dilate(a);
    if (rc < 0)
        snprintf(err, sizeof err, "%s: a texel cannot be gathered (or no memory for the bake)",
                 o->lightmap);
    else
        rc = lm_write(a, o->lightmap, o->exposure, err, sizeof err);
    if (rc < 0)
        fprintf(stderr, PROG ": %s\n", err);
    else if (o->stats)
        printf("lightmap: %dx%d texels, %d charts, texel %.6g, %ld gathers at res %d (%d passes, "
               "tolerance %g) on %d "
               "threads, %.2f s (the sharp lights at every texel %.2f s)\n",
               a->size, a->size, a->file_uv ? a->file_charts : a->ncharts, a->texel, gathers, res,
               a->pass - 1, a->tol, o->threads > 1 ? o->threads : 1, host_now() - t0, t_direct);
    return rc;
}

/* The atlas's memory for N x N texels: lm_atlas's arrays of N^2 entries and lm_build's
 * ring of a size_t a texel (tools/bake/lightmap.c), the largest of its transients. */
static double atlas_bytes(int n)
{
    const lm_atlas *a = NULL; /* for the sizes of its entries only */
    size_t per = sizeof *a->owner + 2 * sizeof *a->sample + 3 * sizeof *a->rgb + sizeof *a->poly +
                 sizeof *a->state + sizeof *a->block + sizeof(size_t);
    return (double)n * n * (double)per;
}

/* The lightmap's memory said before it is allocated, and refused over the memory budget
 * (fio_memory_budget: half the physical memory). 0 or -1. */
static int lightmap_memory(const opts_t *o, int n)
{
    double bytes = atlas_bytes(n), budget = fio_memory_budget();
    if (bytes > budget) {
        fprintf(
            stderr,
            PROG
            ": %s: --lightmap-size %d needs about %.1f MB for its %d x %d texels, over the memory "
            "budget of %.1f MB (%s): lower --lightmap-size\n",
            o->lightmap, n, bytes / 1e6, n, n, budget / 1e6,
            getenv("RAD_MEMORY_BUDGET") ? "RAD_MEMORY_BUDGET" : "half the physical memory");
        return -1;
    }
    if (!o->quiet)
        fprintf(stderr, PROG ": lightmap: %d x %d texels, about %.1f MB\n", n, n, bytes / 1e6);
    return 0;
}

static int bake_probes(run_t *r, const struct bake_state *b, gather_ctx *c)
{
    const opts_t *o = r->o;
    char err[1024] = "";
    int rc = -1;
    pr_probe *pr = malloc((size_t)b->npts * sizeof *pr);
    progress_t pg;
    progress_begin(&pg, "probes", o->quiet);
    c->pg = &pg;
    c->total = b->npts;
    c->unit = "probes";
    if (pr && pr_bake(b->polys, b->n, b->pts, b->npts, pr_gather, c, pr, err, sizeof err) == 0)
        rc = pr_write_json(o->probes_out, pr, b->npts, o->probes ? o->probe_dims : NULL, err,
                           sizeof err);
    progress_end(&pg);
    if (rc < 0) fprintf(stderr, PROG ": %s\n", *err ? err : "out of memory for the probes");
    free(pr);
    return rc;
}

/* The line of PATH's probe K (0-based), the file read once more: probes.h's rule, each
 * line that is not blank or a '#' comment holds one (pr_read_points checked them). 0
 * when the file cannot be read again. */
static int probe_line(const char *path, int k)
{
    char *data, *s;
    size_t size;
    int line = 1, found = 0;
    if (fio_read_all(path, FIO_LIMIT_TEXT, &data, &size, NULL, 0) != 0) return 0;
    for (s = data; !found && *s; line++) {
        char *t = s + strspn(s, " \t\r");
        if (*t && *t != '\n' && *t != '#' && k-- == 0) found = line;
        s = strchr(s, '\n');
        s = s ? s + 1 : data + size;
    }
    free(data);
    return found;
}

/* The probes' points, before the solve: a malformed --probe-file fails now, and points
 * outside the box of the scene's polygons (they see it from outside: a file in other
 * units, or of another scene) are counted in one warning naming the first. 0 or -1. */
static int read_probes(run_t *r, struct bake_state *b)
{
    const opts_t *o = r->o;
    char err[1024] = "";
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    int i, k, a, out = 0, first = -1;
    if (o->probes) {
        b->npts = o->probe_dims[0] * o->probe_dims[1] * o->probe_dims[2];
        b->pts = pr_grid_points(b->polys, b->n, o->probe_dims);
    } else {
        b->pts = pr_read_points(o->probe_file, &b->npts, err, sizeof err);
    }
    if (!b->pts) {
        fprintf(stderr, PROG ": %s\n", *err ? err : "out of memory for the probes");
        return -1;
    }
    for (i = 0; i < b->n; i++)
        for (k = 0; k < b->polys[i].n; k++)
            for (a = 0; a < 3; a++) {
                lo[a] = fmin(lo[a], b->polys[i].v[k][a]);
                hi[a] = fmax(hi[a], b->polys[i].v[k][a]);
            }
    for (i = 0; i < b->npts; i++) {
        const double *p = &b->pts[3 * i];
        if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] ||
            p[2] > hi[2]) {
            if (!out++) first = i;
        }
    }
    if (out && !o->quiet)
        fprintf(stderr,
                PROG ": warning: %s:%d: %d of %d probes lie outside the scene's bounding box (%g "
                     "%g %g to %g "
                     "%g %g), the first here, %g %g %g: they see the scene from outside\n",
                o->probe_file, probe_line(o->probe_file, first), out, b->npts, lo[0], lo[1], lo[2],
                hi[0], hi[1], hi[2], b->pts[3 * first], b->pts[3 * first + 1],
                b->pts[3 * first + 2]);
    return 0;
}

/* The file's UVs' faults (lm_file_report), each counted in one warning. */
static void file_uv_warnings(const opts_t *o, const lm_file_report *rep)
{
    if (o->quiet) return;
    if (rep->outside)
        fprintf(stderr,
                PROG ": warning: %s: %ld polygon corners have lightmap UVs outside [0, 1]: their "
                     "texels past "
                     "the atlas's edge are lost\n",
                o->scene, rep->outside);
    if (rep->overlap)
        fprintf(stderr,
                PROG
                ": warning: %s: %ld lightmap texels lie inside the UV triangles of two polygons "
                "(overlapping charts): each holds the nearer one's light\n",
                o->scene, rep->overlap);
    if (rep->zero_area)
        fprintf(stderr,
                PROG
                ": warning: %s: %ld triangles have lightmap UVs of no area: they get no texels\n",
                o->scene, rep->zero_area);
    if (rep->missing)
        fprintf(stderr,
                PROG
                ": warning: %s: %ld polygons have no second UV set: they get no lightmap texels\n",
                o->scene, rep->missing);
}

/* The atlas: laid out by the file's second UV set (--lightmap-uv file, or auto when the
 * scene has one and faces have one side) or by rad's charts. 0 or -1. */
static int build_atlas(run_t *r, struct bake_state *b, const lm_opts *lo)
{
    const opts_t *o = r->o;
    char err[1024];
    lm_file_report rep;
    double *uv;
    int rc;
    if (o->lightmap_uv == LIGHTMAP_UV_FILE && (!r->sc.uv2 || o->two_sided)) {
        fprintf(stderr, PROG ": %s: --lightmap-uv file: %s\n", o->scene,
                o->two_sided
                    ? "--two-sided would put both sides of a face on the file's texels (use "
                      "--lightmap-uv rad)"
                    : "the scene has no second UV set (glTF TEXCOORD_1, an FBX's or COLLADA "
                      "file's second channel)");
        return -1;
    }
    if (o->lightmap_uv == LIGHTMAP_UV_RAD || !r->sc.uv2 || o->two_sided)
        rc = lm_build(&b->atlas, b->polys, b->n, lo, err, sizeof err);
    else if (!(uv = lm_poly_file_uvs(&r->sc, b->polys, b->n))) {
        snprintf(err, sizeof err, "out of memory");
        rc = -1;
    } else {
        rc = lm_build_file(&b->atlas, b->polys, b->n, uv, lo, &rep, err, sizeof err);
        free(uv);
        if (rc == 0) file_uv_warnings(o, &rep);
    }
    if (rc < 0) fprintf(stderr, PROG ": %s: %s\n", o->lightmap, err);
    return rc;
}
/* cli_bake_prepare's work, timed into r->t_layout. */
static int prepare(run_t *r);

int cli_bake_prepare(run_t *r)
{
    double t = host_now();
    int rc = prepare(r);
    r->t_layout = host_now() - t;
    return rc;
}

static int prepare(run_t *r)
{
    const opts_t *o = r->o;
    lm_opts lo = {o->lightmap_size ? o->lightmap_size : DEF_LIGHTMAP_SIZE, 0.0,
                  o->lightmap_pad < 0 ? 0
                  : o->lightmap_pad   ? o->lightmap_pad
                                      : -1,
                  o->lightmap_tol, 0.0};
    struct bake_state *b;
    if (!o->lightmap && !o->probes && !o->probe_file) return 0;
    b = r->bake = calloc(1, sizeof *b);
    if (b) b->polys = polys_from_obj(&r->sc, &b->n, NULL, NULL); /* warned of when built */
    if (!b || !b->polys) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    if (o->lightmap && lightmap_memory(o, lo.size) < 0) return -1;
    if (o->lightmap && build_atlas(r, b, &lo) < 0) return -1;
    b->has_atlas = o->lightmap != NULL;
    return o->probes || o->probe_file ? read_probes(r, b) : 0;
}

int cli_bake_step(run_t *r)
{
    const opts_t *o = r->o;
    struct bake_state *b = r->bake;
    int rc = 0, res = o->gather_res ? o->gather_res : DEF_GATHER_RES;
    gather_ctx c = {NULL, r->ambient ? SC_AMBIENT : 0, 0, NULL, 0.0, NULL, NULL, NULL};
    double t = host_now();
    if (!b) return 0;
    if (b->has_atlas) rc = bake_lightmap(r, &b->atlas, res);
    r->t_lightmap = host_now() - t;
    t = host_now();
    if (rc == 0 && (o->probes || o->probe_file)) {
        c.g = sc_gatherer_new(r->s, res, 1);
        rc = c.g ? bake_probes(r, b, &c) : -1;
        if (!c.g) fprintf(stderr, PROG ": out of memory for a gather of resolution %d\n", res);
        sc_gatherer_free(c.g);
    }
    r->t_probes = host_now() - t;
    return rc;
}

int cli_bake_export_gltf(run_t *r, gltf_warn_fn warn)
{
    if (!r->o->gltf || !r->bake || !r->bake->has_atlas) return 0;
    return cli_write_gltf(r, &r->bake->atlas, warn);
}

void cli_bake_free(run_t *r)
{
    if (!r->bake) return;
    if (r->bake->has_atlas) lm_free(&r->bake->atlas);
    free(r->bake->pts);
    free(r->bake->polys);
    free(r->bake);
    r->bake = NULL;
}
