/* SPDX-License-Identifier: MIT */
/* rad host glue (see scene.h): stored form factor rows and Gauss-Seidel. Compiled once per build of the core. */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "host/scene_impl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/ff_file.h"
#include "formats/file_io.h"

#if RAD_FLOAT
#define FF_KIND FF_FILE_KIND_FLOAT
#else
#define FF_KIND FF_FILE_KIND_FIXED
#endif

static void rows_free(struct sc_solver *h)
{
    free(h->rows.start);
    free(h->rows.ids);
    free(h->rows.ffs);
    memset(&h->rows, 0, sizeof h->rows);
    h->has_rows = 0;
    h->rows_raster = 0;
}

/* Room for ENTRIES entries (contents kept). 0 or -1 (out of memory: nothing changed). */
static int rows_reserve(struct sc_solver *h, uint32_t entries)
{
    rad_index_t *ids = realloc(h->rows.ids, (entries ? entries : 1) * sizeof *ids);
    uint16_t *ffs;
    if (!ids) return -1;
    h->rows.ids = ids;
    ffs = realloc(h->rows.ffs, (entries ? entries : 1) * sizeof *ffs);
    if (!ffs) return -1;
    h->rows.ffs = ffs;
    h->rows.max_entries = entries;
    return 0;
}

static uint32_t bits32(rad_real_t r)
{
    uint32_t b;
    memcpy(&b, &r, sizeof b); /* Q16.16 int32, or IEEE float: 4 bytes either way */
    return b;
}

static uint32_t idx32(rad_index_t i)
{
    return i == RAD_INDEX_NONE ? 0xFFFFFFFFu : (uint32_t)i;
}

/* The meshed geometry as the core holds it (see ff_file.h). */
static uint64_t fingerprint(const struct sc_solver *h)
{
    const rad_scene_t *s = &h->s;
    uint64_t x = FF_FILE_FNV_START;
    uint32_t i, k;
    typedef char real_is_4_bytes[sizeof(rad_real_t) == 4 ? 1 : -1];
    (void)sizeof(real_is_4_bytes);
    x = ff_file_fnv_u32(x, s->n_surfaces);
    x = ff_file_fnv_u32(x, s->n_patches);
    x = ff_file_fnv_u32(x, s->n_elements);
    x = ff_file_fnv_u32(x, s->n_vertices);
    for (i = 0; i < s->n_vertices; i++) {
        const rad_vec3_t *v = &s->pools.vertices[i];
        x = ff_file_fnv_u32(x, bits32(v->x));
        x = ff_file_fnv_u32(x, bits32(v->y));
        x = ff_file_fnv_u32(x, bits32(v->z));
    }
    for (i = 0; i < s->n_elements; i++) {
        const rad_element_t *e = &s->pools.elements[i];
        for (k = 0; k < 4; k++) x = ff_file_fnv_u32(x, idx32(e->v[k]));
        x = ff_file_fnv_u32(x, idx32(e->patch));
        x = ff_file_fnv_u32(x, idx32(e->surface));
    }
    for (i = 0; i < s->n_patches; i++) {
        const rad_patch_t *p = &s->pools.patches[i];
        x = ff_file_fnv_u32(x, idx32(p->surface));
        x = ff_file_fnv_u32(x, idx32(p->first_element));
        x = ff_file_fnv_u32(x, idx32(p->n_elements));
    }
    return x;
}

static void ff_info(const struct sc_solver *h, ff_file_info *in)
{
    memset(in, 0, sizeof *in);
    in->kind = FF_KIND;
    in->res = h->s.cfg.res;
    in->patches = h->s.n_patches;
    in->elements = h->s.n_elements;
    in->vertices = h->s.n_vertices;
    in->entries = h->has_rows ? h->rows.start[h->s.n_patches] : 0;
    in->fingerprint = fingerprint(h);
}

void sc_set_memory_limit(sc_solver *h, double bytes)
{
    h->mem_limit = bytes > 0 ? bytes : 0;
}

/* The memory limit in bytes: the one set, else fio_memory_budget (half the physical
 * memory). */
static double memory_limit(const struct sc_solver *h)
{
    return h->mem_limit > 0 ? h->mem_limit : fio_memory_budget();
}

/* Refuses (-1 with err) WHAT needing BYTES over the memory limit; the fix is named. */
static int within_memory(const struct sc_solver *h, double bytes, const char *what, const char *fix,
                         char *err, size_t errlen)
{
    double lim = memory_limit(h);
    if (bytes <= lim) return 0;
    snprintf(err, errlen, "%s may need up to %.3g MB, over the limit of %.3g MB%s: %s", what,
             bytes / 1e6, lim / 1e6,
             h->mem_limit > 0              ? ""
             : getenv("RAD_MEMORY_BUDGET") ? " (RAD_MEMORY_BUDGET)"
                                           : " (half the physical memory)",
             fix);
    return -1;
}

/* A sound bound: a row holds at most one entry per element and one per pixel of the
 * hemi-cube (3 res^2: the top face and four half sides), each an id and a code. */
static int rows_fit(const struct sc_solver *h, char *err, size_t errlen)
{
    const rad_scene_t *s = &h->s;
    double pixels = 3.0 * s->cfg.res * s->cfg.res,
           per_row = s->n_elements < pixels ? s->n_elements : pixels;
    double bytes = ((double)s->n_patches + 1.0) * sizeof *h->rows.start +
                   (double)s->n_patches * per_row * (sizeof *h->rows.ids + sizeof *h->rows.ffs);
    char what[96];
    snprintf(what, sizeof what, "the form factor rows (%u patches x up to %.0f entries)",
             s->n_patches, per_row);
    return within_memory(
        h, bytes, what,
        "lower the hemi-cube resolution (--res) or coarsen the mesh (--max-element, --max-patch)",
        err, errlen);
}

int sc_gauss_seidel_check(sc_solver *h, char *err, size_t errlen)
{
    uint32_t np = h->s.n_patches;
    if (np > 16384u) {
        snprintf(err, errlen,
                 "Gauss-Seidel takes at most 16384 patches, this scene has %u (raise the patch "
                 "size or shoot)",
                 np);
        return -1;
    }
    return within_memory(h, (double)RAD_GS_ENTRIES(np) * sizeof *h->gs, "the Gauss-Seidel matrix",
                         "raise the patch size (--max-patch) or shoot", err, errlen);
}

int sc_rows_compute(sc_solver *h, sc_rows_progress_fn progress, void *ctx, char *err, size_t errlen)
{
    rad_scene_t *s = &h->s;
    uint32_t np = s->n_patches, ne = s->n_elements;
    unsigned long calls0 = s->stats.raster_calls;
    /* First guess: each patch sees a quarter of the elements (a closed room: about
     * half); grown by doubling, rows already stored are kept. */
    uint64_t cap = (uint64_t)np * (ne / 4u + 1u);
    if (rows_fit(h, err, errlen) < 0) return -1;
    rows_free(h);
    if (cap > 0xFFFFFFFFu) cap = 0xFFFFFFFFu;
    h->rows.start = malloc(((size_t)np + 1u) * sizeof *h->rows.start);
    if (!h->rows.start || rows_reserve(h, (uint32_t)cap) < 0) {
        snprintf(err, errlen, "out of memory for the form factor rows");
        rows_free(h);
        return -1;
    }
    h->rows.max_rows = np;
    h->rows.n_rows = 0;
    for (;;) {
        int rc = rad_rows_compute(s, &h->rows, progress ? 1u : np);
        if (rc == 0) break;
        if (rc == RAD_ERR_FULL) {
            uint64_t more = 2u * (uint64_t)h->rows.max_entries;
            if (more < (uint64_t)h->rows.max_entries + ne)
                more = (uint64_t)h->rows.max_entries + ne;
            if (h->rows.max_entries == 0xFFFFFFFFu) {
                snprintf(
                    err, errlen,
                    "the form factor rows need more than 2^32 entries: raise the element size");
                rows_free(h);
                return -1;
            }
            if (more > 0xFFFFFFFFu) more = 0xFFFFFFFFu;
            if (rows_reserve(h, (uint32_t)more) < 0) {
                snprintf(err, errlen, "out of memory for %llu form factor entries",
                         (unsigned long long)more);
                rows_free(h);
                return -1;
            }
            continue;
        }
        if (rc < 0) {
            snprintf(err, errlen, "cannot compute the form factor rows: %s", rad_strerror(rc));
            rows_free(h);
            return -1;
        }
        if (progress && progress(ctx, (int)h->rows.n_rows, (int)np)) {
            snprintf(err, errlen, "stopped");
            rows_free(h);
            return -1;
        }
    }
    rows_reserve(h, h->rows.start[np]); /* shrink to fit (a failure keeps the larger) */
    h->has_rows = 1;
    h->rows_raster = s->stats.raster_calls - calls0;
    return 0;
}

int sc_rows_save(sc_solver *h, const char *path, char *err, size_t errlen)
{
    ff_file_info in;
    if (!h->has_rows) {
        snprintf(err, errlen, "%s: no form factor rows to save", path);
        return -1;
    }
    ff_info(h, &in);
    return ff_file_save(path, &in, h->rows.start, h->rows.ids, (unsigned)sizeof(rad_index_t),
                        h->rows.ffs, err, errlen);
}

int sc_rows_load(sc_solver *h, const char *path, char *err, size_t errlen)
{
    ff_file_t f;
    ff_file_info want;
    uint32_t np = h->s.n_patches;
    if (ff_file_load(path, &f, err, errlen) < 0) return -1;
    rows_free(h);
    ff_info(h, &want);
    if (ff_file_match(&f, &want, path, err, errlen) < 0) {
        ff_file_free(&f);
        return -1;
    }
    h->rows.start = malloc(((size_t)np + 1u) * sizeof *h->rows.start);
    if (!h->rows.start || rows_reserve(h, f.info.entries) < 0) {
        snprintf(err, errlen, "%s: out of memory for %u form factor entries", path, f.info.entries);
        rows_free(h);
        ff_file_free(&f);
        return -1;
    }
    ff_file_rows(&f, h->rows.start, h->rows.ids, (unsigned)sizeof(rad_index_t), h->rows.ffs);
    ff_file_free(&f);
    h->rows.max_rows = np;
    h->rows.n_rows = np;
    h->has_rows = 1;
    h->rows_raster = 0;
    return 0;
}

void sc_get_rows_stats(sc_solver *h, sc_rows_stats *st)
{
    memset(st, 0, sizeof *st);
    if (!h->has_rows) return;
    st->rows = (int)h->rows.n_rows;
    st->entries = h->rows.start[h->rows.n_rows];
    st->bytes = ((size_t)h->rows.n_rows + 1u) * sizeof *h->rows.start +
                (size_t)st->entries * (sizeof *h->rows.ids + sizeof *h->rows.ffs);
    st->matrix_bytes = h->gs_entries * sizeof *h->gs;
    st->raster_calls = h->rows_raster;
}

int sc_rows_solve(sc_solver *h, int max_shots, double tol, sc_progress_fn progress, void *ctx)
{
    int done = 0;
    rad_real_t t = RAD_REAL(tol);
    if (!h->has_rows) return -1;
    sc__unmix(h);
    sc_solve_started(h, tol);
    while (done < max_shots) {
        int k = rad_rows_shoot(&h->s, &h->rows, progress ? 16u : (uint32_t)(max_shots - done), t);
        if (k <= 0) break;
        done += k;
        if (progress && progress(ctx, done, RAD_TO_DOUBLE(rad_unshot_fraction(&h->s)))) break;
    }
    return done;
}

int sc_rows_gauss_seidel(sc_solver *h, int max_iter, double tol, char *err, size_t errlen)
{
    uint32_t np = h->s.n_patches;
    size_t need = RAD_GS_ENTRIES(np);
    int rc;
    if (!h->has_rows) {
        snprintf(err, errlen, "Gauss-Seidel needs the form factor rows");
        return -1;
    }
    if (sc_gauss_seidel_check(h, err, errlen) < 0) return -1;
    if (h->gs_entries < need) {
        free(h->gs);
        h->gs = malloc(need * sizeof *h->gs);
        h->gs_entries = h->gs ? need : 0;
        if (!h->gs) {
            snprintf(err, errlen, "out of memory for the %u x %u Gauss-Seidel matrix", np, np);
            return -1;
        }
    }
    sc__unmix(h); /* Gauss-Seidel starts from the emission */
    rc = rad_rows_gauss_seidel(&h->s, &h->rows, h->gs, h->gs_entries,
                               (uint32_t)(max_iter > 0 ? max_iter : 1), RAD_REAL(tol));
    if (rc < 0) {
        snprintf(err, errlen, "Gauss-Seidel: %s", rad_strerror(rc));
        return -1;
    }
    h->solve_kind = rc < (max_iter > 0 ? max_iter : 1) ? 2 : 3;
    h->tol = tol;
    return rc;
}
