/* SPDX-License-Identifier: MIT */
/* One-sided faces in what is gathered from a solution: the lightmap's texels
 * (tools/bake/lightmap.c), the final gather's vertices and pixels (tools/host/fgather.c)
 * and the probes all see a face's back as the solve leaves it: opaque and black.
 *
 * The scene: a lamp above a one-sided panel facing up, over a floor. The lamp's shots
 * meet the panel's front, so the solve leaves the floor under the panel dark; a gather
 * from that floor looks at the panel's back, and a cube that left backs out saw the lamp
 * through the panel (the lightmap's texel there was the floor's brightest).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sys/wait.h>

#include <cmocka.h>

#include "check.h"
#include "tmpdir.h"
#include "bake/lightmap.h"
#include "formats/file_io.h"
#include "formats/obj.h"
#include "host/fgather.h"
#include "host/polys.h"
#include "host/scene.h"

TMPDIR_GROUP("sides")

#define GATHER_RES 64
#define RHO        0.5

/* Floor 4 x 4 at y = 0 facing up; panel 1 x 1 at y = 1 facing up; lamp 0.5 x 0.5 at
 * y = 2 facing down (emission 10). The lamp's edge at x = 0.25 and the panel's at 0.5
 * put the umbra on the floor at |x|, |z| < 0.75 and the penumbra out to 1.25. */
static const char panel_obj[] = "mtllib panel.mtl\n"
                                "v -2 0 -2\nv -2 0 2\nv 2 0 2\nv 2 0 -2\n"
                                "v -0.5 1 -0.5\nv -0.5 1 0.5\nv 0.5 1 0.5\nv 0.5 1 -0.5\n"
                                "v -0.25 2 -0.25\nv 0.25 2 -0.25\nv 0.25 2 0.25\nv -0.25 2 0.25\n"
                                "usemtl grey\nf 1 2 3 4\nf 5 6 7 8\n"
                                "usemtl lamp\nf 9 10 11 12\n";
static const char panel_mtl[] = "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n";

typedef struct {
    obj_scene sc;
    sc_poly *p;
    int n;
    sc_solver *s;
} scene_t;

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* OBJ and MTL written, loaded and solved at the default element size, without the
 * ambient term read anywhere below (so "dark" is exactly zero). */
static void panel_scene(scene_t *t)
{
    char err[512] = "";
    sc_opts o;
    write_file(tmp_path("panel.obj"), panel_obj);
    write_file(tmp_path("panel.mtl"), panel_mtl);
    memset(t, 0, sizeof *t);
    if (obj_load(tmp_path("panel.obj"), &t->sc, NULL, NULL, err, sizeof err) < 0)
        fail_msg("%s", err);
    t->p = polys_from_obj(&t->sc, &t->n, NULL, NULL);
    assert_non_null(t->p);
    memset(&o, 0, sizeof o);
    o.res = 128;
    t->s = sc_create(t->p, t->n, &o, NULL, NULL, err, sizeof err);
    if (!t->s) fail_msg("sc_create: %s", err);
    CHECK_INT_GT(sc_solve(t->s, 100000, 1e-4, NULL, NULL), 0, "shots");
}

static void scene_free(scene_t *t)
{
    sc_destroy(t->s);
    free(t->p);
    obj_free(&t->sc);
}

static int under_panel(const double *p)
{
    return fabs(p[0]) <= 0.5 && fabs(p[2]) <= 0.5;
}

static int gather_cb(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    return sc_gather(ctx, p, n, 0, rgb);
}

/* The solve's floor under the panel is dark: every floor element there shows 0 (no
 * shot reaches it: the lamp's meet the panel's front, the panel's look up). */
static void check_solve_dark(scene_t *t)
{
    sc_stats st;
    int e, n = 0;
    sc_get_stats(t->s, &st);
    for (e = 0; e < st.elements; e++) {
        double c[3], rgb[3];
        sc_element_centroid(t->s, e, c);
        if (sc_element_tag(t->s, e) != 0 || !under_panel(c)) continue;
        sc_element_rgb(t->s, e, 0, rgb);
        CHECK_EQ(rgb[1], 0.0, "the solve's floor element %d at (%.3f, %.3f) under the panel", e,
                 c[0], c[2]);
        n++;
    }
    CHECK_INT_GE(n, 16, "floor elements under the panel");
}

/* The lightmap's floor texels under the panel hold E = 0 exactly: from there the cube
 * sees the panel's back (black, up to 45 degrees from the zenith, while the lamp lies
 * within 9.5 degrees of it: hidden with a margin of many pixels), the void around it,
 * and no other surface's front (the floor is one plane below the lifted sample). Before
 * backs were drawn, the lamp showed through the panel: the floor's brightest texels.
 * Elsewhere on the floor, away from the penumbra (|x| or |z| in 0.75..1.25, widened by
 * an element), the texel under each element's centre against the element's E = B /
 * rho: the element's mean over its area against a point value, and the cube's aliasing
 * of the small lamp (up to 4% at resolution 64, tests/test_bake.c's Lambert test on
 * a smaller lamp): bound 5% of the floor's brightest. */
static void test_lightmap_backs(void **state)
{
    scene_t t;
    lm_atlas a;
    lm_opts lo = {128, 0.0, 0, LM_TOL, 0.0};
    char err[256] = "";
    sc_gatherer *g;
    sc_stats st;
    double worst_under = 0.0, peak = 0.0, worst = 0.0;
    int x, y, e, under = 0, compared = 0;
    (void)state;
    panel_scene(&t);
    check_solve_dark(&t);
    g = sc_gatherer_new(t.s, GATHER_RES, 0);
    assert_non_null(g);
    CHECK_INT_EQ(lm_build(&a, t.p, t.n, &lo, err, sizeof err), 0, "lm_build (%s)", err);
    CHECK_INT_EQ(lm_bake(&a, gather_cb, NULL, g), 0, "lm_bake");
    for (y = 0; y < a.size; y++)
        for (x = 0; x < a.size; x++) {
            double p[3];
            size_t at = (size_t)y * a.size + x;
            if (!lm_texel_point(&a, x, y, p) || a.poly[at] != 0) continue;
            peak = fmax(peak, a.rgb[3 * at + 1]);
            if (!under_panel(p)) continue;
            CHECK_EQ(a.rgb[3 * at + 1], 0.0, "floor texel %d,%d at (%.3f, %.3f) under the panel", x,
                     y, p[0], p[2]);
            worst_under = fmax(worst_under, a.rgb[3 * at + 1]);
            under++;
        }
    CHECK_INT_GE(under, 100, "floor texels under the panel");
    sc_get_stats(t.s, &st);
    for (e = 0; e < st.elements; e++) {
        double c[3], rgb[3], xy[2], lm[3], ax, az, half = 0.125;
        sc_element_centroid(t.s, e, c);
        ax = fabs(c[0]);
        az = fabs(c[2]);
        if (sc_element_tag(t.s, e) != 0) continue;
        if ((ax > 0.75 - half && ax < 1.25 + half && az < 1.25 + half) ||
            (az > 0.75 - half && az < 1.25 + half && ax < 1.25 + half))
            continue; /* the penumbra */
        sc_element_rgb(t.s, e, 0, rgb);
        lm_uv(&a, 0, c, xy);
        lm_lookup(&a, xy, lm);
        CHECK_LE(fabs(lm[1] - rgb[1] / RHO), 0.05 * peak,
                 "element %d at (%.3f, %.3f): lightmap %.5f, solve %.5f", e, c[0], c[2], lm[1],
                 rgb[1] / RHO);
        worst = fmax(worst, fabs(lm[1] - rgb[1] / RHO) / peak);
        compared++;
    }
    printf("lightmap under a one-sided panel: %d floor texels under it, largest E %.3g (solve 0, "
           "bound 0); "
           "elsewhere %d elements against the texel at their centre, worst %.2f%% of the floor's "
           "brightest E %.4f "
           "(bound 5%%)\n",
           under, worst_under, compared, 100.0 * worst, peak);
    lm_free(&a);
    sc_gatherer_free(g);
    scene_free(&t);
}

/* The final gather (--gather): the floor's core vertices under the panel, and the
 * pixels of a view looking under it, show 0 (the reason as for the texels above). */
static void test_fgather_backs(void **state)
{
    const sc_camera cam = {{0, 0.5, 3}, {0, 0, 0}, {0, 1, 0}, 10.0};
    enum { W = 33, H = 33 };
    scene_t t;
    sc_fgather *f;
    const double *ve;
    const unsigned char *ok;
    float rgb[3 * W * H];
    char err[256] = "";
    sc_stats st;
    double worst = 0.0, centre;
    int v, n = 0, x, y;
    (void)state;
    panel_scene(&t);
    f = sc_fgather_new(t.s, t.p, t.n, GATHER_RES, 1, 0);
    assert_non_null(f);
    CHECK_INT_EQ(sc_fgather_vertices(f, &ve, &ok), 0, "sc_fgather_vertices");
    sc_get_stats(t.s, &st);
    for (v = 0; v < st.vertices; v++) {
        double p[3];
        sc_vertex_pos(t.s, v, p);
        if (!ok[v] || fabs(p[1]) > 1e-9 || !under_panel(p)) continue;
        CHECK_EQ(ve[3 * v + 1], 0.0, "gathered floor vertex %d at (%.3f, %.3f) under the panel", v,
                 p[0], p[2]);
        worst = fmax(worst, ve[3 * v + 1]);
        n++;
    }
    CHECK_INT_GE(n, 16, "floor vertices under the panel");
    /* The view's middle 3 x 3 pixels show the floor within 0.2 of the origin (a 10
     * degree view from 3 away, 9.5 degrees above the floor: 0.06 a pixel along z). */
    CHECK_INT_EQ(sc_fgather_render(f, &cam, W, H, rgb, NULL, err, sizeof err), 0,
                 "sc_fgather_render (%s)", err);
    centre = 0.0;
    for (y = H / 2 - 1; y <= H / 2 + 1; y++)
        for (x = W / 2 - 1; x <= W / 2 + 1; x++) centre = fmax(centre, rgb[3 * (y * W + x) + 1]);
    CHECK_EQ(centre, 0.0,
             "the brightest of the view's middle 3 x 3 pixels (the floor under the panel)");
    printf("final gather under a one-sided panel: %d floor vertices, largest E %.3g; the view's "
           "middle pixels %.3g "
           "(solve 0, bound 0)\n",
           n, worst, centre);
    sc_fgather_free(f);
    scene_free(&t);
}

/* A probe under the panel: above it the panel's back (black) and the void, below it
 * the floor, so the band-1 coefficient along +y (sh[1]: the radiosity seen weighted by
 * the direction's y) is at most 0: only directions below the horizon show light (each
 * pixel's weight is its centre's direction, and the floor is drawn below the horizon
 * only). Through the panel the lamp made it positive. */
static void test_probe_backs(void **state)
{
    const double p[3] = {0, 0.5, 0};
    double sh[9][3];
    scene_t t;
    sc_gatherer *g;
    (void)state;
    panel_scene(&t);
    g = sc_gatherer_new(t.s, GATHER_RES, 1);
    assert_non_null(g);
    CHECK_INT_EQ(sc_gather_sh(g, p, 0, sh), 0, "sc_gather_sh");
    CHECK_LE(sh[1][1], 0.0, "the probe's SH y coefficient under the panel (SH0 %.4f)", sh[0][1]);
    CHECK_GT(sh[0][1], 0.0, "the probe's SH0: the lit floor around is seen");
    printf("probe under a one-sided panel: SH0 %.4f, SH y %.4f (bound <= 0)\n", sh[0][1], sh[1][1]);
    sc_gatherer_free(g);
    scene_free(&t);
}

/* The float twin's final gather: its floor vertices under the panel show 0 too (the
 * same source, the reason as above). */
static void test_float_twin_backs(void **state)
{
    scene_t t;
    scf_solver *s;
    scf_fgather *f;
    sc_opts o;
    sc_stats st;
    const double *ve;
    const unsigned char *ok;
    char err[256] = "";
    int v, n = 0;
    (void)state;
    panel_scene(&t);
    memset(&o, 0, sizeof o);
    o.res = 128;
    s = scf_create(t.p, t.n, &o, NULL, NULL, err, sizeof err);
    if (!s) fail_msg("scf_create: %s", err);
    CHECK_INT_GT(scf_solve(s, 100000, 1e-4, NULL, NULL), 0, "shots of the float twin");
    f = scf_fgather_new(s, t.p, t.n, GATHER_RES, 1, 0);
    assert_non_null(f);
    CHECK_INT_EQ(scf_fgather_vertices(f, &ve, &ok), 0, "scf_fgather_vertices");
    scf_get_stats(s, &st);
    for (v = 0; v < st.vertices; v++) {
        double p[3];
        scf_vertex_pos(s, v, p);
        if (!ok[v] || fabs(p[1]) > 1e-9 || !under_panel(p)) continue;
        CHECK_EQ(ve[3 * v + 1], 0.0, "the float twin's floor vertex %d at (%.3f, %.3f)", v, p[0],
                 p[2]);
        n++;
    }
    CHECK_INT_GE(n, 16, "the float twin's floor vertices under the panel");
    scf_fgather_free(f);
    scf_destroy(s);
    scene_free(&t);
}

/* ---- winding against vn, and --two-sided ------------------------------------------ */

/* Runs build/rad_cli on OBJ (in the temporary directory) with ARGS, --quiet-free so that
 * warnings show, stderr into *ERR (malloc'd); returns the exit status. */
static int cli(const char *obj, const char *args, char **err)
{
    char cmd[2048];
    size_t len;
    int st;
    snprintf(cmd, sizeof cmd, "build/rad_cli %s --res 32 --tol 0.01 -o %s %s 2> %s", tmp_path(obj),
             tmp_path("out.png"), args, tmp_path("cli.err"));
    st = system(cmd);
    if (fio_read_all(tmp_path("cli.err"), 1u << 20, err, &len, NULL, 0) != 0) *err = NULL;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static char *read_text(const char *path)
{
    char *text = NULL;
    size_t len;
    CHECK_INT_EQ(fio_read_all(path, 1u << 24, &text, &len, NULL, 0), 0, "%s read back", path);
    return text;
}

/* A closed unit box lit by a lamp under its ceiling, every face's vn pointing into the
 * room. BOX_WRONG winds the ceiling, the four walls and the lamp outwards (against
 * their vn; the floor agrees), BOX_RIGHT winds every face into the room, each written
 * as BOX_WRONG's reversed. 5 walls and the lamp: 5.04 of 6.04 units of area, 83.4%. */
#define BOX_HEAD                                                                               \
    "mtllib box.mtl\n"                                                                         \
    "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"                 \
    "v 0.4 0.99 0.4\nv 0.6 0.99 0.4\nv 0.6 0.99 0.6\nv 0.4 0.99 0.6\n"                         \
    "vn 0 1 0\nvn 0 -1 0\nvn 1 0 0\nvn -1 0 0\nvn 0 0 1\nvn 0 0 -1\nusemtl grey\nf 1//1 4//1 " \
    "3//1 2//1\n"
static const char box_wrong[] =
    BOX_HEAD "f 8//2 7//2 6//2 5//2\nf 4//3 8//3 5//3 1//3\nf 6//4 7//4 3//4 2//4\n"
             "f 5//5 6//5 2//5 1//5\nf 3//6 7//6 8//6 4//6\n"
             "usemtl lamp\nf 12//2 11//2 10//2 9//2\n";
static const char box_right[] =
    BOX_HEAD "f 5//2 6//2 7//2 8//2\nf 1//3 5//3 8//3 4//3\nf 2//4 3//4 7//4 6//4\n"
             "f 1//5 2//5 6//5 5//5\nf 4//6 8//6 7//6 3//6\n"
             "usemtl lamp\nf 9//2 10//2 11//2 12//2\n";
static const char box_mtl[] = "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n";

/* The box wound against its vn lights as the box wound right, to the bit (each turned
 * face is the right one's corners in the same order): the same --dump-radiosity file,
 * every element lit; and rad_cli says how many faces it turned and their share of the
 * area. Before, the room's inside was the walls' backs: black. */
static void test_winding_by_normals(void **state)
{
    char *err = NULL, *wrong, *right, args[512];
    const char *line;
    int rows = 0, lit = 0;
    (void)state;
    write_file(tmp_path("box.mtl"), box_mtl);
    write_file(tmp_path("wrong.obj"), box_wrong);
    write_file(tmp_path("right.obj"), box_right);
    snprintf(args, sizeof args, "--dump-radiosity %s", tmp_path("right.csv"));
    CHECK_INT_EQ(cli("right.obj", args, &err), 0, "exit status on the box wound right (%s)",
                 err ? err : "");
    CHECK_LACKS(err, "wound against", "no faces turned in the box wound right");
    free(err);
    snprintf(args, sizeof args, "--dump-radiosity %s", tmp_path("wrong.csv"));
    CHECK_INT_EQ(cli("wrong.obj", args, &err), 0,
                 "exit status on the box wound against its vn (%s)", err ? err : "");
    CHECK_CONTAINS(
        err, "6 faces (83.4% of the area) were wound against their vn normals and were flipped",
        "the warning");
    free(err);
    wrong = read_text(tmp_path("wrong.csv"));
    right = read_text(tmp_path("right.csv"));
    for (line = strchr(right, '\n'); line && line[1]; line = strchr(line + 1, '\n')) {
        const char *c = line + 1;
        int k;
        for (k = 0; k < 7 && c; k++) c = strchr(c + 1, ','); /* to r, g, b */
        lit += c && strtod(c + 1, NULL) > 0.0;
        rows++;
    }
    /* all but the ceiling above the lamp, in its shadow (the lamp is 0.01 below it) */
    CHECK_INT_GE(lit, rows - rows / 20, "elements lit in the box wound right, of %d", rows);
    CHECK_INT_EQ(strcmp(wrong, right), 0,
                 "the box wound against its vn gives the right one's --dump-radiosity");
    printf("winding against vn: 6 faces turned (83.4%% of the area); %d elements (%d lit) the same "
           "as the box wound "
           "right\n",
           rows, lit);
    free(wrong);
    free(right);
}

/* A one-sided panel facing up between a red lamp above and a blue one below. With
 * --two-sided (polys_two_sided, as rad_cli does) each side is a face: the top receives
 * only red, the bottom only blue, and the lightmap's charts of the two sides mirror
 * each other: their mean E within 1% (the scene is its own mirror image through the
 * panel's plane, but for the cube's turns and rounding: measured equal to 5 digits). Before,
 * the panel had no bottom: the blue light passed its back. */
static const char panel2_obj[] =
    "mtllib panel2.mtl\n"
    "v -0.5 0 -0.5\nv -0.5 0 0.5\nv 0.5 0 0.5\nv 0.5 0 -0.5\n"
    "v -0.25 1 -0.25\nv 0.25 1 -0.25\nv 0.25 1 0.25\nv -0.25 1 0.25\n"
    "v -0.25 -1 -0.25\nv -0.25 -1 0.25\nv 0.25 -1 0.25\nv 0.25 -1 -0.25\n"
    "usemtl grey\nf 1 2 3 4\nusemtl red\nf 5 6 7 8\nusemtl blue\nf 9 10 11 12\n";
static const char panel2_mtl[] = "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl red\nKd 0 0 0\nKe 10 0 0\n"
                                 "newmtl blue\nKd 0 0 0\nKe 0 0 10\n";

static void test_two_sided(void **state)
{
    obj_scene sc;
    sc_poly *p;
    sc_solver *s;
    sc_gatherer *g;
    sc_opts o;
    lm_atlas a;
    lm_opts lo = {64, 0.0, 0, LM_TOL, 0.0};
    char err[512] = "", *cerr = NULL, args[512], *csv;
    const char *line;
    double sum[2][3] = {{0}}, rel;
    int n, x, y, cnt[2] = {0, 0}, lit[2] = {0, 0};
    (void)state;
    write_file(tmp_path("panel2.obj"), panel2_obj);
    write_file(tmp_path("panel2.mtl"), panel2_mtl);
    /* rad_cli's elements (without the ambient term, which mixes every lamp's colour) */
    snprintf(args, sizeof args, "--two-sided --no-ambient --dump-radiosity %s",
             tmp_path("two.csv"));
    CHECK_INT_EQ(cli("panel2.obj", args, &cerr), 0, "exit status with --two-sided (%s)",
                 cerr ? cerr : "");
    free(cerr);
    csv = read_text(tmp_path("two.csv"));
    for (line = strchr(csv, '\n'); line && line[1]; line = strchr(line + 1, '\n')) {
        double v[7];
        const char *c = strchr(line + 1, ',');
        int k;
        c = c ? strchr(c + 1, ',') : NULL; /* past the surface */
        c = c ? strchr(c + 1, ',') : NULL; /* past the material */
        for (k = 0; k < 7 && c; k++) {
            v[k] = strtod(c + 1, NULL);
            c = strchr(c + 1, ',');
        }
        if (k < 7 || v[2] != 0.0) continue; /* cy: the panel's elements */
        if (v[4] > 0 && v[6] == 0) lit[0]++;
        if (v[6] > 0 && v[4] == 0) lit[1]++;
    }
    free(csv);
    CHECK_INT_GT(lit[0], 0, "rad_cli --two-sided: panel elements lit red alone");
    CHECK_INT_EQ(lit[1], lit[0],
                 "rad_cli --two-sided: panel elements lit blue alone, as many as red");
    /* the lightmap of both sides */
    if (obj_load(tmp_path("panel2.obj"), &sc, NULL, NULL, err, sizeof err) < 0) fail_msg("%s", err);
    CHECK_INT_EQ(polys_two_sided(&sc), 0, "polys_two_sided");
    CHECK_INT_EQ(sc.nfaces, 6, "faces after polys_two_sided");
    p = polys_from_obj(&sc, &n, NULL, NULL);
    assert_non_null(p);
    memset(&o, 0, sizeof o);
    o.res = 128;
    s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    if (!s) fail_msg("sc_create: %s", err);
    CHECK_INT_GT(sc_solve(s, 100000, 1e-4, NULL, NULL), 0, "shots");
    g = sc_gatherer_new(s, GATHER_RES, 0);
    assert_non_null(g);
    CHECK_INT_EQ(lm_build(&a, p, n, &lo, err, sizeof err), 0, "lm_build (%s)", err);
    CHECK_INT_EQ(lm_bake(&a, gather_cb, NULL, g), 0, "lm_bake");
    for (y = 0; y < a.size; y++)
        for (x = 0; x < a.size; x++) {
            size_t at = (size_t)y * a.size + x;
            double q[3];
            int side, k;
            if (!lm_texel_point(&a, x, y, q) || (p[a.poly[at]].tag != 0 && p[a.poly[at]].tag != 3))
                continue;
            side = p[a.poly[at]].tag == 3;
            CHECK_EQ(a.rgb[3 * at + (side ? 0 : 2)], 0.0,
                     "texel %d,%d of the panel's %s: the other lamp's channel", x, y,
                     side ? "bottom" : "top");
            for (k = 0; k < 3; k++) sum[side][k] += a.rgb[3 * at + k];
            cnt[side]++;
        }
    CHECK_INT_GT(cnt[0], 100, "texels of the panel's top");
    CHECK_INT_EQ(cnt[1], cnt[0], "texels of the panel's bottom, as many as the top's");
    rel = fabs(sum[0][0] - sum[1][2]) / sum[0][0];
    CHECK_LE(rel, 0.01, "the top's mean red %.5f against the bottom's mean blue %.5f",
             sum[0][0] / cnt[0], sum[1][2] / cnt[1]);
    printf("--two-sided panel: %d elements lit on each side; lightmap %d texels a side, mean red "
           "on top %.5f, "
           "blue below %.5f (%.3f%% apart, bound 1%%)\n",
           lit[0], cnt[0], sum[0][0] / cnt[0], sum[1][2] / cnt[1], 100.0 * rel);
    lm_free(&a);
    sc_gatherer_free(g);
    sc_destroy(s);
    free(p);
    obj_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lightmap_backs),     cmocka_unit_test(test_fgather_backs),
        cmocka_unit_test(test_probe_backs),        cmocka_unit_test(test_float_twin_backs),
        cmocka_unit_test(test_winding_by_normals), cmocka_unit_test(test_two_sided),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
