/* SPDX-License-Identifier: MIT */
/* libFuzzer harness: the MTL map_Kd path and texture loading (tools/formats/obj.c's
 * map_Kd statement, tools/formats/texture.c) on arbitrary bytes.
 *
 * Input: MTL text, optionally followed by a line "%%TEX" and the bytes of t.png. Both
 * are written to a private temporary directory, with a fixed OBJ (one textured
 * triangle, "mtllib m.mtl") that obj_load reads from there, so map_Kd names resolve
 * against it. Inputs naming a special file tree (dev, proc, sys) or a parent folder
 * are skipped: the harness reads only its own files.
 *
 * Checked: obj_load never crashes and on failure leaves one line; tex_load_materials
 * never crashes, each warning is one line, a loaded texture is 1..TEX_MAX_PIXELS texels
 * with pixels, a material whose map_Kd failed keeps a Kd that is not all zero, and the
 * mean of every loaded texture over a triangle, and a sample, are finite values in
 * [0, 1]. tex_decode on the raw bytes agrees with the file load, and accepts only PNG,
 * JPEG, BMP and TGA. gltf_write exports the
 * scene with the loaded textures (material names from the MTL, escaped; images
 * embedded or left out with a warning): it succeeds, and the file starts with the GLB
 * header and its declared length is the file's.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "formats/gltf.h"
#include "formats/obj.h"
#include "formats/texture.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(c)                                                                          \
    do {                                                                                  \
        if (!(c)) {                                                                       \
            fprintf(stderr, "fuzz_mtl_texture: check failed: %s (%s:%d)\n", #c, __FILE__, \
                    __LINE__);                                                            \
            abort();                                                                      \
        }                                                                                 \
    } while (0)

static char dir[64];

static const char obj_text[] = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                               "vt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n";

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

static void put_file(const char *name, const void *bytes, size_t n)
{
    char path[128];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    f = fopen(path, "wb");
    CHECK(f != NULL);
    if (n) CHECK(fwrite(bytes, 1, n, f) == n);
    CHECK(fclose(f) == 0);
}

static void check_in_unit(const double *v)
{
    int k;
    for (k = 0; k < 3; k++)
        CHECK(v[k] >= 0 && v[k] <= 1 + 1e-12); /* weights summing to 1 in rounding */
}

static void check_map(const obj_material *m, const tex_image *t)
{
    static const obj_vec2 tri[3] = {{0, 0}, {1, 0}, {0, 1}};
    double v[3];
    if (!t->rgb) {
        CHECK(t->w == 0 && t->h == 0);
        if (m->map_kd.line) CHECK(m->kd[0] != 0 || m->kd[1] != 0 || m->kd[2] != 0);
        return;
    }
    CHECK(m->map_kd.path != NULL);
    CHECK(t->w >= 1 && t->h >= 1 && (long)t->w * t->h <= TEX_MAX_PIXELS);
    tex_triangle_mean(t, tri, v);
    check_in_unit(v);
    tex_sample(t, 0.3, -7.25, v);
    check_in_unit(v);
}

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void check_export(const obj_scene *sc, const tex_image *maps, long *warnings)
{
    const char **tex = calloc((size_t)sc->nmaterials + 1, sizeof *tex);
    char path[128], err[256];
    unsigned char head[12];
    gltf_input in;
    FILE *f;
    long len;
    int i;
    CHECK(tex != NULL);
    for (i = 0; i < sc->nmaterials; i++) tex[i] = maps[i].rgb ? sc->materials[i].map_kd.path : NULL;
    memset(&in, 0, sizeof in);
    in.sc = sc;
    in.texture = tex;
    in.warn = on_warning;
    in.ctx = warnings;
    snprintf(path, sizeof path, "%s/out.glb", dir);
    CHECK(gltf_write(path, &in, err, sizeof err) == 0);
    f = fopen(path, "rb");
    CHECK(f != NULL);
    CHECK(fread(head, 1, 12, f) == 12);
    fseek(f, 0, SEEK_END);
    len = ftell(f);
    fclose(f);
    CHECK(le32(head) == 0x46546C67u && le32(head + 4) == 2 && (long)le32(head + 8) == len);
    CHECK(len % 4 == 0);
    free((void *)tex);
}

/* The texture bytes decoded straight from memory: accepted exactly when the file was. */
static void check_decode(const uint8_t *tex, size_t n, int loaded_ok)
{
    tex_image t;
    char err[256];
    int rc = tex_decode(tex, n, "t.png", &t, err, sizeof err);
    CHECK(rc == 0 || rc == -1);
    if (loaded_ok >= 0) CHECK((rc == 0) == (loaded_ok == 1));
    if (rc)
        CHECK(t.rgb == NULL && strchr(err, '\n') == NULL && err[0]);
    else /* only PNG, JPEG, BMP and TGA (byte 1, its colour map type, 0 or 1) reach stb */
        CHECK((n >= 8 && !memcmp(tex, "\x89PNG", 4)) ||
              (n >= 3 && tex[0] == 0xff && tex[1] == 0xd8) ||
              (n >= 2 && tex[0] == 'B' && tex[1] == 'M') || (n >= 18 && tex[1] <= 1));
    tex_free(&t);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *tex = find(data, size, "\n%%TEX\n");
    size_t mtllen = tex ? (size_t)(tex - data) + 1 : size, texlen = 0;
    obj_scene sc;
    tex_image *maps;
    char err[256], objpath[96];
    long warnings = 0;
    int i, direct = -1;

    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/rad_fuzz_tex.XXXXXX");
        CHECK(mkdtemp(dir) != NULL);
    }
    if (find(data, mtllen, "dev") || find(data, mtllen, "proc") || find(data, mtllen, "sys") ||
        find(data, mtllen, ".."))
        return 0;
    if (tex) {
        tex += 7;
        texlen = size - (size_t)(tex - data);
    }
    put_file("m.mtl", data, mtllen);
    put_file("t.png", tex ? (const void *)tex : "", texlen);
    put_file("s.obj", obj_text, sizeof obj_text - 1);
    snprintf(objpath, sizeof objpath, "%s/s.obj", dir);
    memset(err, 'x', sizeof err);
    if (obj_load(objpath, &sc, on_warning, &warnings, err, sizeof err)) {
        CHECK(err[0] && memchr(err, '\0', sizeof err) && !strchr(err, '\n'));
        check_decode(tex ? tex : (const uint8_t *)"", texlen, -1);
        return 0;
    }
    maps = calloc((size_t)sc.nmaterials + 1, sizeof *maps);
    CHECK(maps != NULL);
    tex_load_materials(&sc, maps, on_warning, &warnings, 1);
    CHECK(sc.nwarnings == warnings);
    check_export(&sc, maps, &warnings);
    for (i = 0; i < sc.nmaterials; i++) {
        const obj_material *m = &sc.materials[i];
        char want[128];
        check_map(m, &maps[i]);
        snprintf(want, sizeof want, "%s/t.png", dir);
        if (m->map_kd.path && !strcmp(m->map_kd.path, want)) direct = maps[i].rgb != NULL;
    }
    for (i = 0; i < sc.nmaterials; i++) /* after every use: maps may borrow earlier ones */
        tex_free(&maps[i]);
    check_decode(tex ? tex : (const uint8_t *)"", texlen, direct);
    free(maps);
    obj_free(&sc);
    return 0;
}
