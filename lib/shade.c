/* SPDX-License-Identifier: MIT */
/* rad — shading output: element and vertex radiosity, and the viewer's camera, drawn
 * by the same rasterizer as the hemi-cube (raster.c) with colours instead of ids. */
#include "internal.h"

/* Element E as shown (rad__shown), its saturations counted in the scene. */
static rad_rgb_t display(rad_scene_t *s, uint32_t e, const rad_rgb_t *amb)
{
    e = rad__group_element(s, &s->pools.surfaces[s->pools.elements[e].surface], e);
    return rad__shown(s, e, amb, &s->stats.saturations);
}

/* The ambient term in the core's scale, when FLAGS ask for it, into AMB; else null. */
static const rad_rgb_t *shade_ambient(rad_scene_t *s, int flags, rad_rgb_t *amb)
{
    rad_real_t a[3];
    if (!(flags & RAD_SHADE_AMBIENT)) return 0;
    rad__ambient(s, a, &s->stats.saturations);
    amb->r = a[0];
    amb->g = a[1];
    amb->b = a[2];
    return amb;
}

/* B from the core's scale to the caller's, unless FLAGS keep the core's. */
static rad_rgb_t to_caller(rad_scene_t *s, int flags, rad_rgb_t b)
{
    if (flags & RAD_SHADE_SCALED) return b;
    return rad__scale2_rgb(b, -s->power_shift, &s->stats.saturations);
}

int rad_element_radiosity(rad_scene_t *s, uint32_t e, int flags, rad_rgb_t *out)
{
    rad_rgb_t amb;
    RAD__CHECK_SCENE(s);
    if (!out || e >= s->n_elements) return RAD_ERR_ARG;
    *out = to_caller(s, flags, display(s, e, shade_ambient(s, flags, &amb)));
    return RAD_OK;
}

int rad_element_geometry(rad_scene_t *s, uint32_t e, rad_vec3_t *centre, rad_energy_t *area)
{
    const rad_element_t *el;
    RAD__CHECK_SCENE(s);
    if (e >= s->n_elements) return RAD_ERR_ARG;
    el = &s->pools.elements[e];
    if (centre) {
        static const uint32_t one[4] = {1, 1, 1, 1};
        rad_vec3_t c[4];
        unsigned k, n = rad__nverts(el);
        for (k = 0; k < n; k++) c[k] = s->pools.vertices[el->v[k]];
        *centre = rad__scale2_vec(rad__wavg(c, one, n, n), -s->length_shift, &s->stats.saturations);
    }
    if (area) *area = rad__area_scale(el->area, -s->length_shift);
    return RAD_OK;
}

int rad_shade_elements(rad_scene_t *s, int flags, rad_rgb_t *out, uint32_t n)
{
    rad_rgb_t amb;
    const rad_rgb_t *pamb;
    uint32_t e;
    RAD__CHECK_SCENE(s);
    if (!out || n < s->n_elements) return RAD_ERR_ARG;
    pamb = shade_ambient(s, flags, &amb); /* once: a pass over the patches */
    for (e = 0; e < s->n_elements; e++) out[e] = to_caller(s, flags, display(s, e, pamb));
    return (int)s->n_elements;
}

int rad_shade_vertices(rad_scene_t *s, int flags, rad_rgb_t *out, uint32_t n)
{
    rad_rgb_t amb;
    const rad_rgb_t *pamb;
    rad_ff_t *wsum;
    uint32_t e, v, k;
    RAD__CHECK_SCENE(s);
    if (!out || n < s->n_vertices) return RAD_ERR_ARG;
    pamb = shade_ambient(s, flags, &amb);
    /* Two passes over the elements: the weight sums per vertex (in the accumulator
     * scratch, sized for max(elements, vertices)), then each element's share. */
    wsum = s->acc;
    for (v = 0; v < s->n_vertices; v++) {
        wsum[v] = 0;
        out[v].r = out[v].g = out[v].b = 0;
    }
    for (e = 0; e < s->n_elements; e++) {
        const rad_element_t *el = &s->pools.elements[e];
        for (k = 0; k < rad__nverts(el); k++) wsum[el->v[k]] += rad__vweight(el->area);
    }
    for (e = 0; e < s->n_elements; e++) {
        const rad_element_t *el = &s->pools.elements[e];
        rad_rgb_t b = display(s, e, pamb);
        rad_ff_t w = rad__vweight(el->area);
        for (k = 0; k < rad__nverts(el); k++) {
            rad_rgb_t *o = &out[el->v[k]];
            rad_ff_t ws = wsum[el->v[k]];
            o->r = rad__add_sat(o->r, rad__wpart(b.r, w, ws), &s->stats.saturations);
            o->g = rad__add_sat(o->g, rad__wpart(b.g, w, ws), &s->stats.saturations);
            o->b = rad__add_sat(o->b, rad__wpart(b.b, w, ws), &s->stats.saturations);
        }
    }
    for (v = 0; v < s->n_vertices; v++) out[v] = to_caller(s, flags, out[v]);
    return (int)s->n_vertices;
}

/* Surfaces meshed independently meet at T-junctions whose vertices round to slightly
 * different subpixels, which can leave a pixel between them uncovered. A pixel left
 * empty between two covered neighbours (left and right, or above and below) takes
 * their mean; it is marked with depth 1, which no surface has (depths are >= 2^22 /
 * 554), so filled pixels never vouch for others. */
static void fill_cracks(rad_rgb_t *fb, uint32_t *z, unsigned w, unsigned h)
{
    unsigned x, y;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x, a = 0, b = 0;
            if (z[i] != 0) continue;
            if (x > 0 && x + 1 < w && z[i - 1] > 1 && z[i + 1] > 1) {
                a = i - 1;
                b = i + 1;
            } else if (y > 0 && y + 1 < h && z[i - w] > 1 && z[i + w] > 1) {
                a = i - w;
                b = i + w;
            } else
                continue;
            fb[i].r = fb[a].r / 2 + fb[b].r / 2;
            fb[i].g = fb[a].g / 2 + fb[b].g / 2;
            fb[i].b = fb[a].b / 2 + fb[b].b / 2;
            z[i] = 1;
        }
}

static int point_ok(rad_vec3_t p, rad_real_t lim)
{
    return p.x >= -lim && p.x <= lim && p.y >= -lim && p.y <= lim && p.z >= -lim && p.z <= lim;
}

int rad_render(rad_scene_t *s, const rad_rgb_t *vrgb, const rad_camera_t *cam, rad_rgb_t *fb,
               uint32_t *zbuf, unsigned w, unsigned h)
{
    const rad_real_t lim = RAD__Q(4 * RAD_COORD_LIMIT);
    rad_vec3_t ax[3]; /* right, up, forward */
    rad__frustum_t f;
    rad__target_t t;
    rad_stats_t st = {0};
    rad_vec3_t eye, target;
    rad_real_t kx, ky;
    uint32_t e, i, sat = 0;

    RAD__CHECK_SCENE(s);
    if (!vrgb || !cam || !fb || !zbuf || w < 1 || h < 1 || w > RAD_MAX_RASTER || h > RAD_MAX_RASTER)
        return RAD_ERR_ARG;
    /* The camera in the core's scale (exact: a shift; saturation is out of range). */
    eye = rad__scale2_vec(cam->eye, s->length_shift, &sat);
    target = rad__scale2_vec(cam->target, s->length_shift, &sat);
    if (sat || !point_ok(eye, lim) || !point_ok(target, lim) ||
        !(cam->tan_half_fov >= RAD__Q(1.0 / 16.0) && cam->tan_half_fov <= RAD__Q(16.0)))
        return RAD_ERR_ARG;
    if (!rad__normalize(rad__sub(target, eye), &ax[2]) ||
        !rad__normalize(rad__cross(ax[2], cam->up), &ax[0]))
        return RAD_ERR_ARG;
    ax[1] = rad__cross(ax[0], ax[2]);

    /* Scale the screen axes so the field of view has unit slopes: 1 / tan vertically,
     * 1 / (tan * aspect) across; within [1/16, 16] both keep 12 bits or more. */
    ky = rad__div(RAD__ONE, cam->tan_half_fov, &sat);
    kx = rad__div(ky, rad__div(rad__from_int((int32_t)w), rad__from_int((int32_t)h), &sat), &sat);
    if (sat || !(kx >= RAD__Q(1.0 / 16.0) && kx <= RAD__Q(16.0) && ky >= RAD__Q(1.0 / 16.0) &&
                 ky <= RAD__Q(16.0)))
        return RAD_ERR_ARG;
    for (i = 0; i < 3; i++) {
        rad_real_t *r = i == 0 ? &ax[0].x : i == 1 ? &ax[0].y : &ax[0].z;
        rad_real_t *u = i == 0 ? &ax[1].x : i == 1 ? &ax[1].y : &ax[1].z;
        *r = rad__mul(*r, kx, &sat);
        *u = rad__mul(*u, ky, &sat);
    }
    f.half = 0;
    f.ortho = 0;
    f.recede = 0;
    f.width = (int)w;
    f.height = (int)h;
    t.z = zbuf;
    t.ids = 0;
    t.rgb = fb;
    t.lat = 0;
    t.steps = 0;
    t.width = (int)w;
    t.row0 = 0;
    t.row1 = (int)h;
    t.least = 0;
    for (i = 0; i < w * h; i++) {
        zbuf[i] = 0;
        fb[i].r = fb[i].g = fb[i].b = 0;
    }
    for (e = 0; e < s->n_elements; e++) {
        const rad_element_t *el = &s->pools.elements[e];
        rad__cvert_t cv[4];
        unsigned k, nv = rad__nverts(el);
        if (rad__dot(s->pools.surfaces[el->surface].normal,
                     rad__sub(eye, s->pools.vertices[el->v[0]])) <= 0)
            continue; /* seen from behind: radiosity is one-sided */
        for (k = 0; k < nv; k++) {
            rad_vec3_t d = rad__sub(s->pools.vertices[el->v[k]], eye);
            const rad_rgb_t *c = &vrgb[el->v[k]];
            cv[k].a = rad__dot(d, ax[0]);
            cv[k].b = rad__dot(d, ax[1]);
            cv[k].d = rad__dot(d, ax[2]);
            cv[k].c[0] = c->r;
            cv[k].c[1] = c->g;
            cv[k].c[2] = c->b;
        }
        rad__draw(&st, &t, &f, cv, nv, rad__outcodes(&f, cv, nv), 0);
    }
    fill_cracks(fb, zbuf, w, h);
    return (int)st.raster_calls;
}
