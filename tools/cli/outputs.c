/* rad_cli's outputs: images of the views, the PLY mesh, the CSV of elements; every
 * output name checked before the solve.
 */
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "formats/image.h"
#include "host/clock.h"

const char *ext_of(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) ? dot : "";
}

char *insert_name(const char *path, const char *sep, const char *mid)
{
    const char *ext = ext_of(path);
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

char *default_output(const char *scene)
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

/* Fails early (exit 1) when PATH could not be written after a long solve: a folder
 * that does not exist or is not writable, or (for images) an unknown extension. */
static void check_output(const char *path, int image)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    size_t len = slash ? (size_t)(slash - path) : 0;
    if (image && strcasecmp(ext_of(path), ".png") != 0 && strcasecmp(ext_of(path), ".ppm") != 0) {
        fprintf(stderr, PROG ": %s: unknown image extension (use .png or .ppm)\n", path);
        exit(CLI_EXIT_ERROR);
    }
    if (len >= sizeof dir) len = sizeof dir - 1;
    if (slash) memcpy(dir, path, len ? len : 1);
    dir[slash ? (len ? len : 1) : 0] = '\0';
    if (!slash) strcpy(dir, ".");
    if (access(dir, W_OK) != 0) {
        fprintf(stderr, PROG ": %s: cannot write into '%s': %s\n", path, dir, strerror(errno));
        exit(CLI_EXIT_ERROR);
    }
}

void check_outputs(const opts_t *o)
{
    int i;
    for (i = 0; i < o->nviews; i++) check_output(o->views[i].out, 1);
    if (o->ply) check_output(o->ply, 0);
    if (o->csv) check_output(o->csv, 0);
    if (o->save_ff) check_output(o->save_ff, 0);
}

int render_view(sc_solver *s, const opts_t *o, const sc_camera *cam, const char *path, int ambient, out_t *ot)
{
    char err[1024];
    double t1 = host_now();
    size_t npix = (size_t)o->width * o->height;
    if (sc_render(s, cam, ambient, o->width, o->height, ot->img, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s: %s\n", path ? path : o->views[0].out, err);
        return -1;
    }
    if (ot->exposure <= 0) ot->exposure = o->exposure > 0 ? o->exposure : tonemap_auto_exposure(ot->img, npix);
    tonemap(ot->img, npix, ot->exposure, ot->rgb8);
    ot->t_render += host_now() - t1;
    t1 = host_now();
    if (path && img_write(path, ot->rgb8, o->width, o->height, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    ot->t_write += host_now() - t1;
    return 0;
}

static void csv_rows(FILE *f, sc_solver *s, const obj_scene *sc, int ambient, const sc_stats *st)
{
    int e;
    fprintf(f, "element,surface,material,area,cx,cy,cz,r,g,b\n");
    for (e = 0; e < st->elements; e++) {
        double c[3], rgb[3];
        int tag = sc_element_tag(s, e);
        const char *name = sc->materials[sc->faces[tag].material].name, *q;
        sc_element_centroid(s, e, c);
        sc_element_rgb(s, e, ambient, rgb);
        fprintf(f, "%d,%d,\"", e, tag);
        for (q = name; *q; q++) fprintf(f, *q == '"' ? "\"\"" : "%c", *q);
        fprintf(f, "\",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", sc_element_area(s, e), c[0], c[1], c[2], rgb[0], rgb[1],
                rgb[2]);
    }
}

int write_csv(const char *path, sc_solver *s, const obj_scene *sc, int ambient, const sc_stats *st)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, PROG ": %s: cannot write: %s\n", path, strerror(errno));
        return -1;
    }
    csv_rows(f, s, sc, ambient, st);
    if (fclose(f) != 0) {
        fprintf(stderr, PROG ": %s: write failed\n", path);
        return -1;
    }
    return 0;
}

static void ply_body(FILE *f, sc_solver *s, const double *rgb, double exposure, const sc_stats *st)
{
    int v, e;
    fprintf(f, "ply\nformat ascii 1.0\ncomment rad radiosity, sRGB vertex colours at exposure %g\n", exposure);
    fprintf(f, "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n", st->vertices);
    fprintf(f, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    fprintf(f, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", st->elements);
    for (v = 0; v < st->vertices; v++) {
        double p[3];
        float lin[3];
        unsigned char c[3];
        sc_vertex_pos(s, v, p);
        lin[0] = (float)rgb[3 * v];
        lin[1] = (float)rgb[3 * v + 1];
        lin[2] = (float)rgb[3 * v + 2];
        tonemap(lin, 1, exposure, c);
        fprintf(f, "%.7g %.7g %.7g %u %u %u\n", p[0], p[1], p[2], c[0], c[1], c[2]);
    }
    for (e = 0; e < st->elements; e++) {
        int vi[4], k, n = sc_element_vertices(s, e, vi);
        fprintf(f, "%d", n);
        for (k = 0; k < n; k++) fprintf(f, " %d", vi[k]);
        fprintf(f, "\n");
    }
}

int write_ply(const char *path, sc_solver *s, int ambient, double exposure, const sc_stats *st)
{
    FILE *f;
    double *rgb = malloc((size_t)(st->vertices ? st->vertices : 1) * 3 * sizeof *rgb);
    if (!rgb || sc_shade(s, ambient, rgb) < 0) {
        free(rgb);
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    f = fopen(path, "w");
    if (!f) {
        free(rgb);
        fprintf(stderr, PROG ": %s: cannot write: %s\n", path, strerror(errno));
        return -1;
    }
    ply_body(f, s, rgb, exposure, st);
    free(rgb);
    if (fclose(f) != 0) {
        fprintf(stderr, PROG ": %s: write failed\n", path);
        return -1;
    }
    return 0;
}
