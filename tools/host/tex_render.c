/* SPDX-License-Identifier: MIT */
/* rad host glue: rendered views with the textures' detail (see tex_render.h). */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "host/tex_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rad/rad.h"

/* Surface numbers go to the id render as three integers below 1024 (exact in Q16.16
   and in float, and a constant over the surface, so interpolation keeps them). */
#define ID_BASE 1024.0

static int face_of_surface(sc_solver *s, const rad_surface_t *sf)
{
    return sf->n_elements ? sc_element_tag(s, (int)sf->first_element) : -1;
}

/* Texture coordinates of P on face F: barycentric in the face's triangle (a fan from
   corner 0) that holds it best (largest smallest weight), projected on its plane. */
static void uv_at(const obj_scene *sc, const obj_face *f, const double p[3], double uv[2])
{
    const int *ix = sc->indices + f->first, *ti = sc->uv_indices + f->first;
    double best = -HUGE_VAL;
    int t, k;
    uv[0] = sc->uvs[ti[0]].u;
    uv[1] = sc->uvs[ti[0]].v;
    for (t = 1; t + 1 < f->count; t++) {
        const obj_vec3 *a = &sc->verts[ix[0]], *b = &sc->verts[ix[t]], *c = &sc->verts[ix[t + 1]];
        double e1[3] = {b->x - a->x, b->y - a->y, b->z - a->z};
        double e2[3] = {c->x - a->x, c->y - a->y, c->z - a->z};
        double d[3] = {p[0] - a->x, p[1] - a->y, p[2] - a->z};
        double d11 = 0, d12 = 0, d22 = 0, d1 = 0, d2 = 0, det, wb, wc, lo;
        for (k = 0; k < 3; k++) {
            d11 += e1[k] * e1[k];
            d12 += e1[k] * e2[k];
            d22 += e2[k] * e2[k];
            d1 += d[k] * e1[k];
            d2 += d[k] * e2[k];
        }
        det = d11 * d22 - d12 * d12;
        if (!(fabs(det) > 0)) continue;
        wb = (d1 * d22 - d2 * d12) / det;
        wc = (d2 * d11 - d1 * d12) / det;
        lo = fmin(1 - wb - wc, fmin(wb, wc));
        if (lo > best) {
            best = lo;
            for (k = 0; k < 2; k++) {
                double u0 = k ? sc->uvs[ti[0]].v : sc->uvs[ti[0]].u;
                double u1 = k ? sc->uvs[ti[t]].v : sc->uvs[ti[t]].u;
                double u2 = k ? sc->uvs[ti[t + 1]].v : sc->uvs[ti[t + 1]].u;
                uv[k] = u0 + wb * (u1 - u0) + wc * (u2 - u0);
            }
        }
    }
}

/* Is surface SF drawn with texture detail: a textured material, texture coordinates,
   no emission? Then *MAP is its texture. */
static const tex_image *surface_map(sc_solver *s, const obj_scene *sc, const tex_image *maps,
                                    const rad_surface_t *sf, int *face)
{
    int f = face_of_surface(s, sf);
    *face = f;
    if (f < 0 || sf->emission.r > 0 || sf->emission.g > 0 || sf->emission.b > 0) return NULL;
    if (sc->uv_indices[sc->faces[f].first] < 0 || !maps[sc->faces[f].material].rgb) return NULL;
    return &maps[sc->faces[f].material];
}

/* Per core vertex: the surface number + 1 in base 1024. */
static void id_values(sc_solver *s, double *ids)
{
    const rad_scene_t *core = sc_core(s);
    uint32_t si, v;
    for (si = 0; si < core->n_surfaces; si++) {
        const rad_surface_t *sf = &core->pools.surfaces[si];
        for (v = sf->first_vertex; v < sf->first_vertex + sf->n_vertices; v++) {
            double id = si + 1.0;
            int k;
            for (k = 0; k < 3; k++, id = floor(id / ID_BASE)) ids[3 * v + k] = fmod(id, ID_BASE);
        }
    }
}

int sc_render_surfaces(sc_solver *s, const sc_camera *cam, int w, int h, int *surface, char *err,
                       size_t errlen)
{
    const rad_scene_t *core = sc_core(s);
    size_t nv = (size_t)core->n_vertices + 1, np = (size_t)w * (size_t)h, i;
    double *vid = malloc(3 * nv * sizeof *vid), *pid = malloc(3 * np * sizeof *pid);
    unsigned char *solid = malloc(np);
    int rc = -1;
    if (!vid || !pid || !solid)
        snprintf(err, errlen, "out of memory for a %dx%d image", w, h);
    else {
        id_values(s, vid);
        rc = sc_render_values(s, cam, vid, w, h, pid, solid, err, errlen);
        for (i = 0; rc == 0 && i < np; i++) {
            double id = floor(pid[3 * i] + 0.5) + ID_BASE * floor(pid[3 * i + 1] + 0.5) +
                        ID_BASE * ID_BASE * floor(pid[3 * i + 2] + 0.5) - 1;
            surface[i] = solid[i] && id >= 0 && id < core->n_surfaces ? (int)id : -1;
        }
    }
    free(vid);
    free(pid);
    free(solid);
    return rc;
}

/* Per core vertex: (u, v) in the map's own coordinates (its -s / -o applied), shifted
   by whole periods to be >= 0 when it wraps (the renderer's values are unsigned). */
static void vertex_values(sc_solver *s, const obj_scene *sc, const tex_image *maps, double *uv)
{
    const rad_scene_t *core = sc_core(s);
    uint32_t si, v;
    for (si = 0; si < core->n_surfaces; si++) {
        const rad_surface_t *sf = &core->pools.surfaces[si];
        int f, k;
        const tex_image *t = surface_map(s, sc, maps, sf, &f);
        double shift[2] = {0, 0};
        if (t && !t->clamp)
            for (k = 0; k < sc->faces[f].count; k++) {
                const obj_vec2 *c = &sc->uvs[sc->uv_indices[sc->faces[f].first + k]];
                double a = c->u * t->scale[0] + t->offset[0], b = c->v * t->scale[1] + t->offset[1];
                shift[0] = k ? fmin(shift[0], floor(a)) : floor(a);
                shift[1] = k ? fmin(shift[1], floor(b)) : floor(b);
            }
        for (v = sf->first_vertex; v < sf->first_vertex + sf->n_vertices; v++) {
            double p[3], q[2] = {0, 0};
            if (t) {
                sc_vertex_pos(s, (int)v, p);
                uv_at(sc, &sc->faces[f], p, q);
                q[0] = q[0] * t->scale[0] + t->offset[0] - shift[0];
                q[1] = q[1] * t->scale[1] + t->offset[1] - shift[1];
            }
            uv[3 * v] = fmin(fmax(q[0], 0), 65535);
            uv[3 * v + 1] = fmin(fmax(q[1], 0), 65535);
            uv[3 * v + 2] = 0;
        }
    }
}

int sc_texture_elements(sc_solver *s, const obj_scene *sc, const tex_image *maps, char *err,
                        size_t errlen)
{
    const rad_scene_t *core = sc_core(s);
    uint32_t si, e;
    int n = 0;
    tex_memo *memo = malloc(sizeof *memo); /* NULL: each element on its own */
    if (memo) memo->image = NULL;
    for (si = 0; si < core->n_surfaces; si++) {
        const rad_surface_t *sf = &core->pools.surfaces[si];
        int f, k;
        const tex_image *t = surface_map(s, sc, maps, sf, &f);
        /* one element: the face's own mean already (polys_from_obj_tex); joined to a
           group: it reflects as the group's receiver */
        if (!t || sf->n_elements < 2 || sf->n_patches == 0) continue;
        for (e = sf->first_element; e < (uint32_t)sf->first_element + sf->n_elements; e++) {
            int v[4], nv = sc_element_vertices(s, (int)e, v);
            double p[4][3], mean[3], rho[3];
            obj_vec2 uv[4];
            for (k = 0; k < nv; k++) {
                double q[2];
                sc_vertex_pos(s, v[k], p[k]);
                uv_at(sc, &sc->faces[f], p[k], q);
                uv[k].u = q[0];
                uv[k].v = q[1];
            }
            tex_polygon_mean(t, (const double(*)[3])p, uv, nv, memo, mean);
            tex_reflectance(sc->materials[sc->faces[f].material].kd, mean, rho);
            if (sc_set_element_rho(s, (int)e, rho, err, errlen) < 0) {
                free(memo);
                return -1;
            }
            n++;
        }
    }
    free(memo);
    return n;
}

/* Per core vertex of a textured surface: the area-weighted mean of the reflectances of
   its surface's elements around it (as rad_shade_vertices weighs their radiosities), so
   that a pixel's radiosity and reflectance are interpolated alike. */
static void vertex_rho(sc_solver *s, const obj_scene *sc, const tex_image *maps, double *vr)
{
    const rad_scene_t *core = sc_core(s);
    uint32_t si, e, v;
    for (v = 0; v < 4u * core->n_vertices; v++) vr[v] = 0; /* 3 a vertex, then the weights */
    for (si = 0; si < core->n_surfaces; si++) {
        const rad_surface_t *sf = &core->pools.surfaces[si];
        int f;
        if (!surface_map(s, sc, maps, sf, &f)) continue;
        for (e = sf->first_element; e < (uint32_t)sf->first_element + sf->n_elements; e++) {
            int vs[4], nv = sc_element_vertices(s, (int)e, vs), k, c;
            double rho[3], a = sc_element_area(s, (int)e);
            sc_element_rho(s, (int)e, rho);
            for (k = 0; k < nv; k++) {
                for (c = 0; c < 3; c++) vr[3 * vs[k] + c] += a * rho[c];
                vr[3 * core->n_vertices + vs[k]] += a;
            }
        }
    }
    for (v = 0; v < core->n_vertices; v++) {
        double w = vr[3 * core->n_vertices + v];
        int c;
        for (c = 0; c < 3; c++) vr[3 * v + c] = w > 0 ? vr[3 * v + c] / w : 0;
    }
}

/* Multiplies pixel I, of surface ID, by its texel over the reflectance the solution
   used there: RHO_AT (3 a pixel, the elements' interpolated) or else its surface's. */
static void detail(sc_solver *s, const obj_scene *sc, const tex_image *maps, const double *uv,
                   const double *rho_at, int id, size_t i, float *rgb)
{
    const rad_scene_t *core = sc_core(s);
    const rad_surface_t *sf;
    const tex_image *t;
    tex_image plain;
    double texel[3], rho[3], sr[3];
    int f, k;
    if (id < 0) return;
    sf = &core->pools.surfaces[id];
    if (!(t = surface_map(s, sc, maps, sf, &f))) return;
    plain = *t; /* the values carry the map's scale and offset already */
    plain.scale[0] = plain.scale[1] = 1;
    plain.offset[0] = plain.offset[1] = 0;
    tex_sample(&plain, uv[3 * i], uv[3 * i + 1], texel);
    tex_reflectance(sc->materials[sc->faces[f].material].kd, texel, rho);
    sr[0] = rho_at ? rho_at[3 * i] : RAD_TO_DOUBLE(sf->reflectance.r);
    sr[1] = rho_at ? rho_at[3 * i + 1] : RAD_TO_DOUBLE(sf->reflectance.g);
    sr[2] = rho_at ? rho_at[3 * i + 2] : RAD_TO_DOUBLE(sf->reflectance.b);
    for (k = 0; k < 3; k++)
        if (sr[k] > 0) rgb[3 * i + k] = (float)(rgb[3 * i + k] * rho[k] / sr[k]);
}

int sc_texture_detail(sc_solver *s, const obj_scene *sc, const tex_image *maps,
                      const sc_camera *cam, int w, int h, float *rgb, char *err, size_t errlen)
{
    const rad_scene_t *core = sc_core(s);
    size_t nv = (size_t)core->n_vertices + 1, np = (size_t)w * (size_t)h, i;
    int own = core->element_rho != NULL; /* elements' reflectances: a fourth render */
    double *vuv = malloc(4 * nv * sizeof *vuv), *puv = malloc(3 * np * sizeof *puv);
    double *prho = own ? malloc(3 * np * sizeof *prho) : NULL;
    unsigned char *solid = malloc(np);
    int *id = malloc(np * sizeof *id);
    int rc = -1;
    if (!vuv || !puv || !solid || !id || (own && !prho))
        snprintf(err, errlen, "out of memory for a %dx%d image", w, h);
    else {
        rc = 0;
        if (own) {
            vertex_rho(s, sc, maps, vuv);
            rc = sc_render_values(s, cam, vuv, w, h, prho, solid, err, errlen);
        }
        vertex_values(s, sc, maps, vuv);
        rc = rc || sc_render_values(s, cam, vuv, w, h, puv, solid, err, errlen) ||
                     sc_render_surfaces(s, cam, w, h, id, err, errlen)
                 ? -1
                 : 0;
        for (i = 0; rc == 0 && i < np; i++)
            if (solid[i]) detail(s, sc, maps, puv, prho, id[i], i, rgb);
    }
    free(vuv);
    free(puv);
    free(prho);
    free(solid);
    free(id);
    return rc;
}

int sc_render_textured(sc_solver *s, const obj_scene *sc, const tex_image *maps,
                       const sc_camera *cam, int ambient, int w, int h, float *rgb, char *err,
                       size_t errlen)
{
    if (sc_render(s, cam, ambient, w, h, rgb, err, errlen)) return -1;
    return sc_texture_detail(s, sc, maps, cam, w, h, rgb, err, errlen);
}
