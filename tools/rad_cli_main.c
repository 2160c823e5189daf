/* rad_cli — load an OBJ/MTL scene, solve its radiosity, render views, write images.
 *
 * Built twice from this source: rad_cli (the fixed-point core) and rad_cli_float (the
 * float twin, for comparisons). Exit status: 0 success, 1 runtime or input error, 2 usage.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

#include "image.h"
#include "obj.h"
#include "objpoly.h"
#include "scene.h"

#if defined(RAD_FLOAT) && RAD_FLOAT
#define SC(x) scf_##x
#define PROG "rad_cli_float"
#else
#define SC(x) sc_##x
#define PROG "rad_cli"
#endif

#define MAX_VIEWS 4096

typedef struct {
    int has_cam;
    sc_camera cam;
    const char *out;
} view_t;

typedef struct {
    const char *scene;
    view_t views[MAX_VIEWS];
    int nviews, pending_cam;       /* pending_cam: a --camera still waiting for its -o */
    int width, height, res, max_shots, quiet, stats, list, no_ambient;
    double tol, exposure, max_patch, max_element;
    const char *ply, *csv, *views_file;
    char **emit; int nemit;
} opts_t;

static void usage(FILE *f)
{
    fprintf(f,
        "usage: " PROG " [options] scene.obj\n"
        "Solves the diffuse global illumination of an OBJ/MTL scene (hemi-cube radiosity,\n"
        "progressive refinement) and renders it. Kd is reflectance, Ke emission.\n"
        "\n"
        "output:\n"
        "  -o FILE                 image to write (.png or .ppm); default: scene name + .png\n"
        "  --camera EX,EY,EZ,LX,LY,LZ[,FOV]\n"
        "                          eye, look-at point, vertical field of view (degrees, 45);\n"
        "                          repeat '--camera ... -o FILE' to render many views of one solve\n"
        "  --views FILE            one view a line: EX EY EZ LX LY LZ [FOV] OUTPUT\n"
        "  --width N, --height N   image size (512 x 512)\n"
        "  --exposure X            linear scale before sRGB (default: automatic)\n"
        "  --no-ambient            show the partial solution without the ambient term\n"
        "  --export-ply FILE       the meshed scene with vertex colours (PLY)\n"
        "  --dump-radiosity FILE   one CSV row per element: element,surface,material,area,cx,cy,cz,r,g,b\n"
        "solver:\n"
        "  --res N                 hemi-cube resolution, even, 8..1024 (128)\n"
        "  --max-patch L           longest patch edge (4 x the element edge)\n"
        "  --max-element L         longest element edge (scene extent / 24)\n"
        "  --tol F                 stop when the unshot fraction is below F (0.001)\n"
        "  --max-shots N           stop after N shots (1000000)\n"
        "  --emit NAME=R,G,B       set the emission of material NAME (repeatable)\n"
        "information:\n"
        "  --list-materials        print materials with Kd, Ke and area, then exit\n"
        "  --stats                 print counts, times and memory\n"
        "  --quiet                 no progress or warnings\n"
        "  --help                  this text\n");
}

static void die_usage(const char *msg, const char *arg)
{
    fprintf(stderr, PROG ": %s%s%s\n", msg, arg ? ": " : "", arg ? arg : "");
    usage(stderr);
    exit(2);
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* Parses N comma-separated finite numbers, or N-1 when OPT_LAST is set; anything
 * else (junk, a trailing comma, more values) fails. Returns the count or -1. */
static int parse_list(const char *s, double *v, int n, int opt_last)
{
    int k = 0;
    for (;;) {
        char *end;
        if (k == n) return -1; /* more values than wanted */
        errno = 0;
        v[k] = strtod(s, &end);
        if (end == s || errno || !isfinite(v[k])) return -1;
        k++;
        if (*end == '\0') break;
        if (*end != ',') return -1;
        s = end + 1;
    }
    return (k == n || (opt_last && k == n - 1)) ? k : -1;
}

static long parse_int(const char *opt, const char *s, long lo, long hi)
{
    char *end;
    long v;
    errno = 0;
    v = strtol(s, &end, 10);
    if (end == s || *end || errno || v < lo || v > hi) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s wants a whole number from %ld to %ld", opt, lo, hi);
        die_usage(msg, s);
    }
    return v;
}

static double parse_pos(const char *opt, const char *s)
{
    double v;
    if (parse_list(s, &v, 1, 0) != 1 || !(v > 0)) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s wants a positive number", opt);
        die_usage(msg, s);
    }
    return v;
}

/* A camera from EX,EY,EZ,LX,LY,LZ[,FOV]: up is +y, or -z when looking straight up or
 * down. Fails for a zero view direction or a field of view outside 8..170 degrees. */
static int set_camera(sc_camera *c, const double *v, int k)
{
    double d[3], len2 = 0, side;
    int a;
    for (a = 0; a < 3; a++) {
        c->eye[a] = v[a];
        c->target[a] = v[3 + a];
        d[a] = v[3 + a] - v[a];
        len2 += d[a] * d[a];
    }
    c->fov_deg = k == 7 ? v[6] : 45.0;
    side = d[0] * d[0] + d[2] * d[2]; /* |d x y|^2 */
    c->up[0] = 0;
    c->up[1] = side > 1e-6 * len2 ? 1 : 0;
    c->up[2] = side > 1e-6 * len2 ? 0 : -1;
    return len2 > 0 && c->fov_deg >= 8.0 && c->fov_deg <= 170.0; /* the core's 1/16..16 */
}

static void add_view(opts_t *o, const sc_camera *cam, const char *out)
{
    if (o->nviews >= MAX_VIEWS) die_usage("too many views", NULL);
    o->views[o->nviews].has_cam = cam != NULL;
    if (cam) o->views[o->nviews].cam = *cam;
    o->views[o->nviews].out = out;
    o->nviews++;
}

static void parse_args(int argc, char **argv, opts_t *o)
{
    int i;
    sc_camera pending;
    memset(o, 0, sizeof *o);
    o->width = o->height = 512;
    o->tol = 0.001;
    o->max_shots = 1000000;
    o->emit = calloc((size_t)argc, sizeof *o->emit);
    if (!o->emit) { fprintf(stderr, PROG ": out of memory\n"); exit(1); }
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = NULL;
        int needs = strcmp(a, "-o") == 0 || strcmp(a, "--camera") == 0 || strcmp(a, "--views") == 0 ||
                    strcmp(a, "--width") == 0 || strcmp(a, "--height") == 0 ||
                    strcmp(a, "--exposure") == 0 || strcmp(a, "--export-ply") == 0 ||
                    strcmp(a, "--dump-radiosity") == 0 || strcmp(a, "--res") == 0 ||
                    strcmp(a, "--max-patch") == 0 || strcmp(a, "--max-element") == 0 ||
                    strcmp(a, "--tol") == 0 || strcmp(a, "--max-shots") == 0 || strcmp(a, "--emit") == 0;
        if (needs) {
            if (i + 1 >= argc) die_usage("option needs a value", a);
            val = argv[++i];
        }
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) { usage(stdout); exit(0); }
        else if (strcmp(a, "-o") == 0) {
            add_view(o, o->pending_cam ? &pending : NULL, val);
            o->pending_cam = 0;
        } else if (strcmp(a, "--camera") == 0) {
            double v[7];
            int k = parse_list(val, v, 7, 1);
            if (o->pending_cam) die_usage("--camera without its -o FILE", NULL);
            if (k < 0 || !set_camera(&pending, v, k))
                die_usage("--camera wants EX,EY,EZ,LX,LY,LZ[,FOV], eye and look-at apart, FOV 8..170", val);
            o->pending_cam = 1;
        } else if (strcmp(a, "--views") == 0) o->views_file = val;
        else if (strcmp(a, "--width") == 0) o->width = (int)parse_int(a, val, 1, 2048);
        else if (strcmp(a, "--height") == 0) o->height = (int)parse_int(a, val, 1, 2048);
        else if (strcmp(a, "--exposure") == 0) o->exposure = parse_pos(a, val);
        else if (strcmp(a, "--export-ply") == 0) o->ply = val;
        else if (strcmp(a, "--dump-radiosity") == 0) o->csv = val;
        else if (strcmp(a, "--res") == 0) {
            o->res = (int)parse_int(a, val, 8, 1024);
            if (o->res % 2) die_usage("--res must be even", val);
        } else if (strcmp(a, "--max-patch") == 0) o->max_patch = parse_pos(a, val);
        else if (strcmp(a, "--max-element") == 0) o->max_element = parse_pos(a, val);
        else if (strcmp(a, "--tol") == 0) {
            if (parse_list(val, &o->tol, 1, 0) != 1 || !(o->tol >= 0 && o->tol < 1)) die_usage("--tol wants a number in [0, 1)", val);
        } else if (strcmp(a, "--max-shots") == 0) o->max_shots = (int)parse_int(a, val, 0, 1000000000);
        else if (strcmp(a, "--emit") == 0) {
            const char *eq = strrchr(val, '=');
            double v[3];
            if (!eq || eq == val || parse_list(eq + 1, v, 3, 0) != 3 || v[0] < 0 || v[1] < 0 || v[2] < 0)
                die_usage("--emit wants NAME=R,G,B with R, G, B >= 0", val);
            o->emit[o->nemit++] = (char *)val;
        } else if (strcmp(a, "--list-materials") == 0) o->list = 1;
        else if (strcmp(a, "--stats") == 0) o->stats = 1;
        else if (strcmp(a, "--quiet") == 0) o->quiet = 1;
        else if (strcmp(a, "--no-ambient") == 0) o->no_ambient = 1;
        else if (a[0] == '-' && a[1]) die_usage("unknown option", a);
        else if (o->scene) die_usage("more than one scene given", a);
        else o->scene = a;
    }
    if (!o->scene) die_usage("no scene given", NULL);
    if (o->pending_cam) die_usage("--camera without its -o FILE", NULL);
}

/* ---- output checks, before the solve ------------------------------------------ */

static const char *ext_of(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) ? dot : "";
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
        exit(1);
    }
    if (len >= sizeof dir) len = sizeof dir - 1;
    if (slash) memcpy(dir, path, len ? len : 1);
    dir[slash ? (len ? len : 1) : 0] = '\0';
    if (!slash) strcpy(dir, ".");
    if (access(dir, W_OK) != 0) {
        fprintf(stderr, PROG ": %s: cannot write into '%s': %s\n", path, dir, strerror(errno));
        exit(1);
    }
}

/* ---- loading ------------------------------------------------------------------- */

static void obj_warning(void *ctx, const char *msg)
{
    const opts_t *o = ctx;
    if (!o->quiet) fprintf(stderr, PROG ": warning: %s\n", msg);
}

static void poly_warning(void *ctx, int line, const char *msg)
{
    const opts_t *o = ctx;
    fprintf(stderr, PROG ": warning: %s:%d: %s\n", o->scene, line, msg);
}

static void apply_emit(const opts_t *o, obj_scene *sc)
{
    int i;
    for (i = 0; i < o->nemit; i++) {
        const char *eq = strrchr(o->emit[i], '=');
        char name[512];
        double v[3];
        int m;
        size_t len = (size_t)(eq - o->emit[i]);
        if (len >= sizeof name) len = sizeof name - 1;
        memcpy(name, o->emit[i], len);
        name[len] = '\0';
        parse_list(eq + 1, v, 3, 0);
        m = obj_find_material(sc, name);
        if (m < 0) {
            fprintf(stderr, PROG ": %s: --emit: no material named '%s' (--list-materials shows them)\n", o->scene, name);
            exit(1);
        }
        memcpy(sc->materials[m].ke, v, sizeof v);
    }
}

static void list_materials(const obj_scene *sc)
{
    int i;
    printf("%-24s %-26s %-26s %10s %6s\n", "material", "Kd", "Ke", "area", "faces");
    for (i = 0; i < sc->nmaterials; i++) {
        const obj_material *m = &sc->materials[i];
        char kd[64], ke[64];
        snprintf(kd, sizeof kd, "%.4g %.4g %.4g", m->kd[0], m->kd[1], m->kd[2]);
        snprintf(ke, sizeof ke, "%.4g %.4g %.4g", m->ke[0], m->ke[1], m->ke[2]);
        printf("%-24s %-26s %-26s %10.4g %6d\n", m->name, kd, ke, m->area, m->nfaces);
    }
}

/* ---- views --------------------------------------------------------------------- */

static void default_camera(const obj_scene *sc, int w, int h, sc_camera *c)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double half[3], ctr[3], t = tan(22.5 * 3.14159265358979323846 / 180.0), fit, aspect = (double)w / h;
    int i, a;
    for (i = 0; i < sc->nindices; i++)
        for (a = 0; a < 3; a++) {
            const double *v = &sc->verts[sc->indices[i]].x;
            if (v[a] < lo[a]) lo[a] = v[a];
            if (v[a] > hi[a]) hi[a] = v[a];
        }
    for (a = 0; a < 3; a++) { half[a] = 0.5 * (hi[a] - lo[a]); ctr[a] = 0.5 * (hi[a] + lo[a]); }
    /* Back off along +Z until the box's front face fits the frame, with 5% margin. */
    fit = half[1] > half[0] / aspect ? half[1] : half[0] / aspect;
    for (a = 0; a < 3; a++) { c->eye[a] = ctr[a]; c->target[a] = ctr[a]; c->up[a] = 0; }
    c->eye[2] = ctr[2] + half[2] + 1.05 * fit / t;
    c->up[1] = 1;
    c->fov_deg = 45.0;
}

static void read_views(opts_t *o)
{
    FILE *f = fopen(o->views_file, "r");
    char line[4096];
    int ln = 0;
    if (!f) {
        fprintf(stderr, PROG ": %s: cannot open: %s\n", o->views_file, strerror(errno));
        exit(1);
    }
    while (fgets(line, sizeof line, f)) {
        char *tok[9], *save = NULL, *t;
        double v[7];
        sc_camera c;
        int nt = 0, k;
        ln++;
        for (t = strtok_r(line, " \t\r\n", &save); t && nt < 9; t = strtok_r(NULL, " \t\r\n", &save)) tok[nt++] = t;
        if (nt == 0 || tok[0][0] == '#') continue;
        for (k = 0; k < nt - 1 && nt >= 7 && nt <= 8; k++) {
            char *end;
            v[k] = strtod(tok[k], &end);
            if (*end || !isfinite(v[k])) break;
        }
        if (nt < 7 || nt > 8 || k != nt - 1 || !set_camera(&c, v, nt - 1)) {
            fprintf(stderr, PROG ": %s:%d: expected EX EY EZ LX LY LZ [FOV] OUTPUT\n", o->views_file, ln);
            exit(1);
        }
        add_view(o, &c, strdup(tok[nt - 1]));
    }
    fclose(f);
}

/* ---- outputs ------------------------------------------------------------------- */

static int write_csv(const char *path, SC(solver) *s, const obj_scene *sc, int ambient, const sc_stats *st)
{
    FILE *f = fopen(path, "w");
    int e;
    if (!f) { fprintf(stderr, PROG ": %s: cannot write: %s\n", path, strerror(errno)); return -1; }
    fprintf(f, "element,surface,material,area,cx,cy,cz,r,g,b\n");
    for (e = 0; e < st->elements; e++) {
        double c[3], rgb[3];
        int tag = SC(element_tag)(s, e);
        const char *name = sc->materials[sc->faces[tag].material].name, *q;
        SC(element_centroid)(s, e, c);
        SC(element_rgb)(s, e, ambient, rgb);
        fprintf(f, "%d,%d,\"", e, tag);
        for (q = name; *q; q++) fprintf(f, *q == '"' ? "\"\"" : "%c", *q);
        fprintf(f, "\",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", SC(element_area)(s, e), c[0], c[1], c[2], rgb[0], rgb[1], rgb[2]);
    }
    if (fclose(f) != 0) { fprintf(stderr, PROG ": %s: write failed\n", path); return -1; }
    return 0;
}

static int write_ply(const char *path, SC(solver) *s, int ambient, double exposure, const sc_stats *st)
{
    FILE *f;
    double *rgb = malloc((size_t)(st->vertices ? st->vertices : 1) * 3 * sizeof *rgb);
    int v, e;
    if (!rgb || SC(shade)(s, ambient, rgb) < 0) { free(rgb); fprintf(stderr, PROG ": out of memory\n"); return -1; }
    f = fopen(path, "w");
    if (!f) { free(rgb); fprintf(stderr, PROG ": %s: cannot write: %s\n", path, strerror(errno)); return -1; }
    fprintf(f, "ply\nformat ascii 1.0\ncomment rad radiosity, sRGB vertex colours at exposure %g\n", exposure);
    fprintf(f, "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n", st->vertices);
    fprintf(f, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    fprintf(f, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", st->elements);
    for (v = 0; v < st->vertices; v++) {
        double p[3];
        float lin[3];
        unsigned char c[3];
        SC(vertex_pos)(s, v, p);
        lin[0] = (float)rgb[3 * v]; lin[1] = (float)rgb[3 * v + 1]; lin[2] = (float)rgb[3 * v + 2];
        tonemap(lin, 1, exposure, c);
        fprintf(f, "%.7g %.7g %.7g %u %u %u\n", p[0], p[1], p[2], c[0], c[1], c[2]);
    }
    for (e = 0; e < st->elements; e++) {
        int vi[4], k, n = SC(element_vertices)(s, e, vi);
        fprintf(f, "%d", n);
        for (k = 0; k < n; k++) fprintf(f, " %d", vi[k]);
        fprintf(f, "\n");
    }
    free(rgb);
    if (fclose(f) != 0) { fprintf(stderr, PROG ": %s: write failed\n", path); return -1; }
    return 0;
}

static char *default_output(const char *scene)
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

/* ---- progress ------------------------------------------------------------------ */

typedef struct {
    double start, last, tol;
    int tty;
} progress_t;

static int progress(void *ctx, int shots, double unshot)
{
    progress_t *p = ctx;
    double t = now();
    if (p->tty && t - p->last >= 0.1) {
        /* Progress on a log scale: from 1 (nothing shot) down to the tolerance. */
        double frac = unshot > 0 && p->tol > 0 ? log(unshot) / log(p->tol) : 1.0;
        int bar = frac < 0 ? 0 : frac > 1 ? 30 : (int)(30.0 * frac);
        fprintf(stderr, "\rsolving [%.*s%*s] shots %d  unshot %.5f  %.1fs ", bar,
                "##############################", 30 - bar, "", shots, unshot, t - p->start);
        p->last = t;
    }
    return 0;
}

/* ---- main ---------------------------------------------------------------------- */

int main(int argc, char **argv)
{
    static opts_t o;
    obj_scene sc;
    sc_poly *polys;
    sc_opts so;
    sc_stats st;
    SC(solver) *s;
    progress_t pg;
    char err[1024];
    double t0 = now(), t_load, t_mesh, t_solve, t_render = 0, t_write = 0, exposure = 0;
    int npolys, i, emitters = 0, rc = 0, ambient;
    float *img;
    unsigned char *rgb8;

    parse_args(argc, argv, &o);
    if (o.views_file) read_views(&o);
    if (o.nviews == 0) add_view(&o, NULL, default_output(o.scene));
    if (!o.list) {
        for (i = 0; i < o.nviews; i++) check_output(o.views[i].out, 1);
        if (o.ply) check_output(o.ply, 0);
        if (o.csv) check_output(o.csv, 0);
    }
    ambient = !o.no_ambient;

    if (obj_load(o.scene, &sc, o.quiet ? NULL : obj_warning, &o, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return 1;
    }
    apply_emit(&o, &sc);
    if (o.list) { list_materials(&sc); obj_free(&sc); return 0; }
    if (sc.nfaces == 0) {
        fprintf(stderr, PROG ": %s: the scene has no faces\n", o.scene);
        obj_free(&sc);
        return 1;
    }
    for (i = 0; i < sc.nmaterials; i++)
        if (sc.materials[i].nfaces && (sc.materials[i].ke[0] > 0 || sc.materials[i].ke[1] > 0 || sc.materials[i].ke[2] > 0))
            emitters++;
    if (!emitters && !o.quiet)
        fprintf(stderr, PROG ": warning: %s: no material emits light (Ke), so the image is black; "
                        "set one with --emit NAME=R,G,B (--list-materials shows them)\n", o.scene);
    polys = obj_to_polys(&sc, &npolys, o.quiet ? NULL : poly_warning, &o);
    if (!polys) { fprintf(stderr, PROG ": out of memory\n"); obj_free(&sc); return 1; }
    t_load = now();

    memset(&so, 0, sizeof so);
    so.max_patch = o.max_patch;
    so.max_element = o.max_element;
    so.res = o.res ? o.res : 128; /* 64 aliases visibly on elements a few pixels wide */
    s = SC(create)(polys, npolys, &so, NULL, NULL, err, sizeof err);
    free(polys);
    if (!s) {
        fprintf(stderr, PROG ": %s: %s\n", o.scene, err);
        obj_free(&sc);
        return 1;
    }
    t_mesh = now();

    pg.start = pg.last = now();
    pg.last -= 1.0;
    pg.tty = !o.quiet && isatty(2);
    pg.tol = o.tol;
    SC(solve)(s, o.max_shots, o.tol, pg.tty ? progress : NULL, &pg);
    if (pg.tty) fprintf(stderr, "\r%70s\r", "");
    t_solve = now();
    SC(get_stats)(s, &st);

    img = malloc((size_t)o.width * o.height * 3 * sizeof *img);
    rgb8 = malloc((size_t)o.width * o.height * 3);
    if (!img || !rgb8) { fprintf(stderr, PROG ": out of memory\n"); rc = 1; }
    for (i = 0; rc == 0 && i < o.nviews; i++) {
        sc_camera cam;
        double t1 = now();
        if (o.views[i].has_cam) cam = o.views[i].cam;
        else default_camera(&sc, o.width, o.height, &cam);
        if (SC(render)(s, &cam, ambient, o.width, o.height, img, err, sizeof err) < 0) {
            fprintf(stderr, PROG ": %s: %s\n", o.views[i].out, err);
            rc = 1;
            break;
        }
        /* One exposure for every output, from the first view, so views match. */
        if (i == 0) exposure = o.exposure > 0 ? o.exposure : tonemap_auto_exposure(img, (size_t)o.width * o.height);
        tonemap(img, (size_t)o.width * o.height, exposure, rgb8);
        t_render += now() - t1;
        t1 = now();
        if (img_write(o.views[i].out, rgb8, o.width, o.height, err, sizeof err) < 0) {
            fprintf(stderr, PROG ": %s\n", err);
            rc = 1;
        }
        t_write += now() - t1;
    }
    if (rc == 0 && o.csv && write_csv(o.csv, s, &sc, ambient, &st) < 0) rc = 1;
    if (rc == 0 && o.ply && write_ply(o.ply, s, ambient, exposure, &st) < 0) rc = 1;

    if (o.stats) {
        printf("surfaces %d (split quads %d, skipped %d, reflectances clamped %d)\n", st.surfaces, st.split, st.skipped, st.clamped);
        printf("patches %d  elements %d  vertices %d\n", st.patches, st.elements, st.vertices);
        printf("shots %d  unshot fraction %.6f  saturations %lu\n", st.shots, st.unshot, st.saturations);
        printf("hemi-cube: resolution %d, %lu polygons, %llu pixels\n", so.res, st.raster_calls, st.raster_pixels);
        printf("unknown statements skipped %ld, warnings %ld\n", sc.unknown_statements, sc.nwarnings);
        printf("time: load %.3fs  mesh %.3fs  solve %.3fs  render %.3fs  write %.3fs\n", t_load - t0,
               t_mesh - t_load, t_solve - t_mesh, t_render, t_write);
        printf("memory: pools %zu bytes, work buffer %zu bytes\n", st.pool_bytes, st.work_bytes);
    }
    free(img);
    free(rgb8);
    SC(destroy)(s);
    obj_free(&sc);
    return rc;
}
