/* SPDX-License-Identifier: MIT */
/* ply — PLY export, ASCII 8-bit sRGB or binary linear float with welded vertices. See
 * ply.h.
 *
 * Welding hashes each vertex's nine floats into an open-addressed table of at least
 * twice as many slots as vertices (a power of two, linear probing), so it is O(n)
 * expected; a vertex joins the first earlier vertex with the same nine floats, and the
 * welded vertices keep the order of their first occurrence. */
#include "formats/ply.h"

#include "formats/file_io.h"
#include "formats/image.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define KEY 9 /* floats a welded vertex is written with: position, normal, colour */

static int face_corners(const ply_mesh *m, int f)
{
    return m->face[4 * f + 3] < 0 ? 3 : 4;
}

static void header(FILE *f, const ply_mesh *m, int format, int nv)
{
    static const char *const attr[] = {"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue"};
    int k;
    fprintf(f, "ply\nformat %s 1.0\n", format == PLY_ASCII_SRGB ? "ascii" : "binary_little_endian");
    if (m->comment) fprintf(f, "comment %s\n", m->comment);
    fprintf(f, "element vertex %d\n", nv);
    for (k = 0; k < KEY; k++) {
        if (format == PLY_ASCII_SRGB && k >= 3 && k < 6) continue; /* no normals */
        fprintf(f, "property %s %s\n", format == PLY_ASCII_SRGB && k >= 6 ? "uchar" : "float",
                attr[k]);
    }
    fprintf(f, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", m->nf);
}

static void ascii_body(FILE *f, const ply_mesh *m, double exposure)
{
    int v, i, k;
    for (v = 0; v < m->nv; v++) {
        const double *p = &m->pos[3 * v];
        float lin[3];
        unsigned char c[3];
        for (k = 0; k < 3; k++) lin[k] = (float)m->rgb[3 * v + k];
        tonemap(lin, 1, exposure, c);
        fprintf(f, "%.7g %.7g %.7g %u %u %u\n", p[0], p[1], p[2], c[0], c[1], c[2]);
    }
    for (i = 0; i < m->nf; i++) {
        int n = face_corners(m, i);
        fprintf(f, "%d", n);
        for (k = 0; k < n; k++) fprintf(f, " %d", m->face[4 * i + k]);
        fprintf(f, "\n");
    }
}

/* The nine floats vertex V is written with: not finite as 0, beyond float's range as
 * its largest, -0 as +0 (so that equal values weld whatever their sign of zero). */
static void vertex_key(const ply_mesh *m, int v, float key[KEY])
{
    const double *src[3] = {&m->pos[3 * v], &m->normal[3 * v], &m->rgb[3 * v]};
    int k;
    for (k = 0; k < KEY; k++) {
        double d = src[k / 3][k % 3];
        float f = !isfinite(d) ? 0.0f : d > FLT_MAX ? FLT_MAX : d < -FLT_MAX ? -FLT_MAX : (float)d;
        key[k] = f == 0 ? 0.0f : f;
    }
}

/* FNV-1a over the key's bytes. */
static uint32_t key_hash(const float key[KEY])
{
    const unsigned char *b = (const unsigned char *)key;
    uint32_t h = 2166136261u;
    size_t i;
    for (i = 0; i < KEY * sizeof(float); i++) h = (h ^ b[i]) * 16777619u;
    return h;
}

/* Welds M's vertices: KEYS[KEY c ..] holds welded vertex c, ID[v] the welded vertex of
 * vertex v. Returns the welded count, or -1 when out of memory. */
static int weld(const ply_mesh *m, float *keys, int *id)
{
    size_t slots = 16, mask, s;
    int *table, v, n = 0;
    while (slots < 2 * (size_t)m->nv) slots *= 2;
    if (!(table = malloc(slots * sizeof *table))) return -1;
    memset(table, 0xff, slots * sizeof *table); /* -1: empty */
    mask = slots - 1;
    for (v = 0; v < m->nv; v++) {
        float *k = &keys[KEY * (size_t)n];
        vertex_key(m, v, k);
        for (s = key_hash(k) & mask; table[s] >= 0; s = (s + 1) & mask)
            if (memcmp(&keys[KEY * (size_t)table[s]], k, sizeof(float) * KEY) == 0) break;
        if (table[s] < 0) table[s] = n++;
        id[v] = table[s];
    }
    free(table);
    return n;
}

/* N (at most KEY) 32-bit words, little-endian. */
static void put_words(FILE *f, const uint32_t *w, int n)
{
    unsigned char b[4 * KEY];
    int i, k;
    for (i = 0; i < n; i++)
        for (k = 0; k < 4; k++) b[4 * i + k] = (unsigned char)(w[i] >> 8 * k);
    fwrite(b, 4, (size_t)n, f);
}

static void binary_body(FILE *f, const ply_mesh *m, const float *keys, int nw, const int *id)
{
    uint32_t w[KEY];
    int i, k;
    for (i = 0; i < nw; i++) {
        memcpy(w, &keys[KEY * (size_t)i], sizeof w);
        put_words(f, w, KEY);
    }
    for (i = 0; i < m->nf; i++) {
        int n = face_corners(m, i);
        for (k = 0; k < n; k++) w[k] = (uint32_t)id[m->face[4 * i + k]];
        fputc(n, f);
        put_words(f, w, n);
    }
}

int ply_write(const char *path, const ply_mesh *m, int format, double exposure, char *err,
              size_t errlen)
{
    float *keys = NULL;
    int *id = NULL, nw = m->nv;
    fio_out *o;
    if (format == PLY_BINARY_LINEAR) {
        keys = malloc(((size_t)m->nv + 1) * KEY * sizeof *keys);
        id = malloc(((size_t)m->nv + 1) * sizeof *id);
        if (!keys || !id || (nw = weld(m, keys, id)) < 0) {
            free(keys);
            free(id);
            fio_err(err, errlen, path, "out of memory for %d vertices", m->nv);
            return -1;
        }
    }
    o = fio_out_open(path, err, errlen);
    if (o) {
        header(fio_out_stream(o), m, format, nw);
        if (keys)
            binary_body(fio_out_stream(o), m, keys, nw, id);
        else
            ascii_body(fio_out_stream(o), m, exposure);
    }
    free(keys);
    free(id);
    return o && fio_out_commit(o, err, errlen) == 0 ? nw : -1;
}
