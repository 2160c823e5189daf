/* SPDX-License-Identifier: MIT */
/* rad_cli — what its files share: the options, the views and light groups, the steps.
 *
 * Every file of tools/cli/ is built twice: rad_cli (the fixed-point core) and
 * rad_cli_float (the float twin, -DRAD_FLOAT=1). This header comes first in each, so
 * that the float build calls the twin's glue (host/float_names.h) under the sc_ names.
 *
 * Files: options.c (the option table, --help from it), views.c (the --views and
 * --animate parsers, on a buffer), rad_cli.c (main: load, build, solve, outputs),
 * lights.c (the lights' fields, --lights files, --sky-hdr maps),
 * solve.c (the solves), progress.c (every long stage's progress and ETA), outputs.c (images, PLY, CSV, output and
 * camera checks), balance.c (where the emitted light goes), bake.c (lightmaps and
 * probes from the solution, tools/bake/).
 */
#ifndef RAD_CLI_H
#define RAD_CLI_H

#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#define PROG "rad_cli_float"
#else
#define PROG "rad_cli"
#endif

#include <stddef.h>
#include <stdio.h>

#include "formats/gltf.h"
#include "formats/obj.h"
#include "formats/texture.h"
#include "host/fgather.h"
#include "bake/gltf_export.h"
#include "host/defaults.h"
#include "host/scene.h"

/* Exit statuses (docs/cli.md's and --help's list). */
#define CLI_EXIT_OK     0 /* success */
#define CLI_EXIT_ERROR  1 /* runtime or input error: one line on stderr */
#define CLI_EXIT_USAGE  2 /* usage error */
#define CLI_EXIT_WARNED 3 /* outputs written, but not converged or saturated */

#define MAX_VIEWS 4096

/* The largest emission channel accepted: the OBJ loader's limit on any number, now also
 * on --emit. The core holds radiosity up to 128 times the brightest emission (Q16.16
 * below 32768 with that emission at 256; past it values saturate, and are reported),
 * and a group's intensity is below 2^15, so an image value stays below
 * 2^22 * 1e30 = 4.2e36 per light group: inside float's 3.4e38 for up to 80 groups at
 * full intensity, and no infinity reaches the auto exposure. */
#define CLI_EMIT_LIMIT 1e30
#define MAX_GROUP_NAME 64
#define OTHER_GROUP    "other"

typedef struct {
    int has_cam;
    sc_camera cam;
    const char *out;
    int line; /* its line in the --views file; 0: -o */
} view_t;

/* A light group: emitting materials solved together, mixed with an intensity. */
typedef struct {
    char name[MAX_GROUP_NAME];
    const char *mats; /* "MAT1,MAT2,..." as given */
    double k[3];      /* --group-intensity (1,1,1) */
} group_t;

typedef struct {
    sc_camera cam;
    double (*k)[3]; /* intensity of every group in this frame */
} frame_t;

typedef struct {
    const char *scene;
    view_t views[MAX_VIEWS];
    int nviews, pending_cam; /* pending_cam: a --camera still waiting for its -o */
    sc_camera pending;
    int width, height, res, max_shots, threads, quiet, stats, list, no_ambient, no_overshoot;
    int batch; /* --batch: shots whose hemi-cubes render at once */
    double tol, exposure, max_patch, max_element;
    double coarse; /* --coarse (0: never; -1: not given), --coarse-res (0: not given) */
    int coarse_res;
    const char *ply, *csv, *views_file;
    const char *gltf;   /* --export-gltf */
    int no_textures;    /* --no-textures: map_Kd ignored (Kd alone) */
    int allow_outside;  /* --allow-outside-paths: inputs outside the scene's
                                       folder, --views outputs outside the current one */
    int two_sided;      /* --two-sided: every face doubled, back to back */
    int no_file_lights; /* --no-file-lights: the scene file's lights left out */
    int ply_linear;     /* --ply-linear: --export-ply binary, float, welded */
    char **emit;
    int nemit;
    sc_light *lights; /* --sun, --point, --spot, --sky, --sky-hdr's suns and
                                       --lights files' lights, in the command line's order */
    int nlights, max_lights;
    const char **light_files; /* --lights and --sky-hdr files (cli_check_collisions) */
    int nlight_files;
    /* stored form factors and relighting */
    const char *save_ff, *load_ff, *animate;
    int gauss_seidel, each_group, ncams;
    group_t *groups; /* --light-group, then "other" once the scene is known */
    int ngroups, nuser_groups;
    char **gint; /* --group-intensity as given */
    int ngint;
    frame_t *frames;
    int nframes;
    char *views_text, *frames_text; /* the files' contents: views' names point into them */
    char *default_out;              /* scene name + .png, when no -o */
    /* bake.c: lightmap and probes */
    const char *lightmap, *probe_file, *probes_out;
    char *probes_default; /* scene name + .probes.json, when no --probes-out */
    int lightmap_size, gather_res, probe_dims[3], probes;
    double lightmap_tol; /* --lightmap-tol: lm_opts' tol */
    int lightmap_pad;    /* --lightmap-pad; -1: lm_opts' default, 0: none */
    int lightmap_uv;     /* --lightmap-uv: LIGHTMAP_UV_AUTO, _FILE or _RAD */
    int lightmap_soft;   /* --lightmap-soft: LIGHTMAP_SOFT_GATHER or _ELEMENTS */
    const char *
        lightmap_opt; /* the last --lightmap-size, -pad, -tol, -uv or -soft given (they need --lightmap) */
} opts_t;

enum { LIGHTMAP_UV_AUTO, LIGHTMAP_UV_FILE, LIGHTMAP_UV_RAD };
enum { LIGHTMAP_SOFT_GATHER, LIGHTMAP_SOFT_ELEMENTS };

void cli_shot_settings(const opts_t *o, int rows, sc_opts *so);

typedef struct {
    float *img;
    unsigned char *rgb8;
    double exposure;     /* 0 until the first view fixes it */
    const obj_scene *sc; /* with MAPS: views drawn with the textures' detail */
    const tex_image *maps;
    sc_fgather *fg; /* --gather: views and vertex exports by gathering, else NULL */
    long gathers;   /* the views' gathers */
    double t_render, t_write;
    double t_csv, t_gltf;         /* --dump-radiosity's and --export-gltf's writes (--stats) */
    unsigned long export_ambient; /* the ambient terms they had the core compute */
    double gltf_scale;            /* the light one unit of the .glb's COLOR_0 stands for */
} out_t;

/* One run's state, from step to step (rad_cli.c's main). */
typedef struct {
    opts_t *o;
    obj_scene sc;
    int have_scene;
    sc_solver *s;
    sc_opts so;
    sc_stats st;
    tex_image *maps; /* per material (map_Kd), NULL with --no-textures */
    sc_poly *polys;  /* what the solver was made from (--export-gltf) */
    int npolys;
    sc_solution **sol;   /* groups: each group's solution, for mixing */
    double (*ks)[3];     /* groups: the run's intensities */
    int *group_of;       /* material -> group, or -1 */
    int *light_group_of; /* light (of lights) -> group, or -1 */
    int rows_mode, groups_mode, ambient;
    int work;        /* shots (or Gauss-Seidel sweeps) of the solve */
    int unconverged; /* solves that stopped at the limit above --tol */
    int soft_kept;   /* the solve kept its elements' soft light (sc_solve_lights) */
    unsigned long raster_before_solve;
    double t0, t_load, t_mesh, t_rows, t_solve;
    double t_vertices, t_ply, t_lightmap,
        t_probes; /* --stats: the outputs' stages (CSV, glTF: out_t's) */
    double
        t_layout; /* --stats: cli_bake_prepare (the lightmap's charts, packing and samples; the probes' points),
                      * between the meshing and the solve */
    double landing; /* share of the emitted light reaching front faces, or -1 */
    out_t ot;
    struct bake_state *bake; /* bake.c: the polygons and the lightmap's atlas */
    sc_light *lights;        /* --sun, --point, --spot, then the scene file's lights */
    int nlights;
} run_t;

/* ---- options.c ---- */
/* Reads the command line into O; prints usage and exits 2 on a usage error. */
void cli_parse_args(int argc, char **argv, opts_t *o);
void cli_die_usage(const char *msg, const char *arg);
void cli_add_view(opts_t *o, const sc_camera *cam, const char *out);
/* The outputs of the run against its inputs (the scene, its libraries and textures,
 * --views, --animate, --probe-file, --load-ff) and each other, by file identity:
 * one line on stderr and -1 for the first that would write over another. */
int cli_check_collisions(const opts_t *o, const obj_scene *sc);
void cli_free_opts(opts_t *o);

/* ---- lights.c ---- */
/* The kinds of light the options and --lights files give; each's values in the
 * options' order (lights.c's table): sun DX,DY,DZ,R,G,B,ANGLE; point X,Y,Z,R,G,B; spot
 * X,Y,Z,DX,DY,DZ,R,G,B,ANGLE,SOFTNESS; sky R,G,B,HR,HG,HB,N; sky-hdr -,N,SCALE (the
 * file aside). An optional value left out is NAN (its default). */
#define CLI_LIGHT_SUN        0
#define CLI_LIGHT_POINT      1
#define CLI_LIGHT_SPOT       2
#define CLI_LIGHT_SKY        3
#define CLI_LIGHT_SKY_HDR    4
#define CLI_LIGHT_MAX_VALUES 11
#define CLI_MAX_LIGHTS       65535 /* the core's count (rad_use_lights) */
/* The count of KIND's values. */
int cli_light_values(int kind);
/* The first field of KIND whose values V break its rule (lights.c), or -1. */
int cli_light_check(int kind, const double *v);
/* A new light at the end of O's (zeroed); exits 2 beyond CLI_MAX_LIGHTS, 1 out of memory. */
sc_light *cli_new_light(opts_t *o);
/* Light KIND (not CLI_LIGHT_SKY_HDR) of checked values V appended to O's. */
void cli_light_make(opts_t *o, int kind, const double *v);
/* --sky-hdr: the map at PATH (tools/formats/hdr.h) shot as the sky dome of DIRS
 * directions (0: 192) times SCALE, its suns appended to O's (tools/host/sky_map.h).
 * 0, or -1 with "PATH: what" in err. */
int cli_add_sky_map(opts_t *o, const char *path, int dirs, double scale, char *err, size_t errlen);
/* --lights: the JSON file at PATH (docs: {"lights": [...]}) appended to O's lights in
 * its order. 0, or -1 with "PATH:LINE:COL: what" (or "PATH: what") in err. */
int cli_read_lights(opts_t *o, const char *path, char *err, size_t errlen);

/* ---- views.c: parsers that take a buffer (the fuzz harness calls them) ---- */
/* N comma-separated finite numbers, or N-1 when OPT_LAST is set; anything else (junk,
 * a trailing comma, more values) fails. Returns the count or -1. */
int cli_parse_list(const char *s, double *v, int n, int opt_last);
/* A camera from EX,EY,EZ,LX,LY,LZ[,FOV] (K values): up is +y, or -z when looking straight
 * up or down. Returns 0 for a zero view direction or a field of view outside 8..170. */
int cli_set_camera(sc_camera *c, const double *v, int k);
group_t *cli_find_group(group_t *g, int n, const char *name, size_t len);
/* Called for each view line: the camera, the output name (a string inside TEXT) and
 * the line. Nonzero stops the parse: cli_views_parse fails with "NAME:LINE: " + WHY. */
typedef int (*view_fn)(void *ctx, const sc_camera *cam, const char *out, int line, char *why,
                       size_t whylen);
/* --views: TEXT (LEN bytes, NUL after them, modified in place: output names point into
 * it) one view a line "EX EY EZ LX LY LZ [FOV] OUTPUT", '#' lines are comments to their
 * end. Returns the views, or -1 with "NAME:LINE: what" in err. */
int cli_views_parse(char *text, size_t len, const char *name, view_fn add, void *ctx, char *err,
                    size_t errlen);
/* --animate: TEXT as above, a frame a line "EX EY EZ LX LY LZ [FOV] [GROUP=R,G,B ...]",
 * intensities starting from the groups' own. *FRAMES is malloc'd (cli_frames_free). Returns
 * the frames (at least one), or -1 with err and nothing to free. */
int cli_frames_parse(char *text, size_t len, const char *name, group_t *groups, int ngroups,
                     frame_t **frames, char *err, size_t errlen);
void cli_frames_free(frame_t *frames, int n);

/* ---- outputs.c ---- */

const char *cli_ext_of(const char *path);
/* PATH with SEP + MID inserted before its extension: out.png -> out.MID.png (malloc'd;
 * exits on out of memory). */
char *cli_insert_name(const char *path, const char *sep, const char *mid);
/* --animate's frame I: -o's name + _0000, _0001, ... (malloc'd). */
char *cli_frame_name(const opts_t *o, int i);
char *cli_default_output(const char *scene);
/* Every output of the run checked before the solve; exits 1 on the first that cannot be
 * written. */
void cli_check_outputs(const opts_t *o);
/* The names made from them: --animate's frames and --each-group's images (once the
 * frames and groups are known, still before the solve). */
void cli_check_group_outputs(const opts_t *o);
/* Renders CAM and writes PATH (NULL: only render, to fix the exposure). One exposure
 * for every output, from the first view rendered (or --exposure), so views match. */
int cli_render_view(sc_solver *s, const opts_t *o, const sc_camera *cam, const char *path,
                    int ambient, out_t *ot);
/* Renders every view and frame once, small, before the solve: a camera the core refuses
 * (too far, too narrow for the image's shape) fails now, not after it. 0 or -1. */
int cli_check_cameras(sc_solver *s, const opts_t *o);
/* --dump-radiosity: a row per element, the radiosities from sc_shade_elements (the
 * ambient term computed once); its time added to OT's t_csv. 0 or -1 (said). */
int cli_write_csv(const char *path, sc_solver *s, const obj_scene *sc, int ambient,
                  const sc_stats *st, out_t *ot);
/* --export-gltf: the .glb of the input's meshes (sc_export_gltf_lightmap, with the
 * lightmap LM or NULL); WARN gets the writer's warnings; its time added to t_gltf.
 * 0 or -1 (said). */
int cli_write_gltf(run_t *r, const lm_atlas *lm, gltf_warn_fn warn);
/* --stats: the exports' line (times), when any was written. */
void cli_print_export_stats(const opts_t *o, const out_t *ot);
/* --export-ply: the meshed scene, its vertex colours from sc_vertex_colours (gathered
 * with FG when --gather is given), 8-bit sRGB at EXPOSURE, or with LINEAR (--ply-linear)
 * binary float radiosity, welded vertices and normals (tools/formats/ply.h). 0 or -1. */
int cli_write_ply(const char *path, sc_solver *s, sc_fgather *fg, int ambient, int linear,
                  double exposure, const sc_stats *st);

/* ---- balance.c ---- */
/* The power-weighted share of the emitters' light that their hemi-cubes land on front
 * faces of elements (1 in a closed scene), from up to 64 hemi-cubes at res 128; -1 when
 * nothing emits. Renders hemi-cubes: call it after the solve's statistics are kept. */
double cli_emitted_share_landing(run_t *r);

/* ---- bake.c ---- */
/* Before the solve: the lightmap's atlas laid out (an atlas that cannot fit fails
 * now, not after the solve). 0, or -1 after one line on stderr. Nothing asked: 0. */
int cli_bake_prepare(run_t *r);
/* --lightmap and --probes / --probe-file: baked from the solution (after the views);
 * 0, or -1 after one line on stderr. Nothing asked: 0. */
int cli_bake_step(run_t *r);
/* --export-gltf with --lightmap: the .glb written after the bake, with TEXCOORD_1 and
 * the atlas (sc_export_gltf_lightmap); WARN gets the writer's warnings. 0 (nothing to
 * do, or written) or -1 (said). */
int cli_bake_export_gltf(run_t *r, gltf_warn_fn warn);
void cli_bake_free(run_t *r);
/* The scene's name + .probes.json (malloc'd), as cli_default_output. */
char *cli_probes_output(const char *scene);

/* ---- solve.c ---- */
/* The solve, by shooting or from the rows (computed, loaded or saved), each light group
 * alone then mixed. 0, or -1 after one line on stderr. */
int cli_solve_step(run_t *r);
/* Sets the mix of the groups with intensities K (one RGB per group); 0 or -1. */
int cli_mix_groups(run_t *r, sc_solution *const *sol, const double (*k)[3], int n);

#endif
