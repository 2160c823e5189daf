/* rad — progressive refinement (Cohen, Chen, Wallace & Greenberg 1988).
 *
 * Each step shoots a patch's unshot power U through a hemi-cube at its centre: the
 * patch with the most unshot power, or, overshooting, the one whose shot moves most.
 * With F the form factor from the patch to element j (the item buffer's sum),
 * reciprocity gives element j the power rho_j F U, hence radiosity rho_j F U / A_j,
 * and adds that power to the unshot power of j's patch. No element-to-patch division
 * is needed. Shooting plainly, unshot power never grows: the sum of F is at most 1 and
 * rho < 1.
 *
 * Overshooting (the default; Feda & Purgathofer 1992) adds to a shot the power the
 * patch will get back: its reflectance times its area times the ambient radiosity
 * (the unshot power spread over the scene, times 1 / (1 - mean reflectance)). The
 * patch is left owing that much, as negative unshot power; when it arrives the debt
 * is paid, and if the estimate was too high the patch shoots the difference back as
 * negative power. The fixed point of the iteration is unchanged.
 */
#include "internal.h"

/* Power RECV = rho * F * U reaching an element (computed on U's magnitude, with U's
 * sign), added to its radiosity and patch. */
static inline rad_real_t receive(uint32_t *sat, rad_energy_t u, rad_ff_t f, rad_real_t rho,
                                 rad_real_t area, rad_real_t b, rad_energy_t *patch_unshot)
{
    rad_energy_t recv = rad__energy_refl(rad__energy_ff(rad__eabs(u), f), rho);
    rad_real_t db = rad__energy_to_rad(recv, area, sat);
    if (u < 0) {
        *patch_unshot = rad__eclamp(*patch_unshot - recv, sat);
        return rad__add_sat(b, -db, sat);
    }
    *patch_unshot = rad__eclamp(*patch_unshot + recv, sat);
    return rad__add_sat(b, db, sat);
}

/* The ambient radiosity per channel (negative while more power is owed than held). */
static void ambient(const rad_scene_t *s, rad_real_t *amb, uint32_t *sat)
{
    rad_energy_t area = 0, unshot[3] = {0, 0, 0}, rho[3] = {0, 0, 0};
    uint32_t p, c;
    for (p = 0; p < s->n_patches; p++) {
        const rad_patch_t *pt = &s->pools.patches[p];
        const rad_rgb_t *r = &s->pools.surfaces[pt->surface].reflectance;
        area = rad__esum(area, rad__energy(RAD__ONE, pt->area));
        rho[0] = rad__esum(rho[0], rad__energy(r->r, pt->area));
        rho[1] = rad__esum(rho[1], rad__energy(r->g, pt->area));
        rho[2] = rad__esum(rho[2], rad__energy(r->b, pt->area));
        for (c = 0; c < 3; c++) unshot[c] = rad__esum(unshot[c], pt->unshot[c]);
    }
    /* ambient = (sum of unshot power / total area) / (1 - area-weighted reflectance) */
    for (c = 0; c < 3; c++) {
        rad_real_t inter = rad__div(RAD__ONE, RAD__ONE - rad__energy_ratio(rho[c], area), sat);
        rad_real_t a = rad__mul(rad__energy_ratio(rad__eabs(unshot[c]), area), inter, sat);
        amb[c] = unshot[c] < 0 ? -a : a;
    }
}

/* The power patch PT will get back in channel C, from the ambient radiosity AMB:
 * what overshooting adds to its shot (0 for every patch when AMB is 0). */
static rad_energy_t overshoot(const rad_scene_t *s, const rad_patch_t *pt, const rad_real_t *amb,
                              unsigned c)
{
    rad_energy_t over;
    if (amb[c] == 0) return 0; /* shooting plainly */
    over = rad__energy_refl(rad__energy(amb[c] < 0 ? -amb[c] : amb[c], pt->area),
                            rad__channel(&s->pools.surfaces[pt->surface].reflectance, c));
    if (over > RAD__EMAX) over = RAD__EMAX; /* the float build's ambient term has no ceiling */
    return amb[c] < 0 ? -over : over;
}

/* The ambient radiosity to overshoot by: 0 when shooting plainly. */
static void shot_ambient(const rad_scene_t *s, rad_real_t *amb, uint32_t *sat)
{
    amb[0] = amb[1] = amb[2] = 0;
    if (!(s->cfg.flags & RAD_NO_OVERSHOOT)) ambient(s, amb, sat);
}

/* The patch whose shot moves the most power (its unshot power plus the overshoot, in
 * magnitude, summed over channels), or RAD_INDEX_NONE; TOTAL gets the magnitude of all
 * unshot power. Choosing by the shot, not by the unshot power alone, skips a patch
 * whose debt is just what it expects back: shooting it would move nothing. */
static uint32_t select_shooter(const rad_scene_t *s, const rad_real_t *amb, rad_energy_t *total)
{
    uint32_t p, c, best = RAD_INDEX_NONE;
    rad_energy_t most = 0, sum = 0;
    for (p = 0; p < s->n_patches; p++) {
        const rad_patch_t *pt = &s->pools.patches[p];
        rad_energy_t u = 0;
        for (c = 0; c < 3; c++) {
            sum = rad__esum(sum, rad__eabs(pt->unshot[c]));
            u += rad__eabs(pt->unshot[c] + overshoot(s, pt, amb, c));
        }
        if (u > most) {
            most = u;
            best = p;
        }
    }
    *total = sum;
    return best;
}

/* Element E receives power F * U (per channel) from a shooter. The channels are worked
 * out before anything is stored, and saturations counted locally: a store to the
 * element or to the counter could otherwise alias the next channel's inputs, which kept
 * the channels from overlapping. */
void rad__receive(rad_scene_t *s, const rad_energy_t *u, uint32_t e, rad_ff_t f)
{
    rad_element_t *el = &s->pools.elements[e];
    const rad_surface_t *sf = &s->pools.surfaces[el->surface];
    rad_energy_t *pu = s->pools.patches[el->patch].unshot;
    rad_real_t a = el->area;
    uint32_t sat = 0;
    rad_real_t r = receive(&sat, u[0], f, sf->reflectance.r, a, el->radiosity.r, &pu[0]);
    rad_real_t g = receive(&sat, u[1], f, sf->reflectance.g, a, el->radiosity.g, &pu[1]);
    rad_real_t b = receive(&sat, u[2], f, sf->reflectance.b, a, el->radiosity.b, &pu[2]);
    el->radiosity.r = r;
    el->radiosity.g = g;
    el->radiosity.b = b;
    s->stats.saturations += sat;
}

/* Shoots patch P's unshot power, overshooting by ambient radiosity AMB, through its
 * stored row, or through the form factors in s->acc, rendering its hemi-cube first
 * when CUBE is set. */
static void shoot_patch(rad_scene_t *s, uint32_t p, const rad_real_t *amb, const rad_rows_t *rows,
                        int cube)
{
    rad_patch_t *pt = &s->pools.patches[p];
    rad_energy_t u[3];
    uint32_t e, c;

    for (c = 0; c < 3; c++) {
        /* The power coming back to this patch is shot now and owed until it comes. */
        rad_energy_t over = overshoot(s, pt, amb, c);
        u[c] = rad__eclamp(pt->unshot[c] + over, &s->stats.saturations);
        pt->unshot[c] = -over;
    }
    if (rows) {
        for (e = rows->start[p]; e < rows->start[p + 1]; e++)
            rad__receive(s, u, rows->ids[e], rad__ff_from_q30(rad__ff_decode(rows->ffs[e])));
    } else {
        if (cube) rad__hemicube(s, p);
        for (e = 0; e < s->n_elements; e++)
            if (s->acc[e] > 0) rad__receive(s, u, e, s->acc[e]);
    }
    s->stats.shots++;
}

int rad__shoot(rad_scene_t *s, const rad_rows_t *rows, uint32_t max_shots, rad_real_t tol)
{
    uint32_t done = 0;
    rad__freeze(s);
    while (done < max_shots && done < (uint32_t)INT32_MAX) {
        rad_energy_t total;
        rad_real_t amb[3];
        uint32_t p;
        shot_ambient(s, amb, &s->stats.saturations);
        p = select_shooter(s, amb, &total);
        if (p == RAD_INDEX_NONE || rad__energy_ratio(total, s->emitted) <= tol) break;
        shoot_patch(s, p, amb, rows, 1);
        done++;
    }
    return (int)done;
}

int rad_shoot(rad_scene_t *s, uint32_t max_shots, rad_real_t tol)
{
    if (!s) return RAD_ERR_ARG;
    if (s->emitted == 0) return 0; /* nothing can be shot: the scene stays open */
    return rad__shoot(s, 0, max_shots, tol);
}

rad_real_t rad_unshot_fraction(const rad_scene_t *s)
{
    static const rad_real_t none[3] = {0, 0, 0};
    rad_energy_t total;
    if (!s) return 0;
    select_shooter(s, none, &total);
    return rad__energy_ratio(total, s->emitted);
}

void rad__ambient(const rad_scene_t *s, rad_real_t *amb, uint32_t *sat)
{
    ambient(s, amb, sat);
}

int rad_ambient(rad_scene_t *s, rad_rgb_t *out)
{
    rad_real_t amb[3];
    rad_rgb_t a;
    if (!s || !out) return RAD_ERR_ARG;
    ambient(s, amb, &s->stats.saturations);
    a.r = amb[0];
    a.g = amb[1];
    a.b = amb[2];
    *out = rad__scale2_rgb(a, -s->power_shift, &s->stats.saturations); /* the caller's scale */
    return RAD_OK;
}

int rad_form_factors(rad_scene_t *s, uint32_t p, rad_ff_t *out)
{
    uint32_t e;
    if (!s || !out || p >= s->n_patches) return RAD_ERR_ARG;
    if (!s->solving) rad__scale_geometry(s); /* the row the solver will use */
    rad__hemicube(s, p);
    for (e = 0; e < s->n_elements; e++) out[e] = s->acc[e];
    return (int)s->n_elements;
}

int rad_shot_begin(rad_scene_t *s, rad_real_t tol, uint32_t *patch)
{
    rad_energy_t total;
    rad_real_t amb[3];
    uint32_t p;
    if (!s || !patch) return RAD_ERR_ARG;
    if (s->emitted == 0) return 0; /* as rad_shoot */
    if (s->band_rows != 0) return RAD_ERR_STATE;
    rad__freeze(s);
    shot_ambient(s, amb, &s->stats.saturations);
    p = select_shooter(s, amb, &total);
    if (p == RAD_INDEX_NONE || rad__energy_ratio(total, s->emitted) <= tol) return 0;
    *patch = p;
    return 1;
}

int rad_shot_part(const rad_scene_t *s, uint32_t patch, unsigned part, unsigned nparts, void *buf,
                  size_t bytes)
{
    if (!s || !buf || part >= nparts || patch >= s->n_patches || s->band_rows != 0 ||
        bytes < RAD_PART_BYTES(s->cfg.res) || ((uintptr_t)buf & 7u))
        return RAD_ERR_ARG;
    return rad__cube_part(s, patch, part, nparts, buf);
}

int rad_shot_end(rad_scene_t *s, uint32_t patch, void *const *bufs, unsigned nparts)
{
    rad_real_t amb[3];
    unsigned k;
    if (!s || !bufs || nparts == 0 || patch >= s->n_patches || s->band_rows != 0)
        return RAD_ERR_ARG;
    for (k = 0; k < nparts; k++)
        if (!bufs[k]) return RAD_ERR_ARG;
    rad__cube_merge(s, bufs, nparts);
    shot_ambient(s, amb, &s->stats.saturations);
    shoot_patch(s, patch, amb, 0, 0);
    return 1;
}
