/* SPDX-License-Identifier: MIT */
/* soak — randomised scenes solved through the host glue (make check-soak).
 *
 *   build/tests/soak/soak [SEED [SCENES]]     (19 and 1000)
 *
 * Scene k is made from seed SEED + k: a room of random proportions, size and place
 * (every face of reflectance up to 0.9999, half the rooms open on one side), lit by a
 * face or by a lamp under the ceiling, with up to two blocks in it, meshed coarsely at
 * resolution 8, 16 or 32, solved in the fixed build or the float twin (one in four) with
 * or without overshooting, to a random tolerance with a shot cap. Every run must
 *   - end converged or say that it did not: sc_stats.converged agrees with the unshot
 *     fraction against the tolerance, and a run that stopped short of the cap converged;
 *   - report every saturation: an element at the fixed core's clamp counts one;
 *   - when converged without a saturation, meet the energy balance: the emitted power
 *     against the absorbed plus what escapes, within 2% (the balance uses the shots'
 *     own form factors, so off means power made or lost, plus the unshot part, at most
 *     the tolerance: 0.01 at the loosest);
 *   - render a view with only finite, non-negative values.
 * The first failure prints its seed (rerun it alone with SCENES = 1) and exits 1.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scenes.h"
#include "balance.h"

#define SHOT_CAP 4000

static uint64_t rng;

static double uniform(void) /* [0, 1), xorshift64* */
{
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return (double)((rng * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

static double between(double a, double b)
{
    return a + (b - a) * uniform();
}

/* Half the faces a reflectance of 1 - 10^-u, u up to 4 (0.9999): the bright cases.
 * At least 0.05: the balance divides radiosity by reflectance, which would turn the
 * core's 2^-16 rounding of a face of 0.001 into a thousand times as much. */
static double reflectance(void)
{
    return uniform() < 0.5 ? between(0.05, 0.9) : 1.0 - pow(10.0, -between(1.0, 4.0));
}

typedef struct {
    sc_poly p[24];
    int n;
    sc_opts o;
    double tol, cam[6];
    int twin;
} scene_t;

static void make_scene(scene_t *sc)
{
    double size = pow(10.0, between(-2.0, 3.0)), lo[3], hi[3];
    int i, a, open = uniform() < 0.5 ? (int)(uniform() * 6) : -1, lamp = uniform() < 0.5, k;
    for (a = 0; a < 3; a++) {
        lo[a] = between(-2.0, 2.0) * size;
        hi[a] = lo[a] + between(0.5, 2.0) * size;
    }
    sc->n = 0;
    {
        sc_poly room[6];
        box(room, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], 1);
        for (i = 0; i < 6; i++)
            if (i != open) sc->p[sc->n++] = room[i];
    }
    for (i = 0; i < sc->n; i++) {
        double r = reflectance();
        set_mat(&sc->p[i], r, r * between(0.5, 1.0), r * between(0.5, 1.0), 0, 0, 0);
    }
    if (lamp) { /* a square under the ceiling, facing down */
        double cx = 0.5 * (lo[0] + hi[0]), cz = 0.5 * (lo[2] + hi[2]),
               h = hi[1] - 0.01 * (hi[1] - lo[1]);
        double w = between(0.05, 0.3) * (hi[0] - lo[0]);
        sc->p[sc->n] =
            quad(cx - w, h, cz - w, cx + w, h, cz - w, cx + w, h, cz + w, cx - w, h, cz + w);
        set_mat(&sc->p[sc->n], 0.5, 0.5, 0.5, between(1, 20), between(1, 20), between(1, 20));
        sc->n++;
    } else {
        int f = (int)(uniform() * sc->n);
        set_mat(&sc->p[f], sc->p[f].rho[0], sc->p[f].rho[1], sc->p[f].rho[2], between(0.1, 10),
                between(0.1, 10), between(0.1, 10));
    }
    /* Blocks just above the floor, one in each half of the room along x: apart, since
     * the balance below takes a patch's hemi-cube for all of it, and a patch reaching
     * into another block sees that block's inside (culled) as light escaping. */
    for (k = (int)(uniform() * 3); k > 0; k--) {
        double b0[3], b1[3];
        int first = sc->n;
        for (a = 0; a < 3; a++) {
            double span = hi[a] - lo[a];
            b0[a] = lo[a] + between(0.05, 0.2) * span;
            b1[a] = b0[a] + between(0.1, 0.25) * span;
        }
        if (k == 2) {
            b0[0] += 0.5 * (hi[0] - lo[0]);
            b1[0] += 0.5 * (hi[0] - lo[0]);
        }
        b1[1] -= b0[1] - lo[1] - 0.02 * (hi[1] - lo[1]);
        b0[1] = lo[1] + 0.02 * (hi[1] - lo[1]);
        sc->n += box(sc->p + sc->n, b0[0], b0[1], b0[2], b1[0], b1[1], b1[2], 0);
        for (i = first; i < sc->n; i++) {
            double r = reflectance();
            set_mat(&sc->p[i], r, r, r, 0, 0, 0);
        }
    }
    for (i = 0; i < sc->n; i++) sc->p[i].tag = i;
    memset(&sc->o, 0, sizeof sc->o);
    sc->o.max_element = between(0.08, 0.5) * size;
    sc->o.res = 8 << (int)(uniform() * 3); /* 8, 16 or 32 */
    sc->o.no_overshoot = uniform() < 0.15;
    sc->twin = uniform() < 0.25;
    sc->tol = pow(10.0, -between(2.0, 3.5));
    for (a = 0; a < 3; a++) { /* from inside the room towards a point inside */
        sc->cam[a] = lo[a] + between(0.2, 0.8) * (hi[a] - lo[a]);
        sc->cam[3 + a] = lo[a] + between(0.2, 0.8) * (hi[a] - lo[a]);
    }
}

/* An element at the fixed core's clamp (Q16.16 INT32_MAX). */
static int clamped_element(sc_solver *s, const sc_stats *st)
{
    const rad_scene_t *c = sc_core(s);
    int e;
    for (e = 0; e < st->elements; e++) {
        const rad_rgb_t *b = &c->pools.elements[e].radiosity;
        if (b->r == INT32_MAX || b->g == INT32_MAX || b->b == INT32_MAX) return 1;
    }
    return 0;
}

static int finite_image(void *s, int twin, const scene_t *sc, char *err, size_t errlen)
{
    enum { W = 24, H = 16 };
    float img[W * H * 3];
    sc_camera cam;
    int i, rc;
    memset(&cam, 0, sizeof cam);
    memcpy(cam.eye, sc->cam, sizeof cam.eye);
    memcpy(cam.target, sc->cam + 3, sizeof cam.target);
    cam.up[1] = 1;
    cam.fov_deg = 60;
    rc = twin ? scf_render(s, &cam, 1, W, H, img, err, errlen)
              : sc_render(s, &cam, 1, W, H, img, err, errlen);
    if (rc < 0) return 1; /* a camera the renderer refuses (eye on the target): no image */
    for (i = 0; i < W * H * 3; i++)
        if (!isfinite(img[i]) || img[i] < 0) {
            snprintf(err, errlen, "pixel value %g in the rendered view", (double)img[i]);
            return 0;
        }
    return 1;
}

typedef struct {
    int runs, converged, capped, backoffs, saturated, twin, plain, refused;
    double worst_balance;
} tally_t;

/* Runs scene SEED; 0, or 1 with the failure in err. */
static int run(uint64_t seed, tally_t *t, char *err, size_t errlen)
{
    scene_t sc;
    sc_stats st;
    void *s;
    int shots;
    rng = seed * 0x9E3779B97F4A7C15ull + 1;
    make_scene(&sc);
    s = sc.twin ? (void *)scf_create(sc.p, sc.n, &sc.o, NULL, NULL, err, errlen)
                : (void *)sc_create(sc.p, sc.n, &sc.o, NULL, NULL, err, errlen);
    if (!s) {
        t->refused++;
        return 0;
    } /* refused with a message: allowed */
    shots = sc.twin ? scf_solve(s, SHOT_CAP, sc.tol, NULL, NULL)
                    : sc_solve(s, SHOT_CAP, sc.tol, NULL, NULL);
    if (sc.twin)
        scf_get_stats(s, &st);
    else
        sc_get_stats(s, &st);
    t->runs++;
    t->twin += sc.twin;
    t->plain += sc.o.no_overshoot;
    t->converged += st.converged;
    t->capped += shots >= SHOT_CAP;
    t->backoffs += st.backoffs > 0;
    t->saturated += st.saturations > 0;
    if (getenv("SOAK_VERBOSE") && (!st.converged || st.saturations || st.backoffs))
        printf("seed %llu: %d shots, unshot %g (tol %g), %lu back-offs, %lu saturations%s%s\n",
               (unsigned long long)seed, shots, st.unshot, sc.tol, st.backoffs, st.saturations,
               sc.twin ? ", float" : "", sc.o.no_overshoot ? ", plain" : "");
    /* The fixed build compares in Q16.16: the tolerance rounds by up to 2^-17. */
    if (!st.solved ||
        (st.converged ? st.unshot > sc.tol + 1.0 / 65536 : st.unshot < sc.tol - 1.0 / 65536) ||
        (shots < SHOT_CAP && !st.converged)) {
        snprintf(err, errlen, "%d shots, unshot %g, tol %g: converged says %d", shots, st.unshot,
                 sc.tol, st.converged);
    } else if (!sc.twin && st.saturations == 0 && clamped_element(s, &st)) {
        snprintf(err, errlen, "an element at the clamp, saturations 0");
    } else if (!sc.twin && st.converged && st.saturations == 0) {
        double absorbed = 0, escaped = 0, off = balance(s, sc.p, &absorbed, &escaped);
        if (off > t->worst_balance) t->worst_balance = off;
        if (off < 0 || off > 0.02)
            snprintf(err, errlen,
                     "converged (%d shots, unshot %g) but the energy balance is off by %g", shots,
                     st.unshot, off);
    }
    if (!err[0] && !finite_image(s, sc.twin, &sc, err, errlen)) { /* err written */
    }
    if (sc.twin)
        scf_destroy(s);
    else
        sc_destroy(s);
    return err[0] != 0;
}

int main(int argc, char **argv)
{
    uint64_t base = argc > 1 ? strtoull(argv[1], NULL, 10) : 19;
    long n = argc > 2 ? strtol(argv[2], NULL, 10) : 1000, k;
    tally_t t;
    clock_t t0 = clock();
    memset(&t, 0, sizeof t);
    for (k = 0; k < n; k++) {
        char err[512] = "";
        if (run(base + (uint64_t)k, &t, err, sizeof err)) {
            fprintf(stderr, "soak: seed %llu (rerun: soak %llu 1): %s\n",
                    (unsigned long long)(base + (uint64_t)k),
                    (unsigned long long)(base + (uint64_t)k), err);
            return 1;
        }
    }
    printf("soak: %ld scenes from seed %llu in %.1f s: %d solved (%d float, %d plain), %d refused "
           "at create; "
           "%d converged, %d at the %d-shot cap (reported), %d backed off, %d saturated "
           "(reported); worst "
           "balance %.4f%%\n",
           n, (unsigned long long)base, (double)(clock() - t0) / CLOCKS_PER_SEC, t.runs, t.twin,
           t.plain, t.refused, t.converged, t.capped, SHOT_CAP, t.backoffs, t.saturated,
           100 * t.worst_balance);
    return 0;
}
