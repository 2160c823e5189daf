/* SPDX-License-Identifier: MIT */
/* rad — which element of a surface a hemi-cube pixel sees.
 *
 * The hemi-cube draws each surface as one polygon (its outline, clipped and rasterized
 * once) and finds the element under each pixel from the surface's lattice, not by
 * drawing every element. A quad's element column lies between lattice lines k and
 * k + 1, where line k joins the points k/n along two opposite edges (the mesher's
 * bilinear grid); its row likewise; a triangle's elements lie between lines of its
 * barycentric lattice in three directions (i, j and i + j).
 *
 * Line k and the cube's centre span a plane, with normal L_k = P_k x R_k for the line's
 * two end points; a pixel's ray is past line k when E_k = L_k . ray >= 0. With the
 * corners as integers relative to the centre, P_k = (n - k) p0 + k p1 and R_k alike,
 * so L_k = C0 + k C1 + k^2 C2 exactly, and along a row of pixels every E_k steps by a
 * constant. A span finds its first and last pixels' columns by a walk from the
 * previous span's (or by bisection); then each family walks the lines between them,
 * each line's first pixel one division away and the next line's test a few adds away
 * (by differences), and adds the line's change of the element id to a row of steps.
 * One pass over the pixels sums the steps into ids and depth-tests, without a branch:
 * an element's run in a row is under two pixels on average at res 128, too short for
 * branches on it to be predicted.
 *
 * Integer ranges: corners scaled to |c| <= 2^S with S = 22 - bitlen(n); the ray's
 * components are at most RES <= 2^10; then |C0| <= 2 n^2 2^2S, |C1| <= 8 n 2^2S,
 * |C2| <= 8 2^2S, and every E_k, k in [0, n], stays below 54 2^10 n^2 2^2S < 2^60, so
 * differences of two fit as well.
 * The same integers serve both builds; a pixel's element depends on its own span
 * alone, so parts of a cube rendered apart, or in bands, give the same bits.
 *
 * Precision: a corner moves by at most M 2^-S (M its largest coordinate from the
 * centre), and so does every lattice line; seen from distance D that is M / D 2^-S
 * radians: a tenth of a pixel at res 128 for M / D = 100 and n < 64 (S = 16). Only a
 * huge lattice passing close to the shooter errs by more, and there its elements are
 * many pixels wide. The outline, and so which surface a pixel sees, is exact.
 */
#include "internal.h"

/* Corners (and their sums, shifted) are within +-2^22: int32, products below 2^45. */
static void cross(const int32_t *a, const int32_t *b, int64_t *r)
{
    r[0] = rad__mul32(a[1], b[2]) - rad__mul32(a[2], b[1]);
    r[1] = rad__mul32(a[2], b[0]) - rad__mul32(a[0], b[2]);
    r[2] = rad__mul32(a[0], b[1]) - rad__mul32(a[1], b[0]);
}

/* -V when NEG, else V. */
static int64_t negate_if(int64_t v, int neg)
{
    return neg ? -v : v;
}

/* The family of lines k = 0..N joining (N - k) P0 + k P1 to (N - k) R0 + k R1, K
 * elements to a patch along it, oriented so that E_k >= 0 on P1's side; X = P0 x R0,
 * Y = P0 x R1 + P1 x R0, Z = P1 x R1 (lattice_setup's, which the families share). */
static void family(rad__family_t *f, const int64_t *x, const int64_t *y, const int64_t *z,
                   const int32_t *p0, const int32_t *p1, const int32_t *r0, const int32_t *r1,
                   uint32_t n, uint32_t k, unsigned shift)
{
    int64_t l[3];
    int32_t pm[3], rm[3], far[3];
    const int32_t nn = (int32_t)n; /* < 2^12 */
    unsigned c;
    f->n = n;
    f->k = k;
    f->unit = f->coarse = 0;
    for (c = 0; c < 3; c++) {
        f->c[0][c] = rad__mul16(rad__mul16(x[c], nn), nn);
        f->c[1][c] = rad__mul16(y[c] - 2 * x[c], nn);
        f->c[2][c] = x[c] - y[c] + z[c];
    }
    /* The sign of the line half way, (p0 + p1) to (r0 + r1), seen against P1: on at most
     * 17 bits a corner, so the triple product fits (the same sign as for every line
     * k < n, unless the surface is seen edge-on, where it covers next to no pixels). */
    for (c = 0; c < 3; c++) {
        int32_t sp = p0[c] + p1[c], sr = r0[c] + r1[c]; /* within +-2^23 */
        pm[c] = shift ? rad__shr_round32(sp, shift) : sp;
        rm[c] = shift ? rad__shr_round32(sr, shift) : sr;
        far[c] = shift ? rad__shr_round32(p1[c], shift) : p1[c];
    }
    cross(pm, rm, l);
    if (l[0] * far[0] + l[1] * far[1] + l[2] * far[2] < 0)
        for (c = 0; c < 3; c++) { /* no c / 3, c % 3: calls on M0 */
            f->c[0][c] = -f->c[0][c];
            f->c[1][c] = -f->c[1][c];
            f->c[2][c] = -f->c[2][c];
        }
}

static void lattice_setup(rad__lattice_t *lt);
static void face_setup(rad__lattice_t *lt, const unsigned char *axis, const signed char *sign);

void rad__lattice_init(rad__lattice_t *lt, const rad_surface_t *sf, const rad_vec3_t *corner,
                       unsigned n, int32_t res)
{
    unsigned c;
    lt->sf = sf;
    lt->corner = corner;
    lt->ncorner = n;
    lt->res = res;
    lattice_setup(lt);
    for (c = 0; c < 3; c++) { /* the families' coefficients are on the cube's axes */
        lt->axis[c] = (unsigned char)c;
        lt->sign[c] = 1;
    }
    lt->ready = 1;
}

/* The families of LT's surface from its corners (rad__lattice_init's). */
static void lattice_setup(rad__lattice_t *lt)
{
    const rad_surface_t *sf = lt->sf;
    const rad_vec3_t *corner = lt->corner;
    const unsigned n = lt->ncorner;
    int32_t q[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    rad_real_t m = RAD__EPS;
    rad__grid_t g;
    uint32_t len = sf->pu * sf->ku > sf->pv * sf->kv ? sf->pu * sf->ku : sf->pv * sf->kv;
    /* len < 2^12 (edges of at most 222 units in elements of at least 1/16: mesh.c's
     * limits), so S >= 10. */
    unsigned i, nb = rad__bitlen64(len), s = nb < 22u ? 22u - nb : 0u,
                shift = s > 17u ? s - 17u : 0u;
    for (i = 0; i < n; i++) {
        rad_real_t a = corner[i].x < 0 ? -corner[i].x : corner[i].x;
        rad_real_t b = corner[i].y < 0 ? -corner[i].y : corner[i].y;
        rad_real_t c = corner[i].z < 0 ? -corner[i].z : corner[i].z;
        if (a > m) m = a;
        if (b > m) m = b;
        if (c > m) m = c;
    }
    g = rad__grid_init(m, s);
    for (i = 0; i < n; i++) {
        q[i][0] = (int32_t)rad__grid(corner[i].x, &g);
        q[i][1] = (int32_t)rad__grid(corner[i].y, &g);
        q[i][2] = (int32_t)rad__grid(corner[i].z, &g);
    }
    lt->first = sf->first_element;
    lt->pu = sf->pu;
    if (n == 4) {
        /* Columns between Q0Q3 and Q1Q2, rows between Q0Q1 and Q3Q2: of their eight
         * cross products, two are shared (Q0 x Q2, and Q1 x Q3 = -Q3 x Q1). */
        int64_t c03[3], c02[3], c13[3], c12[3], c01[3], c32[3], y0[3], y1[3];
        cross(q[0], q[3], c03);
        cross(q[0], q[2], c02);
        cross(q[1], q[3], c13);
        cross(q[1], q[2], c12);
        cross(q[0], q[1], c01);
        cross(q[3], q[2], c32);
        for (i = 0; i < 3; i++) {
            y0[i] = c02[i] + c13[i];
            y1[i] = c02[i] - c13[i];
        }
        lt->nfam = 2;
        family(&lt->fam[0], c03, y0, c12, q[0], q[1], q[3], q[2], sf->pu * sf->ku, sf->ku, shift);
        family(&lt->fam[1], c01, y1, c32, q[0], q[3], q[1], q[2], sf->pv * sf->kv, sf->kv, shift);
        /* id = first + (pj pu + pi) ku kv + b ku + a, for column pi ku + a, row pj kv + b */
        lt->fam[0].unit = 1u;
        lt->fam[0].coarse = (uint32_t)sf->ku * sf->kv;
        lt->fam[1].unit = sf->ku;
        lt->fam[1].coarse = (uint32_t)sf->pu * sf->ku * sf->kv;
    } else {
        /* T0 = (0, 0), T1 = (m, 0), T2 = (0, m), m = len: lines of constant i, j and
         * i + j. */
        int64_t c01[3], c02[3], c12[3], y[3][3];
        const int64_t zero[3] = {0, 0, 0};
        /* Of the twelve cross products three are distinct: the others are a corner
         * with itself (0) or these reversed. */
        cross(q[0], q[1], c01);
        cross(q[0], q[2], c02);
        cross(q[1], q[2], c12);
        for (i = 0; i < 3; i++) {
            y[0][i] = c01[i] + c12[i]; /* Q0 x Q1 + Q1 x Q2 */
            y[1][i] = c02[i] - c12[i]; /* Q0 x Q2 + Q2 x Q1 */
            y[2][i] = c02[i] - c01[i]; /* Q0 x Q2 + Q1 x Q0 */
        }
        lt->nfam = 3;
        family(&lt->fam[0], c02, y[0], zero, q[0], q[1], q[2], q[1], len, sf->ku, shift);
        family(&lt->fam[1], c01, y[1], zero, q[0], q[2], q[1], q[2], len, sf->ku, shift);
        family(&lt->fam[2], zero, y[2], c12, q[0], q[1], q[0], q[2], len, sf->ku, shift);
    }
}

void rad__lattice_face(rad__lattice_t *lt, const unsigned char *axis, const signed char *sign)
{
    face_setup(lt, axis, sign);
    lt->ready = 2;
}

/* The coefficients of LT's families on the face whose axes a, b, d are the cube's AXIS
 * times SIGN, from those on LT's axes (the last face's, or the cube's). They are kept
 * on the axes a, -b, d (x right and y down, as pixels go), so that E's changes along a
 * row and a column, 2 c[j][0] and 2 c[j][1], need no negation: GCC makes a 64-bit
 * product of -2 x, a library call on M0. */
static void face_setup(rad__lattice_t *lt, const unsigned char *axis, const signed char *sign)
{
    unsigned f, j, i, from[3], ax[3], src[3];
    int flip[3];
    const int32_t res = lt->res;
    /* The axes are a permutation, the signs +-1: new axis i is the cube's ax[i], which
     * is old axis from[i], so the coefficients move over exactly. */
    for (i = 0; i < 3; i++) {
        ax[i] = axis[i] < 3u ? axis[i] : 2u; /* x, y or z (no % 3: a call on M0) */
        from[lt->axis[i]] = i;
    }
    for (i = 0; i < 3; i++) {
        src[i] = from[ax[i]];
        flip[i] = ((sign[i] < 0) != (i == 1)) != (lt->sign[src[i]] < 0);
    }
    for (f = 0; f < lt->nfam; f++) {
        rad__family_t *fm = &lt->fam[f];
        for (j = 0; j < 3; j++) {
            /* The ray (2 x + 1 - res, 2 y + 1 - res, res) on the axes a, -b, d: within
             * +-res <= 2^10 a component, so E at any pixel keeps the bound above. At
             * pixel (0, 0), (1 - res) (k0 + k1) + res k2 as one product: each
             * coefficient times res fits (E's bound), so three of them summed do. */
            int64_t *k = fm->c[j], old[3];
            for (i = 0; i < 3; i++) old[i] = k[i];
            for (i = 0; i < 3; i++) k[i] = negate_if(old[src[i]], flip[i]);
            fm->o[j] = k[0] + k[1] + rad__mul16(k[2] - k[0] - k[1], res);
        }
        fm->hint[0] = fm->hint[1] = -1; /* no span yet on this face */
        fm->wk = -1;                    /* no walker yet */
    }
    for (i = 0; i < 3; i++) {
        lt->axis[i] = (unsigned char)ax[i];
        lt->sign[i] = (sign[i] < 0) != (i == 1) ? -1 : 1;
    }
}

/* ---- spans --------------------------------------------------------------------- */

/* One family along a span. Its first pixel lies between lines I and I + 1; the walk goes
 * by STEP (+1, -1 or 0) to END, the cell of its last pixel. T tests the next line,
 * k = I + 1 up or k = I down: T = E_k up, -E_k - 1 down, so the line is crossed at the
 * first pixel where T >= 0. Crossing it adds D to T, and D2 to D. All three are linear
 * along the row: T + x ST at the span's pixel x (D and D2 alike, by SD and SD2). */
typedef struct {
    int64_t t, d, d2, st, sd, sd2;
    int32_t i, end, step;
} walk_t;

/* E_k for k in [0, n], n < 2^12. */
static int64_t at(const int64_t *e, int32_t k)
{
    return e[0] + rad__mul16(e[1] + rad__mul16(e[2], k), k);
}

/* Largest k in [0, n - 1] with E_k >= 0 (0 when none), the coefficients E at a pixel:
 * a bisection whose halving does not branch (its tests are coin flips). */
static int32_t search(const int64_t *e, uint32_t n)
{
    int32_t lo = 0, size = (int32_t)n;
    while (size > 1) {
        int32_t half = size / 2;
        lo = at(e, lo + half) >= 0 ? lo + half : lo;
        size -= half;
    }
    return lo;
}

/* search(E, N), found by walking from cell H, the previous span's (-1: none): most
 * spans start in the previous row's cell or the next, few more than two away. The
 * walk gives the bisection's answer when E_k does not
 * increase with k over [0, N - 1]: then {k : E_k >= 0} is a prefix, and both find its
 * last k (or 0). E_k's step to k + 1, e1 + (2 k + 1) e2, is linear in k, so two ends
 * check that. Otherwise, and past two cells, the bisection: the result never depends
 * on H, so parts and bands give the same bits. */
static int32_t search_from(const int64_t *e, uint32_t n, int32_t h)
{
    int32_t last = (int32_t)n - 1, i;
    int64_t v, d;
    if (h < 0 || n < 2 || e[1] + e[2] > 0 || e[1] + rad__mul16(e[2], 2 * (int32_t)n - 3) > 0)
        return search(e, n);
    /* E_h, then its neighbours by differences: E_{h+1} - E_h = e1 + (2 h + 1) e2, which
     * changes by 2 e2 a step (every E_k, k in [0, n], and so each difference, fits). */
    v = at(e, h);
    if (v >= 0) {
        d = e[1] + rad__mul16(e[2], 2 * h + 1);
        for (i = 0; i < 2; i++, h++, d += 2 * e[2]) {
            if (h == last || (v += d) < 0) return h;
        }
    } else {
        d = e[1] + rad__mul16(e[2], 2 * h - 1);
        for (i = 0; i < 2; i++, h--, d -= 2 * e[2]) {
            if (h == 0 || (v -= d) >= 0) return h == 0 ? 0 : h - 1;
        }
    }
    return search(e, n);
}

/* Sets W up for family F on row Y from pixel XS to XE - 1, searching from F's hints
 * and leaving this span's cells there. */
static void walk_start(rad__family_t *f, int32_t y, int32_t xs, int32_t xe, walk_t *w)
{
    int64_t e[3], de[3], last[3];
    int32_t k, sg, span = xe - 1 - xs;
    unsigned j;
    for (j = 0; j < 3; j++) {
        /* pixel (xs, y) and the last, (xe - 1, y): x, y, span < res <= 2^10 */
        de[j] = 2 * f->c[j][0];
        e[j] = f->o[j] + rad__mul16(de[j], xs) + rad__mul16(2 * f->c[j][1], y);
        last[j] = e[j] + rad__mul16(de[j], span);
    }
    w->i = f->hint[0] = search_from(e, f->n, f->hint[0]);
    w->end = f->hint[1] = search_from(last, f->n, f->hint[1]);
    w->step = w->end > w->i ? 1 : w->end < w->i ? -1 : 0;
    if (!w->step) return;
    sg = w->step;
    k = w->i + (sg > 0);
    w->t = negate_if(at(e, k), sg < 0) - (sg < 0);
    w->st = negate_if(at(de, k), sg < 0);
    w->d = e[1] + rad__mul16(e[2], 2 * k + sg);
    w->sd = de[1] + rad__mul16(de[2], 2 * k + sg);
    w->d2 = negate_if(2 * e[2], sg < 0);
    w->sd2 = negate_if(2 * de[2], sg < 0);
}

/* ---- the walker: a span's start cell and values by adds from the last span's ---- */

/* V times M (|M| < 2^10): no product for the steps of one pixel or row. Inlined on
 * RAD__MUL_SPLIT targets: 119k calls in the M0 port test's solve, 60% of them by 0 or
 * +-1, where the call cost more than the rest. */
RAD__ALWAYS_INLINE int64_t times(int64_t v, int32_t m)
{
    return m == 1 ? v : m == -1 ? -v : m == 0 ? 0 : rad__mul16(v, m);
}

/* F's walker at line K of pixel (X, Y), whose coefficients are A, from them and their
 * changes along a row and a column (the values the old-style start computes: at, and
 * the differences in k, of each). */
static void walker_init(rad__family_t *f, int32_t x, int32_t y, const int64_t *a, int32_t k)
{
    int64_t ox[3], oy[3];
    unsigned j;
    for (j = 0; j < 3; j++) {
        ox[j] = 2 * f->c[j][0];
        oy[j] = 2 * f->c[j][1];
    }
    f->w[0] = at(a, k);
    f->w[1] = a[1] + rad__mul16(a[2], 2 * k + 1);
    f->w[2] = 2 * a[2];
    f->w[3] = at(ox, k);
    f->w[4] = ox[1] + rad__mul16(ox[2], 2 * k + 1);
    f->w[5] = at(oy, k);
    f->w[6] = oy[1] + rad__mul16(oy[2], 2 * k + 1);
    f->wk = k;
    f->wx = x;
    f->wy = y;
}

/* F's walker to pixel (X, Y): E, D and D2 are linear along rows and columns, and their
 * changes (w[3..6], and 4 c[2][0], 4 c[2][1] for D2) do not depend on the pixel. */
static void walker_move(rad__family_t *f, int32_t x, int32_t y)
{
    int32_t dx = x - f->wx, dy = y - f->wy;
    if (dx) {
        f->w[0] += times(f->w[3], dx);
        f->w[1] += times(f->w[4], dx);
        f->w[2] += times(4 * f->c[2][0], dx);
    }
    if (dy) {
        f->w[0] += times(f->w[5], dy);
        f->w[1] += times(f->w[6], dy);
        f->w[2] += times(4 * f->c[2][1], dy);
    }
    f->wx = x;
    f->wy = y;
}

/* The walker from line k to k + 1 (UP) or k - 1: E_{k+1} = E_k + D_k, D_{k+1} = D_k +
 * D2; down, D_{k-1} = D_k - D2 first, then E_{k-1} = E_k - D_{k-1}; their changes
 * along rows and columns alike. */
static void walker_line(rad__family_t *f, int up)
{
    int64_t sd2 = 4 * f->c[2][0], yd2 = 4 * f->c[2][1];
    if (up) {
        f->w[0] += f->w[1];
        f->w[1] += f->w[2];
        f->w[3] += f->w[4];
        f->w[4] += sd2;
        f->w[5] += f->w[6];
        f->w[6] += yd2;
        f->wk++;
    } else {
        f->w[1] -= f->w[2];
        f->w[0] -= f->w[1];
        f->w[4] -= sd2;
        f->w[3] -= f->w[4];
        f->w[6] -= yd2;
        f->w[5] -= f->w[6];
        f->wk--;
    }
}

/* The cell search gives when E_k does not increase with k: the largest k in
 * [0, n - 1] with E_k >= 0, or 0; from line K (in that range) with E = E_k, D = E_{k+1}
 * - E_k, D2 = D's change, by whole lines. */
static int32_t cell_walk(int64_t e, int64_t d, int64_t d2, int32_t k, uint32_t n)
{
    const int32_t last = (int32_t)n - 1;
    if (e >= 0) {
        while (k < last && e + d >= 0) {
            e += d;
            d += d2;
            k++;
        }
    } else {
        while (k > 0 && e < 0) {
            d -= d2;
            e -= d;
            k--;
        }
    }
    return k;
}

/* Whether E_k does not increase with k over [0, n - 1] at a pixel, from its D = E_{k+1}
 * - E_k and D2 at line K: D is linear in k, so its largest value over [0, n - 2] is at
 * one end (the search's own test, at the walker). */
static int mono_at(int64_t d, int64_t d2, int32_t k, uint32_t n)
{
    if (n < 2) return 1; /* one cell: every search gives 0 */
    return (d2 > 0 ? d + times(d2, (int32_t)n - 2 - k) : d - times(d2, k)) <= 0;
}

/* walk_start's W, the same cells and values, from F's walker when E_k does not
 * increase with k at the span's two ends (there the cell is the search's unique
 * answer, and a walk over lines finds it); else walk_start's own way. */
static void walk_start_walker(rad__family_t *f, int32_t y, int32_t xs, int32_t xe, walk_t *w)
{
    int32_t span = xe - 1 - xs, i;
    int64_t sd2 = 4 * f->c[2][0], e, d, d2;
    if (f->wk < 0) {
        int64_t a[3];
        unsigned j;
        for (j = 0; j < 3; j++)
            a[j] = f->o[j] + rad__mul16(2 * f->c[j][0], xs) + rad__mul16(2 * f->c[j][1], y);
        walker_init(f, xs, y, a, search(a, f->n));
    } else {
        walker_move(f, xs, y);
    }
    if (!mono_at(f->w[1], f->w[2], f->wk, f->n)) {
        walk_start(f, y, xs, xe, w);
        return;
    }
    i = cell_walk(f->w[0], f->w[1], f->w[2], f->wk, f->n);
    while (f->wk < i) walker_line(f, 1);
    while (f->wk > i) walker_line(f, 0);
    e = f->w[0] + times(f->w[3], span);
    d = f->w[1] + times(f->w[4], span);
    d2 = f->w[2] + times(sd2, span);
    if (!mono_at(d, d2, i, f->n)) {
        walk_start(f, y, xs, xe, w);
        return;
    }
    w->i = i;
    w->end = cell_walk(e, d, d2, i, f->n);
    w->step = w->end > i ? 1 : w->end < i ? -1 : 0;
    if (w->step > 0) {
        w->t = f->w[0] + f->w[1];
        w->st = f->w[3] + f->w[4];
        w->d = f->w[1] + f->w[2];
        w->sd = f->w[4] + sd2;
        w->d2 = f->w[2];
        w->sd2 = sd2;
    } else if (w->step < 0) {
        w->t = -f->w[0] - 1;
        w->st = -f->w[3];
        w->d = f->w[1] - f->w[2];
        w->sd = f->w[4] - sd2;
        w->d2 = -f->w[2];
        w->sd2 = -sd2;
    }
}

/* A triangle's element needs its cell's column x and row y and which side of the
 * i + j line l it is on: the steps add up to x + 2^12 y + 2^24 (l - x - y + 128), mod
 * 2^32, and these are each family's steps. */
static const uint32_t tri_unit[3] = {1u - (1u << 24), (1u << 12) - (1u << 24), 1u << 24};
#define TRI_BIAS (128u << 24)

/* Family F (of LT) along the span XS..XE-1 of row Y: every line it crosses adds its
 * change of the element id to STEPS at the first pixel past it. A quad's change is F's
 * unit within a patch and what moves to the next patch at a patch's edge; a
 * triangle's, F's part of the packed cell (tri_unit). Returns the first pixel's part
 * of the id (or of the packed cell). Steps add mod 2^32.
 *
 * The pixel past a line: with ST > 0, T grows along the row, and it is the first pixel
 * from P on where T >= 0. Where a 64-bit division is an instruction (RAD__DIV64), it
 * is the ceiling of -T / ST (or P), with T, D and D2 at the span's first pixel.
 * Elsewhere (a long library call) it is found by stepping: V, U and W are T, D and D2
 * at pixel P, and a pixel to the right adds ST, SD and SD2 to them; P never moves
 * back, so a span costs a step a pixel and a line. Either way a line crossed adds U
 * to V and W to U, SD to ST and SD2 to SD. V, U and W are E_k and its first and
 * second differences in k at a pixel of the face, k in [0, n + 1]: within the
 * header's bound (< 2^62), like every value stepped before. */
static uint32_t family_steps(rad__lattice_t *lt, unsigned f, int32_t y, int32_t xs, int32_t xe,
                             uint32_t *steps)
{
    rad__family_t *fm = &lt->fam[f];
    const uint32_t k = fm->k;
    const int32_t n = xe - xs;
    int64_t v, u, wv, st, sd, sd2;
    uint32_t unit, wrap, first, fi, q, left;
    int32_t i, p = 0;
    walk_t w;
    walk_start_walker(fm, y, xs, xe, &w);
    q = (uint32_t)w.i / k; /* w.i >= 0: one unsigned division, no signed one */
    fi = (uint32_t)w.i - q * k;
    if (lt->nfam == 3) {
        unit = wrap = tri_unit[f];
        first = (uint32_t)w.i * unit;
    } else {
        unit = fm->unit;
        wrap = fm->coarse - (k - 1u) * fm->unit;
        first = q * fm->coarse + fi * fm->unit;
    }
    if (!w.step) return first;
    if (w.step < 0) {
        unit = 0u - unit;
        wrap = 0u - wrap;
    }
    v = w.t;
    st = w.st;
    u = w.d;
    sd = w.sd;
    wv = w.d2;
    sd2 = w.sd2;
    i = w.i;
    /* lines to cross before the next patch edge: up from cell fi, k - fi; down, fi + 1 */
    left = w.step > 0 ? k - fi : fi + 1u;
    while (i != w.end) {
        uint32_t wraps;
        if (st <= 0) { /* a line seen going backwards: crossed here or not at all */
#if RAD__DIV64
            if (v + p * st < 0) break;
#else
            if (v < 0) break;
#endif
        } else {
#if RAD__DIV64
            /* v, u, wv at pixel 0; a negative quotient truncates to at most 0 */
            int64_t c = (-v + st - 1) / st;
            if (c >= n) break;
            p = c > p ? (int32_t)c : p;
#else
            while (v < 0) {
                if (++p >= n) return first;
                v += st;
                u += sd;
                wv += sd2;
            }
#endif
        }
        i += w.step;
        wraps = --left == 0u;
        left = wraps ? k : left;
        steps[p] += wraps ? wrap : unit;
        v += u;
        u += wv;
        st += sd;
        sd += sd2;
    }
    return first;
}

/* The element of a triangle's lattice cell, packed as family_steps sums it, as mesh_tri
 * numbers them (up patches, then down patches; in each, rows of up and down elements).
 * l - x - y is 0 or 1 inside the lattice; at pixels the outline covers but the
 * quantised lattice misses (a tenth of a pixel wide) it is down to minus the elements
 * that fit across that strip: -30 with elements of 1/300 pixel. Past -128
 * (elements under 1/1000 pixel) it wraps, which only moves such a pixel to the other
 * element of its cell. */
static uint32_t tri_element(const rad__lattice_t *lt, uint32_t packed)
{
    uint32_t m = lt->fam[0].n, k = lt->fam[0].k, np = lt->pu;
    uint32_t x = packed & 4095u, y = (packed >> 12) & 4095u;
    int32_t l = (int32_t)(packed >> 24) - 128 + (int32_t)(x + y);
    uint32_t I, a, J, b, dn, patch;
    if (x + y > m - 1u) y = m - 1u - x; /* past the far edge by rounding */
    I = x / k;
    a = x % k;
    J = y / k;
    b = y % k;
    dn = l > (int32_t)(x + y) && x + y + 1u <= m - 1u;
    if (a + b + dn <= k - 1u) {
        patch = J * np - J * (J - 1u) / 2u + I;
    } else {
        patch = np * (np + 1u) / 2u + J * (np - 1u) - J * (J - 1u) / 2u + I;
        a = k - 1u - a;
        b = k - 1u - b;
        dn = 1u - dn;
    }
    return lt->first + patch * k * k + 2u * k * b - b * b + 2u * a + dn;
}

/* The families' steps first, then one pass over the pixels: each sums the steps so
 * far into its element id and is depth-tested (rad__depth_put). The pass zeroes the
 * steps for the next span. */
void rad__lattice_span(rad__lattice_t *lt, int32_t y, int32_t xs, int32_t xe, uint32_t *z,
                       rad_index_t *ids, uint64_t w, uint64_t dw, uint32_t *steps)
{
    uint32_t acc;
    unsigned f;
    int32_t x, n = xe - xs;
    if (n <= 0) return;
    acc = lt->nfam == 3 ? TRI_BIAS : lt->first;
    for (f = 0; f < lt->nfam; f++) acc += family_steps(lt, f, y, xs, xe, steps);
    z += xs;
    ids += xs;
    if (lt->nfam == 2) {
        /* The depth is bits 16..47 of W + x DW: stepped as those bits (wh) and the 16
         * below them (wl, in its top half, so that their carry out is wl's wrap), all
         * in 32 bits (on M0 the 64-bit sum and shift would take the registers). */
        uint32_t wh = (uint32_t)(w >> 16), wl = (uint32_t)w << 16;
        const uint32_t dh = (uint32_t)(dw >> 16), dl = (uint32_t)dw << 16;
        for (x = 0; x < n; x++) {
            uint32_t t = wl + dl;
            acc += steps[x];
            steps[x] = 0;
            rad__depth_put(z, ids, x, wh, acc);
            wh += dh + (t < wl);
            wl = t;
        }
    } else {
        uint32_t last = acc, id = tri_element(lt, acc);
        for (x = 0; x < n; x++, w += dw) {
            acc += steps[x];
            steps[x] = 0;
            if (acc != last) {
                last = acc;
                id = tri_element(lt, acc);
            }
            rad__depth_put(z, ids, x, (uint32_t)(w >> 16), id);
        }
    }
}
