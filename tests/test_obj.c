/* SPDX-License-Identifier: MIT */
/* Tests for the OBJ + MTL loader (tools/formats/obj.c). Run from the repository root. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "formats/file_io.h"
#include "formats/obj.h"
#include "tmpdir.h"
#include "warnings.h"

TMPDIR_GROUP("obj")

#define DATA "tests/data/obj/"

/* ---- helpers ------------------------------------------------------------------- */

static void near_at(double a, double b, double eps, const char *expr, const char *file, int line)
{
    if (fabs(a - b) <= eps) return;
    print_error("%s = %.17g, expected %.17g (+-%g)\n", expr, a, b, eps);
    _fail(file, line);
}
#define assert_near(a, b, eps) near_at((a), (b), (eps), #a, __FILE__, __LINE__)

static void assert_vec_at(obj_vec3 v, double x, double y, double z, const char *file, int line)
{
    near_at(v.x, x, 0, "x", file, line);
    near_at(v.y, y, 0, "y", file, line);
    near_at(v.z, z, 0, "z", file, line);
}
#define assert_vec(v, x, y, z) assert_vec_at((v), (x), (y), (z), __FILE__, __LINE__)

static warnings seen;
static char err[512];

/* Parses a string as "mem.obj" whose mtllib files live in the test data directory. */
static int parse(const char *text, obj_scene *sc)
{
    memset(&seen, 0, sizeof seen);
    return obj_parse(text, strlen(text), "mem.obj", DATA, sc, collect, &seen, err, sizeof err);
}

/* The parse must fail with exactly this message and leave an empty scene. */
static void expect_error_at(const char *text, size_t len, const char *msg, const char *file,
                            int line)
{
    obj_scene sc;
    memset(&seen, 0, sizeof seen);
    if (obj_parse(text, len, "mem.obj", DATA, &sc, collect, &seen, err, sizeof err) != -1) {
        print_error("parse succeeded, expected \"%s\"\n", msg);
        obj_free(&sc);
        _fail(file, line);
    }
    if (strcmp(err, msg) != 0) {
        print_error("error \"%s\", expected \"%s\"\n", err, msg);
        _fail(file, line);
    }
    if (sc.verts || sc.faces || sc.indices || sc.materials || sc.nverts || sc.nfaces) {
        print_error("scene not empty after error\n");
        _fail(file, line);
    }
    obj_free(&sc); /* must be harmless */
}
#define expect_error(text, msg) expect_error_at((text), strlen(text), (msg), __FILE__, __LINE__)

static const int *face_indices(const obj_scene *sc, int f)
{
    return sc->indices + sc->faces[f].first;
}

static void assert_face_at(const obj_scene *sc, int f, int count, const int *want, const char *file,
                           int line)
{
    int i;
    if (sc->faces[f].count != count) {
        print_error("face %d has %d vertices, expected %d\n", f, sc->faces[f].count, count);
        _fail(file, line);
    }
    for (i = 0; i < count; i++)
        if (face_indices(sc, f)[i] != want[i]) {
            print_error("face %d vertex %d is %d, expected %d\n", f, i, face_indices(sc, f)[i],
                        want[i]);
            _fail(file, line);
        }
}
#define assert_face(sc, f, ...)                                                           \
    do {                                                                                  \
        static const int want_[] = {__VA_ARGS__};                                         \
        assert_face_at((sc), (f), (int)(sizeof want_ / sizeof want_[0]), want_, __FILE__, \
                       __LINE__);                                                         \
    } while (0)

/* ---- geometry helpers for the triangulation checks ----------------------------- */

static obj_vec3 sub(obj_vec3 a, obj_vec3 b)
{
    obj_vec3 r = {a.x - b.x, a.y - b.y, a.z - b.z};
    return r;
}

static obj_vec3 cross(obj_vec3 a, obj_vec3 b)
{
    obj_vec3 r = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return r;
}

static double dot(obj_vec3 a, obj_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

/* 2-D coordinates of p after dropping the normal's dominant axis. */
static void flat(obj_vec3 p, obj_vec3 n, double *u, double *v)
{
    double ax = fabs(n.x), ay = fabs(n.y), az = fabs(n.z);
    if (az >= ax && az >= ay) {
        *u = p.x;
        *v = p.y;
    } else if (ay >= ax) {
        *u = p.z;
        *v = p.x;
    } else {
        *u = p.y;
        *v = p.z;
    }
}

/* Even-odd test of point p against face f, in the plane given by n. */
static int inside(const obj_scene *sc, const obj_face *f, obj_vec3 p, obj_vec3 n)
{
    const int *ix = sc->indices + f->first;
    double px, py, ax, ay, bx, by;
    int i, in = 0;
    flat(p, n, &px, &py);
    for (i = 0; i < f->count; i++) {
        flat(sc->verts[ix[i]], n, &ax, &ay);
        flat(sc->verts[ix[(i + 1) % f->count]], n, &bx, &by);
        if ((ay > py) != (by > py) && px < ax + (py - ay) * (bx - ax) / (by - ay)) in = !in;
    }
    return in;
}

/* Checks obj_triangulate on face f: count-2 triangles of the face's own vertices, each
   wound like the polygon, inside it, adding up to its area. */
static void check_triangulation(const obj_scene *sc, int face)
{
    const obj_face *f = &sc->faces[face];
    obj_vec3 n = obj_face_normal(sc, f);
    int *out = malloc(sizeof *out * 3 * (size_t)(f->count - 2));
    double total = 0;
    int t, k, j;
    assert_non_null(out);
    assert_int_equal(obj_triangulate(sc, f, out), f->count - 2);
    for (t = 0; t < f->count - 2; t++) {
        const int *tri = out + 3 * t;
        obj_vec3 a, b, c, tn, centroid;
        for (k = 0; k < 3; k++) { /* a vertex of this polygon */
            for (j = 0; j < f->count && face_indices(sc, face)[j] != tri[k]; j++)
                ;
            CHECK_INT_LT(j, f->count,
                         "face %d, triangle %d: corner %d's vertex %d among the face's", face, t, k,
                         tri[k]);
        }
        a = sc->verts[tri[0]];
        b = sc->verts[tri[1]];
        c = sc->verts[tri[2]];
        tn = cross(sub(b, a), sub(c, a));
        CHECK_GT(dot(tn, n), 0, "face %d, triangle %d: its normal along the face's", face, t);
        total += 0.5 * sqrt(dot(tn, tn));
        centroid.x = (a.x + b.x + c.x) / 3;
        centroid.y = (a.y + b.y + c.y) / 3;
        centroid.z = (a.z + b.z + c.z) / 3;
        CHECK_THAT(inside(sc, f, centroid, n),
                   "face %d, triangle %d: centroid %g %g %g inside the face", face, t, centroid.x,
                   centroid.y, centroid.z);
    }
    assert_near(total, obj_face_area(sc, f), 1e-9);
    free(out);
}

/* Appends to a growing OBJ text. */
static void add(char *buf, size_t size, const char *fmt, ...)
{
    size_t used = strlen(buf);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf + used, size - used, fmt, ap);
    va_end(ap);
}

/* ---- tests: geometry statements ------------------------------------------------ */

static void test_index_forms(void **state)
{
    obj_scene sc;
    (void)state;
    assert_int_equal(parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                           "vn 0 0 1\nvp 0.5\n"
                           "f 1 2 3\n"
                           "f 1/1 2/2 3/3\n"
                           "f 1//1 3//1 4//1\n"
                           "f 4/4/1 3/3/1 2/2/1 1/1/1\n"
                           "f +1 +2 +4\n",
                           &sc),
                     0);
    assert_int_equal(sc.nverts, 4);
    assert_int_equal(sc.nfaces, 5);
    assert_int_equal(sc.nindices, 16);
    assert_face(&sc, 0, 0, 1, 2);
    assert_face(&sc, 1, 0, 1, 2);
    assert_face(&sc, 2, 0, 2, 3);
    assert_face(&sc, 3, 3, 2, 1, 0);
    assert_face(&sc, 4, 0, 1, 3);
    assert_int_equal(sc.faces[3].line, 14);
    assert_vec(sc.verts[2], 1, 1, 0);
    assert_int_equal(sc.unknown_statements, 0);
    assert_int_equal(seen.n, 0);
    obj_free(&sc);
}

static void test_negative_indices(void **state)
{
    obj_scene sc;
    (void)state;
    assert_int_equal(parse("v 0 0 0\nv 1 0 0\nv 1 1 0\n"
                           "f -3 -2 -1\n"
                           "v 0 1 0\n"
                           "f -1/-1 -2//-3 -3/-1/-2 1\n",
                           &sc),
                     0);
    assert_int_equal(sc.nfaces, 2);
    assert_face(&sc, 0, 0, 1, 2);
    assert_face(&sc, 1, 3, 2, 1, 0);
    obj_free(&sc);
}

static void test_grouping_and_comments(void **state)
{
    obj_scene sc;
    (void)state;
    assert_int_equal(parse("# header comment\n"
                           "   # indented comment\n"
                           "o thing\n"
                           "g a b c\n"
                           "s 1\n"
                           "s off\n"
                           "mg 1 0.5\n"
                           "v 0 0 0 # trailing comment\n"
                           "v 1 0 0\n"
                           "v 0 1 0\n"
                           "l 1 2 3\n"
                           "p 1\n"
                           "f 1 2 3#not-a-comment-start-so-still-junk\n",
                           &sc),
                     -1);
    assert_string_equal(err, "mem.obj:13: bad face vertex '3#not-a-comment-start-so-still-junk'");
    assert_int_equal(parse("# c\no x\ng\ns 2\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\n\t\n"
                           "f 1 2 3 # the end\n",
                           &sc),
                     0);
    assert_int_equal(sc.nfaces, 1);
    assert_int_equal(sc.unknown_statements, 0);
    obj_free(&sc);
}

static void test_unknown_statements_counted(void **state)
{
    obj_scene sc;
    (void)state;
    assert_int_equal(parse("cstype bspline\ndeg 3\nfrobnicate\nv 0 0 0\n\x01\x7f\xff junk\n", &sc),
                     0);
    assert_int_equal(sc.unknown_statements, 4);
    assert_int_equal(sc.nverts, 1);
    obj_free(&sc);
}

static void test_continuations(void **state)
{
    obj_scene sc;
    (void)state;
    assert_int_equal(parse("v 1 \\\n"
                           "  2 3\n"
                           "v 0 0 0 \\   \n"
                           "\n"
                           "v 4\\\n"
                           " 5 6\n"
                           "f 1 \\\n"
                           "2 \\\n"
                           "3\n"
                           "f 3 2 1 \\", /* ends inside a continuation */
                           &sc),
                     0);
    assert_int_equal(sc.nverts, 3);
    assert_vec(sc.verts[0], 1, 2, 3);
    assert_vec(sc.verts[2], 4, 5, 6);
    assert_int_equal(sc.nfaces, 2);
    assert_face(&sc, 0, 0, 1, 2);
    assert_int_equal(sc.faces[0].line, 7);
    assert_int_equal(sc.faces[1].line, 10);
    obj_free(&sc);
    /* errors name the statement's first line */
    expect_error("v 0 0 0\nv 1 \\\n2 \\\nx\n", "mem.obj:2: bad number 'x'");
    expect_error("v 0 0 0\nv 1 1 1\n\nf 1 \\\n2\n",
                 "mem.obj:4: face needs at least 3 vertices, got 2");
}

static void test_crlf(void **state)
{
    obj_scene sc;
    (void)state;
    memset(&seen, 0, sizeof seen);
    assert_int_equal(obj_load(DATA "crlf.obj", &sc, collect, &seen, err, sizeof err), 0);
    assert_int_equal(sc.nverts, 4);
    assert_vec(sc.verts[3], 0, 1, 0);
    assert_int_equal(sc.nfaces, 2);
    assert_face(&sc, 0, 0, 1, 2);
    assert_int_equal(sc.faces[0].line, 5);
    assert_face(&sc, 1, 0, 1, 2, 3);
    assert_int_equal(sc.faces[1].line, 8);
    obj_free(&sc);
    expect_error("v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nf 1 2 4\r\n",
                 "mem.obj:4: vertex index 4 out of range (3 vertices defined so far)");
}

static void test_number_forms(void **state)
{
    obj_scene sc;
    (void)state;
    assert_int_equal(parse("v .5 -.5 +.25\n"
                           "v 1e-3 2E+2 -3e2\n"
                           "v 5. -0 1e30\n"
                           "v\t1\t2\t3\t1.0\n"         /* w ignored */
                           "v 1 2 3 0.5 0.25 0.125\n", /* vertex colours ignored */
                           &sc),
                     0);
    assert_int_equal(sc.nverts, 5);
    assert_vec(sc.verts[0], 0.5, -0.5, 0.25);
    assert_vec(sc.verts[1], 0.001, 200, -300);
    assert_vec(sc.verts[2], 5, 0, 1e30);
    assert_vec(sc.verts[3], 1, 2, 3);
    assert_vec(sc.verts[4], 1, 2, 3);
    obj_free(&sc);
}

/* ---- tests: polygons and triangulation ----------------------------------------- */

static void test_polygons(void **state)
{
    obj_scene sc;
    (void)state;
    /* a convex hexagon, a concave L (area 3) and the L reversed */
    assert_int_equal(parse("v 2 0 1\nv 1 1.7 1\nv -1 1.7 1\nv -2 0 1\nv -1 -1.7 1\nv 1 -1.7 1\n"
                           "f 1 2 3 4 5 6\n"
                           "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
                           "f 7 8 9 10 11 12\n"
                           "f 12 11 10 9 8 7\n"
                           "f 1 2 3 4 5\n",
                           &sc),
                     0);
    assert_int_equal(sc.nfaces, 4);
    assert_int_equal(sc.faces[0].count, 6);
    assert_int_equal(sc.faces[1].count, 6);
    assert_int_equal(sc.faces[3].count, 5);
    assert_near(obj_face_area(&sc, &sc.faces[0]), 10.2, 1e-12);
    assert_near(obj_face_area(&sc, &sc.faces[1]), 3, 1e-12);
    assert_near(obj_face_normal(&sc, &sc.faces[1]).z, 6, 1e-12);
    assert_near(obj_face_normal(&sc, &sc.faces[2]).z, -6, 1e-12);
    check_triangulation(&sc, 0);
    check_triangulation(&sc, 1);
    check_triangulation(&sc, 2);
    check_triangulation(&sc, 3);
    obj_free(&sc);
}

/* A star and a comb, concave, in a tilted plane far from the origin, both windings. */
static void test_concave_tilted(void **state)
{
    static char text[16384];
    const obj_vec3 o = {100, -50, 20}, u = {0.6, 0.8, 0}, v = {-0.48, 0.36, 0.8};
    obj_scene sc;
    int i, teeth = 12;
    (void)state;
    text[0] = '\0';
    for (i = 0; i < 10; i++) { /* star: radius 1 and 0.35 alternately */
        double a = i * 3.14159265358979323846 / 5, r = i % 2 ? 0.35 : 1.0;
        double x = r * cos(a), y = r * sin(a);
        add(text, sizeof text, "v %.17g %.17g %.17g\n", o.x + x * u.x + y * v.x,
            o.y + x * u.y + y * v.y, o.z + x * u.z + y * v.z);
    }
    add(text, sizeof text, "f 1 2 3 4 5 6 7 8 9 10\nf 10 9 8 7 6 5 4 3 2 1\n");
    for (i = 0; i < teeth; i++) { /* comb: teeth of height 3 along a spine of height 1 */
        add(text, sizeof text, "v %d 0 %d\nv %d 0 %d\nv %d 0 %d\nv %d 0 %d\n", 2 * i, 1, 2 * i, 4,
            2 * i + 1, 4, 2 * i + 1, 1);
    }
    add(text, sizeof text, "v %d 0 1\nv %d 0 0\nv 0 0 0\nf", 2 * teeth, 2 * teeth);
    for (i = 0; i < 4 * teeth + 3; i++) add(text, sizeof text, " %d", 11 + i);
    add(text, sizeof text, "\n");
    assert_int_equal(parse(text, &sc), 0);
    assert_int_equal(sc.nfaces, 3);
    assert_int_equal(sc.faces[2].count, 4 * teeth + 3);
    assert_near(obj_face_area(&sc, &sc.faces[2]), 2 * teeth + teeth * 3, 1e-9);
    check_triangulation(&sc, 0);
    check_triangulation(&sc, 1);
    check_triangulation(&sc, 2);
    obj_free(&sc);
}

static void test_degenerate_polygon(void **state)
{
    obj_scene sc;
    int out[6];
    (void)state;
    assert_int_equal(parse("v 0 0 0\nv 1 1 1\nv 2 2 2\nv 3 3 3\nf 1 2 3 4\nf 1 1 1\n", &sc), 0);
    assert_int_equal(obj_triangulate(&sc, &sc.faces[0], out), -1);
    assert_int_equal(obj_triangulate(&sc, &sc.faces[1], out), -1);
    assert_near(obj_face_area(&sc, &sc.faces[0]), 0, 0);
    obj_free(&sc);
}

/* ---- tests: materials ---------------------------------------------------------- */

static void assert_rgb_at(const double *c, double r, double g, double b, const char *file, int line)
{
    near_at(c[0], r, 0, "r", file, line);
    near_at(c[1], g, 0, "g", file, line);
    near_at(c[2], b, 0, "b", file, line);
}
#define assert_rgb(c, r, g, b) assert_rgb_at((c), (r), (g), (b), __FILE__, __LINE__)

static void test_materials(void **state)
{
    obj_scene sc;
    const obj_material *m;
    int red, plain, light, warm, def, ghost;
    (void)state;
    memset(&seen, 0, sizeof seen);
    assert_int_equal(obj_load(DATA "scene.obj", &sc, collect, &seen, err, sizeof err), 0);
    assert_int_equal(sc.nmaterials, 6);
    red = obj_find_material(&sc, "red");
    plain = obj_find_material(&sc, "plain");
    light = obj_find_material(&sc, "light");
    warm = obj_find_material(&sc, "warm white");
    def = obj_find_material(&sc, "(default)");
    ghost = obj_find_material(&sc, "ghost");
    assert_int_equal(red, 0); /* libraries in order, then names as first used */
    assert_int_equal(plain, 1);
    assert_int_equal(light, 2);
    assert_int_equal(warm, 3);
    assert_int_equal(def, 4);
    assert_int_equal(ghost, 5);
    assert_int_equal(obj_find_material(&sc, "warm"), -1);

    m = &sc.materials[red];
    assert_rgb(m->kd, 0.8, 0.1, 0.1);
    assert_rgb(m->ke, 0, 0, 0);
    assert_int_equal(m->nfaces, 1);
    assert_near(m->area, 3, 1e-12);
    CHECK_INT_NE(m->defined, 0, "material red defined by newmtl");
    assert_int_equal(m->use_line, 12);
    m = &sc.materials[plain]; /* no Kd, no Ke: defaults */
    assert_rgb(m->kd, 0.8, 0.8, 0.8);
    assert_rgb(m->ke, 0, 0, 0);
    assert_int_equal(m->nfaces, 0);
    assert_near(m->area, 0, 0);
    m = &sc.materials[light]; /* one value means grey */
    assert_rgb(m->kd, 0.5, 0.5, 0.5);
    assert_rgb(m->ke, 10, 10, 10);
    assert_int_equal(m->nfaces, 1);
    assert_near(m->area, 6, 1e-12);
    m = &sc.materials[warm];
    assert_rgb(m->kd, 0.7, 0.6, 0.5);
    assert_rgb(m->ke, 0.001, 200, 0.5);
    assert_int_equal(m->nfaces, 2);
    assert_near(m->area, 9, 1e-12);
    m = &sc.materials[def];
    assert_rgb(m->kd, 0.8, 0.8, 0.8);
    assert_int_equal(m->nfaces, 1);
    assert_near(m->area, 6, 1e-12);
    CHECK_INT_EQ(m->defined, 0, "material %s: not defined by newmtl", m->name);
    m = &sc.materials[ghost];
    assert_rgb(m->kd, 0.8, 0.8, 0.8);
    assert_rgb(m->ke, 0, 0, 0);
    assert_int_equal(m->nfaces, 1);
    assert_near(m->area, 3, 1e-12);
    CHECK_INT_EQ(m->defined, 0, "material %s: not defined by newmtl", m->name);

    assert_int_equal(sc.nfaces, 6);
    assert_int_equal(sc.faces[0].material, def);
    assert_int_equal(sc.faces[1].material, red);
    assert_int_equal(sc.faces[2].material, warm);
    assert_int_equal(sc.faces[3].material, warm);
    assert_int_equal(sc.faces[4].material, light);
    assert_int_equal(sc.faces[5].material, ghost);
    assert_int_equal(sc.faces[5].line, 20);
    assert_int_equal(sc.unknown_statements, 2); /* "foo" in a.mtl, "cstype" in the OBJ */
    assert_int_equal(sc.nwarnings, 1);
    assert_int_equal(seen.n, 1);
    assert_string_equal(seen.msg[0],
                        DATA "scene.obj:19: usemtl 'ghost': material not defined, using Kd 0.8");
    obj_free(&sc);
}

static void test_usemtl_before_mtllib(void **state)
{
    obj_scene sc;
    (void)state;
    assert_int_equal(parse("usemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nmtllib a.mtl\n", &sc),
                     0);
    assert_int_equal(seen.n, 0);
    assert_int_equal(sc.nmaterials, 2);
    assert_int_equal(sc.faces[0].material, obj_find_material(&sc, "red"));
    assert_rgb(sc.materials[sc.faces[0].material].kd, 0.8, 0.1, 0.1);
    assert_near(sc.materials[sc.faces[0].material].area, 0.5, 1e-12);
    obj_free(&sc);
}

static void test_missing_mtl(void **state)
{
    obj_scene sc;
    (void)state;
    memset(&seen, 0, sizeof seen);
    assert_int_equal(obj_load(DATA "missing_mtl.obj", &sc, collect, &seen, err, sizeof err), 0);
    assert_int_equal(sc.nfaces, 1);
    assert_int_equal(seen.n, 2);
    assert_int_equal(sc.nwarnings, 2);
    assert_string_equal(seen.msg[0], DATA "missing_mtl.obj:4: cannot open material library "
                                          "'nowhere.mtl': No such file or directory");
    assert_string_equal(seen.msg[1], DATA "missing_mtl.obj:5: usemtl 'red': material not "
                                          "defined, using Kd 0.8");
    assert_rgb(sc.materials[sc.faces[0].material].kd, 0.8, 0.8, 0.8);
    obj_free(&sc);
    /* without a callback the warnings are still counted */
    assert_int_equal(obj_load(DATA "missing_mtl.obj", &sc, NULL, NULL, err, sizeof err), 0);
    assert_int_equal(sc.nwarnings, 2);
    obj_free(&sc);
    /* from memory without a base directory, mtllib cannot be followed */
    memset(&seen, 0, sizeof seen);
    assert_int_equal(
        obj_parse("mtllib a.mtl\n", 13, "mem.obj", NULL, &sc, collect, &seen, err, sizeof err), 0);
    assert_int_equal(seen.n, 1);
    assert_string_equal(seen.msg[0], "mem.obj:1: mtllib 'a.mtl' ignored: no directory to look in");
    obj_free(&sc);
    /* a library that cannot be read (a directory) is a warning too */
    assert_int_equal(parse("\nmtllib .\n", &sc), 0);
    assert_int_equal(seen.n, 1);
    assert_string_equal(seen.msg[0], "mem.obj:2: cannot read material library '.': is a directory");
    obj_free(&sc);
}

static void test_mtl_errors(void **state)
{
    (void)state;
    expect_error("v 0 0 0\nmtllib b.mtl bad_kd.mtl\n", DATA "bad_kd.mtl:4: bad number '0.5abc'");
    expect_error("mtllib neg_kd.mtl\n", DATA "neg_kd.mtl:2: negative Kd value '-0.1'");
    expect_error("mtllib nan_ke.mtl\n", DATA "nan_ke.mtl:3: bad number 'nan'");
    expect_error("mtllib inf_ke.mtl\n", DATA "inf_ke.mtl:2: bad number 'inf'");
    expect_error("mtllib two_kd.mtl\n", DATA "two_kd.mtl:2: Kd takes 1 or 3 values, got 2");
    expect_error("mtllib kd_first.mtl\n", DATA "kd_first.mtl:2: Kd before any newmtl");
}

/* ---- tests: errors ------------------------------------------------------------- */

static void test_index_errors(void **state)
{
    (void)state;
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",
                 "mem.obj:4: vertex index 0 (OBJ indices start at 1)");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n",
                 "mem.obj:5: vertex index 4 out of range (3 vertices defined so far)");
    expect_error("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n",
                 "mem.obj:3: vertex index 3 out of range (2 vertices defined so far)");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
                 "mem.obj:4: vertex index -4 out of range (3 vertices defined so far)");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
                 "mem.obj:4: vertex index 99999999999999999999 out of range (3 vertices defined "
                 "so far)");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x/2 2 3\n", "mem.obj:4: bad face vertex '1/x/2'");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n", "mem.obj:4: bad face vertex '1/'");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1// 2 3\n", "mem.obj:4: bad face vertex '1//'");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2/3/4 2 3\n",
                 "mem.obj:4: bad face vertex '1/2/3/4'");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1.0 2 3\n", "mem.obj:4: bad face vertex '1.0'");
    expect_error("v 0 0 0\nv 1 0 0\nf 1 2\n", "mem.obj:3: face needs at least 3 vertices, got 2");
    expect_error("f\n", "mem.obj:1: face needs at least 3 vertices, got 0");
    expect_error("v 0 0 0\nusemtl   \n", "mem.obj:2: usemtl without a material name");
    expect_error("mtllib\n", "mem.obj:1: mtllib without a file name");
}

static void test_number_errors(void **state)
{
    (void)state;
    expect_error("v 0 0 0\nv nan 0 0\n", "mem.obj:2: bad number 'nan'");
    expect_error("v 0 0 0\nv 0 -inf 0\n", "mem.obj:2: bad number '-inf'");
    expect_error("v 0 0 Infinity\n", "mem.obj:1: bad number 'Infinity'");
    expect_error("v 0x1p3 0 0\n", "mem.obj:1: bad number '0x1p3'");
    expect_error("\n\nv 1.0abc 0 0\n", "mem.obj:3: bad number '1.0abc'");
    expect_error("v 1 2 3 4abc\n", "mem.obj:1: bad number '4abc'");
    expect_error("v . 0 0\n", "mem.obj:1: bad number '.'");
    expect_error("v 1e 0 0\n", "mem.obj:1: bad number '1e'");
    expect_error("v 1,5 0 0\n", "mem.obj:1: bad number '1,5'");
    expect_error("v 0 0 0\nv 1 2\n", "mem.obj:2: vertex needs 3 coordinates, got 2");
    expect_error("v\n", "mem.obj:1: vertex needs 3 coordinates, got 0");
    expect_error("v 0 0 1e31\n", "mem.obj:1: number out of range '1e31' (limit 1e30)");
    expect_error("v 0 -2e300 0\n", "mem.obj:1: number out of range '-2e300' (limit 1e30)");
    expect_error("v 0 1e999 0\n", "mem.obj:1: number out of range '1e999' (limit 1e30)");
}

static void test_empty(void **state)
{
    obj_scene sc;
    (void)state;
    assert_int_equal(obj_load(DATA "empty.obj", &sc, NULL, NULL, err, sizeof err), 0);
    assert_int_equal(sc.nfaces, 0);
    assert_int_equal(sc.nverts, 0);
    assert_int_equal(sc.nmaterials, 0);
    obj_free(&sc);
    assert_int_equal(parse("", &sc), 0);
    assert_int_equal(sc.nfaces, 0);
    obj_free(&sc);
    assert_int_equal(parse("# only a comment\n\n   \n", &sc), 0);
    assert_int_equal(sc.nfaces, 0);
    assert_int_equal(sc.nmaterials, 0); /* "(default)" only exists once a face uses it */
    obj_free(&sc);
}

static void test_binary(void **state)
{
    static const char junk[] = "v 0 0 0\nv 1 0 0\n\x7f"
                               "ELF\x01\x02\n\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\n";
    static const char comment[] = "# a comment \x00 with a NUL\n";
    (void)state;
    expect_error_at(junk, sizeof junk - 1, "mem.obj:6: binary data (NUL byte)", __FILE__, __LINE__);
    expect_error_at(comment, sizeof comment - 1, "mem.obj:1: binary data (NUL byte)", __FILE__,
                    __LINE__);
    expect_error_at("v 1 2 3\0", 8, "mem.obj:1: binary data (NUL byte)", __FILE__, __LINE__);
}

static void test_long_lines(void **state)
{
    const size_t mb = 1 << 20;
    char *text = malloc(mb + 64), want[128];
    obj_scene sc;
    size_t i;
    (void)state;
    assert_non_null(text);
    /* a 1 MB vertex: three coordinates and a lot of ignored extras */
    strcpy(text, "v 1 2 3");
    for (i = 7; i + 2 <= mb; i += 2) memcpy(text + i, " 4", 2);
    strcpy(text + i, "\n");
    assert_int_equal(parse(text, &sc), 0);
    assert_int_equal(sc.nverts, 1);
    assert_vec(sc.verts[0], 1, 2, 3);
    obj_free(&sc);
    /* a 1 MB face after three vertices, a 1 MB comment */
    strcpy(text, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf");
    for (i = strlen(text); i + 2 <= mb; i += 2) memcpy(text + i, " 1", 2);
    strcpy(text + i, "\n#");
    assert_int_equal(parse(text, &sc), 0);
    assert_int_equal(sc.nfaces, 1);
    assert_int_equal(sc.faces[0].count, (int)((mb - 25) / 2));
    obj_free(&sc);
    memset(text, 'x', mb);
    text[0] = '#';
    text[mb] = '\0';
    assert_int_equal(parse(text, &sc), 0);
    obj_free(&sc);
    /* a malformed 1 MB token */
    strcpy(text, "v 0 0 0\nv 1 2 ");
    memset(text + 14, '7', mb);
    strcpy(text + 14 + mb, "\n");
    assert_int_equal(parse(text, &sc), -1);
    snprintf(want, sizeof want, "mem.obj:2: number out of range '%.40s' (limit 1e30)", text + 14);
    assert_string_equal(err, want);
    text[14] = 'y';
    assert_int_equal(parse(text, &sc), -1);
    snprintf(want, sizeof want, "mem.obj:2: bad number '%.40s'", text + 14);
    assert_string_equal(err, want);
    free(text);
}

static void test_missing_obj(void **state)
{
    obj_scene sc;
    (void)state;
    assert_int_equal(obj_load(DATA "nope.obj", &sc, NULL, NULL, err, sizeof err), -1);
    assert_string_equal(err, DATA "nope.obj: cannot open: No such file or directory");
    assert_int_equal(sc.nfaces, 0);
    assert_null(sc.verts);
    obj_free(&sc);
    /* a small error buffer truncates, a NULL one is allowed */
    assert_int_equal(obj_load(DATA "nope.obj", &sc, NULL, NULL, err, 8), -1);
    assert_string_equal(err, "tests/d");
    assert_int_equal(obj_load(DATA "nope.obj", &sc, NULL, NULL, NULL, 0), -1);
    assert_int_equal(obj_parse("f 1 2 3", 7, NULL, NULL, &sc, NULL, NULL, NULL, 0), -1);
}

/* ---- files outside the scene's folder ------------------------------------------- */

static void put(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

/* TMP/scene/s.obj whose library s.mtl gives material m "map_Kd MAP" (Kd 0 0 0); TMP/x.png
 * and TMP/out.mtl lie outside the scene's folder. Returns the OBJ's path. */
static const char *outside_scene(const char *map, const char *mtllib)
{
    char text[600];
    mkdir(tmp_path("scene"), 0700);
    put(tmp_path("x.png"), "not read");
    put(tmp_path("out.mtl"), "newmtl m\nKd 0.1 0.2 0.3\n");
    snprintf(text, sizeof text, "mtllib %s\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n",
             mtllib);
    put(tmp_path("scene/s.obj"), text);
    snprintf(text, sizeof text, "newmtl m\nKd 0 0 0\nmap_Kd %s\n", map);
    put(tmp_path("scene/s.mtl"), text);
    return tmp_path("scene/s.obj");
}

/* Loads OBJ with ALLOW; the texture path it keeps (or NULL) in *PATH (malloc'd). */
static void load_outside(const char *obj, int allow, obj_scene *sc)
{
    obj_opts o = {0};
    o.allow_outside = allow;
    memset(&seen, 0, sizeof seen);
    assert_int_equal(obj_load_opts(obj, &o, sc, collect, &seen, err, sizeof err), 0);
}

/* A map_Kd that leaves the folder (WHERE: how, for messages): not kept, one warning
 * naming the MTL line, the file, the folder and the option, the Kd fallback. */
static void expect_refused_map(const char *map, const char *shown, const char *where)
{
    obj_scene sc;
    char want[1200], *root = fio_resolve(tmpdir);
    assert_non_null(root);
    load_outside(outside_scene(map, "s.mtl"), 0, &sc);
    snprintf(want, sizeof want,
             "%s:3: map_Kd: %s is outside the scene's folder %s/scene; using Kd 0.5 0.5 0.5; "
             "--allow-outside-paths reads it",
             tmp_path("scene/s.mtl"), shown, root);
    CHECK_THAT(sc.nmaterials == 1 && sc.materials[0].map_kd.path == NULL,
               "%s: map_Kd kept as %s (want none)", where, sc.materials[0].map_kd.path);
    assert_int_equal(seen.n, 1);
    CHECK_THAT(!strcmp(seen.msg[0], want), "%s: warning\n  %s\nwant\n  %s", where, seen.msg[0],
               want);
    assert_near(sc.materials[0].kd[0], OBJ_FALLBACK_KD, 0);
    obj_free(&sc);
    free(root);
}

static void test_map_outside_folder(void **state)
{
    char abs[400], shown[400];
    obj_scene sc;
    (void)state;
    snprintf(shown, sizeof shown, "%s/../x.png", tmp_path("scene"));
    expect_refused_map("../x.png", shown, "../");
    snprintf(abs, sizeof abs, "%s", tmp_path("x.png"));
    expect_refused_map(abs, abs, "an absolute path");
    /* a link inside the folder that leads out of it */
    unlink(tmp_path("scene/link.png"));
    assert_int_equal(symlink(tmp_path("x.png"), tmp_path("scene/link.png")), 0);
    snprintf(shown, sizeof shown, "%s/link.png", tmp_path("scene"));
    expect_refused_map("link.png", shown, "a symbolic link");
    /* a sibling folder whose name starts like the scene's: outside too */
    mkdir(tmp_path("scenery"), 0700);
    put(tmp_path("scenery/y.png"), "not read");
    snprintf(shown, sizeof shown, "%s/../scenery/y.png", tmp_path("scene"));
    expect_refused_map("../scenery/y.png", shown, "a sibling folder of the same prefix");
    /* inside (through a '..' that comes back): kept, no warning */
    load_outside(outside_scene("../scene/in.png", "s.mtl"), 0, &sc);
    CHECK_THAT(sc.materials[0].map_kd.path != NULL, "../scene/in.png is inside: kept");
    assert_int_equal(seen.n, 0);
    obj_free(&sc);
    /* --allow-outside-paths: kept as written, no warning, Kd as given */
    load_outside(outside_scene("../x.png", "s.mtl"), 1, &sc);
    snprintf(shown, sizeof shown, "%s/../x.png", tmp_path("scene"));
    assert_string_equal(sc.materials[0].map_kd.path, shown);
    assert_int_equal(seen.n, 0);
    assert_near(sc.materials[0].kd[0], 0, 0);
    obj_free(&sc);
}

static void test_mtllib_outside_folder(void **state)
{
    obj_scene sc;
    char want[1200], *root = fio_resolve(tmpdir);
    (void)state;
    assert_non_null(root);
    load_outside(outside_scene("in.png", "../out.mtl"), 0, &sc);
    snprintf(want, sizeof want,
             "%s:1: mtllib: %s/../out.mtl is outside the scene's folder %s/scene; library not "
             "read; --allow-outside-paths reads it",
             tmp_path("scene/s.obj"), tmp_path("scene"), root);
    CHECK_THAT(seen.n >= 1 && !strcmp(seen.msg[0], want), "warning\n  %s\nwant\n  %s", seen.msg[0],
               want);
    CHECK_THAT(!sc.materials[0].defined, "material m is not defined from the library outside");
    obj_free(&sc);
    load_outside(outside_scene("in.png", "../out.mtl"), 1, &sc);
    assert_int_equal(seen.n, 0);
    CHECK_THAT(sc.materials[0].defined && sc.materials[0].kd[2] == 0.3,
               "m read from ../out.mtl with the option");
    obj_free(&sc);
    free(root);
}

/* ---- the memory budget --------------------------------------------------------- */

/* 3 vertices and 100 faces "f 1 2 3" (824 bytes of text) under a budget of 2000 bytes:
   the text, 24 bytes a vertex and 24 + 3 x 12 a face make 896 + 60 k after k faces,
   over 2000 from the 19th face, line 22: refused there, before anything is parsed. */
static void test_memory_budget(void **state)
{
    char text[1000];
    size_t n = 0;
    int i;
    obj_scene sc;
    (void)state;
    n += (size_t)sprintf(text, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for (i = 0; i < 100; i++) n += (size_t)sprintf(text + n, "f 1 2 3\n");
    assert_int_equal(n, 824);
    assert_int_equal(setenv("RAD_MEMORY_BUDGET", "2000", 1), 0);
    expect_error_at(
        text, n,
        "mem.obj:22: loading the scene up to this line needs more than the memory budget of "
        "0.002 MB (19 faces so far; RAD_MEMORY_BUDGET): simplify or split the scene",
        __FILE__, __LINE__);
    assert_int_equal(setenv("RAD_MEMORY_BUDGET", "2060", 1), 0); /* one face more: line 23 */
    expect_error_at(
        text, n,
        "mem.obj:23: loading the scene up to this line needs more than the memory budget of "
        "0.00206 MB (20 faces so far; RAD_MEMORY_BUDGET): simplify or split the scene",
        __FILE__, __LINE__);
    assert_int_equal(setenv("RAD_MEMORY_BUDGET", "6896", 1), 0); /* 896 + 6000: all of it fits */
    assert_int_equal(obj_parse(text, n, "mem.obj", NULL, &sc, NULL, NULL, err, sizeof err), 0);
    assert_int_equal(sc.nfaces, 100);
    obj_free(&sc);
    unsetenv("RAD_MEMORY_BUDGET");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_index_forms),
        cmocka_unit_test(test_negative_indices),
        cmocka_unit_test(test_grouping_and_comments),
        cmocka_unit_test(test_unknown_statements_counted),
        cmocka_unit_test(test_continuations),
        cmocka_unit_test(test_crlf),
        cmocka_unit_test(test_number_forms),
        cmocka_unit_test(test_polygons),
        cmocka_unit_test(test_concave_tilted),
        cmocka_unit_test(test_degenerate_polygon),
        cmocka_unit_test(test_materials),
        cmocka_unit_test(test_usemtl_before_mtllib),
        cmocka_unit_test(test_missing_mtl),
        cmocka_unit_test(test_mtl_errors),
        cmocka_unit_test(test_index_errors),
        cmocka_unit_test(test_number_errors),
        cmocka_unit_test(test_empty),
        cmocka_unit_test(test_binary),
        cmocka_unit_test(test_long_lines),
        cmocka_unit_test(test_missing_obj),
        cmocka_unit_test(test_map_outside_folder),
        cmocka_unit_test(test_mtllib_outside_folder),
        cmocka_unit_test(test_memory_budget),
    };
    return cmocka_run_group_tests_name("obj", tests, group_setup, group_teardown);
}
