/* SPDX-License-Identifier: MIT */
/* bench — what the files of rad_bench share: its scenes and runs, the report it writes,
 * the helpers more than one section calls, and each section's entry for main.
 *
 *   rad_bench.c      main, the scenes and the two builds' runs, the report's small
 *                    sections, docs/bench.md and the plots
 *   bench_peer.c     rad_cli against a peer (rpkCpp) as whole processes; accuracy
 *                    per element against a res-512 solve
 *   bench_threads.c  the parallel solve and batch shooting on threads
 *   bench_bake.c     culled gathers, lightmap baking, --gather-res and --level
 *   bench_tex.c      textures: loading and sampling them, whole processes
 *
 * A function here is named bench_*; one a single file uses stays static there. */
#ifndef RAD_TOOLS_BENCH_H
#define RAD_TOOLS_BENCH_H

#include <stddef.h>

#include "formats/obj.h"
#include "host/scene.h"

/* ---- scenes and runs (rad_bench.c) ----------------------------------------------- */

typedef struct {
    const char *name;
    sc_poly *polys;
    int n;
    double max_element; /* 0: rad_cli's default */
    double max_patch;   /* 0: the glue's default (1/8 of the extent) */
    int res;
    int runs;
    int big;              /* one of the two largest: not in the overshooting and parallel tables */
    const obj_scene *obj; /* the OBJ scene of POLYS, or NULL (generated) */
} bscene;

/* One solve's record. */
typedef struct {
    int elements, patches, shots[3]; /* shots to unshot 0.1, 0.01, 0.001 */
    int all_shots;
    double t[3], total, mesh; /* seconds to each, whole solve, meshing */
    double pix_per_s;
    size_t bytes;
    int npts;
    double *xs, *xt, *y; /* convergence: shots, seconds, unshot */
} brun;

/* V[0..N-1] sorted ascending. */
void bench_sort(double *v, long n);
/* The median of V[0..N-1], which it sorts. */
double bench_median(double *v, int n);
/* The scene's mesh and resolution as solver options. */
sc_opts bench_scene_opts(const bscene *sc);
/* A fixed-build solver of POLYS (the scene's, or a variant of them) with O; exits on
 * failure. */
sc_solver *bench_fixed_solver(const bscene *sc, const sc_poly *polys, const sc_opts *o);
/* Whether P emits. */
int bench_poly_emits(const sc_poly *p);
/* The polygons of the OBJ file PATH, its scene kept in KEEP (or freed: NULL). */
sc_poly *bench_load_obj(const char *path, int *n, obj_scene *keep);
/* A quad V (reflectance RHO, emission EM) appended to P[*N], tagged with its index. */
void bench_add_quad(sc_poly *p, int *n, const double v[4][3], const double rho[3],
                    const double em[3]);
/* Faces of the box [lo, hi], inward for a room or outward for furniture, skipping
 * face SKIP (2 * axis + high side; -1 for none), appended to P[*N]. */
void bench_add_box(sc_poly *p, int *n, const double lo[3], const double hi[3], int inward, int skip,
                   const double rho[3]);

/* ---- the report (rad_bench.c) ---------------------------------------------------- */

typedef struct {
    char md[65536];
    size_t len;
} report_t;

/* printf's FMT appended to the report's Markdown. */
void bench_out(report_t *rp, const char *fmt, ...);

/* ---- the peer (bench_peer.c) ----------------------------------------------------- */

/* The programs of the peer table: rad_cli to 0.01 and 0.001 at its defaults, rpkCpp,
 * then every shot at 128 (rad_cli's default before coarse shots), and at the bench's
 * element edge 0.08 the defaults, every shot at 128 and coarse shots from res 256. */
#define PEER_CMDS 7
#define PEER_RPK  2

/* Each rad_cli row of the peer table as the solver's settings: its tolerance, element
 * edge (0: rad_cli's default), res, coarse fraction and floor, and its flags. */
typedef struct {
    double tol, edge;
    int res;
    double coarse;
    int coarse_res;
    const char *flags;
} peer_row_t;

/* The rows; row 1 is rad_cli's defaults to 0.001. */
extern const peer_row_t bench_peer_rows[PEER_CMDS];

typedef struct {
    char why[3072];                              /* empty when measured; else why not */
    double t[PEER_CMDS], ratio[PEER_CMDS];       /* medians: each program; rad/rpkCpp per round */
    double cpu[PEER_CMDS], cpu_ratio[PEER_CMDS]; /* the same in processor time */
    long kb[PEER_CMDS];                          /* peaks over the runs */
    /* per element against a res-512 solve to 1e-4 of the same mesh (bench_peer_accuracy):
     * rms and max relative error over elements above 10% and above 1% of the brightest */
    double rms[PEER_CMDS][2], max[PEER_CMDS][2];
    int elements[PEER_CMDS];
    size_t bytes[PEER_CMDS]; /* pools and work buffer */
} peer_t;

/* Runs ARGV (output to the file OUT, or /dev/null: NULL) and waits for it: wall and
 * processor seconds, peak resident KB; 0 when it exited with status 0. */
int bench_run_child(char *const argv[], const char *out, double *secs, double *cpu, long *kb);
/* Whether PATH is a regular file. */
int bench_is_file(const char *path);
/* PATH's folder (up to its last '/', or "." ) into OUT. */
void bench_dir_of(const char *path, char *out, size_t n);
/* O with peer row ROW's res and coarse shots (rad_cli's defaults, or a row's flags). */
sc_opts bench_row_opts(sc_opts o, const peer_row_t *row);
/* SC's solve at O to TOL (fixed build). */
sc_solver *bench_solved(const bscene *sc, const sc_opts *o, double tol);
/* Per element, A against the reference REF of the same mesh: rms and largest relative
 * error over SC's non-emitting elements above FLOOR[k] of the brightest of them. */
void bench_element_accuracy(const bscene *sc, sc_solver *ref, sc_solver *a, const double floor[2],
                            double *rms, double *mx);
/* rad_cli (beside SELF) against rpkCpp on SCENE, whole processes in turn, into PR. */
void bench_peer(const char *self, const char *scene, peer_t *pr);
/* The accuracy column of PR: each rad_cli row solved in this process. */
void bench_peer_accuracy(const char *scene, peer_t *pr);
void bench_report_peers(report_t *rp, const peer_t *p, const brun *fx);

/* The cost curve (rad_bench --curve): rad_cli against rpkCpp on CornellBox-Original at
 * CURVE_SIZES refinements, to 0.01 and 0.001 (rpkCpp: 7 and 10 iterations), whole
 * processes in turn, ROUNDS <= CURVE_ROUNDS rounds. */
#define CURVE_SIZES  4
#define CURVE_CMDS   4 /* rad 0.01, rpkCpp 7, rad 0.001, rpkCpp 10 */
#define CURVE_ROUNDS 9
typedef struct {
    char why[3072]; /* empty when measured; else why not */
    int rounds;
    long elements[CURVE_SIZES][2];       /* rad's, rpkCpp's */
    double cpu[CURVE_SIZES][CURVE_CMDS]; /* medians of processor seconds */
    double ratio[CURVE_SIZES][2];        /* medians of rad/rpkCpp per round: 0.01, 0.001 */
    long kb[CURVE_SIZES][2];             /* peak resident KB, rad's and rpkCpp's */
} curve_t;
void bench_curve(const char *self, const char *scene, int rounds, curve_t *cv);
/* The curve's table and slopes into RP, its plot into PNG. */
void bench_report_curve(report_t *rp, const curve_t *cv, const char *png);

/* ---- threads (bench_threads.c) --------------------------------------------------- */

/* This thread's processor time, seconds. */
double bench_thread_cpu(void);
void bench_report_parallel(report_t *rp, const bscene *scenes, int ns, const brun *fx);
void bench_report_batch_k(report_t *rp, const bscene *sc);
void bench_report_batch_speed(report_t *rp, const bscene *scenes, int ns);

/* ---- gathers and baking (bench_bake.c) ------------------------------------------- */

void bench_report_cull(report_t *rp);
/* Shots through the hierarchy against drawing every surface (bench_report_cull's). */
void bench_report_cull_shots(report_t *rp);
void bench_report_lightmap(report_t *rp, const bscene *sc, const char *shared);
/* rad_bench --gather-res and --level: their tables to stdout; main's exit status. */
int bench_gather_res(int argc, char **argv);
int bench_level(int argc, char **argv);

/* ---- textures (bench_tex.c) ------------------------------------------------------ */

void bench_report_textures(report_t *rp, const char *self);

#endif
