/* SPDX-License-Identifier: MIT */
/* The shooter selection (lib/solve.c's select_shooter, fixed build) against the rule
 * it implements, scanned in full here: the patch whose shot, its unshot power plus the
 * overshoot (the ambient term times its area and reflectance, halved per back-off), moves
 * the most power summed over channels in magnitude, the first of equals. The core skips
 * patches by a bound on that sum; the bound must never skip the one the full scan picks.
 * Shot after shot, in a closed box of coloured walls, an open bright box (which backs
 * the overshoot off) and a box whose elements have reflectances of their own. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "check.h"
#include "core_values.h"
#include "internal.h"
#include "world.h"

/* The faces of the box [-32, 32]^3, face i of reflectance RHO[i % 3]: all six and a
 * lamp under the top, or (OPEN) five, the floor emitting. */
static void box(world_t *w, int open, const rad_rgb_t *rho)
{
    const double Z = 32;
    const rad_vec3_t f[6][4] = {
        {V(-32, -32, -32), V(-32, -32, Z), V(32, -32, Z), V(32, -32, -32)},
        {V(-32, 32, -32), V(32, 32, -32), V(32, 32, Z), V(-32, 32, Z)},
        {V(-32, -32, -32), V(-32, 32, -32), V(-32, 32, Z), V(-32, -32, Z)},
        {V(32, -32, -32), V(32, -32, Z), V(32, 32, Z), V(32, 32, -32)},
        {V(-32, -32, -32), V(32, -32, -32), V(32, 32, -32), V(-32, 32, -32)},
        {V(-32, -32, Z), V(-32, 32, Z), V(32, 32, Z), V(32, -32, Z)},
    };
    const rad_vec3_t lamp[4] = {V(-6, 20, -6), V(6, 20, -6), V(6, 20, 6), V(-6, 20, 6)};
    const rad_rgb_t em = C(60, 50, 40);
    int i;
    for (i = 0; i < (open ? 5 : 6); i++)
        assert_true(rad_add_polygon(&w->s, f[i], 4, &rho[i % 3], open && i == 4 ? &em : NULL) >= 0);
    if (!open) assert_true(rad_add_polygon(&w->s, lamp, 4, NULL, &em) >= 0);
}

/* The ambient term as the core's solver takes it (lib/solve.c's ambient). */
static void ambient_of(const rad_scene_t *s, rad_real_t *amb)
{
    rad_energy_t area = 0, unshot[3] = {0, 0, 0}, rho[3] = {0, 0, 0};
    uint32_t p, c, sat = 0;
    for (p = 0; p < s->n_patches; p++) {
        const rad_patch_t *pt = &s->pools.patches[p];
        const rad_rgb_t *r = rad__patch_rho(s, p);
        area = rad__esum(area, rad__energy(RAD__ONE, pt->area));
        rho[0] = rad__esum(rho[0], rad__energy(r->r, pt->area));
        rho[1] = rad__esum(rho[1], rad__energy(r->g, pt->area));
        rho[2] = rad__esum(rho[2], rad__energy(r->b, pt->area));
        for (c = 0; c < 3; c++) unshot[c] = rad__esum(unshot[c], pt->unshot[c]);
    }
    for (c = 0; c < 3; c++) {
        rad_real_t inter = rad__div(RAD__ONE, RAD__ONE - rad__energy_ratio(rho[c], area), &sat);
        rad_real_t a = rad__mul(rad__energy_ratio(rad__eabs(unshot[c]), area), inter, &sat);
        amb[c] = unshot[c] < 0 ? -a : a;
    }
}

/* The full scan: every patch's shot, the first of the largest (none: RAD_INDEX_NONE). */
static uint32_t full_scan(const rad_scene_t *s)
{
    rad_real_t amb[3];
    rad_energy_t most = 0;
    uint32_t p, c, k, best = RAD_INDEX_NONE;
    ambient_of(s, amb);
    for (p = 0; p < s->n_patches; p++) {
        const rad_patch_t *pt = &s->pools.patches[p];
        const rad_rgb_t *rho = rad__patch_rho(s, p);
        rad_energy_t u = 0;
        for (c = 0; c < 3; c++) {
            rad_energy_t over = 0;
            if (amb[c] != 0 && s->over_halvings < 16u) {
                over = rad__energy_refl(rad__energy(amb[c] < 0 ? -amb[c] : amb[c], pt->area),
                                        rad__channel(rho, c));
                for (k = 0; k < s->over_halvings; k++) over = rad__energy_refl(over, RAD_REAL(0.5));
                if (over > RAD__EMAX) over = RAD__EMAX;
                if (amb[c] < 0) over = -over;
            }
            u += rad__eabs(pt->unshot[c] + over);
        }
        if (u > most) {
            most = u;
            best = p;
        }
    }
    return best;
}

/* SHOTS shots of W, each shooter from rad_shot_begin against the full scan's. */
static void compare(world_t *w, const char *name, int shots)
{
    int i, same = 0;
    for (i = 0; i < shots; i++) {
        uint32_t p = RAD_INDEX_NONE, want;
        int rc = rad_shot_begin(&w->s, 0, &p);
        assert_true(rc >= 0);
        if (rc == 0) break;
        want = full_scan(&w->s); /* after the begin: the frozen scale, the back-off's halvings */
        CHECK_INT_EQ(p, want, "%s, shot %d: the core's shooter against the full scan's", name,
                     i + 1);
        same++;
        assert_int_equal(rad_shoot(&w->s, 1, 0), 1);
    }
    print_message("%s: %d shots, each shooter the full scan's (%u patches, %u back-offs)\n", name,
                  same, (unsigned)w->s.n_patches, (unsigned)w->s.stats.backoffs);
    CHECK_INT_GE(same, 50, "%s: shots compared", name);
}

static void test_closed_box(void **st)
{
    const rad_rgb_t rho[3] = {C(0.7, 0.2, 0.2), C(0.2, 0.6, 0.3), C(0.5, 0.5, 0.8)};
    world_t *w = world(12, 6);
    (void)st;
    box(w, 0, rho);
    compare(w, "closed box", 400);
    free(w);
}

/* Walls of Kd 0.998 and no top (test_diverge's case): the ambient estimate owes more
 * than comes back, and the watch halves the overshoot (stats.backoffs), which the scan
 * must follow. */
static void test_open_bright_box(void **st)
{
    const rad_rgb_t rho[3] = {C(0.998, 0.998, 0.998), C(0.998, 0.998, 0.998),
                              C(0.998, 0.998, 0.998)};
    world_t *w = world(12, 6);
    (void)st;
    box(w, 1, rho);
    compare(w, "open bright box", 3000);
    CHECK_INT_GE(w->s.stats.backoffs, 1, "open bright box: back-offs");
    free(w);
}

/* Elements of their own reflectance: patches shoot with their elements' mean. */
static void test_element_reflectance(void **st)
{
    const rad_rgb_t rho[3] = {C(0.5, 0.5, 0.5), C(0.5, 0.5, 0.5), C(0.5, 0.5, 0.5)};
    world_t *w = world(12, 6);
    uint32_t e;
    (void)st;
    assert_int_equal(rad_use_element_reflectance(&w->s, w->rho), RAD_OK);
    box(w, 0, rho);
    for (e = 0; e < w->s.n_elements; e++) {
        rad_rgb_t r = C(0.1 + 0.8 * (double)(e % 7) / 6, 0.3 + 0.1 * (double)(e % 3),
                        0.9 - 0.1 * (double)(e % 5));
        assert_int_equal(rad_set_element_reflectance(&w->s, e, &r), RAD_OK);
    }
    compare(w, "element reflectances", 400);
    free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_box),
        cmocka_unit_test(test_open_bright_box),
        cmocka_unit_test(test_element_reflectance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
