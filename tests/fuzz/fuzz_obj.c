/* SPDX-License-Identifier: MIT */
/* libFuzzer harness: the OBJ/MTL loader (tools/formats/obj.c) on arbitrary bytes.
 *
 * Input: OBJ text, optionally followed by a line "%%MTL" and MTL text. The MTL part is
 * written to m.mtl in a private temporary directory that is the loader's base directory,
 * so "mtllib m.mtl" in the OBJ part reaches the MTL parser. Inputs whose OBJ part names
 * a library outside that directory through a special file (dev, proc, sys) are skipped:
 * reading /dev/zero would only measure the machine's memory (see the report on mtllib).
 *
 * Checked: obj_parse never crashes; on success every face is well formed (count >= 3,
 * indices resolved into verts, a valid material), every material has a name and the
 * per-material face counts add up; on failure the scene is empty and the message is one
 * line "NAME:LINE: text". obj_triangulate returns count-2 triangles whose indices are the
 * face's own, or -1; obj_face_area is >= 0 or NaN-free for finite input.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <math.h>

#include "formats/obj.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(c)                                                                             \
    do {                                                                                     \
        if (!(c)) {                                                                          \
            fprintf(stderr, "fuzz_obj: check failed: %s (%s:%d)\n", #c, __FILE__, __LINE__); \
            abort();                                                                         \
        }                                                                                    \
    } while (0)

static char dir[64];
static char mtlpath[96];

static void on_warning(void *ctx, const char *msg)
{
    long *n = ctx;
    CHECK(msg && *msg && !strchr(msg, '\n'));
    (*n)++;
}

static const void *find(const void *hay, size_t n, const char *needle)
{
    size_t k = strlen(needle), i;
    const char *h = hay;
    for (i = 0; k <= n && i <= n - k; i++)
        if (memcmp(h + i, needle, k) == 0) return h + i;
    return NULL;
}

static void check_scene(const obj_scene *sc, long warnings)
{
    int i, k, faces = 0;
    CHECK(sc->nverts >= 0 && sc->nindices >= 0 && sc->nfaces >= 0 && sc->nmaterials >= 0);
    CHECK(sc->nwarnings == warnings);
    for (i = 0; i < sc->nverts; i++)
        CHECK(fabs(sc->verts[i].x) <= 1e30 && fabs(sc->verts[i].y) <= 1e30 &&
              fabs(sc->verts[i].z) <= 1e30);
    for (i = 0; i < sc->nmaterials; i++) {
        CHECK(sc->materials[i].name != NULL);
        CHECK(obj_find_material(sc, sc->materials[i].name) == i);
        for (k = 0; k < 3; k++) CHECK(sc->materials[i].kd[k] >= 0 && sc->materials[i].ke[k] >= 0);
        faces += sc->materials[i].nfaces;
    }
    CHECK(faces == sc->nfaces);
    for (i = 0; i < sc->nfaces; i++) {
        const obj_face *f = &sc->faces[i];
        int *tri, nt;
        double a;
        CHECK(f->count >= 3 && f->first >= 0 && f->first <= sc->nindices - f->count);
        CHECK(f->material >= 0 && f->material < sc->nmaterials);
        CHECK(f->line >= 1);
        for (k = 0; k < f->count; k++)
            CHECK(sc->indices[f->first + k] >= 0 && sc->indices[f->first + k] < sc->nverts);
        a = obj_face_area(sc, f);
        CHECK(!(a < 0));
        /* Ear clipping is cubic in the worst case: the loader's files keep faces small,
         * and a fuzz input of a few kB cannot hold more than about a thousand corners. */
        tri = malloc((size_t)(f->count - 2) * 3 * sizeof *tri);
        CHECK(tri != NULL);
        nt = obj_triangulate(sc, f, tri);
        CHECK(nt == -1 || nt == f->count - 2);
        for (k = 0; k < 3 * nt; k++) {
            int j, own = 0;
            for (j = 0; j < f->count && !own; j++) own = sc->indices[f->first + j] == tri[k];
            CHECK(own);
        }
        free(tri);
    }
}

static int make_dir(void)
{
    if (dir[0]) return 0;
    snprintf(dir, sizeof dir, "/tmp/rad_fuzz_obj.XXXXXX");
    if (!mkdtemp(dir)) return -1;
    snprintf(mtlpath, sizeof mtlpath, "%s/m.mtl", dir);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *mtl = find(data, size, "\n%%MTL\n");
    size_t objlen = mtl ? (size_t)(mtl - data) + 1 : size;
    obj_scene sc;
    char err[256];
    long warnings = 0;
    int rc;

    if (make_dir() < 0) abort();
    if (find(data, objlen, "mtllib") &&
        (find(data, objlen, "dev") || find(data, objlen, "proc") || find(data, objlen, "sys")))
        return 0;
    {
        FILE *f = fopen(mtlpath, "wb");
        CHECK(f != NULL);
        if (mtl) fwrite(mtl + 7, 1, size - objlen - 6, f);
        CHECK(fclose(f) == 0);
    }
    memset(err, 'x', sizeof err);
    rc = obj_parse((const char *)data, objlen, "fuzz.obj", dir, &sc, on_warning, &warnings, err,
                   sizeof err);
    CHECK(memchr(err, '\0', sizeof err) != NULL);
    if (rc == 0) {
        CHECK(err[0] == '\0');
        check_scene(&sc, warnings);
    } else {
        CHECK(rc == -1);
        CHECK(err[0] != '\0' && !strchr(err, '\n'));
        CHECK(sc.nverts == 0 && sc.nfaces == 0 && sc.nmaterials == 0 && sc.verts == NULL);
    }
    obj_free(&sc);
    /* Without a base directory mtllib is a warning, never a file access. */
    rc = obj_parse((const char *)data, objlen, NULL, NULL, &sc, NULL, NULL, NULL, 0);
    CHECK(rc == 0 || rc == -1);
    obj_free(&sc);
    return 0;
}
