/* SPDX-License-Identifier: MIT */
/* tset — 2D triangles by cell, for overlap queries. See tset.h. */
#include "bake/tset.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define CELL_LIMIT 1073741824.0 /* 2^30: cell coordinates clamped to +-this fit the key's halves */

struct tset {
    double cell, tol;
    double (*tri)[3][2];
    int ntri, captri;
    int *etri, *enext, nent, capent; /* a cell's triangles: a list through enext from its head */
    uint64_t *key;
    int *head;
    unsigned *gen; /* a slot is in use when its gen is cur: tset_clear is one increment */
    unsigned cur;
    int nslot, used;
    int *big, nbig, capbig; /* triangles too large to file by cell */
};

static int grow(void **p, int *cap, int need, size_t each)
{
    void *q;
    int c = *cap ? *cap : 64;
    if (need <= *cap) return 0;
    while (c < need) c *= 2;
    if (!(q = realloc(*p, (size_t)c * each))) return -1;
    *p = q;
    *cap = c;
    return 0;
}

static int alloc_slots(tset *s, int n)
{
    s->key = malloc((size_t)n * sizeof *s->key);
    s->head = malloc((size_t)n * sizeof *s->head);
    s->gen = calloc((size_t)n, sizeof *s->gen);
    s->nslot = n;
    s->used = 0;
    return s->key && s->head && s->gen ? 0 : -1;
}

tset *tset_new(double cell, double tol)
{
    tset *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->cell = cell;
    s->tol = tol;
    s->cur = 1;
    if (alloc_slots(s, 1024) != 0) {
        tset_free(s);
        return NULL;
    }
    return s;
}

void tset_clear(tset *s)
{
    s->ntri = s->nent = s->nbig = s->used = 0;
    if (++s->cur == 0) { /* wrapped: an old stamp could match again */
        memset(s->gen, 0, (size_t)s->nslot * sizeof *s->gen);
        s->cur = 1;
    }
}

void tset_free(tset *s)
{
    if (!s) return;
    free(s->tri);
    free(s->etri);
    free(s->enext);
    free(s->key);
    free(s->head);
    free(s->gen);
    free(s->big);
    free(s);
}

static uint64_t key_of(long cx, long cy)
{
    return (uint64_t)(uint32_t)cx << 32 | (uint32_t)cy;
}

static unsigned slot_hash(uint64_t k)
{
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    return (unsigned)k;
}

/* The slot of KEY, or the empty one where it would go. */
static int find_slot(const tset *s, uint64_t key)
{
    int i = (int)(slot_hash(key) & (unsigned)(s->nslot - 1));
    while (s->gen[i] == s->cur && s->key[i] != key) i = (i + 1) & (s->nslot - 1);
    return i;
}

/* Twice the slots, the cells in use moved over. 0 or -1. */
static int rehash(tset *s)
{
    tset old = *s;
    int i;
    if (alloc_slots(s, 2 * old.nslot) != 0) {
        free(s->key);
        free(s->head);
        free(s->gen);
        s->key = old.key;
        s->head = old.head;
        s->gen = old.gen;
        s->nslot = old.nslot;
        s->used = old.used;
        return -1;
    }
    for (i = 0; i < old.nslot; i++)
        if (old.gen[i] == old.cur) {
            int j = find_slot(s, old.key[i]);
            s->gen[j] = s->cur;
            s->key[j] = old.key[i];
            s->head[j] = old.head[i];
            s->used++;
        }
    free(old.key);
    free(old.head);
    free(old.gen);
    return 0;
}

static long cell_coord(const tset *s, double x)
{
    double c = floor(x / s->cell);
    return (long)fmin(fmax(c, -CELL_LIMIT), CELL_LIMIT);
}

/* The cells of T's box into LO, HI; 1 when it spans more than TSET_SPAN a side. */
static int cells_of(const tset *s, const double t[3][2], long lo[2], long hi[2])
{
    int a;
    for (a = 0; a < 2; a++) {
        lo[a] = cell_coord(s, fmin(t[0][a], fmin(t[1][a], t[2][a])) - s->tol);
        hi[a] = cell_coord(s, fmax(t[0][a], fmax(t[1][a], t[2][a])) + s->tol);
    }
    return hi[0] - lo[0] >= TSET_SPAN || hi[1] - lo[1] >= TSET_SPAN;
}

/* Whether A's and B's extents along unit axis (NX, NY) overlap by more than TOL. */
static int axis_overlap(const double a[3][2], const double b[3][2], double nx, double ny,
                        double tol)
{
    double amin = HUGE_VAL, amax = -HUGE_VAL, bmin = HUGE_VAL, bmax = -HUGE_VAL;
    int k;
    for (k = 0; k < 3; k++) {
        double sa = a[k][0] * nx + a[k][1] * ny, sb = b[k][0] * nx + b[k][1] * ny;
        amin = fmin(amin, sa);
        amax = fmax(amax, sa);
        bmin = fmin(bmin, sb);
        bmax = fmax(bmax, sb);
    }
    return amax > bmin + tol && bmax > amin + tol;
}

int tset_tri_overlap(const double a[3][2], const double b[3][2], double tol)
{
    const double(*t[2])[2] = {a, b};
    int i, k;
    for (i = 0; i < 2; i++)
        for (k = 0; k < 3; k++) {
            const double *p = t[i][k], *q = t[i][(k + 1) % 3];
            double nx = p[1] - q[1], ny = q[0] - p[0], l = hypot(nx, ny);
            if (l > 0.0 && !axis_overlap(a, b, nx / l, ny / l, tol)) return 0;
        }
    return 1;
}

int tset_hits(const tset *s, const double t[3][2])
{
    long lo[2], hi[2], x, y;
    int i, e;
    if (cells_of(s, t, lo, hi)) { /* a large query: every triangle */
        for (i = 0; i < s->ntri; i++)
            if (tset_tri_overlap(t, (const double(*)[2])s->tri[i], s->tol)) return 1;
        return 0;
    }
    for (i = 0; i < s->nbig; i++)
        if (tset_tri_overlap(t, (const double(*)[2])s->tri[s->big[i]], s->tol)) return 1;
    for (y = lo[1]; y <= hi[1]; y++)
        for (x = lo[0]; x <= hi[0]; x++) {
            int at = find_slot(s, key_of(x, y));
            if (s->gen[at] != s->cur) continue;
            for (e = s->head[at]; e >= 0; e = s->enext[e])
                if (tset_tri_overlap(t, (const double(*)[2])s->tri[s->etri[e]], s->tol)) return 1;
        }
    return 0;
}

int tset_add(tset *s, const double t[3][2])
{
    long lo[2], hi[2], x, y;
    int big = cells_of(s, t, lo, hi), id = s->ntri;
    int need = big ? 0 : (int)((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1));
    if (grow((void **)&s->tri, &s->captri, id + 1, sizeof *s->tri) != 0) return -1;
    if (big && grow((void **)&s->big, &s->capbig, s->nbig + 1, sizeof *s->big) != 0) return -1;
    if (!big) {
        int cap = s->capent;
        if (grow((void **)&s->etri, &cap, s->nent + need, sizeof *s->etri) != 0) return -1;
        if (grow((void **)&s->enext, &s->capent, s->nent + need, sizeof *s->enext) != 0) return -1;
        while (2 * (s->used + need) > s->nslot)
            if (rehash(s) != 0) return -1;
    }
    memcpy(s->tri[id], t, sizeof s->tri[id]);
    s->ntri++;
    if (big) {
        s->big[s->nbig++] = id;
        return 0;
    }
    for (y = lo[1]; y <= hi[1]; y++)
        for (x = lo[0]; x <= hi[0]; x++) {
            uint64_t k = key_of(x, y);
            int at = find_slot(s, k);
            if (s->gen[at] != s->cur) {
                s->gen[at] = s->cur;
                s->key[at] = k;
                s->head[at] = -1;
                s->used++;
            }
            s->etri[s->nent] = id;
            s->enext[s->nent] = s->head[at];
            s->head[at] = s->nent++;
        }
    return 0;
}
