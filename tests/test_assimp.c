/* SPDX-License-Identifier: MIT */
/* Scenes in other formats through assimp (tools/formats/assimp_scene.c).
 *
 * The test writes one room twice: as a glTF 2.0 file (.gltf, its buffer a data URI)
 * whose meshes sit under nodes with translations, a scale and a mirror, and as the OBJ
 * of the same faces with every transform applied by hand. The coordinates are
 * multiples of 1/8 below 16, exact in glTF's float32 and in every transform's double
 * products, so the two loaders must give the same faces and the same solve to the bit:
 * the same element count and every element's radiosity equal. The mirrored node
 * (scale -1 on x) must come out wound as the OBJ writes it, front side where the file
 * put it. COLLADA and 3DS files written by assimp's own exporter from the OBJ
 * (assimp-utils; skipped without it) load to the same area per material. A truncated
 * file, a file with no meshes and a FIFO are refused with one line naming the file.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "formats/assimp_scene.h"
#include "formats/file_io.h"
#include "formats/image.h"
#include "formats/obj.h"
#include "formats/texture.h"
#include "host/obj_polys.h"
#include "host/scene.h"
#include "tmpdir.h"

TMPDIR_GROUP("assimp")

/* ---- the room ---------------------------------------------------------------------- */

/* A mesh of a node: triangles on local vertices, one material. */
typedef struct {
    const char *node;
    double t[3], s[3];   /* the node's translation and scale (no rotation) */
    int material;        /* 0 wall, 1 lamp, 2 block */
    int nv, nt;
    float v[8][3];
    unsigned short tri[12][3];
} part_t;

static const char *const mat_names[3] = {"wall", "lamp", "block"};
static const double mat_kd[3][3] = {{0.75, 0.5, 0.25}, {0, 0, 0}, {0.5, 0.5, 0.5}};
static const double mat_ke[3][3] = {{0, 0, 0}, {1, 0.75, 0.5}, {0, 0, 0}};

/* The floor and ceiling and two walls of a 4 x 3 x 4 room (a box open on two sides),
 * a lamp under the ceiling (a unit square scaled to 1 x 1 and moved up), and a block
 * mirrored on x (its faces wound so that, mirrored, they face out). */
static const part_t parts[3] = {
    {"room", {0, 0, 0}, {1, 1, 1}, 0, 8, 8,
     {{-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 0, 2}, {-2, 3, -2}, {2, 3, -2}, {2, 3, 2}, {-2, 3, 2}},
     {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4}, {0, 4, 7}, {0, 7, 3}}},
    {"lamp", {0.5, 2.875, 0.25}, {2, 1, 2}, 1, 4, 2,
     {{-0.25, 0, -0.25}, {0.25, 0, -0.25}, {0.25, 0, 0.25}, {-0.25, 0, 0.25}},
     {{0, 1, 2}, {0, 2, 3}}},
    {"block", {-0.5, 0, 0.5}, {-1, 1, 1}, 2, 8, 10,
     {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}},
     /* outward as written; the mirror turns them inward and the loader back out */
     {{4, 6, 5}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6},
      {3, 0, 4}, {3, 4, 7}}},
};

static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static void put_b64(FILE *f, const unsigned char *d, size_t n)
{
    size_t i;
    for (i = 0; i < n; i += 3) {
        unsigned v = (unsigned)d[i] << 16 | (i + 1 < n ? (unsigned)d[i + 1] << 8 : 0) |
                     (i + 2 < n ? d[i + 2] : 0);
        fputc(b64[v >> 18 & 63], f);
        fputc(b64[v >> 12 & 63], f);
        fputc(i + 1 < n ? b64[v >> 6 & 63] : '=', f);
        fputc(i + 2 < n ? b64[v & 63] : '=', f);
    }
}

/* The glTF: one buffer (per part: positions, then indices padded to 4 bytes), a
 * scene whose root node "house" holds the room and, under a node moved by (0, 0, 0)
 * with no scale, the lamp and the block. The buffer is a data URI, or with BIN the
 * file BIN (a path) named by URI. */
static void write_gltf_bin(const char *path, const char *bin, const char *uri)
{
    unsigned char buf[4096];
    size_t off[3][2], len = 0;
    FILE *f = fopen(path, "w");
    int i, k;
    assert_non_null(f);
    for (i = 0; i < 3; i++) {
        off[i][0] = len;
        memcpy(buf + len, parts[i].v, (size_t)parts[i].nv * 12);
        len += (size_t)parts[i].nv * 12;
        off[i][1] = len;
        memcpy(buf + len, parts[i].tri, (size_t)parts[i].nt * 6);
        len += ((size_t)parts[i].nt * 6 + 3) & ~(size_t)3;
    }
    fprintf(f, "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\n");
    fprintf(f, "\"nodes\":[{\"name\":\"house\",\"mesh\":0,\"children\":[1]},"
               "{\"name\":\"props\",\"translation\":[0,0,0],\"children\":[2,3]}");
    for (i = 1; i < 3; i++)
        fprintf(f, ",{\"name\":\"%s\",\"mesh\":%d,\"translation\":[%g,%g,%g],\"scale\":[%g,%g,%g]}",
                parts[i].node, i, parts[i].t[0], parts[i].t[1], parts[i].t[2], parts[i].s[0],
                parts[i].s[1], parts[i].s[2]);
    fprintf(f, "],\n\"meshes\":[");
    for (i = 0; i < 3; i++)
        fprintf(f, "%s{\"primitives\":[{\"attributes\":{\"POSITION\":%d},\"indices\":%d,"
                   "\"material\":%d}]}",
                i ? "," : "", 2 * i, 2 * i + 1, parts[i].material);
    fprintf(f, "],\n\"materials\":[");
    for (i = 0; i < 3; i++)
        fprintf(f, "%s{\"name\":\"%s\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[%g,%g,%g,1],"
                   "\"metallicFactor\":0},\"emissiveFactor\":[%g,%g,%g]}",
                i ? "," : "", mat_names[i], mat_kd[i][0], mat_kd[i][1], mat_kd[i][2],
                mat_ke[i][0], mat_ke[i][1], mat_ke[i][2]);
    fprintf(f, "],\n\"accessors\":[");
    for (i = 0; i < 3; i++) {
        float lo[3] = {1e9f, 1e9f, 1e9f}, hi[3] = {-1e9f, -1e9f, -1e9f};
        int v;
        for (v = 0; v < parts[i].nv; v++)
            for (k = 0; k < 3; k++) {
                lo[k] = fminf(lo[k], parts[i].v[v][k]);
                hi[k] = fmaxf(hi[k], parts[i].v[v][k]);
            }
        fprintf(f, "%s{\"bufferView\":%d,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\","
                   "\"min\":[%g,%g,%g],\"max\":[%g,%g,%g]},"
                   "{\"bufferView\":%d,\"componentType\":5123,\"count\":%d,\"type\":\"SCALAR\"}",
                i ? "," : "", 2 * i, parts[i].nv, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2],
                2 * i + 1, 3 * parts[i].nt);
    }
    fprintf(f, "],\n\"bufferViews\":[");
    for (i = 0; i < 3; i++)
        fprintf(f, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%d},"
                   "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%d}",
                i ? "," : "", off[i][0], parts[i].nv * 12, off[i][1], parts[i].nt * 6);
    fprintf(f, "],\n\"buffers\":[{\"byteLength\":%zu,\"uri\":\"", len);
    if (bin) {
        FILE *b = fopen(bin, "wb");
        assert_non_null(b);
        assert_int_equal(fwrite(buf, 1, len, b), len);
        assert_int_equal(fclose(b), 0);
        fputs(uri, f);
    } else {
        fputs("data:application/octet-stream;base64,", f);
        put_b64(f, buf, len);
    }
    fprintf(f, "\"}]}\n");
    assert_int_equal(fclose(f), 0);
}

static void write_gltf(const char *path)
{
    write_gltf_bin(path, NULL, NULL);
}

/* The same faces as an OBJ, each vertex moved by its node's scale then translation, a
 * mirrored part's triangles written in reverse order (as the loader must turn them). */
static void write_obj(const char *path, const char *mtl)
{
    FILE *f = fopen(path, "w"), *m = fopen(mtl, "w");
    int i, v, t, base = 1;
    assert_non_null(f);
    assert_non_null(m);
    for (i = 0; i < 3; i++)
        fprintf(m, "newmtl %s\nKd %g %g %g\nKe %g %g %g\n", mat_names[i], mat_kd[i][0],
                mat_kd[i][1], mat_kd[i][2], mat_ke[i][0], mat_ke[i][1], mat_ke[i][2]);
    fprintf(f, "mtllib %s\n", strrchr(mtl, '/') + 1);
    for (i = 0; i < 3; i++) {
        const part_t *p = &parts[i];
        const int mirror = p->s[0] * p->s[1] * p->s[2] < 0;
        fprintf(f, "o %s\nusemtl %s\n", p->node, mat_names[p->material]);
        for (v = 0; v < p->nv; v++)
            fprintf(f, "v %.17g %.17g %.17g\n", p->v[v][0] * p->s[0] + p->t[0],
                    p->v[v][1] * p->s[1] + p->t[1], p->v[v][2] * p->s[2] + p->t[2]);
        for (t = 0; t < p->nt; t++) {
            const unsigned short *q = p->tri[t];
            if (mirror)
                fprintf(f, "f %d %d %d\n", base + q[2], base + q[1], base + q[0]);
            else
                fprintf(f, "f %d %d %d\n", base + q[0], base + q[1], base + q[2]);
        }
        base += p->nv;
    }
    assert_int_equal(fclose(f), 0);
    assert_int_equal(fclose(m), 0);
}

static sc_solver *solve(const obj_scene *sc, int *n_elements)
{
    sc_opts o;
    sc_stats st;
    char err[512];
    int n;
    sc_poly *p = obj_to_polys(sc, &n, NULL, NULL);
    sc_solver *h;
    assert_non_null(p);
    memset(&o, 0, sizeof o);
    o.res = 32;
    o.max_element = 0.5;
    h = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    free(p);
    if (!h) fail_msg("sc_create: %s", err);
    CHECK_INT_GT(sc_solve(h, 100000, 0.01, NULL, NULL), 0, "shots of the room's solve");
    sc_get_stats(h, &st);
    *n_elements = st.elements;
    return h;
}

/* The glTF and the OBJ of one room: the same materials, faces, element count and, to
 * the bit, the same radiosity on every element. */
static void test_gltf_matches_obj(void **state)
{
    obj_scene a, b;
    char err[512];
    int i, k, ea, eb, differ = 0;
    sc_solver *ha, *hb;
    (void)state;
    if (!assimp_scene_available()) {
        print_message("rad built without assimp (libassimp-dev): skipped\n");
        skip();
    }
    write_gltf(tmp_path("room.gltf"));
    write_obj(tmp_path("room.obj"), tmp_path("room.mtl"));
    if (assimp_scene_load(tmp_path("room.gltf"), NULL, &a, NULL, NULL, err, sizeof err) < 0)
        fail_msg("%s", err);
    if (obj_load(tmp_path("room.obj"), &b, NULL, NULL, err, sizeof err) < 0) fail_msg("%s", err);
    CHECK_INT_EQ(a.nfaces, b.nfaces, "faces of the glTF against the OBJ");
    CHECK_INT_EQ(a.nmaterials, 3, "materials of the glTF");
    for (i = 0; i < 3; i++) {
        int j = obj_find_material(&a, mat_names[i]);
        CHECK_INT_GE(j, 0, "glTF material %s found", mat_names[i]);
        for (k = 0; k < 3; k++) {
            CHECK_NEAR(a.materials[j].kd[k], mat_kd[i][k], 1e-7, "%s Kd[%d]", mat_names[i], k);
            CHECK_NEAR(a.materials[j].ke[k], mat_ke[i][k], 1e-7, "%s Ke[%d]", mat_names[i], k);
        }
        CHECK_NEAR(a.materials[j].area, b.materials[obj_find_material(&b, mat_names[i])].area,
                   1e-9, "area of %s", mat_names[i]);
    }
    for (i = 0; i < a.nfaces; i++) {
        obj_vec3 na = obj_face_normal(&a, &a.faces[i]), nb = obj_face_normal(&b, &b.faces[i]);
        CHECK_NEAR(na.x * nb.x + na.y * nb.y + na.z * nb.z,
                   sqrt(na.x * na.x + na.y * na.y + na.z * na.z) *
                       sqrt(nb.x * nb.x + nb.y * nb.y + nb.z * nb.z),
                   1e-9, "face %d (node %s) faces the OBJ's way", i,
                   a.faces[i].object >= 0 ? a.names[a.faces[i].object] : "?");
    }
    ha = solve(&a, &ea);
    hb = solve(&b, &eb);
    print_message("glTF %d faces, %d elements; OBJ %d faces, %d elements\n", a.nfaces, ea,
                  b.nfaces, eb);
    CHECK_INT_EQ(ea, eb, "elements of the glTF's solve against the OBJ's");
    for (i = 0; i < ea; i++) {
        double ra[3], rb[3];
        sc_element_rgb(ha, i, 1, ra);
        sc_element_rgb(hb, i, 1, rb);
        for (k = 0; k < 3; k++) differ += ra[k] != rb[k];
    }
    CHECK_INT_EQ(differ, 0, "element channels whose radiosity differs between the two");
    sc_destroy(ha);
    sc_destroy(hb);
    obj_free(&a);
    obj_free(&b);
}

/* assimp's own exporter (assimp-utils) writes the OBJ as COLLADA and 3DS: each loads
 * with the OBJ's area per material (3DS keeps 32-bit floats: 1e-6 of the room's 48). */
static void test_exported_formats(void **state)
{
    static const char *const ext[] = {"dae", "3ds"};
    unsigned e;
    (void)state;
    if (!assimp_scene_available() || system("command -v assimp >/dev/null 2>&1") != 0) {
        print_message("assimp or assimp-utils missing: skipped\n");
        skip();
    }
    write_obj(tmp_path("x.obj"), tmp_path("x.mtl"));
    for (e = 0; e < 2; e++) {
        char cmd[1024], out[64], err[512];
        obj_scene a, b;
        int i;
        snprintf(out, sizeof out, "x.%s", ext[e]);
        snprintf(cmd, sizeof cmd, "assimp export '%s' '%s' >/dev/null 2>&1", tmp_path("x.obj"),
                 tmp_path(out));
        CHECK_INT_EQ(system(cmd), 0, "assimp export to .%s", ext[e]);
        if (assimp_scene_load(tmp_path(out), NULL, &a, NULL, NULL, err, sizeof err) < 0)
            fail_msg("%s", err);
        assert_int_equal(obj_load(tmp_path("x.obj"), &b, NULL, NULL, err, sizeof err), 0);
        for (i = 0; i < 3; i++) {
            int ja = obj_find_material(&a, mat_names[i]), jb = obj_find_material(&b, mat_names[i]);
            double area = 0;
            int f;
            /* 3DS names materials as it likes: sum by the faces' Kd instead */
            for (f = 0; f < a.nfaces; f++) {
                const double *kd = a.materials[a.faces[f].material].kd;
                if (fabs(kd[0] - mat_kd[i][0]) < 1e-6 && fabs(kd[1] - mat_kd[i][1]) < 1e-6 &&
                    fabs(kd[2] - mat_kd[i][2]) < 1e-6)
                    area += obj_face_area(&a, &a.faces[f]);
            }
            print_message(".%s: material %s (%d) area %.9g, the OBJ's %.9g\n", ext[e],
                          mat_names[i], ja, area, b.materials[jb].area);
            CHECK_NEAR(area, b.materials[jb].area, 1e-6 * 48, ".%s area of Kd %s", ext[e],
                       mat_names[i]);
        }
        obj_free(&a);
        obj_free(&b);
    }
}

static void expect_refused(const char *path, const char *part)
{
    obj_scene sc;
    char err[512];
    int rc = assimp_scene_load(path, NULL, &sc, NULL, NULL, err, sizeof err);
    print_message("%s: %d \"%s\"\n", path, rc, rc < 0 ? err : "");
    CHECK_INT_EQ(rc, -1, "assimp_scene_load of a bad file");
    CHECK_CONTAINS(err, path, "the error names the file");
    CHECK_CONTAINS(err, part, "the error says what is wrong");
    CHECK_LACKS(err, "\n", "the error is one line");
    CHECK_INT_EQ(sc.nfaces, 0, "faces left in the scene");
}

/* Bad input: one line naming the file, nothing loaded. */
static void test_bad_files(void **state)
{
    FILE *f;
    char *text;
    long n;
    (void)state;
    if (!assimp_scene_available()) {
        expect_refused(tmp_path("none.gltf"), "libassimp-dev");
        return;
    }
    write_gltf(tmp_path("whole.gltf"));
    f = fopen(tmp_path("whole.gltf"), "r");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    rewind(f);
    text = malloc((size_t)n);
    assert_non_null(text);
    assert_int_equal(fread(text, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    f = fopen(tmp_path("cut.gltf"), "w");
    fwrite(text, 1, (size_t)n / 2, f);
    fclose(f);
    free(text);
    expect_refused(tmp_path("cut.gltf"), "");
    f = fopen(tmp_path("empty.gltf"), "w");
    fputs("{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[]}],\"scene\":0}\n", f);
    fclose(f);
    expect_refused(tmp_path("empty.gltf"), "");
    expect_refused(tmp_path("missing.glb"), "No such file");
    assert_int_equal(mkfifo(tmp_path("fifo.glb"), 0600), 0);
    expect_refused(tmp_path("fifo.glb"), "");
}

/* A buffer outside the scene's folder (../room.bin) is refused unless allowed, as the
 * OBJ reader refuses an outside mtllib; beside the scene it loads. */
static void test_outside_paths(void **state)
{
    obj_scene sc;
    obj_opts allow = {1};
    char err[1024];
    (void)state;
    if (!assimp_scene_available()) skip();
    assert_int_equal(mkdir(tmp_path("in"), 0700), 0);
    write_gltf_bin(tmp_path("in/out.gltf"), tmp_path("room.bin"), "../room.bin");
    expect_refused(tmp_path("in/out.gltf"), "outside the scene's folder");
    if (assimp_scene_load(tmp_path("in/out.gltf"), &allow, &sc, NULL, NULL, err, sizeof err) < 0)
        fail_msg("with allow_outside: %s", err);
    CHECK_INT_EQ(sc.nfaces, 20, "faces of the room read through ../room.bin when allowed");
    obj_free(&sc);
    write_gltf_bin(tmp_path("in/in.gltf"), tmp_path("in/room.bin"), "room.bin");
    if (assimp_scene_load(tmp_path("in/in.gltf"), NULL, &sc, NULL, NULL, err, sizeof err) < 0)
        fail_msg("buffer beside the scene: %s", err);
    CHECK_INT_EQ(sc.nfaces, 20, "faces of the room read through room.bin beside it");
    obj_free(&sc);
}

/* glTF's KHR_lights_punctual: a point light moved by its node, a spot and a sun turned
 * by theirs to point down (a quarter turn about x takes the light's -z to -y), colour
 * times intensity, the spot's half angles as given. */
static void test_gltf_lights(void **state)
{
    static const char text[] =
        "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_lights_punctual\"],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
        "{\"type\":\"point\",\"color\":[1,0.5,0.25],\"intensity\":5},"
        "{\"type\":\"spot\",\"intensity\":7,\"spot\":{\"innerConeAngle\":0.3,\"outerConeAngle\":0.6}},"
        "{\"type\":\"directional\",\"intensity\":3}]}},"
        "\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2,3]}],\"nodes\":["
        "{\"name\":\"bulb\",\"translation\":[1,2,3],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
        "{\"name\":\"lamp\",\"translation\":[0,2,0],\"rotation\":[-0.70710678,0,0,0.70710678],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
        "{\"name\":\"sun\",\"rotation\":[-0.70710678,0,0,0.70710678],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}},{\"name\":\"m\",\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
        "\"min\":[0,0,0],\"max\":[1,1,0]}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,"
        "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}]}";
    static const struct {
        int type;
        double pos[3], dir[3], rgb[3], cos_outer, cos_inner;
    } want[3] = {{OBJ_LIGHT_POINT, {1, 2, 3}, {0, 0, -1}, {5, 2.5, 1.25}, 0, 0},
                 {OBJ_LIGHT_SPOT, {0, 2, 0}, {0, -1, 0}, {7, 7, 7}, 0.82533561, 0.95533649},
                 {OBJ_LIGHT_SUN, {0, 0, 0}, {0, -1, 0}, {3, 3, 3}, 0, 0}};
    obj_scene sc;
    char err[512];
    FILE *f;
    int i, k;
    (void)state;
    if (!assimp_scene_available()) skip();
    f = fopen(tmp_path("lights.gltf"), "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
    if (assimp_scene_load(tmp_path("lights.gltf"), NULL, &sc, NULL, NULL, err, sizeof err) < 0)
        fail_msg("%s", err);
    CHECK_INT_EQ(sc.nlights, 3, "lights read from KHR_lights_punctual");
    for (i = 0; i < 3; i++) {
        const obj_light *l = &sc.lights[i];
        print_message("light %d %s: type %d at %g %g %g toward %g %g %g, %g %g %g, cone %g %g\n", i,
                      l->name, l->type, l->pos[0], l->pos[1], l->pos[2], l->dir[0], l->dir[1],
                      l->dir[2], l->rgb[0], l->rgb[1], l->rgb[2], l->cos_outer, l->cos_inner);
        CHECK_INT_EQ(l->type, want[i].type, "light %d's type", i);
        for (k = 0; k < 3; k++) {
            /* float32 in the file, a rotation of 0.70710678: 1e-6 */
            CHECK_NEAR(l->pos[k], want[i].pos[k], 1e-6, "light %d position[%d]", i, k);
            if (l->type != OBJ_LIGHT_POINT)
                CHECK_NEAR(l->dir[k], want[i].dir[k], 1e-6, "light %d direction[%d]", i, k);
            CHECK_NEAR(l->rgb[k], want[i].rgb[k], 1e-6, "light %d colour x intensity[%d]", i, k);
        }
        if (l->type == OBJ_LIGHT_SPOT) {
            CHECK_NEAR(l->cos_outer, want[i].cos_outer, 1e-6, "spot's cos(outer half angle 0.6)");
            CHECK_NEAR(l->cos_inner, want[i].cos_inner, 1e-6, "spot's cos(inner half angle 0.3)");
        }
    }
    obj_free(&sc);
}

/* 1 if the N bytes at D hold the text PART. */
static int holds(const char *d, size_t n, const char *part)
{
    size_t i, m = strlen(part);
    for (i = 0; i + m <= n; i++)
        if (!memcmp(d + i, part, m)) return 1;
    return 0;
}

/* A texture the glTF holds in its buffer (an image with a bufferView, as .glb files
 * carry them): read from there, decoded to the file's texels (a 4 x 2 image of eight
 * different colours, so a flip or a swap shows), and embedded again by --export-gltf
 * as a PNG although no file of that name exists. */
static void test_embedded_texture(void **state)
{
    static const unsigned char rgb[4 * 2 * 3] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 0,
                                                 0, 255, 255, 255, 0, 255, 128, 128, 128, 10, 20, 30};
    static const float pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    static const float uv[4][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    static const unsigned short idx[6] = {0, 1, 2, 0, 2, 3};
    unsigned char *png, buf[2048];
    size_t npng, len = 0;
    obj_scene sc;
    tex_image maps[1];
    char err[512], cmd[1024];
    FILE *f;
    int i;
    (void)state;
    if (!assimp_scene_available()) skip();
    assert_int_equal(img_encode_png(rgb, 4, 2, &png, &npng, err, sizeof err), 0);
    assert_true(npng + 120 < sizeof buf);
    memcpy(buf, pos, 48);
    memcpy(buf + 48, uv, 32);
    memcpy(buf + 80, idx, 12);
    memcpy(buf + 92, png, npng);
    len = 92 + npng;
    f = fopen(tmp_path("tex.gltf"), "w");
    assert_non_null(f);
    fprintf(f, "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
               "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
               "{\"POSITION\":0,\"TEXCOORD_0\":1},\"indices\":2,\"material\":0}]}],"
               "\"materials\":[{\"name\":\"tiles\",\"pbrMetallicRoughness\":{\"baseColorTexture\":"
               "{\"index\":0}}}],\"textures\":[{\"source\":0}],"
               "\"images\":[{\"bufferView\":3,\"mimeType\":\"image/png\"}],"
               "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
               "\"min\":[0,0,0],\"max\":[1,1,0]},{\"bufferView\":1,\"componentType\":5126,\"count\":4,"
               "\"type\":\"VEC2\"},{\"bufferView\":2,\"componentType\":5123,\"count\":6,"
               "\"type\":\"SCALAR\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},"
               "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":32},{\"buffer\":0,\"byteOffset\":80,"
               "\"byteLength\":12},{\"buffer\":0,\"byteOffset\":92,\"byteLength\":%zu}],"
               "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,",
            npng, len);
    put_b64(f, buf, len);
    fprintf(f, "\"}]}\n");
    assert_int_equal(fclose(f), 0);
    free(png);
    if (assimp_scene_load(tmp_path("tex.gltf"), NULL, &sc, NULL, NULL, err, sizeof err) < 0)
        fail_msg("%s", err);
    CHECK_INT_EQ(sc.nmaterials, 1, "materials");
    assert_non_null(sc.materials[0].map_kd.data);
    print_message("embedded map: %s, %zu bytes (the PNG's %zu)\n", sc.materials[0].map_kd.path,
                  sc.materials[0].map_kd.size, npng);
    CHECK_INT_EQ(sc.materials[0].map_kd.size, npng, "bytes of the embedded texture");
    CHECK_INT_EQ(tex_load_materials(&sc, maps, NULL, NULL, 1), 1, "textures decoded");
    CHECK_INT_EQ(maps[0].w, 4, "its width");
    CHECK_INT_EQ(maps[0].h, 2, "its height");
    for (i = 0; i < 24; i++) CHECK_INT_EQ(maps[0].rgb[i], rgb[i], "byte %d of the texels", i);
    tex_free(&maps[0]);
    obj_free(&sc);
    /* --export-gltf embeds it again, as a PNG, with no file of its name to copy */
    snprintf(cmd, sizeof cmd,
             "build/rad_cli '%s' --quiet --res 16 --width 8 --height 8 -o '%s' "
             "--export-gltf '%s'",
             tmp_path("tex.gltf"), tmp_path("tex.png"), tmp_path("tex.glb"));
    CHECK_INT_EQ(system(cmd), 0, "rad_cli on the glTF with an embedded texture");
    {
        char *d;
        size_t n;
        assert_int_equal(fio_read_all(tmp_path("tex.glb"), 1 << 20, &d, &n, err, sizeof err), 0);
        CHECK_THAT(holds(d, n, "image/png"), "an image/png in the exported .glb");
        CHECK_THAT(holds(d, n, "\x89PNG"), "PNG bytes in the exported .glb");
        free(d);
    }
}

/* The red column of --dump-radiosity's CSV at PATH into V, and the centres' x and z
 * into X and Z when not NULL (N rows at most); returns how many rows. */
static int csv_rgb(const char *path, double *v, double *x, double *z, int n)
{
    char line[512];
    int rows = 0;
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    if (!fgets(line, sizeof line, f)) line[0] = '\0'; /* the header */
    while (rows < n && fgets(line, sizeof line, f)) {
        const char *c = line, *col[8];
        int k;
        for (k = 0; k < 8 && c; k++) {
            c = strchr(c, ',') ? strchr(c, ',') + 1 : NULL;
            col[k] = c;
        }
        assert_non_null(c);
        if (x) x[rows] = atof(col[3]);
        if (z) z[rows] = atof(col[5]);
        v[rows++] = atof(col[6]);
    }
    fclose(f);
    return rows;
}

/* A glTF floor lit by its own KHR_lights_punctual point light gives rad_cli's solve of
 * the same floor as an OBJ lit by --point with the light's values, element for element
 * (the same faces, the same light: the same bits); --no-file-lights leaves it dark. */
static void test_cli_file_lights(void **state)
{
    static const float pos[4][3] = {{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}};
    static const unsigned short idx[6] = {0, 1, 2, 0, 2, 3};
    static double a[4096], b[4096], x[4096], z[4096];
    double rms = 0;
    unsigned char buf[64];
    char cmd[2048];
    int i, na, nb, dark = 0;
    FILE *f;
    (void)state;
    if (!assimp_scene_available()) skip();
    memcpy(buf, pos, 48);
    memcpy(buf + 48, idx, 12);
    f = fopen(tmp_path("lit.gltf"), "w");
    assert_non_null(f);
    fprintf(f, "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_lights_punctual\"],"
               "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\","
               "\"color\":[1,0.5,0.25],\"intensity\":3}]}},\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],"
               "\"nodes\":[{\"name\":\"floor\",\"mesh\":0},{\"name\":\"bulb\",\"translation\":[0.5,1,0],"
               "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}],"
               "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
               "\"material\":0}]}],\"materials\":[{\"name\":\"floor\",\"pbrMetallicRoughness\":"
               "{\"baseColorFactor\":[0.5,0.5,0.5,1]}}],"
               "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
               "\"min\":[-2,0,-2],\"max\":[2,0,2]},{\"bufferView\":1,\"componentType\":5123,\"count\":6,"
               "\"type\":\"SCALAR\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},"
               "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":12}],"
               "\"buffers\":[{\"byteLength\":60,\"uri\":\"data:application/octet-stream;base64,");
    put_b64(f, buf, 60);
    fprintf(f, "\"}]}\n");
    assert_int_equal(fclose(f), 0);
    f = fopen(tmp_path("lit.obj"), "w");
    assert_non_null(f);
    fprintf(f, "mtllib lit.mtl\nv -2 0 -2\nv -2 0 2\nv 2 0 2\nv 2 0 -2\nusemtl floor\nf 1 2 3\nf 1 3 4\n");
    assert_int_equal(fclose(f), 0);
    f = fopen(tmp_path("lit.mtl"), "w");
    assert_non_null(f);
    fprintf(f, "newmtl floor\nKd 0.5 0.5 0.5\n");
    assert_int_equal(fclose(f), 0);
    snprintf(cmd, sizeof cmd,
             "build/rad_cli '%s' --quiet --width 8 --height 8 -o '%s' --dump-radiosity '%s' && "
             "build/rad_cli '%s' --point 0.5,1,0,3,1.5,0.75 --quiet --width 8 --height 8 -o '%s' "
             "--dump-radiosity '%s'",
             tmp_path("lit.gltf"), tmp_path("a.png"), tmp_path("a.csv"), tmp_path("lit.obj"),
             tmp_path("b.png"), tmp_path("b.csv"));
    CHECK_INT_EQ(system(cmd), 0, "rad_cli on the lit glTF and the OBJ with --point");
    na = csv_rgb(tmp_path("a.csv"), a, x, z, 4096);
    nb = csv_rgb(tmp_path("b.csv"), b, NULL, NULL, 4096);
    print_message("glTF with its light: %d elements; OBJ with --point: %d\n", na, nb);
    CHECK_INT_EQ(na, nb, "elements of the two solves");
    CHECK_INT_GT(na, 0, "elements");
    for (i = 0; i < na; i++) CHECK_NEAR(a[i], b[i], 0, "element %d's red, the file's light against --point", i);
    /* A lone floor sees nothing of itself: each element's radiosity is its direct
     * light, 0.5 I cos t / r^2 at its centre (I = 3, 1 above (0.5, 0, 0)). The light's
     * cube is 4 res = 768 (the glue's choice at rad_cli's res 192): measured 1.2% rms;
     * at the scene's res 11%, at res 128 20.6% (elements of 1/144 of the floor's side
     * meet few of the cube's pixels far from the light). Bound 5%: four times what was
     * measured, under half of what the scene's res gives. */
    for (i = 0; i < na; i++) {
        double dx = x[i] - 0.5, d2 = dx * dx + 1 + z[i] * z[i], want = 0.5 * 3 / (d2 * sqrt(d2));
        rms += (a[i] - want) * (a[i] - want) / (want * want);
    }
    rms = sqrt(rms / na);
    print_message("direct light per element against I cos t / r^2: rms %.4f\n", rms);
    CHECK_LE(rms, 0.05, "rms relative error of the floor's direct light");
    snprintf(cmd, sizeof cmd,
             "build/rad_cli '%s' --no-file-lights --quiet --res 32 --width 8 --height 8 -o '%s' "
             "--dump-radiosity '%s'",
             tmp_path("lit.gltf"), tmp_path("c.png"), tmp_path("c.csv"));
    CHECK_INT_EQ(system(cmd), 0, "rad_cli --no-file-lights");
    na = csv_rgb(tmp_path("c.csv"), a, NULL, NULL, 4096);
    for (i = 0; i < na; i++) dark += a[i] == 0;
    CHECK_INT_EQ(dark, na, "elements dark with --no-file-lights");

    /* A --lights file's light shines with the glTF's, before it (the command line's
     * lights first, the scene file's after), and --no-file-lights leaves the glTF's
     * out but not the file's: the same bits as the OBJ with the options in that order. */
    f = fopen(tmp_path("more.json"), "w");
    assert_non_null(f);
    fprintf(f, "{\"lights\": [{\"type\": \"point\", \"position\": [-1, 2, 1], \"intensity\": [2, 2, 2]}]}\n");
    assert_int_equal(fclose(f), 0);
    for (i = 0; i < 2; i++) {
        snprintf(cmd, sizeof cmd,
                 "build/rad_cli '%s' --lights '%s' %s --quiet --width 8 --height 8 -o '%s' --dump-radiosity '%s' && "
                 "build/rad_cli '%s' --point -1,2,1,2,2,2 %s --quiet --width 8 --height 8 -o '%s' "
                 "--dump-radiosity '%s'",
                 tmp_path("lit.gltf"), tmp_path("more.json"), i ? "--no-file-lights" : "", tmp_path("d.png"),
                 tmp_path("d.csv"), tmp_path("lit.obj"), i ? "" : "--point 0.5,1,0,3,1.5,0.75", tmp_path("e.png"),
                 tmp_path("e.csv"));
        CHECK_INT_EQ(system(cmd), 0, "rad_cli on the glTF with --lights%s and the OBJ with --point",
                     i ? " --no-file-lights" : "");
        na = csv_rgb(tmp_path("d.csv"), a, NULL, NULL, 4096);
        nb = csv_rgb(tmp_path("e.csv"), b, NULL, NULL, 4096);
        CHECK_INT_EQ(na, nb, "elements of the two solves%s", i ? " (--no-file-lights)" : "");
        for (dark = 0; dark < na; dark++)
            CHECK_NEAR(a[dark], b[dark], 0, "element %d's red, --lights%s against --point", dark,
                       i ? " --no-file-lights" : " and the glTF's light");
    }
}

/* .obj in any case goes to the OBJ reader, every other name to assimp. */
static void test_wants(void **state)
{
    (void)state;
    CHECK_INT_EQ(assimp_scene_wants("a/b.obj"), 0, "a/b.obj to assimp");
    CHECK_INT_EQ(assimp_scene_wants("B.OBJ"), 0, "B.OBJ to assimp");
    CHECK_INT_EQ(assimp_scene_wants("a.glb"), 1, "a.glb to assimp");
    CHECK_INT_EQ(assimp_scene_wants("a.obj.fbx"), 1, "a.obj.fbx to assimp");
    CHECK_INT_EQ(assimp_scene_wants("dir.obj/scene"), 1, "dir.obj/scene to assimp");
    CHECK_INT_EQ(assimp_scene_wants("a.objx"), 1, "a.objx to assimp");
    CHECK_INT_EQ(assimp_scene_wants("-"), 0, "standard input to assimp");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wants),
        cmocka_unit_test(test_gltf_matches_obj),
        cmocka_unit_test(test_exported_formats),
        cmocka_unit_test(test_bad_files),
        cmocka_unit_test(test_outside_paths),
        cmocka_unit_test(test_gltf_lights),
        cmocka_unit_test(test_embedded_texture),
        cmocka_unit_test(test_cli_file_lights),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
