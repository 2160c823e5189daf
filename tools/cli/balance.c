/* SPDX-License-Identifier: MIT */
/* rad_cli's check of where the emitted light goes: the share of the emitters' power
 * that their first shot lands on front faces of elements.
 *
 * A hemi-cube row from patch P sums to the fraction of P's power that reaches a surface
 * from its lit side (1 in a closed scene: Cohen & Greenberg 1985); what is missing leaves
 * the scene or meets faces seen from behind, which radiosity, being one-sided, neither
 * lights nor lets reflect. A room whose walls face outwards gives nearly 0, and a flat,
 * dark picture. Every later bounce starts from this light, so when most of it is lost
 * the scene is almost surely wound the wrong way or open.
 */
#include "cli.h"

#include <stdlib.h>

/* At most this many hemi-cubes at resolution 128 (fewer at higher ones, never fewer
 * than one): the emitting patches are sampled evenly, so the share is a power-weighted
 * mean over a sample. The check only tells most of the light lost (a room wound
 * inside out lands nothing) from little, so a few cubes do: 64 cost a tenth of the
 * whole solve of CornellBox-Original at rad_cli's defaults (its lamp is 30 patches). */
#define BALANCE_CUBES  8
#define BALANCE_PIXELS (BALANCE_CUBES * 128 * 128)

/* The emitted power of patch P in caller units of emission (times core area: the
 * scale is common to every patch, so it cancels in the share). */
static double patch_power(const run_t *r, int p)
{
    int first, tag;
    double area;
    const double *ke;
    if (sc_patch(r->s, p, &first, &area) < 0) return 0;
    tag = sc_element_tag(r->s, first);
    if (tag < 0 || tag >= r->sc.nfaces) return 0;
    ke = r->sc.materials[r->sc.faces[tag].material].ke;
    return area * (ke[0] + ke[1] + ke[2]);
}

double cli_emitted_share_landing(run_t *r)
{
    int p, n = sc_patch_count(r->s);
    uint32_t emitting = 0, stride,
             cubes = BALANCE_PIXELS / ((uint32_t)r->so.res * (uint32_t)r->so.res), k = 0;
    double landed = 0, total = 0,
           *ff = malloc((size_t)(r->st.elements ? r->st.elements : 1) * sizeof *ff);
    if (!ff) return -1;
    for (p = 0; p < n; p++) emitting += patch_power(r, p) > 0;
    if (cubes < 1) cubes = 1;
    stride = emitting > cubes ? (emitting + cubes - 1) / cubes : 1;
    for (p = 0; p < n; p++) {
        double w = patch_power(r, p), sum = 0;
        int e;
        if (!(w > 0) || k++ % stride != 0) continue;
        if (sc_form_factors(r->s, p, ff) < 0) break;
        for (e = 0; e < r->st.elements; e++) sum += ff[e];
        landed += w * sum;
        total += w;
    }
    free(ff);
    return total > 0 ? landed / total : -1;
}
