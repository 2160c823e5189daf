/* SPDX-License-Identifier: MIT */
/* rad_cli's outputs: images of the views, the PLY mesh, the CSV of elements; every
 * output name checked before the solve.
 */
#include "cli.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "formats/file_io.h"
#include "formats/image.h"
#include "host/clock.h"
#include "host/ply_export.h"
#include "host/tex_render.h"
#include "progress.h"

const char *cli_ext_of(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) ? dot : "";
}

char *cli_insert_name(const char *path, const char *sep, const char *mid)
{
    const char *ext = cli_ext_of(path);
    size_t base = (size_t)(ext - path);
    char *out = malloc(strlen(path) + strlen(sep) + strlen(mid) + 1);
    if (!out) {
        fprintf(stderr, PROG ": out of memory\n");
        exit(CLI_EXIT_ERROR);
    }
    memcpy(out, path, base);
    strcpy(out + base, sep);
    strcat(out, mid);
    strcat(out, ext);
    return out;
}

char *cli_frame_name(const opts_t *o, int i)
{
    char num[32];
    snprintf(num, sizeof num, "%04d", i);
    return cli_insert_name(o->views[0].out, "_", num);
}

char *cli_default_output(const char *scene)
{
    const char *base = strrchr(scene, '/');
    const char *dot;
    char *out;
    size_t len;
    base = base ? base + 1 : scene;
    dot = strrchr(base, '.');
    len = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    out = malloc(len + 5);
    if (!out) return NULL;
    memcpy(out, base, len);
    memcpy(out + len, ".png", 5);
    return out;
}

/* The image format for PATH: by its extension, .png or .ppm; a name without one under
 * /dev/ or /proc/self/fd/ (-o /dev/stdout, whatever standard output is), or that is a
 * device or a FIFO now, gets PNG: file_io writes those in place, through their own
 * descriptor, so there is no name to tell the format by. Anything else: NULL. */
static const char *image_format(const char *path)
{
    struct stat st;
    if (strcasecmp(cli_ext_of(path), ".png") == 0) return "png";
    if (strcasecmp(cli_ext_of(path), ".ppm") == 0) return "ppm";
    if (strncmp(path, "/dev/", 5) == 0 || strncmp(path, "/proc/self/fd/", 14) == 0) return "png";
    if (stat(path, &st) == 0 && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode))) return "png";
    return NULL;
}

/* Fails early (exit 1) when PATH could not be written after a long solve (fio_check_out:
 * a folder that does not exist or is not writable, a directory, a name too long for its
 * temporary file) or, for images, has an unknown extension. */
static void check_output(const char *path, int image)
{
    char err[1024];
    if (image && !image_format(path)) {
        fprintf(stderr, PROG ": %s: unknown image extension (use .png or .ppm)\n", path);
        exit(CLI_EXIT_ERROR);
    }
    if (fio_check_out(path, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        exit(CLI_EXIT_ERROR);
    }
}

void cli_check_outputs(const opts_t *o)
{
    int i;
    for (i = 0; i < o->nviews; i++) check_output(o->views[i].out, 1);
    if (o->ply) check_output(o->ply, 0);
    if (o->csv) check_output(o->csv, 0);
    if (o->gltf) check_output(o->gltf, 0);
    if (o->save_ff) check_output(o->save_ff, 0);
    if (o->lightmap) check_output(o->lightmap, 0);
    if (o->probes_out) check_output(o->probes_out, 0);
}

void cli_check_group_outputs(const opts_t *o)
{
    int i, g;
    for (i = 0; o->animate && i < o->nframes; i++) {
        char *path = cli_frame_name(o, i);
        check_output(path, 1);
        free(path);
    }
    for (g = 0; o->each_group && g < o->ngroups; g++)
        for (i = 0; i < o->nviews; i++) {
            char *path = cli_insert_name(o->views[i].out, ".", o->groups[g].name);
            check_output(path, 1);
            free(path);
        }
}

static int gcd(int a, int b)
{
    while (b) {
        int t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* CAM at the shape of the run's images (their sides divided by their gcd, or at full
 * size when that is still large: the core's checks depend on the aspect). */
static int try_camera(sc_solver *s, const opts_t *o, const sc_camera *cam, const char *name,
                      float *buf)
{
    char err[1024];
    int g = gcd(o->width, o->height), w = o->width / g, h = o->height / g;
    if ((long)w * h > 256L * 256L) {
        w = o->width;
        h = o->height;
    }
    if (sc_render(s, cam, 0, w, h, buf, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s: %s\n", name, err);
        return -1;
    }
    return 0;
}

int cli_check_cameras(sc_solver *s, const opts_t *o)
{
    float *buf = malloc((size_t)o->width * o->height * 3 * sizeof *buf);
    int i, rc = buf ? 0 : -1;
    if (!buf) fprintf(stderr, PROG ": out of memory\n");
    for (i = 0; rc == 0 && !o->animate && i < o->nviews; i++)
        rc = try_camera(s, o, &o->views[i].cam, o->views[i].out, buf);
    for (i = 0; rc == 0 && o->animate && i < o->nframes; i++) {
        char *path = cli_frame_name(o, i);
        rc = try_camera(s, o, &o->frames[i].cam, path, buf);
        free(path);
    }
    free(buf);
    return rc;
}

int cli_render_view(sc_solver *s, const opts_t *o, const sc_camera *cam, const char *path,
                    int ambient, out_t *ot)
{
    char err[1024];
    double t1 = host_now();
    size_t npix = (size_t)o->width * o->height;
    int rc;
    if (ot->fg) {
        progress_t pg;
        progress_begin(&pg, "gathering the view", o->quiet);
        sc_fgather_progress(ot->fg, progress_fraction, &pg);
        rc = sc_fgather_render(ot->fg, cam, o->width, o->height, ot->img, &ot->gathers, err,
                               sizeof err);
        sc_fgather_progress(ot->fg, NULL, NULL);
        progress_end(&pg);
        if (rc == 0 && ot->maps)
            rc = sc_texture_detail(s, ot->sc, ot->maps, cam, o->width, o->height, ot->img, err,
                                   sizeof err);
    } else if (ot->maps) {
        rc = sc_render_textured(s, ot->sc, ot->maps, cam, ambient, o->width, o->height, ot->img,
                                err, sizeof err);
    } else {
        rc = sc_render(s, cam, ambient, o->width, o->height, ot->img, err, sizeof err);
    }
    if (rc < 0) {
        fprintf(stderr, PROG ": %s: %s\n", path ? path : o->views[0].out, err);
        return -1;
    }
    if (ot->exposure <= 0)
        ot->exposure = o->exposure > 0 ? o->exposure : tonemap_auto_exposure(ot->img, npix);
    tonemap(ot->img, npix, ot->exposure, ot->rgb8);
    ot->t_render += host_now() - t1;
    t1 = host_now();
    fflush(stdout); /* what was printed comes before an image sent to /dev/stdout */
    if (path && img_write_as(path, image_format(path), ot->rgb8, o->width, o->height, err,
                             sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    ot->t_write += host_now() - t1;
    return 0;
}

static unsigned long ambient_terms(sc_solver *s)
{
    sc_stats st;
    sc_get_stats(s, &st);
    return st.ambient_terms;
}

/* The rows, the radiosities from sc_shade_elements (RGB, 3 an element). */
static void csv_rows(FILE *f, sc_solver *s, const obj_scene *sc, const double *rgb,
                     const sc_stats *st)
{
    int e;
    fprintf(f, "element,surface,material,area,cx,cy,cz,r,g,b\n");
    for (e = 0; e < st->elements; e++) {
        double c[3];
        int tag = sc_element_tag(s, e);
        const char *name = sc->materials[sc->faces[tag].material].name, *q;
        sc_element_centroid(s, e, c);
        fprintf(f, "%d,%d,\"", e, tag);
        for (q = name; *q; q++) fprintf(f, *q == '"' ? "\"\"" : "%c", *q);
        fprintf(f, "\",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", sc_element_area(s, e), c[0], c[1],
                c[2], rgb[3 * e], rgb[3 * e + 1], rgb[3 * e + 2]);
    }
}

/* PATH through fio_out: written to a temporary file, committed (checked, synced,
 * renamed) only if every write succeeded; on error the old file is intact. */
static FILE *out_open(const char *path, fio_out **fo)
{
    char err[1024];
    *fo = fio_out_open(path, err, sizeof err);
    if (!*fo) {
        fprintf(stderr, PROG ": %s\n", err);
        return NULL;
    }
    return fio_out_stream(*fo);
}

static int out_commit(fio_out *fo)
{
    char err[1024];
    if (fio_out_commit(fo, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    return 0;
}

int cli_write_csv(const char *path, sc_solver *s, const obj_scene *sc, int ambient,
                  const sc_stats *st, out_t *ot)
{
    double t = host_now();
    unsigned long before = ambient_terms(s);
    fio_out *fo;
    FILE *f;
    double *rgb = malloc(((size_t)st->elements + 1) * 3 * sizeof *rgb);
    int rc = -1;
    if (!rgb || sc_shade_elements(s, ambient, rgb) != 0)
        fprintf(stderr, PROG ": %s: out of memory\n", path);
    else if ((f = out_open(path, &fo)) != NULL) {
        csv_rows(f, s, sc, rgb, st);
        rc = out_commit(fo);
    }
    free(rgb);
    ot->t_csv += host_now() - t;
    ot->export_ambient += ambient_terms(s) - before;
    return rc;
}

int cli_write_gltf(run_t *r, const lm_atlas *lm, gltf_warn_fn warn)
{
    char err[1024];
    progress_t pg;
    unsigned long before = ambient_terms(r->s);
    int rc;
    progress_begin(&pg, "writing glTF", r->o->quiet);
    rc = sc_export_gltf_lightmap(r->s, &r->sc, r->polys, r->npolys, r->ot.maps, r->ot.fg, lm,
                                 &r->ot.gltf_scale, r->o->gltf, warn, (void *)r->o,
                                 progress_fraction, &pg, err, sizeof err);
    if (rc < 0) fprintf(stderr, PROG ": %s\n", err);
    r->ot.t_gltf += progress_end(&pg);
    r->ot.export_ambient += ambient_terms(r->s) - before;
    return rc < 0 ? -1 : 0;
}

void cli_print_export_stats(const opts_t *o, const out_t *ot)
{
    if (!o->csv && !o->gltf) return;
    printf("exports:");
    if (o->gltf) printf("  COLOR_0 scale %.6g", ot->gltf_scale);
    printf("  ambient term computed %lu times (their times: the time line)\n", ot->export_ambient);
}

/* The vertex colours are sc_vertex_colours': each core vertex's radiosity (Gouraud), or
 * gathered with FG. */
int cli_write_ply(const char *path, sc_solver *s, sc_fgather *fg, int ambient, int linear,
                  double exposure, const sc_stats *st)
{
    char err[1024];
    int rc = -1;
    double *rgb = malloc((size_t)(st->vertices ? st->vertices : 1) * 3 * sizeof *rgb);
    if (!rgb || sc_vertex_colours(s, fg, ambient, rgb) < 0)
        fprintf(stderr, PROG ": out of memory\n");
    else if ((rc = sc_export_ply(s, rgb, path, linear ? PLY_BINARY_LINEAR : PLY_ASCII_SRGB,
                                 exposure, err, sizeof err)) < 0)
        fprintf(stderr, PROG ": %s\n", err);
    free(rgb);
    return rc < 0 ? -1 : 0;
}
