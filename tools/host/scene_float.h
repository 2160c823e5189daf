/* SPDX-License-Identifier: MIT */
/* rad host glue, the float twin: the functions of host/scene.h and host/parallel.h
 * built against librad_float (tools/host/scene.c compiled with RAD_FLOAT=1 and the
 * renames of host/float_names.h). Each does what its sc_ namesake in scene.h says; a
 * declaration here that differs from the definition fails to compile, since the float
 * build of scene.c sees both. */
#ifndef RAD_TOOLS_SCENE_FLOAT_H
#define RAD_TOOLS_SCENE_FLOAT_H

#ifndef RAD_HOST_FLOAT_NAMES
typedef struct scf_solver scf_solver;
typedef struct scf_solution scf_solution;
typedef struct scf_gatherer scf_gatherer;
#endif

scf_solver *scf_create(const sc_poly *polys, int n, const sc_opts *o, sc_warn_fn warn, void *ctx,
    char *err, size_t errlen);
void scf_destroy(scf_solver *s);
long scf_element_limit(const sc_opts *o);
int scf_solve(scf_solver *s, int max_shots, double tol, sc_progress_fn progress, void *ctx);
void scf_solve_started(scf_solver *s, double tol);
void scf_set_memory_limit(scf_solver *s, double bytes);
int scf_gauss_seidel_check(scf_solver *s, char *err, size_t errlen);
void scf_get_stats(scf_solver *s, sc_stats *st);
void scf_element_rgb(scf_solver *s, int e, int ambient, double rgb[3]);
double scf_element_area(scf_solver *s, int e);
void scf_element_centroid(scf_solver *s, int e, double c[3]);
int scf_element_tag(scf_solver *s, int e);
int scf_set_element_rho(scf_solver *s, int e, const double rho[3], char *err, size_t errlen);
void scf_element_rho(scf_solver *s, int e, double rho[3]);
int scf_element_vertices(scf_solver *s, int e, int v[4]);
void scf_vertex_pos(scf_solver *s, int v, double p[3]);
int scf_shade(scf_solver *s, int ambient, double *rgb);
int scf_shade_elements(scf_solver *s, int ambient, double *rgb);
int scf_render(scf_solver *s, const sc_camera *cam, int ambient, int w, int h, float *rgb, char *err,
    size_t errlen);
int scf_render_values(scf_solver *s, const sc_camera *cam, const double *values, int w, int h,
    double *out, unsigned char *solid, char *err, size_t errlen);
int scf_form_factors(scf_solver *s, int p, double *ff);
uint64_t scf_checksum(scf_solver *s);
void *scf_core(scf_solver *s);
int scf_rows_compute(scf_solver *s, sc_rows_progress_fn progress, void *ctx, char *err,
    size_t errlen);
int scf_rows_save(scf_solver *s, const char *path, char *err, size_t errlen);
int scf_rows_load(scf_solver *s, const char *path, char *err, size_t errlen);
void scf_get_rows_stats(scf_solver *s, sc_rows_stats *st);
int scf_rows_solve(scf_solver *s, int max_shots, double tol, sc_progress_fn progress, void *ctx);
int scf_rows_gauss_seidel(scf_solver *s, int max_iter, double tol, char *err, size_t errlen);
int scf_set_surfaces(scf_solver *s, sc_tag_match_fn match, void *ctx, const double *rho,
    const double *emit, char *err, size_t errlen);
void scf_restart(scf_solver *s);
scf_solution *scf_keep(scf_solver *s, int ambient);
void scf_solution_free(scf_solution *k);
int scf_mix(scf_solver *s, scf_solution *const *groups, const double (*intensity)[3], int n,
    char *err, size_t errlen);
scf_gatherer *scf_gatherer_new(scf_solver *s, int res, int sphere);
void scf_gatherer_free(scf_gatherer *g);
int scf_gather(scf_gatherer *g, const double p[3], const double n[3], int ambient, double rgb[3]);
int scf_gather_on(scf_gatherer *g, const double p[3], const double n[3], int surface, int ambient, double rgb[3]);
int scf_gather_sh(scf_gatherer *g, const double p[3], int ambient, double sh[9][3]);
unsigned long scf_gatherer_saturations(scf_gatherer *g);

int scf_solve_parallel(scf_solver *s, int threads, int max_shots, double tol, sc_progress_fn progress,
    void *ctx);
int scf_solve_batch(scf_solver *s, int threads, int batch, int max_shots, double tol,
    sc_progress_fn progress, void *ctx);

#endif
