/* SPDX-License-Identifier: MIT */
/* rad host glue: the element mesh as PLY (see ply_export.h). */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "host/ply_export.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "formats/file_io.h"
#include "rad/rad.h"

/* Every vertex's surface normal: a surface owns the vertices first_vertex ..
 * first_vertex + n_vertices - 1. The core keeps a unit normal (Q16.16 in the fixed
 * build, within 2^-16 of unit length), made unit again in double. */
static void vertex_normals(sc_solver *s, double *normal)
{
    const rad_scene_t *core = sc_core(s);
    uint32_t i, v;
    for (i = 0; i < core->n_surfaces; i++) {
        const rad_surface_t *sf = &core->pools.surfaces[i];
        double n[3] = {RAD_TO_DOUBLE(sf->normal.x), RAD_TO_DOUBLE(sf->normal.y),
                       RAD_TO_DOUBLE(sf->normal.z)};
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (v = sf->first_vertex; v < sf->first_vertex + sf->n_vertices; v++) {
            normal[3 * v] = len > 0 ? n[0] / len : 0;
            normal[3 * v + 1] = len > 0 ? n[1] / len : 0;
            normal[3 * v + 2] = len > 0 ? n[2] / len : 0;
        }
    }
}

static void element_faces(sc_solver *s, int nf, int *face)
{
    int e;
    for (e = 0; e < nf; e++) {
        int *f = &face[4 * e];
        if (sc_element_vertices(s, e, f) == 3) f[3] = -1;
    }
}

int sc_export_ply(sc_solver *s, const double *rgb, const char *path, int format, double exposure,
                  char *err, size_t errlen)
{
    sc_stats st;
    ply_mesh m;
    double *pos, *normal;
    int *face, v, rc = -1;
    char comment[200];
    sc_get_stats(s, &st);
    pos = malloc(((size_t)st.vertices + 1) * 3 * sizeof *pos);
    normal = malloc(((size_t)st.vertices + 1) * 3 * sizeof *normal);
    face = malloc(((size_t)st.elements + 1) * 4 * sizeof *face);
    if (pos && normal && face) {
        for (v = 0; v < st.vertices; v++) sc_vertex_pos(s, v, &pos[3 * v]);
        vertex_normals(s, normal);
        element_faces(s, st.elements, face);
        if (format == PLY_ASCII_SRGB)
            snprintf(comment, sizeof comment, "rad radiosity, sRGB vertex colours at exposure %g",
                     exposure);
        else
            snprintf(comment, sizeof comment,
                     "rad radiosity, linear float vertex colours in the scene's "
                     "units (the images' exposure %.9g)",
                     exposure);
        m.nv = st.vertices;
        m.nf = st.elements;
        m.pos = pos;
        m.rgb = rgb;
        m.normal = normal;
        m.face = face;
        m.comment = comment;
        rc = ply_write(path, &m, format, exposure, err, errlen);
    } else {
        fio_err(err, errlen, path, "out of memory for %d vertices", st.vertices);
    }
    free(pos);
    free(normal);
    free(face);
    return rc;
}
