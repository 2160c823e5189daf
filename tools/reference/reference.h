/* SPDX-License-Identifier: MIT */
/* rad — analytic references for tests and benchmarks, computed in double and written
 * independently of the core: Lambert's contour formula for the form factor from a
 * point to a polygon, and a set of unoccluded receivers to check the hemi-cube on. */
#ifndef RAD_TOOLS_REFERENCE_H
#define RAD_TOOLS_REFERENCE_H

#include "host/scene.h"

#define REF_RECEIVERS 7

/* A quad from its four corners (reflectance and emission zero, tag 0). */
sc_poly ref_quad(double ax, double ay, double az, double bx, double by, double bz, double cx,
                 double cy, double cz, double dx, double dy, double dz);
/* X against REF, N elements of 3 channels (rgb rgb ...), over the channels above 1% of
 * REF's brightest: the largest relative difference into *WORST, the rms into *RMS;
 * returns the channels compared. */
int ref_rgb_diff(const double *x, const double *ref, int n, double *worst, double *rms);
/* The fixed solver FX against the float twin FL of the same scene, per element with the
 * ambient term, as ref_rgb_diff. */
int ref_twin_diff(sc_solver *fx, scf_solver *fl, double *worst, double *rms);
/* The same for two solutions X and REF of one mesh in the fixed build (-1: no memory). */
int ref_solution_diff(sc_solver *x, sc_solver *ref, double *worst, double *rms);

/* Form factor from a differential area at the origin with normal +z to polygon P
 * (wholly above z = 0): F = 1/(2 pi) |sum theta_i (n . unit(R_i x R_i+1))|. */
double ref_point_ff(const sc_poly *p);
/* Lambert's vector: the integral of the direction w over polygon P (wholly above
 * z = 0) seen from the origin, (1/2) sum theta_i unit(R_i x R_i+1), into PHI; its z
 * component is pi ref_point_ff(P). */
void ref_point_vector(const sc_poly *p, double *phi);
/* Receiver K (0..REF_RECEIVERS-1) facing the origin: parallel centred, parallel
 * offset, perpendicular, tilted 45 degrees, large, grazing, tilted triangle. Returns 0
 * past the last. Its tag is 1. */
int ref_receiver(int k, sc_poly *p);
/* The hemi-cube's form factor to receiver K from a tiny shooter at the origin, at
 * resolution RES, through the fixed core (twin 0) or the float twin (1); the analytic
 * value in *WANT. Returns -1 on failure. */
double ref_hemicube_ff(int k, int res, int twin, double *want);

#endif
