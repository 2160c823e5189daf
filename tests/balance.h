/* SPDX-License-Identifier: MIT */
/* The energy balance of a solution, for tests/test_diverge.c and tests/soak/soak.c. */
#ifndef RAD_TEST_BALANCE_H
#define RAD_TEST_BALANCE_H

#include <math.h>
#include <stdlib.h>
#include "host/scene.h"
#include "internal.h"

/* Fixed build, caller units, all channels: the emitted power against the absorbed,
 * sum (1 - rho) H A with the irradiance H = (B - E) / rho, plus the escaped, each
 * patch's B A times the part of its hemi-cube that sees no element (POLYS: the scene,
 * indexed by tag). The shots used these very form factors, so what is off is power
 * made or lost (clamps, debts never paid) plus the power still unshot. Writes the
 * absorbed and escaped parts of the emitted; returns |emitted - absorbed - escaped| /
 * emitted, or -1 when out of memory. */
static inline double balance(sc_solver *s, const sc_poly *polys, double *out_absorbed,
                             double *out_escaped)
{
    const rad_scene_t *c = sc_core(s);
    sc_stats st;
    double emitted = 0, absorbed = 0, escaped = 0, *bp, *ff;
    int e, p, k, ok;
    sc_get_stats(s, &st);
    bp = calloc((size_t)st.patches, sizeof *bp);
    ff = malloc((size_t)st.elements * sizeof *ff);
    ok = bp && ff;
    for (e = 0; ok && e < st.elements; e++) {
        const sc_poly *q = &polys[sc_element_tag(s, e)];
        double rgb[3], a = sc_element_area(s, e);
        sc_element_rgb(s, e, 0, rgb);
        for (k = 0; k < 3; k++) {
            emitted += q->emit[k] * a;
            if (q->rho[k] > 0) absorbed += (1 - q->rho[k]) * (rgb[k] - q->emit[k]) / q->rho[k] * a;
            bp[c->pools.elements[e].patch] += rgb[k] * a;
        }
    }
    for (p = 0; ok && p < st.patches; p++) {
        double sum = 0;
        ok = sc_form_factors(s, p, ff) == 0;
        for (e = 0; ok && e < st.elements; e++) sum += ff[e];
        escaped += bp[p] * (1 - sum);
    }
    free(bp);
    free(ff);
    if (!ok || !(emitted > 0)) return -1;
    *out_absorbed = absorbed / emitted;
    *out_escaped = escaped / emitted;
    return fabs(emitted - absorbed - escaped) / emitted;
}

#endif
