/* SPDX-License-Identifier: MIT */
/* rad — stored form factors: rows of the patch-to-element matrix kept in caller memory,
 * shooting from them, the full-matrix Gauss-Seidel solve, and light-group mixing.
 * None of this renders a hemi-cube once the rows are stored. */
#include "internal.h"

rad_ff_t rad_ff_from_code(uint16_t code)
{
    return rad__ff_from_q30(rad__ff_decode(code));
}

/* Whether the first N rows of ROWS are rows of scene S: offsets from 0, rising, within
 * max_entries, and every id one of S's elements (a pass over the entries). */
static int rows_valid(const rad_scene_t *s, const rad_rows_t *rows, uint32_t n)
{
    uint32_t p, i;
    if (rows->start[0] != 0) return 0;
    for (p = 0; p < n; p++)
        if (rows->start[p + 1] < rows->start[p] || rows->start[p + 1] > rows->max_entries) return 0;
    for (i = 0; i < rows->start[n]; i++)
        if (rows->ids[i] >= s->n_elements) return 0;
    return 1;
}

int rad_rows_compute(rad_scene_t *s, rad_rows_t *rows, uint32_t count)
{
    uint32_t done = 0;
    RAD__CHECK_SCENE(s);
    if (!rows || !rows->start || !rows->ids || !rows->ffs || rows->max_rows < s->n_patches ||
        rows->n_rows > s->n_patches)
        return RAD_ERR_ARG;
    if (rows->n_rows > 0 && !rows_valid(s, rows, rows->n_rows)) return RAD_ERR_ARG;
    rad__freeze(s); /* rows describe this geometry: no more polygons */
    if (rows->n_rows == 0) rows->start[0] = 0;
    while (done < count && rows->n_rows < s->n_patches) {
        uint32_t p = rows->n_rows, e, n = rows->start[p], seen = 0;
        rad__hemicube(s, p);
        for (e = 0; e < s->n_elements; e++) seen += rad__ff_to_q30(s->acc[e]) > 0;
        if (seen > rows->max_entries - n) return done ? (int)done : RAD_ERR_FULL;
        for (e = 0; e < s->n_elements; e++) {
            uint32_t q = rad__ff_to_q30(s->acc[e]);
            if (q == 0) continue;
            rows->ids[n] = (rad_index_t)e;
            rows->ffs[n] = rad__ff_code(q);
            n++;
        }
        rows->start[p + 1] = n;
        rows->n_rows++;
        done++;
    }
    return (int)done;
}

/* RAD_OK for the rows of every patch of S, RAD_ERR_STATE while rows are missing,
 * RAD_ERR_ARG for rows that are not S's (rows_valid). */
static int rows_ready(const rad_scene_t *s, const rad_rows_t *rows)
{
    if (!rows || !rows->start || !rows->ids || !rows->ffs) return RAD_ERR_ARG;
    if (rows->n_rows != s->n_patches) return RAD_ERR_STATE;
    return rows_valid(s, rows, rows->n_rows) ? RAD_OK : RAD_ERR_ARG;
}

/* Lights are not rows: a light's direct light is its first shot, rendered again on each
 * solve (light.c) exactly as rad_shoot renders it. Stored, a light would need a row of
 * up to every element (a sky one per direction: its dome turns with its colours) in
 * more caller memory, for a handful of renders next to the patches' rows. */
int rad_rows_shoot(rad_scene_t *s, const rad_rows_t *rows, uint32_t max_shots, rad_real_t tol)
{
    int rc;
    RAD__CHECK_SCENE(s);
    if ((rc = rows_ready(s, rows)) < 0) return rc;
    s->shot_patch = RAD_INDEX_NONE; /* as rad_shoot */
    if (rad__lights_pending(s)) return rad__lights_solve(s, rows, max_shots, tol);
    return rad__shoot(s, rows, max_shots, tol);
}

/* G[m][k] = (A_m / A_k) * sum over k's elements j of F(m -> j). */
static void assemble(rad_scene_t *s, const rad_rows_t *rows, rad_ff_t *g)
{
    uint32_t np = s->n_patches, m, i;
    for (i = 0; i < np * np; i++) g[i] = 0;
    for (m = 0; m < np; m++) {
        rad_real_t am = s->pools.patches[m].area;
        for (i = rows->start[m]; i < rows->start[m + 1]; i++) {
            uint32_t k = s->pools.elements[rows->ids[i]].patch;
            rad_ff_t f = rad__ff_from_q30(rad__ff_decode(rows->ffs[i]));
            rad_ff_t add = rad__ff_scale(f, am, s->pools.patches[k].area, &s->stats.saturations);
            rad_ff_t *cell = &g[(size_t)m * np + k];
            /* Sums past Q2.30's 4.0 would be numerical nonsense: clamp and count. */
            if (rad__ff_to_q30(add) > 0xFFFFFFFFu - rad__ff_to_q30(*cell)) {
                *cell = rad__ff_from_q30(0xFFFFFFFFu);
                s->stats.saturations++;
            } else
                *cell += add;
        }
    }
}

/* Patch K's emission-plus-reflection from the current patch radiosities B (3 per patch);
 * E its emission plus the lights' direct light it reflects. */
static rad_real_t gather(rad_scene_t *s, const rad_ff_t *g, const rad_real_t *b, uint32_t k,
                         unsigned c, rad_real_t e, rad_real_t rho)
{
    uint32_t np = s->n_patches, m;
    rad__gsum_t sum = 0;
    for (m = 0; m < np; m++) sum += rad__gs_term(g[(size_t)m * np + k], b[3 * m + c]);
    return rad__add_sat(
        e, rad__mul(rho, rad__gs_value(sum, &s->stats.saturations), &s->stats.saturations),
        &s->stats.saturations);
}

/* Every element at its emission, then the lights' shots: each element's direct light
 * added, and each patch's unshot power the direct light it reflects (rad__receive),
 * which source() reads. */
static void start_direct(rad_scene_t *s)
{
    uint32_t e, k;
    for (e = 0; e < s->n_elements; e++)
        s->pools.elements[e].radiosity =
            rad__emission(s, &s->pools.surfaces[s->pools.elements[e].surface]);
    for (k = 0; k < s->n_patches; k++) {
        rad_patch_t *pt = &s->pools.patches[k];
        pt->unshot[0] = pt->unshot[1] = pt->unshot[2] = 0;
    }
    rad__lights_shoot(s, UINT32_MAX); /* checked in range by the caller */
}

/* Patch K's own radiosity: its emission plus the direct light it reflects (its unshot
 * power over its area, after start_direct). */
static rad_rgb_t source(rad_scene_t *s, uint32_t k)
{
    const rad_patch_t *pt = &s->pools.patches[k];
    rad_rgb_t em = rad__emission(s, &s->pools.surfaces[pt->surface]);
    rad_energy_t a = rad__energy(RAD__ONE, pt->area);
    uint32_t *sat = &s->stats.saturations;
    /* (light received is >= 0; without lights, 0: the emission's own bits) */
    if (pt->unshot[0] > 0) em.r = rad__add_sat(em.r, rad__energy_ratio(pt->unshot[0], a), sat);
    if (pt->unshot[1] > 0) em.g = rad__add_sat(em.g, rad__energy_ratio(pt->unshot[1], a), sat);
    if (pt->unshot[2] > 0) em.b = rad__add_sat(em.b, rad__energy_ratio(pt->unshot[2], a), sat);
    return em;
}

int rad_rows_gauss_seidel(rad_scene_t *s, const rad_rows_t *rows, rad_ff_t *matrix, size_t entries,
                          uint32_t max_iter, rad_real_t tol)
{
    uint32_t np, k, it, e;
    rad_real_t *b;
    int rc;
    RAD__CHECK_SCENE(s);
    if (!rows || !matrix) return RAD_ERR_ARG;
    np = s->n_patches;
    /* The fixed build's sums hold 2^14 patches' terms (see rad__gs_term). */
    if (entries < RAD_GS_ENTRIES(np) || np > 16384u) return RAD_ERR_ARG;
    if ((rc = rows_ready(s, rows)) < 0) return rc;
    if ((rc = rad__lights_check(s, 0)) < 0) return rc;
    s->shot_patch = RAD_INDEX_NONE;
    if (s->n_lights) rad_restart(s); /* the lights shoot again, from the emissions alone */
    rad__freeze(s);
    rad__scale_power(s); /* for the emissions now: this solve starts from them alone */
    assemble(s, rows, matrix);
    start_direct(s);
    /* The patch radiosities live after the matrix, in its type's room (4 bytes). */
    b = (rad_real_t *)(void *)(matrix + (size_t)np * np);
    for (k = 0; k < np; k++) {
        rad_rgb_t em = source(s, k);
        b[3 * k] = em.r;
        b[3 * k + 1] = em.g;
        b[3 * k + 2] = em.b;
    }
    for (it = 0; it < max_iter;) {
        int moved = 0;
        it++;
        for (k = 0; k < np; k++) {
            rad_rgb_t em = source(s, k);
            const rad_rgb_t *rho = rad__patch_rho(s, k);
            unsigned c;
            for (c = 0; c < 3; c++) {
                rad_real_t v =
                    gather(s, matrix, b, k, c, rad__channel(&em, c), rad__channel(rho, c));
                rad_real_t d = v > b[3 * k + c] ? v - b[3 * k + c] : b[3 * k + c] - v;
                /* Relative to each value, so dim patches converge as well as bright ones. */
                /* (saturating: v * tol may already be the largest value) */
                if (d > rad__add_sat(rad__mul(v, tol, 0), RAD__EPS, 0)) moved = 1;
                b[3 * k + c] = v; /* used at once by the patches after it: Gauss-Seidel */
            }
        }
        if (!moved) break;
    }
    /* Elements: their emission and direct light (start_direct) plus every patch's total
     * power shot once. */
    for (k = 0; k < np; k++) {
        rad_energy_t u[3];
        const rad_patch_t *pt = &s->pools.patches[k];
        u[0] = rad__energy(b[3 * k], pt->area);
        u[1] = rad__energy(b[3 * k + 1], pt->area);
        u[2] = rad__energy(b[3 * k + 2], pt->area);
        for (e = rows->start[k]; e < rows->start[k + 1]; e++)
            rad__receive(s, u, rows->ids[e], rad__ff_from_q30(rad__ff_decode(rows->ffs[e])));
    }
    for (k = 0; k < np; k++) {
        rad_patch_t *pt = &s->pools.patches[k];
        pt->unshot[0] = pt->unshot[1] = pt->unshot[2] = 0; /* nothing is left to shoot */
    }
    return (int)it;
}

int rad_mix(rad_scene_t *s, const rad_rgb_t *const *groups, const rad_rgb_t *intensity,
            uint32_t n_groups, rad_rgb_t *out)
{
    uint32_t e, g, *sat;
    RAD__CHECK_SCENE(s);
    if (!groups || !intensity || !out) return RAD_ERR_ARG;
    for (g = 0; g < n_groups; g++)
        if (!groups[g]) return RAD_ERR_ARG;
    sat = &s->stats.saturations;
    for (e = 0; e < s->n_elements; e++) {
        rad_rgb_t o = {0, 0, 0};
        for (g = 0; g < n_groups; g++) {
            o.r = rad__add_sat(o.r, rad__mul(intensity[g].r, groups[g][e].r, sat), sat);
            o.g = rad__add_sat(o.g, rad__mul(intensity[g].g, groups[g][e].g, sat), sat);
            o.b = rad__add_sat(o.b, rad__mul(intensity[g].b, groups[g][e].b, sat), sat);
        }
        out[e] = o;
    }
    return RAD_OK;
}
