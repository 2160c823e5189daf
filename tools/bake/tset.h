/* SPDX-License-Identifier: MIT */
/* tset — a set of 2D triangles that answers "does this one overlap any of them?", for
 * charts unfolded on a plane (uses malloc, libm).
 *
 * Triangles are filed by the square cells of side CELL that their boxes touch, in a
 * hash table of cells (one that would touch more than TSET_SPAN^2 cells is kept in a
 * list every query reads). Two triangles overlap when every one of their six edge
 * normals sees their extents overlap by more than TOL: so triangles that share an edge
 * or a corner, or touch within TOL, do not.
 */
#ifndef RAD_TOOLS_TSET_H
#define RAD_TOOLS_TSET_H

#define TSET_SPAN 16 /* cells a side of a triangle's box filed by cell */

typedef struct tset tset;

/* An empty set of cells of side CELL (> 0) and touch tolerance TOL; NULL out of memory. */
tset *tset_new(double cell, double tol);
/* Empties the set (its memory is kept for the next chart). */
void tset_clear(tset *s);
/* 1 when triangle T overlaps a triangle of the set (see above), else 0. */
int tset_hits(const tset *s, const double t[3][2]);
/* Adds triangle T. 0, or -1 out of memory (the set is then unchanged). */
int tset_add(tset *s, const double t[3][2]);
void tset_free(tset *s);

/* 1 when triangles A and B overlap by more than TOL (see above). */
int tset_tri_overlap(const double a[3][2], const double b[3][2], double tol);

#endif
