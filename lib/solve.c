/* SPDX-License-Identifier: MIT */
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
                                 const rad__area_div_t *area, rad_real_t b,
                                 rad_energy_t *patch_unshot)
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

/* The sums over the patches of area and of reflectance times area, per channel, that
 * the ambient term weighs the reflectance by. */
static void area_sums(const rad_scene_t *s, rad_energy_t *area, rad_energy_t *rho)
{
    uint32_t p;
    *area = rho[0] = rho[1] = rho[2] = 0;
    for (p = 0; p < s->n_patches; p++) {
        const rad_patch_t *pt = &s->pools.patches[p];
        const rad_rgb_t *r = rad__patch_rho(s, p);
        *area = rad__esum(*area, rad__energy(RAD__ONE, pt->area));
        rho[0] = rad__esum(rho[0], rad__energy(r->r, pt->area));
        rho[1] = rad__esum(rho[1], rad__energy(r->g, pt->area));
        rho[2] = rad__esum(rho[2], rad__energy(r->b, pt->area));
    }
}

/* area_sums into the scene, for every shot's ambient term, and the largest patch area,
 * for select_shooter: while solving the areas are frozen, and whatever changes a
 * patch's reflectance clears amb_ok. */
static void keep_area_sums(rad_scene_t *s)
{
    uint32_t p;
    if (s->amb_ok) return;
    area_sums(s, &s->amb_area, s->amb_rho);
    s->amb_max_area = 0;
    for (p = 0; p < s->n_patches; p++)
        if (s->pools.patches[p].area > s->amb_max_area) s->amb_max_area = s->pools.patches[p].area;
    s->amb_ok = 1;
}

/* The ambient radiosity per channel (negative while more power is owed than held). NET,
 * unless null, gets the net unshot power (back_off's), from the same pass. */
static void ambient(const rad_scene_t *s, rad_real_t *amb, uint32_t *sat, rad_energy_t *net)
{
    rad_energy_t area, unshot[3] = {0, 0, 0}, rho[3];
    uint32_t p, c;
    if (s->solving && s->amb_ok) {
        area = s->amb_area;
        for (c = 0; c < 3; c++) rho[c] = s->amb_rho[c];
    } else {
        area_sums(s, &area, rho);
    }
    for (p = 0; p < s->n_patches; p++)
        for (c = 0; c < 3; c++) unshot[c] = rad__esum(unshot[c], s->pools.patches[p].unshot[c]);
    /* ambient = (sum of unshot power / total area) / (1 - area-weighted reflectance) */
    for (c = 0; c < 3; c++) {
        rad_real_t inter = rad__div(RAD__ONE, RAD__ONE - rad__energy_ratio(rho[c], area), sat);
        rad_real_t a = rad__mul(rad__energy_ratio(rad__eabs(unshot[c]), area), inter, sat);
        amb[c] = unshot[c] < 0 ? -a : a;
    }
    if (net)
        *net =
            rad__esum(rad__esum(rad__eabs(unshot[0]), rad__eabs(unshot[1])), rad__eabs(unshot[2]));
}

/* Halvings after which overshooting stops (2^-16 of the estimate is below a Q16.16
 * power's rounding for any power under 2^16 units): the shots are then plain. */
#define OVER_STOP 16u

/* The power patch PT, of reflectance RHO (rad__patch_rho), will get back in channel C,
 * from the ambient radiosity AMB: what overshooting adds to its shot (0 for every
 * patch when AMB is 0), halved once per back-off. */
static rad_energy_t overshoot(const rad_scene_t *s, const rad_patch_t *pt, const rad_rgb_t *rho,
                              const rad_real_t *amb, unsigned c)
{
    rad_energy_t over;
    uint32_t k;
    if (amb[c] == 0 || s->over_halvings >= OVER_STOP) return 0; /* shooting plainly */
    over = rad__energy_refl(rad__energy(amb[c] < 0 ? -amb[c] : amb[c], pt->area),
                            rad__channel(rho, c));
    for (k = 0; k < s->over_halvings; k++) over = rad__energy_refl(over, RAD_REAL(0.5));
    if (over > RAD__EMAX) over = RAD__EMAX; /* the float build's ambient term has no ceiling */
    return amb[c] < 0 ? -over : over;
}

/* The ambient radiosity to overshoot by: 0 when shooting plainly (NET, unless null,
 * then gets the net unshot power). Returns how often the estimate was clamped: not
 * counted in stats.saturations, since the solution is unharmed (the debt is what was
 * shot), but a sign that the estimate is too high. */
static uint32_t shot_ambient(const rad_scene_t *s, rad_real_t *amb, rad_energy_t *net)
{
    uint32_t sat = 0;
    amb[0] = amb[1] = amb[2] = 0;
    if (!(s->cfg.flags & RAD_NO_OVERSHOOT)) ambient(s, amb, &sat, net);
    return sat;
}

/* Inserts patch P, whose shot moves U, into the N best so far (BEST, their shots in
 * MOVE, most first) kept to MAX entries, after those that move as much: the earlier
 * patch first on a tie. Returns the new count. */
static uint32_t rank(uint32_t *best, rad_energy_t *move, uint32_t n, uint32_t max, uint32_t p,
                     rad_energy_t u)
{
    uint32_t i = n < max ? n : max - 1u;
    while (i > 0 && move[i - 1u] < u) {
        best[i] = best[i - 1u];
        move[i] = move[i - 1u];
        i--;
    }
    best[i] = p;
    move[i] = u;
    return n < max ? n + 1u : n;
}

/* The MAX patches whose shots move the most power (each its unshot power plus the
 * overshoot, in magnitude, summed over channels), most first, into BEST (their shots
 * in MOVE); returns how many moved any. TOTAL gets the magnitude of all unshot power.
 * Choosing by the shot, not by the unshot power alone, skips a patch whose debt is
 * just what it expects back: shooting it would move nothing.
 *
 * A channel's overshoot is at most E = rad__energy(A, area), A the largest |AMB[c]|:
 * rad__energy is monotone in both arguments, reflectances are below 1, halvings and
 * the clamp only shrink it. So a patch's shot is at most the sum over channels of
 * |unshot| + E, each term and sum rounded the same way as the shot's (monotone in both
 * builds), and a patch whose bound is not above the MAX-th best so far (0 until there
 * are MAX) cannot be chosen: the choice is the full scan's. E with the largest patch
 * area (amb_max_area, kept while solving) rules most patches out without a product of
 * their own; E with the patch's own area, most of the rest, before the six products of
 * the overshoot. */
static uint32_t select_shooters(const rad_scene_t *s, const rad_real_t *amb, rad_energy_t *total,
                                uint32_t max, uint32_t *best, rad_energy_t *move)
{
    uint32_t p, c, n = 0;
    rad_energy_t most = 0, sum = 0;
    rad_real_t a = 0;
    rad_energy_t emax;
    if (s->over_halvings < OVER_STOP)
        for (c = 0; c < 3; c++) a = amb[c] > a ? amb[c] : -amb[c] > a ? -amb[c] : a;
    emax = a && s->solving && s->amb_ok ? rad__energy(a, s->amb_max_area) : RAD__EMAX;
    for (p = 0; p < s->n_patches; p++) {
        const rad_patch_t *pt = &s->pools.patches[p];
        const rad_energy_t u0 = rad__eabs(pt->unshot[0]), u1 = rad__eabs(pt->unshot[1]),
                           u2 = rad__eabs(pt->unshot[2]);
        const rad_rgb_t *rho;
        rad_energy_t u = 0, e;
        sum = rad__esum(rad__esum(rad__esum(sum, u0), u1), u2);
        if (a == 0) {
            e = 0;
        } else {
            if ((u0 + emax) + (u1 + emax) + (u2 + emax) <= most) continue;
            e = rad__energy(a, pt->area);
        }
        if ((u0 + e) + (u1 + e) + (u2 + e) <= most) continue;
        rho = rad__patch_rho(s, p);
        for (c = 0; c < 3; c++) u += rad__eabs(pt->unshot[c] + overshoot(s, pt, rho, amb, c));
        if (u > most) {
            n = rank(best, move, n, max, p, u);
            if (n == max) most = move[max - 1u];
        }
    }
    *total = sum;
    return n;
}

/* The patch whose shot moves the most power (select_shooters), or RAD_INDEX_NONE. */
static uint32_t select_shooter(const rad_scene_t *s, const rad_real_t *amb, rad_energy_t *total)
{
    uint32_t best;
    rad_energy_t move;
    return select_shooters(s, amb, total, 1, &best, &move) ? best : RAD_INDEX_NONE;
}

/* Overshooting's estimate of the power coming back, the ambient term, assumes that
 * every reflection stays in the scene. Where light escapes (a bright open box), the
 * estimate owes far more than will arrive, the debts are shot back as negative power,
 * overshot again, and the unshot power swings ever wider; where the ambient term's
 * rounding (a step of 2^-16 / (1 - mean reflectance)) is larger than what is left, two
 * shots undo each other for ever. Watched at every selection, the overshoot is halved
 * (stats.backoffs, and the watch starts again from here) when
 *   - the net unshot power exceeds twice the emitted power, or twice its value at the
 *     last back-off (the swing; a working estimate stays within 1x, see below),
 *   - anything saturated since the last selection, CLAMPED included (the ambient term
 *     clamped, not counted in stats: the estimate beyond any radiosity),
 * and overshooting stops at once (OVER_STOP) when the unshot total has not fallen
 * below its lowest value for 4 selections a patch + 64 (the circle; twice the longest
 * wait of a bright closed box, whose first shots raise the total before it falls).
 * Plain shots never make the total grow. Where overshooting works none of these
 * triggers, so the bits are those of the solve without the watch. NET is the net
 * unshot power (ambient's). Returns 1 when it backed off.
 *
 * The net unshot power: each channel's signed sum over the patches, in magnitude,
 * summed. Shooting u from a patch changes a channel's sum by -(1 - rho F) u, with
 * rho F the part of the shot that the scene reflects back, so plainly shot it falls
 * from the emitted power towards 0. Overshot, u carries the debt too; when the scene
 * returns what the estimate says, the sum still only shrinks, but an estimate far
 * above the return (1 - rho F near 1 on a debt that rho F never repays) throws it
 * past 0 to the other side, further each time. */
static int back_off(rad_scene_t *s, rad_energy_t total, rad_energy_t net, int clamped)
{
    uint32_t window = s->n_patches < (1u << 28) ? 4u * s->n_patches + 64u : UINT32_MAX;
    int saturated = clamped || s->stats.saturations != s->over_sat, grown;
    s->over_sat = s->stats.saturations;
    if ((s->cfg.flags & RAD_NO_OVERSHOOT) || s->over_halvings >= OVER_STOP) return 0;
    if (total < s->over_low) {
        s->over_low = total;
        s->over_wait = 0;
    } else if (s->over_wait < UINT32_MAX) {
        s->over_wait++;
    }
    grown = net > rad__esum(s->over_net, s->over_net);
    if (!saturated && !grown && s->over_wait < window) return 0;
    s->over_halvings = grown || saturated ? s->over_halvings + 1u : OVER_STOP;
    s->stats.backoffs++;
    s->over_low = total;
    s->over_wait = 0;
    if (net > s->over_net) s->over_net = net;
    return 1;
}

/* Starts the watch before the first shot, after rad__freeze has set the emitted power
 * at the core's scale (rad_init and rad_restart zero the count; computing rows
 * freezes the scene but shoots nothing). */
static void start_solving(rad_scene_t *s)
{
    if (s->stats.shots != 0) return;
    s->over_low = RAD__ESUM;
    s->over_wait = 0;
    s->over_sat = s->stats.saturations;
    s->over_halvings = 0;
    s->over_net = s->emitted;
}

/* The MAX shooters of the next shots into BEST (MOVE: select_shooters'), after the
 * ambient term AMB and the back-off's watch (once for them all); TOTAL gets the
 * magnitude of all unshot power. Returns how many (0: none). */
static uint32_t next_shooters(rad_scene_t *s, rad_real_t *amb, rad_energy_t *total, uint32_t max,
                              uint32_t *best, rad_energy_t *move)
{
    uint32_t n;
    rad_energy_t net = 0;
    int clamped;
    keep_area_sums(s);
    clamped = shot_ambient(s, amb, &net) != 0;
    n = select_shooters(s, amb, total, max, best, move);
    if (n && back_off(s, *total, net, clamped)) n = select_shooters(s, amb, total, max, best, move);
    return n;
}

/* The shooter for the next shot (RAD_INDEX_NONE: none), as next_shooters with MAX 1.
 * (Written out, not through it: its locals would then sit in rad__shoot's frame
 * under every shot's render, past a Cortex-M0's 16 KB.) */
static uint32_t next_shooter(rad_scene_t *s, rad_real_t *amb, rad_energy_t *total)
{
    uint32_t p;
    rad_energy_t net = 0;
    int clamped;
    keep_area_sums(s);
    clamped = shot_ambient(s, amb, &net) != 0;
    p = select_shooter(s, amb, total);
    if (p != RAD_INDEX_NONE && back_off(s, *total, net, clamped)) p = select_shooter(s, amb, total);
    return p;
}

/* Element E receives power F * U (per channel) from a shooter, its saturations added
 * to SAT. The channels are worked out before anything is stored, and saturations
 * counted locally: a store to the element or to the counter could otherwise alias the
 * next channel's inputs, which kept the channels from overlapping. Writes element E
 * and its patch's unshot power only. */
static void receive_element(rad_scene_t *s, const rad_energy_t *u, uint32_t e, rad_ff_t f,
                            uint32_t *sat_out)
{
    rad_element_t *el = &s->pools.elements[e];
    const rad_rgb_t *rho = rad__element_rho(s, e);
    rad_energy_t *pu = s->pools.patches[el->patch].unshot;
    const rad__area_div_t a = rad__area_div(el->area);
    uint32_t sat = 0;
    rad_real_t r = receive(&sat, u[0], f, rho->r, &a, el->radiosity.r, &pu[0]);
    rad_real_t g = receive(&sat, u[1], f, rho->g, &a, el->radiosity.g, &pu[1]);
    rad_real_t b = receive(&sat, u[2], f, rho->b, &a, el->radiosity.b, &pu[2]);
    el->radiosity.r = r;
    el->radiosity.g = g;
    el->radiosity.b = b;
    *sat_out += sat;
}

void rad__receive(rad_scene_t *s, const rad_energy_t *u, uint32_t e, rad_ff_t f)
{
    receive_element(s, u, e, f, &s->stats.saturations);
}

/* Patch P's shot, overshooting by ambient radiosity AMB: its power into U, and the
 * power coming back to it owed until it comes. */
static void aim(rad_scene_t *s, uint32_t p, const rad_real_t *amb, rad_energy_t *u)
{
    rad_patch_t *pt = &s->pools.patches[p];
    const rad_rgb_t *rho = rad__patch_rho(s, p);
    uint32_t c;
    for (c = 0; c < 3; c++) {
        /* The power coming back to this patch is shot now and owed until it comes. Any
         * overshoot gives the same solution as long as the debt is what was shot, so
         * one that would take the shot past +-RAD__EMAX is cut to reach it, not clamped
         * after (which would lose the difference). |unshot|, |over| <= RAD__EMAX: the
         * sum fits. */
        rad_energy_t over = overshoot(s, pt, rho, amb, c), sum = pt->unshot[c] + over;
        if (sum > RAD__EMAX) over = RAD__EMAX - pt->unshot[c];
        if (sum < -RAD__EMAX) over = -RAD__EMAX - pt->unshot[c];
        u[c] = pt->unshot[c] + over;
        pt->unshot[c] = -over;
    }
    s->stats.shots++;
}

/* Whether patch PT's unshot power is mostly its own emission: at least half of its
 * emitted power (summed over channels), as on its first shot. */
static int shoots_emission(const rad_scene_t *s, const rad_patch_t *pt)
{
    const rad_rgb_t *e = &s->pools.surfaces[pt->surface].emission;
    rad_energy_t own = 0, u = 0;
    uint32_t c;
    if (e->r == 0 && e->g == 0 && e->b == 0) return 0;
    for (c = 0; c < 3; c++) {
        own = rad__esum(own, rad__energy(rad__channel(e, c), pt->area));
        u = rad__esum(u, rad__eabs(pt->unshot[c]));
    }
    return u >= own / 2;
}

/* Coarse shots (rad_config_t.coarse): the level of patch P's shot taken at unshot
 * total TOTAL, each level at an eighth of the last's fraction (so the light shot at
 * level L is at most about 8^-(L-1) COARSE of the emitted; shot_level sets it up
 * through rad__cube_level). The emitters' own light, the direct light, is the most any shots
 * carry: a patch shooting its emission stays at res (its later shots, of light it
 * reflects, coarsen as any other's). Called before the shot is aimed. */
static unsigned level_of(const rad_scene_t *s, uint32_t p, rad_energy_t total)
{
    rad_real_t frac = rad__energy_ratio(total, s->emitted), lim = s->cfg.coarse;
    unsigned level = 0;
    if (lim > 0 && shoots_emission(s, &s->pools.patches[p])) lim = 0;
    while (lim > 0 && frac <= lim && level < 8u) {
        level++;
        lim /= 8;
    }
    return level;
}

/* Sets the cube's level for patch P's shot (level_of). */
static void shot_level(rad_scene_t *s, uint32_t p, rad_energy_t total)
{
    rad__cube_level(s, level_of(s, p, total));
}

/* Shoots patch P's unshot power, overshooting by ambient radiosity AMB, through its
 * stored row, or through the form factors of its hemi-cube (at the level TOTAL, the
 * unshot total, gives). */
static void shoot_patch(rad_scene_t *s, uint32_t p, const rad_real_t *amb, const rad_rows_t *rows,
                        rad_energy_t total)
{
    rad_energy_t u[3];
    uint32_t e;

    if (!rows) shot_level(s, p, total);
    aim(s, p, amb, u);
    if (rows) {
        for (e = rows->start[p]; e < rows->start[p + 1]; e++)
            rad__receive(s, u, rows->ids[e], rad__ff_from_q30(rad__ff_decode(rows->ffs[e])));
    } else {
        if (s->cube_res != s->cfg.res) s->stats.coarse_shots++;
        rad__shot_cube(s, p);
        for (e = 0; e < s->n_elements; e++)
            if (s->acc[e] > 0) rad__receive(s, u, e, s->acc[e]);
    }
}

int rad__shoot(rad_scene_t *s, const rad_rows_t *rows, uint32_t max_shots, rad_real_t tol)
{
    uint32_t done = 0;
    rad__freeze(s);
    start_solving(s);
    while (done < max_shots && done < (uint32_t)INT32_MAX) {
        rad_energy_t total;
        rad_real_t amb[3];
        uint32_t p = next_shooter(s, amb, &total);
        if (p == RAD_INDEX_NONE || rad__energy_ratio(total, s->emitted) <= tol) break;
        shoot_patch(s, p, amb, rows, total);
        done++;
    }
    return (int)done;
}

int rad_shoot(rad_scene_t *s, uint32_t max_shots, rad_real_t tol)
{
    RAD__CHECK_SCENE(s);
    /* lights first (light.c: a call of its own, which keeps this frame as it was) */
    if (rad__lights_pending(s)) {
        s->shot_patch = RAD_INDEX_NONE; /* a shot begun in parts is void now */
        return rad__lights_solve(s, 0, max_shots, tol);
    }
    if (s->emitted == 0) return 0;  /* nothing can be shot: the scene stays open */
    s->shot_patch = RAD_INDEX_NONE; /* a shot begun in parts is void now */
    return rad__shoot(s, 0, max_shots, tol);
}

rad_real_t rad_unshot_fraction(const rad_scene_t *s)
{
    static const rad_real_t none[3] = {0, 0, 0};
    rad_energy_t total;
    if (!s || !rad__live(s)) return 0;
    if (rad__lights_pending(s)) return RAD__ONE; /* none of a light's power has gone */
    select_shooter(s, none, &total);
    return rad__energy_ratio(total, s->emitted);
}

void rad__ambient(const rad_scene_t *s, rad_real_t *amb, uint32_t *sat)
{
    ambient(s, amb, sat, 0);
}

int rad_ambient(rad_scene_t *s, rad_rgb_t *out)
{
    rad_real_t amb[3];
    rad_rgb_t a;
    RAD__CHECK_SCENE(s);
    if (!out) return RAD_ERR_ARG;
    ambient(s, amb, &s->stats.saturations, 0);
    a.r = amb[0];
    a.g = amb[1];
    a.b = amb[2];
    *out = rad__scale2_rgb(a, -s->power_shift, &s->stats.saturations); /* the caller's scale */
    return RAD_OK;
}

int rad_form_factors(rad_scene_t *s, uint32_t p, rad_ff_t *out)
{
    uint32_t e;
    RAD__CHECK_SCENE(s);
    if (!out || p >= s->n_patches) return RAD_ERR_ARG;
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
    int lit;
    RAD__CHECK_SCENE(s);
    if (!patch) return RAD_ERR_ARG;
    s->shot_patch = RAD_INDEX_NONE;
    s->batch_n = 0;                                           /* a batch begun is void now */
    if (s->emitted == 0 && !rad__lights_pending(s)) return 0; /* as rad_shoot */
    if (s->band_rows != 0) return RAD_ERR_STATE;
    rad__freeze(s);
    lit = rad__lights_shoot(s, UINT32_MAX); /* as rad_shoot, here all at once */
    if (lit < 0) return lit;
    start_solving(s);
    p = next_shooter(s, amb, &total);
    if (p == RAD_INDEX_NONE || rad__energy_ratio(total, s->emitted) <= tol) return 0;
    shot_level(s, p, total);
    s->shot_patch = p;
    s->shot_serial++; /* buffers rendered for an earlier shot are stale */
    *patch = p;
    return 1;
}

int rad_shot_part(const rad_scene_t *s, uint32_t patch, unsigned part, unsigned nparts, void *buf,
                  size_t bytes)
{
    RAD__CHECK_SCENE(s);
    if (!buf || part >= nparts || patch >= s->n_patches || s->band_rows != 0 ||
        bytes < RAD_PART_BYTES(s->cfg.res) || ((uintptr_t)buf & 7u))
        return RAD_ERR_ARG;
    if (patch != s->shot_patch || s->batch_n) return RAD_ERR_STATE;
    return rad__cube_part(s, patch, part, nparts, buf);
}

/* The part buffers' heads. */
static rad__part_head_t *head(void *const *bufs, unsigned k)
{
    return (rad__part_head_t *)bufs[k];
}

/* The checks of rad_shot_aim, _receive_part and _end: the arguments, then the shot
 * begun for PATCH, and BUFS its NPARTS parts in order, rendered for it. */
static int shot_args(const rad_scene_t *s, uint32_t patch, void *const *bufs, unsigned nparts)
{
    unsigned k;
    RAD__CHECK_SCENE(s);
    if (!bufs || nparts == 0 || patch >= s->n_patches || s->band_rows != 0) return RAD_ERR_ARG;
    for (k = 0; k < nparts; k++)
        if (!bufs[k] || ((uintptr_t)bufs[k] & 7u)) return RAD_ERR_ARG;
    if (patch != s->shot_patch || s->batch_n) return RAD_ERR_STATE;
    for (k = 0; k < nparts; k++) {
        const rad__part_head_t *h = (const rad__part_head_t *)bufs[k];
        if (h->shot != s->shot_serial || h->part != k || h->nparts != nparts) return RAD_ERR_STATE;
    }
    return RAD_OK;
}

/* Whether every part's head is in state STATE. */
static int parts_in(void *const *bufs, unsigned nparts, uint32_t state)
{
    unsigned k;
    for (k = 0; k < nparts; k++)
        if (head(bufs, k)->state != state) return 0;
    return 1;
}

/* Part PART of NPARTS of the elements, [E0, E1): cut at equal counts, each cut moved
 * down to the first element of its patch. mesh.c appends each patch's elements as one
 * block, so a patch (whose unshot power its elements add to) lies in one part. */
static void receive_range(const rad_scene_t *s, unsigned part, unsigned nparts, uint32_t *e0,
                          uint32_t *e1)
{
    uint32_t c[2], k, n = s->n_elements;
    for (k = 0; k < 2; k++) {
        uint32_t e = (uint32_t)((uint64_t)n * (part + k) / nparts);
        c[k] = e < n ? s->pools.patches[s->pools.elements[e].patch].first_element : n;
    }
    *e0 = c[0];
    *e1 = c[1];
}

static void aim_parts(rad_scene_t *s, uint32_t patch, void *const *bufs, unsigned nparts)
{
    rad_real_t amb[3];
    rad_energy_t u[3];
    unsigned k;
    for (k = 0; k < nparts; k++) {
        s->stats.raster_calls += head(bufs, k)->calls;
        s->stats.raster_pixels += head(bufs, k)->pixels;
    }
    shot_ambient(s, amb, 0);
    aim(s, patch, amb, u);
    if (s->cube_res != s->cfg.res) s->stats.coarse_shots++;
    for (k = 0; k < nparts; k++) {
        rad__part_head_t *h = head(bufs, k);
        h->u[0] = u[0];
        h->u[1] = u[1];
        h->u[2] = u[2];
        h->saturations = 0;
        h->state = RAD__PART_AIMED;
    }
}

int rad_shot_aim(rad_scene_t *s, uint32_t patch, void *const *bufs, unsigned nparts)
{
    int rc = shot_args(s, patch, bufs, nparts);
    if (rc < 0) return rc;
    if (!parts_in(bufs, nparts, RAD__PART_RENDERED)) return RAD_ERR_STATE;
    aim_parts(s, patch, bufs, nparts);
    return 1;
}

static int receive_part(rad_scene_t *s, void *const *bufs, unsigned nparts, unsigned part)
{
    rad__part_head_t *h = head(bufs, part);
    uint32_t e, e0, e1, sat = 0;
    int n = 0;
    receive_range(s, part, nparts, &e0, &e1);
    rad__cube_merge(s, bufs, nparts, e0, e1);
    for (e = e0; e < e1; e++)
        if (s->acc[e] > 0) {
            receive_element(s, h->u, e, s->acc[e], &sat);
            n++;
        }
    h->saturations = sat;
    h->state = RAD__PART_RECEIVED;
    return n;
}

int rad_shot_receive_part(rad_scene_t *s, uint32_t patch, void *const *bufs, unsigned nparts,
                          unsigned part)
{
    int rc = shot_args(s, patch, bufs, nparts);
    if (rc < 0) return rc;
    if (part >= nparts) return RAD_ERR_ARG;
    if (head(bufs, part)->state != RAD__PART_AIMED) return RAD_ERR_STATE;
    return receive_part(s, bufs, nparts, part);
}

int rad_shot_end(rad_scene_t *s, uint32_t patch, void *const *bufs, unsigned nparts)
{
    unsigned k;
    int rc = shot_args(s, patch, bufs, nparts);
    if (rc < 0) return rc;
    if (parts_in(bufs, nparts, RAD__PART_RENDERED)) {
        aim_parts(s, patch, bufs, nparts);
    } else {
        for (k = 0; k < nparts; k++) {
            uint32_t st = head(bufs, k)->state;
            if (st != RAD__PART_AIMED && st != RAD__PART_RECEIVED) return RAD_ERR_STATE;
        }
    }
    for (k = 0; k < nparts; k++) {
        rad__part_head_t *h = head(bufs, k);
        if (h->state == RAD__PART_AIMED) receive_part(s, bufs, nparts, k);
        s->stats.saturations += h->saturations;
        h->state = RAD__PART_SHOT;
    }
    s->shot_patch = RAD_INDEX_NONE;
    return 1;
}

/* ---- batch shooting (rad_batch_begin) ------------------------------------------ */

/* The check word of a batch: its count N and patches P[0..N-1] in order, folded. */
static uint16_t batch_check(const uint32_t *p, unsigned n)
{
    uint32_t h = n;
    unsigned k;
    for (k = 0; k < n; k++) h = (h ^ (p[k] + 1u)) * 0x9E3779B1u;
    return (uint16_t)(h >> 16);
}

int rad_batch_begin(rad_scene_t *s, rad_real_t tol, unsigned k, uint32_t *patches)
{
    rad_energy_t total, move[RAD_BATCH_MAX];
    rad_real_t amb[3];
    uint32_t n, i;
    unsigned level;
    int lit;
    RAD__CHECK_SCENE(s);
    if (!patches || k == 0 || k > RAD_BATCH_MAX) return RAD_ERR_ARG;
    s->shot_patch = RAD_INDEX_NONE; /* a shot or batch begun is void now */
    s->batch_n = 0;
    if (s->emitted == 0 && !rad__lights_pending(s)) return 0; /* as rad_shoot */
    if (s->band_rows != 0) return RAD_ERR_STATE;
    rad__freeze(s);
    lit = rad__lights_shoot(s, UINT32_MAX); /* as rad_shot_begin */
    if (lit < 0) return lit;
    start_solving(s);
    n = next_shooters(s, amb, &total, k, patches, move);
    if (n == 0 || rad__energy_ratio(total, s->emitted) <= tol) return 0;
    /* one cube resolution for the batch: its finest shot's */
    level = level_of(s, patches[0], total);
    for (i = 1; i < n; i++) {
        unsigned l = level_of(s, patches[i], total);
        level = l < level ? l : level;
    }
    rad__cube_level(s, level);
    s->shot_patch = patches[0];
    s->batch_n = (uint16_t)n;
    s->batch_check = batch_check(patches, n);
    s->shot_serial++; /* buffers rendered for an earlier shot or batch are stale */
    return (int)n;
}

/* A batch buffer's accumulators (RAD_BATCH_BYTES: after a part buffer's bytes). */
static rad_ff_t *batch_acc(const rad_scene_t *s, void *buf)
{
    return (rad_ff_t *)(void *)((unsigned char *)buf + RAD_PART_BYTES(s->cfg.res));
}

int rad_batch_render(const rad_scene_t *s, uint32_t patch, unsigned k, void *buf, size_t bytes)
{
    rad__part_head_t *h = (rad__part_head_t *)buf;
    RAD__CHECK_SCENE(s);
    if (!buf || patch >= s->n_patches || bytes < RAD_BATCH_BYTES(s->cfg.res, s->n_elements) ||
        ((uintptr_t)buf & 7u))
        return RAD_ERR_ARG;
    if (s->shot_patch == RAD_INDEX_NONE || k >= s->batch_n) return RAD_ERR_STATE;
    h->seen = rad__cube_list(s, patch, buf, batch_acc(s, buf));
    h->part = k;
    h->nparts = s->batch_n;
    h->patch = patch;
    h->rparts = 0;
    h->state = RAD__CUBE_RENDERED;
    return (int)h->calls;
}

/* Whether BUFS are the batch's N cubes in order, each in state STATE or (unless 0)
 * STATE2: the checks of rad_batch_aim, _receive_part and _end after their arguments'. */
static int batch_ready(const rad_scene_t *s, void *const *bufs, unsigned n, uint32_t state,
                       uint32_t state2)
{
    uint32_t p[RAD_BATCH_MAX];
    unsigned k;
    if (s->shot_patch == RAD_INDEX_NONE || n != s->batch_n) return 0;
    for (k = 0; k < n; k++) {
        const rad__part_head_t *h = head(bufs, k);
        if ((h->state != state && (!state2 || h->state != state2)) || h->shot != s->shot_serial ||
            h->part != k || h->nparts != n || h->patch >= s->n_patches || h->seen > s->n_elements)
            return 0;
        p[k] = h->patch;
    }
    return batch_check(p, n) == s->batch_check;
}

/* The arguments' checks of the batch calls: 0, or the error. */
static int batch_args(const rad_scene_t *s, void *const *bufs, unsigned n)
{
    unsigned k;
    RAD__CHECK_SCENE(s);
    if (!bufs || n == 0 || n > RAD_BATCH_MAX || s->band_rows != 0) return RAD_ERR_ARG;
    for (k = 0; k < n; k++)
        if (!bufs[k] || ((uintptr_t)bufs[k] & 7u)) return RAD_ERR_ARG;
    return RAD_OK;
}

/* The first of the N entries of IDS (rising) at E or above. */
static uint32_t first_at(const rad_index_t *ids, uint32_t n, uint32_t e)
{
    uint32_t lo = 0, hi = n;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2u;
        if (ids[mid] < e)
            lo = mid + 1u;
        else
            hi = mid;
    }
    return lo;
}

/* Shot J's receipts, as receive_element's, for the elements [E0, E1): into the scene,
 * or (UNSHOT given) only into UNSHOT, their patch's unshot power, nothing else written
 * but the saturations SAT. */
static void batch_receipts(rad_scene_t *s, void *const *bufs, unsigned j, uint32_t e0, uint32_t e1,
                           rad_energy_t *unshot, uint32_t *sat)
{
    const rad__part_head_t *h = head(bufs, j);
    rad_index_t *ids;
    rad_ff_t *ffs;
    uint32_t i;
    rad__cube_lists(s, bufs[j], &ids, &ffs);
    for (i = first_at(ids, h->seen, e0); i < h->seen && ids[i] < e1; i++) {
        const rad_element_t *el = &s->pools.elements[ids[i]];
        const rad_rgb_t *rho;
        rad__area_div_t a;
        uint32_t c;
        if (!unshot) {
            receive_element(s, h->u, ids[i], ffs[i], sat);
            continue;
        }
        rho = rad__element_rho(s, ids[i]);
        a = rad__area_div(el->area);
        for (c = 0; c < 3; c++)
            (void)receive(sat, h->u[c], ffs[i], rad__channel(rho, c), &a, 0, &unshot[c]);
    }
}

/* Aims the batch's shots in order, with the ambient term at its start (for K = 1, the
 * shot's own): shot K's power is its patch's unshot power after the receipts of the
 * shots before it, worked out here for its own elements alone (the receipts proper
 * come after, on any threads: batch_receive). Into each head its power U and what its
 * patch is left owing (LEFT). */
static void batch_aim(rad_scene_t *s, void *const *bufs, unsigned n)
{
    rad_real_t amb[3];
    uint64_t tests = 0;
    unsigned k, j;
    shot_ambient(s, amb, 0);
    for (k = 0; k < n; k++) {
        rad__part_head_t *h = head(bufs, k);
        rad_patch_t *pt = &s->pools.patches[h->patch];
        rad_energy_t now[3];
        uint32_t sat = 0, c;
        for (c = 0; c < 3; c++) now[c] = pt->unshot[c];
        for (j = 0; j < k; j++)
            batch_receipts(s, bufs, j, pt->first_element, pt->first_element + pt->n_elements,
                           pt->unshot, &sat);
        aim(s, h->patch, amb, h->u);
        for (c = 0; c < 3; c++) {
            h->left[c] = pt->unshot[c];
            pt->unshot[c] = now[c]; /* until batch_receive */
        }
        s->stats.raster_calls += h->calls;
        s->stats.raster_pixels += h->pixels;
        if (s->cube_res != s->cfg.res) s->stats.coarse_shots++;
        h->saturations = 0;
        h->state = RAD__CUBE_AIMED;
        tests += h->tests;
    }
    if (n) rad__cull_after(s, head(bufs, 0)->tests != RAD__DRAWN_ALL, tests, n);
}

/* Part PART of NPARTS of the receipts (receive_range's run of whole patches), shot
 * after shot: each shooter in the run left owing at its place in the order, then the
 * elements of the run each shot's cube lists receive. Saturations into BUFS[PART]. */
static int batch_receive(rad_scene_t *s, void *const *bufs, unsigned n, unsigned part,
                         unsigned nparts)
{
    rad__part_head_t *r = head(bufs, part);
    uint32_t e0, e1, sat = 0, c;
    unsigned j;
    receive_range(s, part, nparts, &e0, &e1);
    for (j = 0; j < n; j++) {
        const rad__part_head_t *h = head(bufs, j);
        rad_patch_t *pt = &s->pools.patches[h->patch];
        if (pt->first_element >= e0 && pt->first_element < e1)
            for (c = 0; c < 3; c++) pt->unshot[c] = h->left[c];
        batch_receipts(s, bufs, j, e0, e1, 0, &sat);
    }
    r->saturations = sat;
    r->rparts = nparts;
    r->state = RAD__CUBE_RECEIVED;
    return (int)n;
}

int rad_batch_aim(rad_scene_t *s, void *const *bufs, unsigned n)
{
    int rc = batch_args(s, bufs, n);
    if (rc < 0) return rc;
    if (!batch_ready(s, bufs, n, RAD__CUBE_RENDERED, 0)) return RAD_ERR_STATE;
    batch_aim(s, bufs, n);
    return (int)n;
}

/* The parts the batch's receipts were cut into so far (0: none yet). */
static unsigned batch_parts(void *const *bufs, unsigned n)
{
    unsigned k;
    for (k = 0; k < n; k++)
        if (head(bufs, k)->state == RAD__CUBE_RECEIVED) return head(bufs, k)->rparts;
    return 0;
}

int rad_batch_receive_part(rad_scene_t *s, void *const *bufs, unsigned n, unsigned part,
                           unsigned nparts)
{
    unsigned np;
    int rc = batch_args(s, bufs, n);
    if (rc < 0) return rc;
    if (nparts == 0 || nparts > n || part >= nparts) return RAD_ERR_ARG;
    if (!batch_ready(s, bufs, n, RAD__CUBE_AIMED, RAD__CUBE_RECEIVED)) return RAD_ERR_STATE;
    np = batch_parts(bufs, n);
    if ((np && np != nparts) || head(bufs, part)->state != RAD__CUBE_AIMED) return RAD_ERR_STATE;
    return batch_receive(s, bufs, n, part, nparts);
}

int rad_batch_end(rad_scene_t *s, void *const *bufs, unsigned n)
{
    unsigned k, np;
    int rc = batch_args(s, bufs, n);
    if (rc < 0) return rc;
    if (batch_ready(s, bufs, n, RAD__CUBE_RENDERED, 0))
        batch_aim(s, bufs, n);
    else if (!batch_ready(s, bufs, n, RAD__CUBE_AIMED, RAD__CUBE_RECEIVED))
        return RAD_ERR_STATE;
    np = batch_parts(bufs, n);
    if (np == 0) np = 1; /* all at once */
    for (k = 0; k < np; k++)
        if (head(bufs, k)->state == RAD__CUBE_AIMED) batch_receive(s, bufs, n, k, np);
    for (k = 0; k < n; k++) {
        if (head(bufs, k)->state == RAD__CUBE_RECEIVED)
            s->stats.saturations += head(bufs, k)->saturations;
        head(bufs, k)->state = RAD__PART_SHOT;
    }
    s->shot_patch = RAD_INDEX_NONE;
    s->batch_n = 0;
    return (int)n;
}
