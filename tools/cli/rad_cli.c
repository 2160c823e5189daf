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

#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#define PROG "rad_cli_float"
#else
#define PROG "rad_cli"
#endif
#include "formats/ff_file.h"
#include "formats/image.h"
#include "formats/obj.h"
#include "host/obj_polys.h"
#include "host/parallel.h"
#include "host/scene.h"

#define MAX_VIEWS 4096
#define MAX_GROUP_NAME 64
#define GS_MAX_SWEEPS 1000

typedef struct {
    int has_cam;
    sc_camera cam;
    const char *out;
} view_t;

/* A light group: emitting materials solved together, mixed with an intensity. */
typedef struct {
    char name[MAX_GROUP_NAME];
    const char *mats;              /* "MAT1,MAT2,..." as given */
    double k[3];                   /* --group-intensity (1,1,1) */
} group_t;

typedef struct {
    sc_camera cam;
    double (*k)[3];                /* intensity of every group in this frame */
} frame_t;

typedef struct {
    const char *scene;
    view_t views[MAX_VIEWS];
    int nviews, pending_cam;       /* pending_cam: a --camera still waiting for its -o */
    int width, height, res, max_shots, threads, quiet, stats, list, no_ambient, no_overshoot;
    double tol, exposure, max_patch, max_element;
    const char *ply, *csv, *views_file;
    char **emit; int nemit;
    /* stored form factors and relighting */
    const char *save_ff, *load_ff, *animate;
    int gauss_seidel, each_group, ncams;
    group_t *groups; int ngroups;  /* --light-group, then "other" once the scene is known */
    int nuser_groups;
    char **gint; int ngint;        /* --group-intensity as given */
    frame_t *frames; int nframes;
} opts_t;

#define OTHER_GROUP "other"

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
        "  --threads N             render each shot's hemi-cube on N threads, same result (1)\n"
        "  --no-overshoot          shoot only the unshot power (Cohen et al. 1988); by default\n"
        "                          each shot adds the power expected back (fewer shots)\n"
        "  --emit NAME=R,G,B       set the emission of material NAME (repeatable)\n"
        "stored form factors (every patch's hemi-cube row, computed once; relighting renders\n"
        "no hemi-cube):\n"
        "  --save-ff FILE          compute all rows, save them to FILE, solve from them\n"
        "  --load-ff FILE          load rows saved for this scene and settings (same build,\n"
        "                          --max-element, --max-patch, --res), solve from them\n"
        "  --solver shoot|gauss-seidel\n"
        "                          progressive refinement (default) or the full-matrix\n"
        "                          Gauss-Seidel solve (needs rows: computed if not loaded;\n"
        "                          --tol: stop when no patch changes by more than F of itself)\n"
        "  --light-group NAME=MAT1,MAT2,...\n"
        "                          a group of emitting materials (repeatable); emitters in no\n"
        "                          group form the group 'other'; each group is solved once\n"
        "                          from the rows and the image mixes them\n"
        "  --group-intensity NAME=R,G,B\n"
        "                          a group's intensity in the mix (1,1,1)\n"
        "  --each-group            one image per group (group name before the extension:\n"
        "                          out.png -> out.NAME.png), at the exposure of the whole mix\n"
        "  --animate FILE          frames from one visibility computation: each line\n"
        "                          'EX EY EZ LX LY LZ [FOV] [GROUP=R,G,B ...]' is a frame,\n"
        "                          written as -o's name + _0000, _0001, ... (PNG or PPM)\n"
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

/* A group or material list name: letters, digits, '_' and '-' (it goes into file names). */
static int good_group_name(const char *s, size_t len)
{
    size_t i;
    if (len == 0 || len >= MAX_GROUP_NAME) return 0;
    for (i = 0; i < len; i++)
        if (!((s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' && s[i] <= 'Z') || (s[i] >= '0' && s[i] <= '9') ||
              s[i] == '_' || s[i] == '-'))
            return 0;
    return 1;
}

static group_t *find_group(opts_t *o, const char *name, size_t len)
{
    int g;
    for (g = 0; g < o->ngroups; g++)
        if (strlen(o->groups[g].name) == len && strncmp(o->groups[g].name, name, len) == 0) return &o->groups[g];
    return NULL;
}

/* --light-group NAME=MAT1,MAT2,...: checked here, materials resolved with the scene. */
static void add_group(opts_t *o, const char *val)
{
    const char *eq = strchr(val, '='), *p;
    group_t *g;
    size_t len;
    if (!eq || !good_group_name(val, (size_t)(eq - val)))
        die_usage("--light-group wants NAME=MAT1,MAT2,... with NAME of letters, digits, '_', '-' (up to 63)", val);
    len = (size_t)(eq - val);
    if (len == strlen(OTHER_GROUP) && strncmp(val, OTHER_GROUP, len) == 0)
        die_usage("--light-group: 'other' is the group of the emitters in no group; choose another name", val);
    if (find_group(o, val, len)) die_usage("--light-group: a group name given twice", val);
    for (p = eq + 1;; p++) /* no empty material names: "a,,b", ",a", "a," */
        if ((*p == ',' || *p == '\0') && (p == eq + 1 || p[-1] == ',')) die_usage("--light-group: an empty material name", val);
        else if (*p == '\0') break;
    g = &o->groups[o->ngroups++];
    memcpy(g->name, val, len);
    g->name[len] = '\0';
    g->mats = eq + 1;
    g->k[0] = g->k[1] = g->k[2] = 1.0;
    o->nuser_groups = o->ngroups;
}

/* --group-intensity for the groups given; "other" waits for the scene. */
static void resolve_intensities(opts_t *o)
{
    int i, j;
    for (i = 0; i < o->ngint; i++) {
        const char *eq = strrchr(o->gint[i], '=');
        size_t len = (size_t)(eq - o->gint[i]);
        group_t *g = find_group(o, o->gint[i], len);
        for (j = 0; j < i; j++)
            if (strncmp(o->gint[j], o->gint[i], len + 1) == 0) die_usage("--group-intensity: a group given twice", o->gint[i]);
        if (!g && !(len == strlen(OTHER_GROUP) && strncmp(o->gint[i], OTHER_GROUP, len) == 0))
            die_usage("--group-intensity: no --light-group of that name (or 'other')", o->gint[i]);
        if (g) {
            parse_list(eq + 1, g->k, 3, 0);
        }
    }
}

static void parse_args(int argc, char **argv, opts_t *o)
{
    int i;
    sc_camera pending;
    memset(o, 0, sizeof *o);
    o->width = o->height = 512;
    o->tol = 0.001;
    o->max_shots = 1000000;
    o->threads = 1;
    o->emit = calloc((size_t)argc, sizeof *o->emit);
    o->groups = calloc((size_t)argc + 1, sizeof *o->groups);
    o->gint = calloc((size_t)argc, sizeof *o->gint);
    if (!o->emit || !o->groups || !o->gint) { fprintf(stderr, PROG ": out of memory\n"); exit(1); }
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = NULL;
        int needs = strcmp(a, "-o") == 0 || strcmp(a, "--camera") == 0 || strcmp(a, "--views") == 0 ||
                    strcmp(a, "--width") == 0 || strcmp(a, "--height") == 0 ||
                    strcmp(a, "--exposure") == 0 || strcmp(a, "--export-ply") == 0 ||
                    strcmp(a, "--dump-radiosity") == 0 || strcmp(a, "--res") == 0 ||
                    strcmp(a, "--max-patch") == 0 || strcmp(a, "--max-element") == 0 ||
                    strcmp(a, "--tol") == 0 || strcmp(a, "--max-shots") == 0 || strcmp(a, "--emit") == 0 ||
                    strcmp(a, "--threads") == 0 ||
                    strcmp(a, "--save-ff") == 0 || strcmp(a, "--load-ff") == 0 || strcmp(a, "--solver") == 0 ||
                    strcmp(a, "--light-group") == 0 || strcmp(a, "--group-intensity") == 0 ||
                    strcmp(a, "--animate") == 0;
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
            o->ncams++;
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
        else if (strcmp(a, "--threads") == 0) o->threads = (int)parse_int(a, val, 1, 64);
        else if (strcmp(a, "--emit") == 0) {
            const char *eq = strrchr(val, '=');
            double v[3];
            if (!eq || eq == val || parse_list(eq + 1, v, 3, 0) != 3 || v[0] < 0 || v[1] < 0 || v[2] < 0)
                die_usage("--emit wants NAME=R,G,B with R, G, B >= 0", val);
            o->emit[o->nemit++] = (char *)val;
        } else if (strcmp(a, "--save-ff") == 0) o->save_ff = val;
        else if (strcmp(a, "--load-ff") == 0) o->load_ff = val;
        else if (strcmp(a, "--animate") == 0) o->animate = val;
        else if (strcmp(a, "--solver") == 0) {
            if (strcmp(val, "shoot") == 0) o->gauss_seidel = 0;
            else if (strcmp(val, "gauss-seidel") == 0) o->gauss_seidel = 1;
            else die_usage("--solver wants shoot or gauss-seidel", val);
        } else if (strcmp(a, "--light-group") == 0) add_group(o, val);
        else if (strcmp(a, "--group-intensity") == 0) {
            const char *eq = strrchr(val, '=');
            double v[3];
            if (!eq || eq == val || parse_list(eq + 1, v, 3, 0) != 3 || !(v[0] >= 0 && v[1] >= 0 && v[2] >= 0) ||
                v[0] >= 32768 || v[1] >= 32768 || v[2] >= 32768)
                die_usage("--group-intensity wants NAME=R,G,B with R, G, B in [0, 32768)", val);
            o->gint[o->ngint++] = (char *)val;
        } else if (strcmp(a, "--each-group") == 0) o->each_group = 1;
        else if (strcmp(a, "--list-materials") == 0) o->list = 1;
        else if (strcmp(a, "--stats") == 0) o->stats = 1;
        else if (strcmp(a, "--quiet") == 0) o->quiet = 1;
        else if (strcmp(a, "--no-ambient") == 0) o->no_ambient = 1;
        else if (strcmp(a, "--no-overshoot") == 0) o->no_overshoot = 1;
        else if (a[0] == '-' && a[1]) die_usage("unknown option", a);
        else if (o->scene) die_usage("more than one scene given", a);
        else o->scene = a;
    }
    if (!o->scene) die_usage("no scene given", NULL);
    if (o->pending_cam) die_usage("--camera without its -o FILE", NULL);
    if (o->save_ff && o->load_ff) die_usage("--save-ff and --load-ff exclude each other", NULL);
    if (o->each_group && o->nuser_groups == 0) die_usage("--each-group needs at least one --light-group", NULL);
    if (o->animate) {
        if (o->ncams || o->views_file) die_usage("--animate takes its cameras from its file: no --camera or --views", NULL);
        if (o->nviews > 1) die_usage("--animate writes frames from one -o name", NULL);
        if (o->each_group) die_usage("--animate and --each-group exclude each other", NULL);
    }
    resolve_intensities(o);
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

/* The glue's warnings name a polygon by its tag, the OBJ face index: shown as its line. */
typedef struct { const opts_t *o; const obj_scene *sc; } glue_ctx_t;
static void glue_warning(void *ctx, int tag, const char *msg)
{
    const glue_ctx_t *g = ctx;
    fprintf(stderr, PROG ": warning: %s:%d: %s\n", g->o->scene,
            tag >= 0 && tag < g->sc->nfaces ? g->sc->faces[tag].line : 0, msg);
}

/* A solve that stopped short of its tolerance, or clipped values, says so. */
static void solve_warnings(const opts_t *o, const sc_stats *st)
{
    if (o->quiet) return;
    if (st->solved && !st->converged)
        fprintf(stderr, PROG ": warning: %s: not converged: unshot fraction %.3g after %d shots, tolerance %g "
                        "(raise --max-shots, or --no-overshoot)\n", o->scene, st->unshot, st->shots, st->tol);
    if (st->saturations)
        fprintf(stderr, PROG ": warning: %s: %lu values saturated (beyond the core's range): the result is clipped\n",
                o->scene, st->saturations);
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

static int write_csv(const char *path, sc_solver *s, const obj_scene *sc, int ambient, const sc_stats *st)
{
    FILE *f = fopen(path, "w");
    int e;
    if (!f) { fprintf(stderr, PROG ": %s: cannot write: %s\n", path, strerror(errno)); return -1; }
    fprintf(f, "element,surface,material,area,cx,cy,cz,r,g,b\n");
    for (e = 0; e < st->elements; e++) {
        double c[3], rgb[3];
        int tag = sc_element_tag(s, e);
        const char *name = sc->materials[sc->faces[tag].material].name, *q;
        sc_element_centroid(s, e, c);
        sc_element_rgb(s, e, ambient, rgb);
        fprintf(f, "%d,%d,\"", e, tag);
        for (q = name; *q; q++) fprintf(f, *q == '"' ? "\"\"" : "%c", *q);
        fprintf(f, "\",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", sc_element_area(s, e), c[0], c[1], c[2], rgb[0], rgb[1], rgb[2]);
    }
    if (fclose(f) != 0) { fprintf(stderr, PROG ": %s: write failed\n", path); return -1; }
    return 0;
}

static int write_ply(const char *path, sc_solver *s, int ambient, double exposure, const sc_stats *st)
{
    FILE *f;
    double *rgb = malloc((size_t)(st->vertices ? st->vertices : 1) * 3 * sizeof *rgb);
    int v, e;
    if (!rgb || sc_shade(s, ambient, rgb) < 0) { free(rgb); fprintf(stderr, PROG ": out of memory\n"); return -1; }
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
        sc_vertex_pos(s, v, p);
        lin[0] = (float)rgb[3 * v]; lin[1] = (float)rgb[3 * v + 1]; lin[2] = (float)rgb[3 * v + 2];
        tonemap(lin, 1, exposure, c);
        fprintf(f, "%.7g %.7g %.7g %u %u %u\n", p[0], p[1], p[2], c[0], c[1], c[2]);
    }
    for (e = 0; e < st->elements; e++) {
        int vi[4], k, n = sc_element_vertices(s, e, vi);
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

/* ---- light groups and animation ------------------------------------------------ */

static int emits(const obj_material *m)
{
    return m->nfaces > 0 && (m->ke[0] > 0 || m->ke[1] > 0 || m->ke[2] > 0);
}

/* Material -> group (-1: none, or it emits nothing), after --emit. Adds the group
 * "other" for emitting materials in no group, and applies its --group-intensity. */
static int *resolve_groups(opts_t *o, const obj_scene *sc)
{
    int *of = malloc((size_t)(sc->nmaterials ? sc->nmaterials : 1) * sizeof *of), g, m, i, other = 0;
    if (!of) { fprintf(stderr, PROG ": out of memory\n"); exit(1); }
    for (m = 0; m < sc->nmaterials; m++) of[m] = -1;
    for (g = 0; g < o->nuser_groups; g++) {
        const char *p = o->groups[g].mats;
        while (*p) {
            const char *q = strchr(p, ',');
            size_t len = q ? (size_t)(q - p) : strlen(p);
            char name[512];
            if (len >= sizeof name) len = sizeof name - 1;
            memcpy(name, p, len);
            name[len] = '\0';
            m = obj_find_material(sc, name);
            if (m < 0) {
                fprintf(stderr, PROG ": %s: --light-group %s: no material named '%s' (--list-materials shows them)\n",
                        o->scene, o->groups[g].name, name);
                exit(1);
            }
            if (of[m] >= 0 && of[m] != g) {
                fprintf(stderr, PROG ": %s: --light-group %s: material '%s' is already in group '%s'\n", o->scene,
                        o->groups[g].name, name, o->groups[of[m]].name);
                exit(1);
            }
            of[m] = g;
            if (!emits(&sc->materials[m]) && !o->quiet)
                fprintf(stderr, PROG ": warning: %s: --light-group %s: material '%s' emits no light (Ke 0 0 0; --emit sets it)\n",
                        o->scene, o->groups[g].name, name);
            p += len;
            if (*p == ',') p++;
        }
    }
    for (m = 0; m < sc->nmaterials; m++)
        if (of[m] < 0 && emits(&sc->materials[m])) {
            if (!other) {
                group_t *og = &o->groups[o->ngroups];
                memset(og, 0, sizeof *og);
                strcpy(og->name, OTHER_GROUP);
                og->mats = "";
                og->k[0] = og->k[1] = og->k[2] = 1.0;
                other = ++o->ngroups;
            }
            of[m] = other - 1;
        }
    for (i = 0; i < o->ngint; i++) {
        const char *eq = strrchr(o->gint[i], '=');
        if ((size_t)(eq - o->gint[i]) != strlen(OTHER_GROUP) || strncmp(o->gint[i], OTHER_GROUP, strlen(OTHER_GROUP)) != 0)
            continue;
        if (!other) {
            fprintf(stderr, PROG ": %s: --group-intensity other: every emitting material is in a --light-group, "
                            "so there is no group 'other'\n", o->scene);
            exit(1);
        }
        parse_list(eq + 1, o->groups[other - 1].k, 3, 0);
    }
    /* Emitting materials outside the user's groups are all in "other": unused if none. */
    for (m = 0; m < sc->nmaterials; m++)
        if (!emits(&sc->materials[m])) of[m] = -1;
    return of;
}

/* The frames of --animate: "EX EY EZ LX LY LZ [FOV] [GROUP=R,G,B ...]" a line. */
static void read_frames(opts_t *o)
{
    FILE *f = fopen(o->animate, "r");
    char line[8192];
    int ln = 0, cap = 0;
    if (!f) {
        fprintf(stderr, PROG ": %s: cannot open: %s\n", o->animate, strerror(errno));
        exit(1);
    }
    while (fgets(line, sizeof line, f)) {
        char *tok, *save = NULL;
        double v[7];
        int nv = 0, g;
        frame_t fr;
        ln++;
        if (!strchr(line, '\n') && !feof(f)) {
            fprintf(stderr, PROG ": %s:%d: line too long\n", o->animate, ln);
            exit(1);
        }
        tok = strtok_r(line, " \t\r\n", &save);
        if (!tok || tok[0] == '#') continue;
        fr.k = malloc((size_t)(o->ngroups ? o->ngroups : 1) * sizeof *fr.k);
        if (!fr.k) { fprintf(stderr, PROG ": out of memory\n"); exit(1); }
        for (g = 0; g < o->ngroups; g++) memcpy(fr.k[g], o->groups[g].k, sizeof fr.k[g]);
        for (; tok; tok = strtok_r(NULL, " \t\r\n", &save)) {
            char *eq = strchr(tok, '=');
            if (!eq && nv < 7) {
                char *end;
                v[nv] = strtod(tok, &end);
                if (*end || end == tok || !isfinite(v[nv])) break;
                nv++;
            } else if (eq && nv >= 6) {
                group_t *gp = find_group(o, tok, (size_t)(eq - tok));
                double k[3];
                if (!gp) {
                    fprintf(stderr, PROG ": %s:%d: no light group named '%.*s' (", o->animate, ln, (int)(eq - tok), tok);
                    for (g = 0; g < o->ngroups; g++) fprintf(stderr, "%s%s", g ? ", " : "", o->groups[g].name);
                    fprintf(stderr, "%s)\n", o->ngroups ? "" : "the scene has no emitter");
                    exit(1);
                }
                if (parse_list(eq + 1, k, 3, 0) != 3 || !(k[0] >= 0 && k[1] >= 0 && k[2] >= 0) || k[0] >= 32768 ||
                    k[1] >= 32768 || k[2] >= 32768) {
                    fprintf(stderr, PROG ": %s:%d: %s: intensity wants R,G,B in [0, 32768)\n", o->animate, ln, tok);
                    exit(1);
                }
                memcpy(fr.k[gp - o->groups], k, sizeof k);
            } else break;
        }
        if (tok || nv < 6 || !set_camera(&fr.cam, v, nv)) {
            fprintf(stderr, PROG ": %s:%d: expected EX EY EZ LX LY LZ [FOV] [GROUP=R,G,B ...], eye and look-at apart, FOV 8..170\n",
                    o->animate, ln);
            exit(1);
        }
        if (o->nframes == cap) {
            frame_t *nf = realloc(o->frames, (size_t)(cap = cap ? 2 * cap : 64) * sizeof *nf);
            if (!nf) { fprintf(stderr, PROG ": out of memory\n"); exit(1); }
            o->frames = nf;
        }
        o->frames[o->nframes++] = fr;
    }
    fclose(f);
    if (o->nframes == 0) {
        fprintf(stderr, PROG ": %s: no frames (one a line: EX EY EZ LX LY LZ [FOV] [GROUP=R,G,B ...])\n", o->animate);
        exit(1);
    }
}

/* PATH with SEP + MID inserted before its extension: out.png -> out.MID.png. */
static char *insert_name(const char *path, const char *sep, const char *mid)
{
    const char *ext = ext_of(path);
    size_t base = (size_t)(ext - path);
    char *out = malloc(strlen(path) + strlen(sep) + strlen(mid) + 1);
    if (!out) { fprintf(stderr, PROG ": out of memory\n"); exit(1); }
    memcpy(out, path, base);
    strcpy(out + base, sep);
    strcat(out, mid);
    strcat(out, ext);
    return out;
}

typedef struct {
    const obj_scene *sc;
    int material;
} mat_match_t;

static int match_material(void *ctx, int tag)
{
    const mat_match_t *m = ctx;
    return tag >= 0 && tag < m->sc->nfaces && m->sc->faces[tag].material == m->material;
}

/* ---- rows progress ------------------------------------------------------------- */

static int rows_progress(void *ctx, int rows, int total)
{
    progress_t *p = ctx;
    double t = now();
    if (p->tty && (t - p->last >= 0.1 || rows == total)) {
        int bar = total ? (int)(30.0 * rows / total) : 30;
        fprintf(stderr, "\rform factors [%.*s%*s] rows %d/%d  %.1fs ", bar, "##############################", 30 - bar, "",
                rows, total, t - p->start);
        p->last = t;
    }
    return 0;
}

/* ---- rendering ----------------------------------------------------------------- */

typedef struct {
    float *img;
    unsigned char *rgb8;
    double exposure;           /* 0 until the first view fixes it */
    double t_render, t_write;
} out_t;

/* Renders CAM (NULL: the default camera) and writes PATH (NULL: only render, to fix
 * the exposure). One exposure for every output, from the first view, so views match. */
static int render_view(sc_solver *s, const opts_t *o, const obj_scene *sc, const sc_camera *cam, const char *path,
                       int ambient, out_t *ot)
{
    sc_camera c;
    char err[1024];
    double t1 = now();
    size_t npix = (size_t)o->width * o->height;
    if (cam) c = *cam;
    else default_camera(sc, o->width, o->height, &c);
    if (sc_render(s, &c, ambient, o->width, o->height, ot->img, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s: %s\n", path ? path : o->views[0].out, err);
        return -1;
    }
    if (ot->exposure <= 0) ot->exposure = o->exposure > 0 ? o->exposure : tonemap_auto_exposure(ot->img, npix);
    tonemap(ot->img, npix, ot->exposure, ot->rgb8);
    ot->t_render += now() - t1;
    t1 = now();
    if (path && img_write(path, ot->rgb8, o->width, o->height, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    ot->t_write += now() - t1;
    return 0;
}

/* Mixes the group solutions with intensities K (one RGB per group). */
static void mix_groups(sc_solver *s, sc_solution *const *sol, const double (*k)[3], int n)
{
    char err[256];
    if (sc_mix(s, sol, k, n, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        exit(1);
    }
}

/* ---- main ---------------------------------------------------------------------- */

/* Solves from the rows with the chosen solver; returns shots or sweeps. */
static int solve_rows(sc_solver *s, const opts_t *o, progress_t *pg)
{
    char err[512];
    int n;
    if (!o->gauss_seidel) return sc_rows_solve(s, o->max_shots, o->tol, pg->tty ? progress : NULL, pg);
    n = sc_rows_gauss_seidel(s, GS_MAX_SWEEPS, o->tol, err, sizeof err);
    if (n < 0) {
        fprintf(stderr, PROG ": %s: %s\n", o->scene, err);
        exit(1);
    }
    return n;
}

int main(int argc, char **argv)
{
    static opts_t o;
    obj_scene sc;
    glue_ctx_t gctx;
    sc_poly *polys;
    sc_opts so;
    sc_stats st;
    sc_rows_stats rst;
    sc_solver *s;
    sc_solution **sol = NULL;
    progress_t pg;
    out_t ot;
    char err[1024];
    double t0 = now(), t_load, t_mesh, t_rows = 0, t_solve;
    double (*ks)[3] = NULL;
    int npolys, i, g, emitters = 0, rc = 0, ambient, rows_mode, groups_mode, *group_of = NULL, work = 0;
    unsigned long raster_before_solve = 0;

    parse_args(argc, argv, &o);
    if (o.views_file) read_views(&o);
    if (o.nviews == 0) add_view(&o, NULL, default_output(o.scene));
    if (!o.list) {
        for (i = 0; i < o.nviews; i++) check_output(o.views[i].out, 1);
        if (o.ply) check_output(o.ply, 0);
        if (o.csv) check_output(o.csv, 0);
        if (o.save_ff) check_output(o.save_ff, 0);
    }
    ambient = !o.no_ambient;
    rows_mode = o.save_ff || o.load_ff || o.gauss_seidel || o.nuser_groups || o.animate;
    groups_mode = o.nuser_groups || o.animate;

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
        if (emits(&sc.materials[i])) emitters++;
    if (!emitters && !o.quiet)
        fprintf(stderr, PROG ": warning: %s: no material emits light (Ke), so the image is black; "
                        "set one with --emit NAME=R,G,B (--list-materials shows them)\n", o.scene);
    if (groups_mode) group_of = resolve_groups(&o, &sc);
    if (o.animate) read_frames(&o);
    polys = obj_to_polys(&sc, &npolys, o.quiet ? NULL : poly_warning, &o);
    if (!polys) { fprintf(stderr, PROG ": out of memory\n"); obj_free(&sc); return 1; }
    t_load = now();

    memset(&so, 0, sizeof so);
    so.max_patch = o.max_patch;
    so.max_element = o.max_element;
    so.res = o.res ? o.res : 128; /* 64 aliases visibly on elements a few pixels wide */
    so.no_overshoot = o.no_overshoot;
    gctx.o = &o;
    gctx.sc = &sc;
    s = sc_create(polys, npolys, &so, o.quiet ? NULL : glue_warning, &gctx, err, sizeof err);
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
    if (!rows_mode) {
        /* Threads split each shot's hemi-cube by rows: the same bits as one thread. */
        if (o.threads < 2 ||
            sc_solve_parallel(s, o.threads, o.max_shots, o.tol, pg.tty ? progress : NULL, &pg) < 0)
            sc_solve(s, o.max_shots, o.tol, pg.tty ? progress : NULL, &pg);
    } else {
        /* Visibility once: every patch's row, loaded or rendered (then saved). */
        if ((o.gauss_seidel && sc_gauss_seidel_check(s, err, sizeof err) < 0) ||
            (o.load_ff ? sc_rows_load(s, o.load_ff, err, sizeof err) < 0
                       : sc_rows_compute(s, pg.tty ? rows_progress : NULL, &pg, err, sizeof err) < 0)) {
            if (pg.tty) fprintf(stderr, "\r%70s\r", "");
            fprintf(stderr, PROG ": %s%s%s\n", o.load_ff ? "" : o.scene, o.load_ff ? "" : ": ", err);
            sc_destroy(s);
            obj_free(&sc);
            return 1;
        }
        if (pg.tty) fprintf(stderr, "\r%70s\r", "");
        if (o.save_ff && sc_rows_save(s, o.save_ff, err, sizeof err) < 0) {
            fprintf(stderr, PROG ": %s\n", err);
            sc_destroy(s);
            obj_free(&sc);
            return 1;
        }
        sc_get_stats(s, &st);
        raster_before_solve = st.raster_calls;
        t_rows = now() - t_mesh;
        pg.start = pg.last = now();
        pg.last -= 1.0;
        if (!groups_mode) {
            work = solve_rows(s, &o, &pg);
        } else {
            /* Each group alone (the other emitters dark), kept aside for mixing. */
            sol = calloc((size_t)(o.ngroups ? o.ngroups : 1), sizeof *sol);
            ks = calloc((size_t)(o.ngroups ? o.ngroups : 1), sizeof *ks);
            if (!sol || !ks) { fprintf(stderr, PROG ": out of memory\n"); return 1; }
            for (g = 0; g < o.ngroups; g++) {
                int m;
                for (m = 0; m < sc.nmaterials; m++) {
                    static const double dark[3] = {0, 0, 0};
                    mat_match_t mm;
                    if (group_of[m] < 0) continue;
                    mm.sc = &sc;
                    mm.material = m;
                    if (sc_set_surfaces(s, match_material, &mm, NULL, group_of[m] == g ? sc.materials[m].ke : dark,
                                         err, sizeof err) < 0) {
                        fprintf(stderr, PROG ": %s: %s: %s\n", o.scene, sc.materials[m].name, err);
                        return 1;
                    }
                }
                work += solve_rows(s, &o, &pg);
                sol[g] = sc_keep(s, ambient);
                if (!sol[g]) { fprintf(stderr, PROG ": out of memory\n"); return 1; }
                memcpy(ks[g], o.groups[g].k, sizeof ks[g]);
            }
            mix_groups(s, sol, (const double(*)[3])ks, o.ngroups);
        }
    }
    if (pg.tty) fprintf(stderr, "\r%70s\r", "");
    t_solve = now();
    sc_get_stats(s, &st);
    solve_warnings(&o, &st);

    memset(&ot, 0, sizeof ot);
    ot.img = malloc((size_t)o.width * o.height * 3 * sizeof *ot.img);
    ot.rgb8 = malloc((size_t)o.width * o.height * 3);
    if (!ot.img || !ot.rgb8) { fprintf(stderr, PROG ": out of memory\n"); rc = 1; }
    if (rc == 0 && o.animate) {
        const char *pattern = o.views[0].out;
        for (i = 0; rc == 0 && i < o.nframes; i++) {
            char num[32];
            char *path;
            snprintf(num, sizeof num, "%04d", i);
            path = insert_name(pattern, "_", num);
            mix_groups(s, sol, (const double(*)[3])o.frames[i].k, o.ngroups);
            rc = render_view(s, &o, &sc, &o.frames[i].cam, path, ambient, &ot) < 0;
            free(path);
        }
        mix_groups(s, sol, (const double(*)[3])ks, o.ngroups); /* for --dump-radiosity, --export-ply */
    } else if (rc == 0 && o.each_group) {
        /* The exposure of the whole mix, so each group shows its share of the light. */
        rc = render_view(s, &o, &sc, o.views[0].has_cam ? &o.views[0].cam : NULL, NULL, ambient, &ot) < 0;
        for (g = 0; rc == 0 && g < o.ngroups; g++) {
            mix_groups(s, &sol[g], (const double(*)[3])&ks[g], 1);
            for (i = 0; rc == 0 && i < o.nviews; i++) {
                char *path = insert_name(o.views[i].out, ".", o.groups[g].name);
                rc = render_view(s, &o, &sc, o.views[i].has_cam ? &o.views[i].cam : NULL, path, ambient, &ot) < 0;
                free(path);
            }
        }
        mix_groups(s, sol, (const double(*)[3])ks, o.ngroups);
    } else {
        for (i = 0; rc == 0 && i < o.nviews; i++)
            rc = render_view(s, &o, &sc, o.views[i].has_cam ? &o.views[i].cam : NULL, o.views[i].out, ambient, &ot) < 0;
    }
    if (rc == 0 && o.csv && write_csv(o.csv, s, &sc, ambient, &st) < 0) rc = 1;
    if (rc == 0 && o.ply && write_ply(o.ply, s, ambient, ot.exposure, &st) < 0) rc = 1;

    if (o.stats) {
        printf("surfaces %d (split quads %d, skipped %d, reflectances clamped %d)\n", st.surfaces, st.split, st.skipped, st.clamped);
        printf("patches %d  elements %d  vertices %d\n", st.patches, st.elements, st.vertices);
        if (!rows_mode) printf("shots %d  unshot fraction %.6f  saturations %lu\n", st.shots, st.unshot, st.saturations);
        else if (o.gauss_seidel) printf("shots 0  gauss-seidel sweeps %d  saturations %lu\n", work, st.saturations);
        else printf("shots %d  unshot fraction %.6f  saturations %lu\n", work, st.unshot, st.saturations);
        printf("hemi-cube: resolution %d, %lu polygons, %llu pixels\n", so.res, st.raster_calls, st.raster_pixels);
        printf("overshoot back-offs %lu, %s\n", st.backoffs, st.converged ? "converged" : "not converged");
        if (rows_mode) {
            sc_get_rows_stats(s, &rst);
            printf("form factor rows: %d %s%s, %lu entries, %zu bytes (%.0f bytes per patch), %s\n", rst.rows,
                   o.load_ff ? "loaded from " : "computed", o.load_ff ? o.load_ff : "", rst.entries, rst.bytes,
                   rst.rows ? (double)rst.bytes / rst.rows : 0.0, o.save_ff ? "saved" : "not saved");
            printf("solve from rows: %s, %lu hemi-cube polygons rendered during the solve\n",
                   o.gauss_seidel ? "gauss-seidel" : "shoot", st.raster_calls - raster_before_solve);
            if (groups_mode) {
                printf("light groups %d:", o.ngroups);
                for (g = 0; g < o.ngroups; g++)
                    printf(" %s (%g,%g,%g)", o.groups[g].name, o.groups[g].k[0], o.groups[g].k[1], o.groups[g].k[2]);
                printf("\n");
            }
            if (o.gauss_seidel && rst.matrix_bytes) printf("gauss-seidel matrix %zu bytes\n", rst.matrix_bytes);
        }
        printf("unknown statements skipped %ld, warnings %ld\n", sc.unknown_statements, sc.nwarnings);
        if (rows_mode)
            printf("time: load %.3fs  mesh %.3fs  rows %.3fs  solve %.3fs  render %.3fs  write %.3fs\n", t_load - t0,
                   t_mesh - t_load, t_rows, t_solve - t_mesh - t_rows, ot.t_render, ot.t_write);
        else
            printf("time: load %.3fs  mesh %.3fs  solve %.3fs  render %.3fs  write %.3fs\n", t_load - t0,
                   t_mesh - t_load, t_solve - t_mesh, ot.t_render, ot.t_write);
        printf("memory: pools %zu bytes, work buffer %zu bytes\n", st.pool_bytes, st.work_bytes);
    }
    if (sol)
        for (g = 0; g < o.ngroups; g++) sc_solution_free(sol[g]);
    free(sol);
    free(ks);
    free(group_of);
    free(ot.img);
    free(ot.rgb8);
    sc_destroy(s);
    obj_free(&sc);
    return rc;
}
