/* SPDX-License-Identifier: MIT */
/* rad_cli's options: one table (name, argument, help, handler); --help is made from it.
 */
#include "cli.h"

#include "bake/lightmap.h"
#include "bake/probes.h"
#include "formats/assimp_scene.h"
#include "rad/rad.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

typedef void (*opt_fn)(opts_t *o, const char *opt, const char *val);

typedef struct {
    const char *name, *alt; /* alt: another spelling (-h) or NULL */
    const char *arg;        /* the value's name, or NULL for a flag */
    const char *help;       /* lines after the first start with '\n' */
    opt_fn fn;
} option_t;

static void usage(FILE *f);
static void print_option(FILE *f, const option_t *p);

/* The option whose value is being read, for cli_die_usage: NULL between options. */
static const option_t *parsing;

/* A usage error: the message, the help of the option at fault, and where the rest is. */
void cli_die_usage(const char *msg, const char *arg)
{
    fprintf(stderr, PROG ": %s%s%s\n", msg, arg ? ": " : "", arg ? arg : "");
    if (parsing) print_option(stderr, parsing);
    fprintf(stderr, "usage: " PROG " [options] scene.obj   (" PROG " --help lists the options)\n");
    exit(CLI_EXIT_USAGE);
}

/* VAL's index among the N NAMES, or a usage error naming them all. */
static int parse_choice(const char *opt, const char *val, const char *const *names, int n)
{
    char want[128];
    size_t len;
    int k;
    for (k = 0; k < n; k++)
        if (!strcmp(val, names[k])) return k;
    len = (size_t)snprintf(want, sizeof want, "%s wants", opt);
    for (k = 0; k < n && len < sizeof want; k++)
        len += (size_t)snprintf(want + len, sizeof want - len, "%s%s",
                                k == 0       ? " "
                                : k == n - 1 ? " or "
                                             : ", ",
                                names[k]);
    cli_die_usage(want, val);
    return 0;
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
        cli_die_usage(msg, s);
    }
    return v;
}

/* A hemi-cube resolution: even (a cube's sides are half faces), 8..1024. */
static int parse_res(const char *opt, const char *s)
{
    long v = parse_int(opt, s, 8, 1024);
    if (v % 2) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s must be even", opt);
        cli_die_usage(msg, s);
    }
    return (int)v;
}

static double parse_pos(const char *opt, const char *s)
{
    double v;
    if (cli_parse_list(s, &v, 1, 0) != 1 || !(v > 0)) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s wants a positive number", opt);
        cli_die_usage(msg, s);
    }
    return v;
}

void cli_add_view(opts_t *o, const sc_camera *cam, const char *out)
{
    if (o->nviews >= MAX_VIEWS) cli_die_usage("too many views", NULL);
    o->views[o->nviews].has_cam = cam != NULL;
    if (cam) o->views[o->nviews].cam = *cam;
    o->views[o->nviews].out = out;
    o->nviews++;
}

/* A group name: letters, digits, '_' and '-' (it goes into file names). */
static int good_group_name(const char *s, size_t len)
{
    size_t i;
    if (len == 0 || len >= MAX_GROUP_NAME) return 0;
    for (i = 0; i < len; i++)
        if (!((s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' && s[i] <= 'Z') ||
              (s[i] >= '0' && s[i] <= '9') || s[i] == '_' || s[i] == '-'))
            return 0;
    return 1;
}

/* ---- handlers ------------------------------------------------------------------ */

static void opt_help(opts_t *o, const char *opt, const char *val)
{
    (void)o, (void)opt, (void)val;
    usage(stdout);
    exit(CLI_EXIT_OK);
}

static void opt_output(opts_t *o, const char *opt, const char *val)
{
    (void)opt;
    cli_add_view(o, o->pending_cam ? &o->pending : NULL, val);
    o->pending_cam = 0;
}

static void opt_camera(opts_t *o, const char *opt, const char *val)
{
    double v[7];
    int k = cli_parse_list(val, v, 7, 1);
    (void)opt;
    if (o->pending_cam) cli_die_usage("--camera without its -o FILE", NULL);
    if (k < 0 || !cli_set_camera(&o->pending, v, k))
        cli_die_usage("--camera wants EX,EY,EZ,LX,LY,LZ[,FOV], eye and look-at apart, FOV 8..170",
                      val);
    o->pending_cam = 1;
    o->ncams++;
}

static void opt_views(opts_t *o, const char *opt, const char *val)
{
    (void)opt, o->views_file = val;
}
static void opt_width(opts_t *o, const char *opt, const char *val)
{
    o->width = (int)parse_int(opt, val, 1, 2048);
}
static void opt_height(opts_t *o, const char *opt, const char *val)
{
    o->height = (int)parse_int(opt, val, 1, 2048);
}
static void opt_exposure(opts_t *o, const char *opt, const char *val)
{
    o->exposure = parse_pos(opt, val);
}
static void opt_no_ambient(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->no_ambient = 1;
}
static void opt_ply(opts_t *o, const char *opt, const char *val)
{
    (void)opt, o->ply = val;
}
static void opt_allow_outside(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->allow_outside = 1;
}
static void opt_ply_linear(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->ply_linear = 1;
}
static void opt_csv(opts_t *o, const char *opt, const char *val)
{
    (void)opt, o->csv = val;
}
static void opt_gltf(opts_t *o, const char *opt, const char *val)
{
    (void)opt, o->gltf = val;
}
static void opt_no_textures(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->no_textures = 1;
}
static void opt_two_sided(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->two_sided = 1;
}
static void opt_no_file_lights(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->no_file_lights = 1;
}

static void opt_res(opts_t *o, const char *opt, const char *val)
{
    o->res = parse_res(opt, val);
}

static void opt_coarse(opts_t *o, const char *opt, const char *val)
{
    (void)opt;
    if (cli_parse_list(val, &o->coarse, 1, 0) != 1 || !(o->coarse >= 0 && o->coarse <= 64))
        cli_die_usage("--coarse wants a number in [0, 64]", val);
}

static void opt_coarse_res(opts_t *o, const char *opt, const char *val)
{
    o->coarse_res = parse_res(opt, val);
}

static void opt_max_patch(opts_t *o, const char *opt, const char *val)
{
    o->max_patch = parse_pos(opt, val);
}
static void opt_max_element(opts_t *o, const char *opt, const char *val)
{
    o->max_element = parse_pos(opt, val);
}

static void opt_tol(opts_t *o, const char *opt, const char *val)
{
    (void)opt;
    if (cli_parse_list(val, &o->tol, 1, 0) != 1 || !(o->tol >= 0 && o->tol < 1))
        cli_die_usage("--tol wants a number in [0, 1)", val);
}

static void opt_max_shots(opts_t *o, const char *opt, const char *val)
{
    o->max_shots = (int)parse_int(opt, val, 0, 1000000000);
}
static void opt_threads(opts_t *o, const char *opt, const char *val)
{
    o->threads = (int)parse_int(opt, val, 1, 64);
}
static void opt_batch(opts_t *o, const char *opt, const char *val)
{
    o->batch = (int)parse_int(opt, val, 1, RAD_BATCH_MAX);
}
static void opt_no_overshoot(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->no_overshoot = 1;
}

static void opt_emit(opts_t *o, const char *opt, const char *val)
{
    const char *eq = strrchr(val, '=');
    double v[3];
    (void)opt;
    if (!eq || eq == val || cli_parse_list(eq + 1, v, 3, 0) != 3 || v[0] < 0 || v[1] < 0 ||
        v[2] < 0)
        cli_die_usage("--emit wants NAME=R,G,B with R, G, B >= 0", val);
    o->emit[o->nemit++] = (char *)val;
}

/* Option OPT's values V (K of them, -1: not a list of numbers) as light KIND:
 * WANT names the list when it is wrong, SAYS (when not NULL) a wrong value of field
 * FIELD or later. */
static void light_option(opts_t *o, const char *opt, const char *val, int kind, const double *v,
                         int k, const char *want, int field, const char *says)
{
    int bad = k < 0 ? 0 : cli_light_check(kind, v);
    if (bad >= 0) {
        char msg[224];
        snprintf(msg, sizeof msg, "%s wants %s", opt, says && k >= 0 && bad >= field ? says : want);
        cli_die_usage(msg, val);
    }
    cli_light_make(o, kind, v);
}

/* N values, the last optional (NAN when left out): the count or -1. */
static int light_list(const char *val, double *v, int n)
{
    int k = cli_parse_list(val, v, n, 1);
    if (k == n - 1) v[n - 1] = NAN;
    return k;
}

static void opt_sun(opts_t *o, const char *opt, const char *val)
{
    double v[7];
    light_option(o, opt, val, CLI_LIGHT_SUN, v, light_list(val, v, 7),
                 "DX,DY,DZ,R,G,B[,ANGLE]: the way the light travels (not zero), irradiance >= 0, "
                 "ANGLE 0..14",
                 2, "ANGLE (the sun's angular radius, degrees) in [0, 14]");
}

static void opt_point(opts_t *o, const char *opt, const char *val)
{
    double v[6];
    light_option(o, opt, val, CLI_LIGHT_POINT, v, cli_parse_list(val, v, 6, 0),
                 "X,Y,Z,R,G,B with intensities >= 0", 2, NULL);
}

static void opt_spot(opts_t *o, const char *opt, const char *val)
{
    double v[11];
    light_option(o, opt, val, CLI_LIGHT_SPOT, v, light_list(val, v, 11),
                 "X,Y,Z,DX,DY,DZ,R,G,B,ANGLE[,SOFTNESS]: a direction not zero, intensities >= 0, "
                 "ANGLE 0..180, "
                 "SOFTNESS 0..1",
                 3, "ANGLE (the cone's half angle, degrees) in (0, 180] and SOFTNESS in [0, 1]");
}

/* --sky R,G,B[,HR,HG,HB][,N]: 3, 4, 6 or 7 values into the fields R,G,B,HR,HG,HB,N. */
static void opt_sky(opts_t *o, const char *opt, const char *val)
{
    static const int counts[4] = {3, 4, 6, 7};
    double v[7];
    int k;
    for (k = 0; k < 4 && cli_parse_list(val, v, counts[k], 0) != counts[k]; k++) continue;
    if (k < 4) {
        if (counts[k] == 4) v[6] = v[3];
        if (counts[k] < 6) v[3] = v[4] = v[5] = NAN;
        if (counts[k] == 3 || counts[k] == 6) v[6] = NAN;
    }
    light_option(o, opt, val, CLI_LIGHT_SKY, v, k < 4 ? 7 : -1,
                 "R,G,B[,HR,HG,HB][,N]: radiances >= 0, N an integer 3..768", 0, NULL);
}

/* A --lights or --sky-hdr file that cannot be read or is wrong: one line, exit 2. */
static void die_light_file(const char *err)
{
    fprintf(stderr, PROG ": %s\n", err);
    exit(CLI_EXIT_USAGE);
}

/* A file of lights (--lights, --sky-hdr) kept for cli_check_collisions: a copy of PATH. */
static const char *light_file(opts_t *o, const char *path, size_t len)
{
    char *s = malloc(len + 1);
    if (!s) cli_die_usage("out of memory", NULL);
    memcpy(s, path, len);
    s[len] = '\0';
    o->light_files[o->nlight_files++] = s;
    return s;
}

/* --sky-hdr FILE[,N[,SCALE]]: the last one or two comma-separated numbers are N and
 * SCALE, the rest the file's name. */
static void opt_sky_hdr(opts_t *o, const char *opt, const char *val)
{
    double v[3] = {NAN, NAN, NAN}, t[2];
    size_t len = strlen(val);
    int k = 0;
    char err[1024];
    const char *file;
    while (k < 2) {
        size_t c = len, n;
        char num[64];
        while (c > 0 && val[c - 1] != ',') c--;
        n = len - c;
        if (c == 0 || n >= sizeof num) break;
        memcpy(num, val + c, n);
        num[n] = '\0';
        if (cli_parse_list(num, &t[k], 1, 0) != 1) break;
        len = c - 1;
        k++;
    }
    if (k == 1) v[1] = t[0];
    if (k == 2) {
        v[1] = t[1];
        v[2] = t[0];
    }
    if (len == 0 || cli_light_check(CLI_LIGHT_SKY_HDR, v) >= 0) {
        char msg[160];
        snprintf(msg, sizeof msg, "%s wants FILE[,N[,SCALE]]: N a whole number 3..768, SCALE > 0",
                 opt);
        cli_die_usage(msg, val);
    }
    file = light_file(o, val, len);
    if (cli_add_sky_map(o, file, isnan(v[1]) ? 0 : (int)v[1], isnan(v[2]) ? 1.0 : v[2], err,
                        sizeof err) < 0)
        die_light_file(err);
}

static void opt_lights(opts_t *o, const char *opt, const char *val)
{
    char err[1024];
    (void)opt;
    if (cli_read_lights(o, light_file(o, val, strlen(val)), err, sizeof err) < 0)
        die_light_file(err);
}

static void opt_save_ff(opts_t *o, const char *opt, const char *val)
{
    (void)opt, o->save_ff = val;
}
static void opt_load_ff(opts_t *o, const char *opt, const char *val)
{
    (void)opt, o->load_ff = val;
}

static void opt_solver(opts_t *o, const char *opt, const char *val)
{
    static const char *const names[] = {"shoot", "gauss-seidel"};
    o->gauss_seidel = parse_choice(opt, val, names, 2);
}

/* --light-group NAME=MAT1,MAT2,...: checked here, materials resolved with the scene. */
static void opt_light_group(opts_t *o, const char *opt, const char *val)
{
    const char *eq = strchr(val, '='), *p;
    group_t *g;
    size_t len;
    (void)opt;
    if (!eq || !good_group_name(val, (size_t)(eq - val)))
        cli_die_usage("--light-group wants NAME=MAT1,MAT2,... with NAME of letters, digits, '_', "
                      "'-' (up to 63)",
                      val);
    len = (size_t)(eq - val);
    if (len == strlen(OTHER_GROUP) && strncmp(val, OTHER_GROUP, len) == 0)
        cli_die_usage(
            "--light-group: 'other' is the group of the emitters in no group; choose another name",
            val);
    if (cli_find_group(o->groups, o->ngroups, val, len))
        cli_die_usage("--light-group: a group name given twice", val);
    for (p = eq + 1;; p++) /* no empty material names: "a,,b", ",a", "a," */
        if ((*p == ',' || *p == '\0') && (p == eq + 1 || p[-1] == ','))
            cli_die_usage("--light-group: an empty material name", val);
        else if (*p == '\0')
            break;
    g = &o->groups[o->ngroups++];
    memcpy(g->name, val, len);
    g->name[len] = '\0';
    g->mats = eq + 1;
    g->k[0] = g->k[1] = g->k[2] = 1.0;
    o->nuser_groups = o->ngroups;
}

static void opt_group_intensity(opts_t *o, const char *opt, const char *val)
{
    const char *eq = strrchr(val, '=');
    double v[3];
    (void)opt;
    if (!eq || eq == val || cli_parse_list(eq + 1, v, 3, 0) != 3 ||
        !(v[0] >= 0 && v[1] >= 0 && v[2] >= 0) || v[0] >= 32768 || v[1] >= 32768 || v[2] >= 32768)
        cli_die_usage("--group-intensity wants NAME=R,G,B with R, G, B in [0, 32768)", val);
    o->gint[o->ngint++] = (char *)val;
}

static void opt_each_group(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->each_group = 1;
}
static void opt_animate(opts_t *o, const char *opt, const char *val)
{
    (void)opt, o->animate = val;
}
static void opt_list(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->list = 1;
}
static void opt_stats(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->stats = 1;
}
static void opt_quiet(opts_t *o, const char *opt, const char *val)
{
    (void)opt, (void)val, o->quiet = 1;
}

static void opt_lightmap(opts_t *o, const char *opt, const char *val)
{
    (void)opt;
    if (strcasecmp(cli_ext_of(val), ".png") && strcasecmp(cli_ext_of(val), ".ppm") &&
        strcasecmp(cli_ext_of(val), ".hdr"))
        cli_die_usage("--lightmap wants a .png, .ppm or .hdr file", val);
    o->lightmap = val;
}

static void opt_lightmap_size(opts_t *o, const char *opt, const char *val)
{
    o->lightmap_size = (int)parse_int(opt, val, 1, 8192);
    o->lightmap_opt = opt;
}

static void opt_lightmap_pad(opts_t *o, const char *opt, const char *val)
{
    o->lightmap_pad = (int)parse_int(opt, val, 0, LM_MAX_PADDING);
    o->lightmap_opt = opt;
}

static void opt_lightmap_tol(opts_t *o, const char *opt, const char *val)
{
    o->lightmap_opt = opt;
    if (cli_parse_list(val, &o->lightmap_tol, 1, 0) != 1 ||
        !(o->lightmap_tol >= 0 && o->lightmap_tol <= 1))
        cli_die_usage("--lightmap-tol wants a number in [0, 1]", val);
}

static void opt_lightmap_uv(opts_t *o, const char *opt, const char *val)
{
    static const char *const names[] = {"auto", "file", "rad"}; /* LIGHTMAP_UV_* */
    o->lightmap_opt = opt;
    o->lightmap_uv = parse_choice(opt, val, names, 3);
}

static void opt_lightmap_soft(opts_t *o, const char *opt, const char *val)
{
    static const char *const names[] = {"gather", "elements"}; /* LIGHTMAP_SOFT_* */
    o->lightmap_opt = opt;
    o->lightmap_soft = parse_choice(opt, val, names, 2);
}

static void opt_gather(opts_t *o, const char *opt, const char *val)
{
    o->gather_res = parse_res(opt, val);
}

static void opt_probes(opts_t *o, const char *opt, const char *val)
{
    char err[160];
    (void)opt;
    if (pr_parse_grid(val, o->probe_dims, err, sizeof err) < 0) cli_die_usage(err, NULL);
    o->probes = 1;
}

static void opt_probe_file(opts_t *o, const char *opt, const char *val)
{
    (void)opt, o->probe_file = val;
}
static void opt_probes_out(opts_t *o, const char *opt, const char *val)
{
    (void)opt, o->probes_out = val;
}

/* ---- the table ------------------------------------------------------------------ */

#define SECTION(title)                \
    {                                 \
        NULL, NULL, NULL, title, NULL \
    }

static const option_t options[] = {
    SECTION("output:"),
    {"-o", NULL, "FILE",
     "image to write (.png or .ppm; /dev/stdout or a pipe: PNG); default: scene name + .png",
     opt_output},
    {"--camera", NULL, "EX,EY,EZ,LX,LY,LZ[,FOV]",
     "eye, look-at point, vertical field of view (degrees, 45);\n"
     "repeat '--camera ... -o FILE' to render many views of one solve",
     opt_camera},
    {"--views", NULL, "FILE", "one view a line: EX EY EZ LX LY LZ [FOV] OUTPUT", opt_views},
    {"--width", NULL, "N", "image width (" DEF_STR(DEF_IMAGE_SIZE) "), up to 2048", opt_width},
    {"--height", NULL, "N", "image height (" DEF_STR(DEF_IMAGE_SIZE) "), up to 2048", opt_height},
    {"--exposure", NULL, "X",
     "linear scale before sRGB (default: automatic, from the first view:\n"
     "its 97th percentile maps to white; one exposure for every view)",
     opt_exposure},
    {"--no-ambient", NULL, NULL, "show the partial solution without the ambient term",
     opt_no_ambient},
    {"--export-ply", NULL, "FILE", "the meshed scene with vertex colours (PLY)", opt_ply},
    {"--ply-linear", NULL, NULL,
     "--export-ply as binary PLY: linear float radiosity, welded\n"
     "vertices, normals (default: ASCII, sRGB at the images' exposure)",
     opt_ply_linear},
    {"--dump-radiosity", NULL, "FILE",
     "one CSV row per element:\nelement,surface,material,area,cx,cy,cz,r,g,b", opt_csv},
    {"--export-gltf", NULL, "FILE",
     "glTF 2.0 binary (.glb) of the input's meshes: _LIGHT the light\n"
     "arriving at each vertex, COLOR_0 it over a scale into [0, 1] (the\n"
     "scale in the materials' extras and --stats), materials unlit with\n"
     "their textures",
     opt_gltf},
    {"--no-textures", NULL, NULL, "ignore map_Kd: Kd alone, in the solve and the views",
     opt_no_textures},
    {"--allow-outside-paths", NULL, NULL,
     "read mtllib and map_Kd files outside the scene's folder (by\n"
     "default: a warning, and Kd), and let --views write outside\n"
     "the current folder",
     opt_allow_outside},
    {"--two-sided", NULL, NULL,
     "every face lit on both sides: two one-sided faces back to back\n"
     "(by default a face has one side, its winding's or its vn's)",
     opt_two_sided},
    {"--gather", NULL, "RES",
     "shade the views and vertex exports by gathering the light at each\n"
     "pixel and vertex (a cube of resolution RES, even, 8..1024; 64 and up\n"
     "for small lamps): shadows sharper than the elements; also the\n"
     "lightmap's and probes' gather resolution (" DEF_STR(DEF_GATHER_RES) " without it)",
     opt_gather},
    SECTION("solver:"),
    {"--res", NULL, "N",
     "hemi-cube resolution, even, 8..1024 (" DEF_STR(DEF_RES) "; " DEF_STR(
         DEF_ROWS_RES) " with stored rows)",
     opt_res},
    {"--coarse", NULL, "F",
     "once the unshot fraction is below F, shots (but the emitters' own\n"
     "light) render at res / 2, below F / 8 at res / 4, ... (1; 0: never)",
     opt_coarse},
    {"--coarse-res", NULL, "N", "the least resolution of a coarse shot (res / 8, at least 24)",
     opt_coarse_res},
    {"--max-patch", NULL, "L", "longest patch edge (4 x the element edge)", opt_max_patch},
    {"--max-element", NULL, "L", "longest element edge (scene extent / 24)", opt_max_element},
    {"--tol", NULL, "F", "stop when the unshot fraction is below F (0.001)", opt_tol},
    {"--max-shots", NULL, "N", "stop after N shots (1000000)", opt_max_shots},
    {"--threads", NULL, "N",
     "render the hemi-cubes on N threads: a batch's whole cubes (--batch),\nor with --batch 1 each "
     "shot's by rows; the same result for any N\n(the processors online); --lightmap's texels, "
     "--gather's\ngathers and textures too",
     opt_threads},
    {"--batch", NULL, "K",
     "shoot in batches of the K patches that move the most, their\n"
     "hemi-cubes rendered at once on --threads (" DEF_STR(
         DEF_BATCH) "; 1..32; the same\n"
                    "bits for any --threads, and K 1 is the serial solve's)",
     opt_batch},
    {"--no-overshoot", NULL, NULL,
     "shoot only the unshot power (Cohen et al. 1988); by default\n"
     "each shot adds the power expected back (fewer shots)",
     opt_no_overshoot},
    {"--emit", NULL, "NAME=R,G,B", "set the emission of material NAME (repeatable)", opt_emit},
    {"--sun", NULL, "DX,DY,DZ,R,G,B[,ANGLE]",
     "a sun: its light travels along DX,DY,DZ ((0,-1,0): straight\n"
     "down with +Y up), irradiance R,G,B on a plane facing it, in\n"
     "emission units (a plane at angle t gets E cos t); ANGLE (0..14,\n"
     "0) its angular radius in degrees (the sun's: 0.27), 16\n"
     "directions over its disc for soft shadows (repeatable)",
     opt_sun},
    {"--point", NULL, "X,Y,Z,R,G,B",
     "a point light at X,Y,Z of intensity R,G,B per steradian: a plane at\n"
     "distance r, at angle t, gets I cos t / r^2 (repeatable)",
     opt_point},
    {"--spot", NULL, "X,Y,Z,DX,DY,DZ,R,G,B,ANGLE[,SOFTNESS]",
     "a spot light at X,Y,Z pointing along DX,DY,DZ: a point light\n"
     "inside the cone of half angle ANGLE degrees, dark outside;\n"
     "SOFTNESS (0..1, 0) of the angle fades out (repeatable)",
     opt_spot},
    {"--sky", NULL, "R,G,B[,HR,HG,HB][,N]",
     "a sky over +Y: radiance R,G,B at the zenith, HR,HG,HB at the\n"
     "horizon (default: R,G,B, a uniform sky), linear in the cosine\n"
     "of the zenith angle; an open floor gets pi L; N directions\n"
     "(3..768, rounded down to 3 m^2; 192), each a sun's shot",
     opt_sky},
    {"--sky-hdr", NULL, "FILE[,N[,SCALE]]",
     "a sky from an equirectangular Radiance .hdr map (+Y up, its\n"
     "middle column toward +X): each of N directions (as --sky's;\n"
     "192) a sun carrying its cell's light, radiance times SCALE (1)",
     opt_sky_hdr},
    {"--lights", NULL, "FILE",
     "suns, skies, points and spots from a JSON file (repeatable;\n"
     "shining with the options', in the command line's order)",
     opt_lights},
    {"--no-file-lights", NULL, NULL,
     "leave out the lights a glTF, FBX, COLLADA or 3DS scene holds\n"
     "(by default they shine, after --sun, --point, --spot, --sky,\n--sky-hdr and --lights)",
     opt_no_file_lights},
    SECTION("stored form factors (every patch's hemi-cube row, computed once; relighting renders\n"
            "no hemi-cube):"),
    {"--save-ff", NULL, "FILE", "compute all rows, save them to FILE, solve from them",
     opt_save_ff},
    {"--load-ff", NULL, "FILE",
     "load rows saved for this scene and settings (same build,\n"
     "--max-element, --max-patch, --res), solve from them",
     opt_load_ff},
    {"--solver", NULL, "shoot|gauss-seidel",
     "progressive refinement (default) or the full-matrix\n"
     "Gauss-Seidel solve (needs rows: computed if not loaded;\n"
     "--tol: stop when no patch changes by more than F of itself)",
     opt_solver},
    {"--light-group", NULL, "NAME=MAT1,MAT2,...",
     "a group of emitting materials and lights (repeatable; lights:\n"
     "sun1, sky1, point1, spot1, ... in the order given, or a file\n"
     "light's name); emitters and lights in no group form the group\n"
     "'other'; each group is solved once from the rows and the\n"
     "image mixes them",
     opt_light_group},
    {"--group-intensity", NULL, "NAME=R,G,B", "a group's intensity in the mix (1,1,1)",
     opt_group_intensity},
    {"--each-group", NULL, NULL,
     "one image per group (group name before the extension:\n"
     "out.png -> out.NAME.png), at the exposure of the whole mix",
     opt_each_group},
    {"--animate", NULL, "FILE",
     "frames from one visibility computation: each line\n"
     "'EX EY EZ LX LY LZ [FOV] [GROUP=R,G,B ...]' is a frame,\n"
     "written as -o's name + _0000, _0001, ... (PNG or PPM)",
     opt_animate},
    SECTION("baking (lightmaps and light probes):"),
    {"--lightmap", NULL, "FILE",
     "bake the light arriving on every surface into an atlas\n(.png, .ppm or .hdr)", opt_lightmap},
    {"--lightmap-size", NULL, "N",
     "the lightmap atlas is N x N texels, 1..8192 (" DEF_STR(DEF_LIGHTMAP_SIZE) ")",
     opt_lightmap_size},
    {"--lightmap-pad", NULL, "N",
     "texels of gutter around each lightmap chart, 0..64 (size / 128\nwithin 1..4): mip levels m "
     "with 2^m <= N + 1 stay clean",
     opt_lightmap_pad},
    {"--lightmap-tol", NULL, "F",
     "interpolate a lightmap block whose gathered corners agree\nwithin F (0.05); 0: gather every "
     "texel",
     opt_lightmap_tol},
    {"--lightmap-uv", NULL, "MODE",
     "the lightmap's UVs, MODE auto, file or rad: the file's second UV\nset (glTF TEXCOORD_1; "
     "file: required) or rad's own charts\n(auto: the file's if it has one)",
     opt_lightmap_uv},
    {"--lightmap-soft", NULL, "MODE",
     "how the lightmap's soft light is found, MODE gather: a hemi-cube\nat texels "
     "(--lightmap-tol; the default) or elements: painted\nfrom the solve's elements (a preview "
     "in seconds; then every\nlight's direct light is a ray per texel)",
     opt_lightmap_soft},
    {"--probes", NULL, "NX,NY,NZ", "light probes (L2 spherical harmonics) on a grid over the scene",
     opt_probes},
    {"--probe-file", NULL, "FILE", "light probes at the points of FILE, one 'X Y Z' a line",
     opt_probe_file},
    {"--probes-out", NULL, "FILE", "the probes' JSON (scene name + .probes.json)", opt_probes_out},
    SECTION("information:"),
    {"--list-materials", NULL, NULL, "print materials with Kd, Ke and area, then exit", opt_list},
    {"--stats", NULL, NULL, "print counts, times, memory and the exposure used", opt_stats},
    {"--quiet", NULL, NULL, "no progress or warnings", opt_quiet},
    {"--help", "-h", NULL, "this text", opt_help},
};

#define NOPTIONS    (sizeof options / sizeof options[0])
#define HELP_COLUMN 26

/* One option's entry of the help: its name and value, then its help lines. */
static void print_option(FILE *f, const option_t *p)
{
    const char *h = p->help;
    int w = fprintf(f, "  %s%s%s%s%s", p->name, p->alt ? ", " : "", p->alt ? p->alt : "",
                    p->arg ? " " : "", p->arg ? p->arg : "");
    if (w >= HELP_COLUMN) w = fprintf(f, "\n") - 1; /* a long name: its help on the next line */
    for (;;) {
        const char *nl = strchr(h, '\n');
        int len = nl ? (int)(nl - h) : (int)strlen(h);
        fprintf(f, "%*s%.*s\n", HELP_COLUMN - w, "", len, h);
        if (!nl) break;
        h = nl + 1;
        w = 0;
    }
}

static void usage(FILE *f)
{
    size_t i;
    fprintf(f,
            "usage: " PROG " [options] scene.obj   (- reads the scene from standard input)\n"
            "Solves the diffuse global illumination of an OBJ/MTL scene (hemi-cube radiosity,\n"
            "progressive refinement) and renders it. Kd is reflectance, Ke emission.\n"
            "Other formats (glTF .gltf/.glb, FBX, COLLADA .dae, 3DS, ...) are read through\n"
            "assimp: %s.\n\n",
            assimp_scene_available() ? "built in" : "not in this build (libassimp-dev, then make)");
    for (i = 0; i < NOPTIONS; i++) {
        if (!options[i].name)
            fprintf(f, "%s\n", options[i].help);
        else
            print_option(f, &options[i]);
    }
    fprintf(f,
            "\nWithout --camera or --views, the default camera looks along -Z at the centre of\n"
            "the meshed scene's bounding box, from in front of it (+Z), with +Y up, a 45 degree\n"
            "field of view and the box's front face filling the frame with a 5%% margin.\n"
            "Exit status: 0 success; 1 runtime or input error; 2 usage error; 3 outputs\n"
            "written, but the solve did not converge (unshot fraction above --tol at\n"
            "--max-shots) or values saturated (one line on stderr says which).\n");
}

static const option_t *find_option(const char *a)
{
    size_t i;
    for (i = 0; i < NOPTIONS; i++)
        if (options[i].name &&
            (strcmp(a, options[i].name) == 0 || (options[i].alt && strcmp(a, options[i].alt) == 0)))
            return &options[i];
    return NULL;
}

/* --group-intensity for the groups given; "other" waits for the scene. */
static void resolve_intensities(opts_t *o)
{
    int i, j;
    for (i = 0; i < o->ngint; i++) {
        const char *eq = strrchr(o->gint[i], '=');
        size_t len = (size_t)(eq - o->gint[i]);
        group_t *g = cli_find_group(o->groups, o->ngroups, o->gint[i], len);
        for (j = 0; j < i; j++)
            if (strncmp(o->gint[j], o->gint[i], len + 1) == 0)
                cli_die_usage("--group-intensity: a group given twice", o->gint[i]);
        if (!g && !(len == strlen(OTHER_GROUP) && strncmp(o->gint[i], OTHER_GROUP, len) == 0))
            cli_die_usage("--group-intensity: no --light-group of that name (or 'other')",
                          o->gint[i]);
        if (g) cli_parse_list(eq + 1, g->k, 3, 0);
    }
}

/* The combinations that cannot work, refused before anything is read. */
static void check_combinations(opts_t *o)
{
    if (!o->scene) cli_die_usage("no scene given", NULL);
    if (o->pending_cam) cli_die_usage("--camera without its -o FILE", NULL);
    if (!strcmp(o->scene, "-") && o->nviews == 0 && !o->views_file)
        cli_die_usage(
            "a scene on standard input (-) has no name to name outputs after: give -o FILE", NULL);
    if (!strcmp(o->scene, "-") && (o->probes || o->probe_file) && !o->probes_out)
        cli_die_usage("a scene on standard input (-) has no name to name outputs after: give "
                      "--probes-out FILE",
                      NULL);
    if (o->save_ff && o->load_ff) cli_die_usage("--save-ff and --load-ff exclude each other", NULL);
    if (o->ply_linear && !o->ply) cli_die_usage("--ply-linear needs --export-ply FILE", NULL);
    if (o->lightmap_opt && !o->lightmap) {
        char m[64];
        snprintf(m, sizeof m, "%s needs --lightmap FILE", o->lightmap_opt);
        cli_die_usage(m, NULL);
    }
    if (o->each_group && o->nuser_groups == 0)
        cli_die_usage("--each-group needs at least one --light-group", NULL);
    if (o->animate) {
        if (o->ncams || o->views_file)
            cli_die_usage("--animate takes its cameras from its file: no --camera or --views",
                          NULL);
        if (o->nviews > 1) cli_die_usage("--animate writes frames from one -o name", NULL);
        if (o->each_group) cli_die_usage("--animate and --each-group exclude each other", NULL);
    }
}

/* The hemi-cube settings of a run: res 192 and coarse shots by default, so that the
 * direct light, which the emitters' own shots carry, is drawn finer than the late shots
 * that move little (docs/library.md, Coarse shots: on CornellBox-Original more accurate than
 * every shot at 128, in about half the time). Stored rows (ROWS) are every patch's row
 * at res, so there the default stays 128 and nothing coarsens. */
void cli_shot_settings(const opts_t *o, int rows, sc_opts *so)
{
    so->res = o->res ? o->res : rows ? DEF_ROWS_RES : DEF_RES;
    so->coarse = rows ? 0 : o->coarse >= 0 ? o->coarse : DEF_COARSE;
    so->coarse_res = o->coarse_res ? o->coarse_res : DEF_COARSE_FLOOR(so->res);
}

/* --threads without it: the processors online, 1..64 (any count gives the same bits). */
static int default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 64 ? 64 : (int)n;
}

static void set_defaults(opts_t *o, int argc)
{
    memset(o, 0, sizeof *o);
    o->width = o->height = DEF_IMAGE_SIZE;
    o->tol = 0.001;
    o->max_shots = 1000000;
    o->threads = default_threads();
    o->batch = DEF_BATCH;
    o->coarse = -1; /* not given: cli_shot_settings */
    o->lightmap_tol = LM_TOL;
    o->lightmap_pad = -1;
    o->emit = calloc((size_t)argc, sizeof *o->emit);
    o->groups = calloc((size_t)argc + 1, sizeof *o->groups);
    o->gint = calloc((size_t)argc, sizeof *o->gint);
    o->light_files = calloc((size_t)argc, sizeof *o->light_files);
    if (!o->emit || !o->groups || !o->gint || !o->light_files) {
        fprintf(stderr, PROG ": out of memory\n");
        exit(CLI_EXIT_ERROR);
    }
}

void cli_parse_args(int argc, char **argv, opts_t *o)
{
    int i;
    set_defaults(o, argc);
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const option_t *p = a[0] == '-' && a[1] ? find_option(a) : NULL;
        if (p) {
            parsing = p;
            if (p->arg && i + 1 >= argc) cli_die_usage("option needs a value", a);
            p->fn(o, a, p->arg ? argv[++i] : NULL);
            parsing = NULL;
        } else if (a[0] == '-' && a[1])
            cli_die_usage("unknown option", a);
        else if (o->scene)
            cli_die_usage("more than one scene given", a);
        else
            o->scene = a;
    }
    check_combinations(o);
    resolve_intensities(o);
}

void cli_free_opts(opts_t *o)
{
    cli_frames_free(o->frames, o->nframes);
    free(o->views_text);
    free(o->default_out);
    free(o->probes_default);
    free(o->frames_text);
    free(o->emit);
    free(o->groups);
    free(o->gint);
    free(o->lights);
    while (o->nlight_files > 0) free((char *)o->light_files[--o->nlight_files]);
    free(o->light_files);
}
