/* SPDX-License-Identifier: MIT */
/* The camera through the shared rasterizer: orientation, Gouraud interpolation,
 * depth order, and vertex shading's area weights (fixed build and float twin). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "check.h"
#include "core_values.h"
#include "rad/rad.h"

#define W 64
#define H 48

static rad_surface_t sf[8];
static rad_patch_t pt[512];
static rad_element_t el[512];
static rad_vec3_t vx[1024];
static unsigned char work[RAD_WORK_BYTES(16, RAD_PIXELS_ALL(16), 1024)];
static rad_rgb_t vrgb[1024], fb[W * H];
static uint32_t zb[W * H];

static void setup(rad_scene_t *s)
{
    rad_pools_t p = {.surfaces = sf,
                     .max_surfaces = 8,
                     .patches = pt,
                     .max_patches = 512,
                     .elements = el,
                     .max_elements = 512,
                     .vertices = vx,
                     .max_vertices = 1024,
                     .work = work,
                     .work_bytes = sizeof work};
    rad_config_t c = {.max_patch = RAD_REAL(2.0), .max_element = RAD_REAL(1.0), .res = 16};
    assert_int_equal(rad_init(s, &p, &c), RAD_OK);
}

static const rad_camera_t cam = {.eye = {0, 0, RAD_REAL(10)},
                                 .target = {0, 0, 0},
                                 .up = {0, RAD_REAL(1), 0},
                                 .tan_half_fov = RAD_REAL(0.5)};

static double px(int x, int y, int ch)
{
    const rad_rgb_t *c = &fb[y * W + x];
    return RAD_TO_DOUBLE(ch == 0 ? c->r : ch == 1 ? c->g : c->b);
}

static void test_gouraud_orientation(void **st)
{
    rad_scene_t s;
    /* A 6 x 6 quad at z = 0 facing the camera on +z; vertex colour r = (x + 3) / 6,
     * g = (y + 3) / 6: red grows to the right, green to the top. */
    rad_vec3_t q[4] = {V(-3, -3, 0), V(3, -3, 0), V(3, 3, 0), V(-3, 3, 0)};
    uint32_t v;
    int x, y, n;
    (void)st;
    setup(&s);
    assert_int_equal(rad_add_polygon(&s, q, 4, NULL, NULL), 0);
    for (v = 0; v < s.n_vertices; v++) {
        vrgb[v].r = RAD_REAL((RAD_TO_DOUBLE(vx[v].x) + 3) / 6);
        vrgb[v].g = RAD_REAL((RAD_TO_DOUBLE(vx[v].y) + 3) / 6);
        vrgb[v].b = RAD_REAL(0.25);
    }
    n = rad_render(&s, vrgb, &cam, fb, zb, W, H);
    CHECK_INT_GE(n, 2, "triangles drawn of the quad");
    /* The quad spans x, y in [-3, 3] at distance 10; tan(half fov) = 0.5 vertically:
     * 3 / 5 of the half height, the same in pixels horizontally. */
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            double sx = (x + 0.5 - W / 2.0) / (H / 2.0) * 5.0; /* scene x at this pixel */
            double sy = (H / 2.0 - y - 0.5) / (H / 2.0) * 5.0; /* row 0 is the top */
            if (fabs(sx) < 2.9 && fabs(sy) < 2.9) {
                /* Linear colours interpolate exactly up to the Q16.15 attribute format
                 * and the 1/16-pixel snapping of vertices (1/16 px = 0.006 units). */
                CHECK_LT(fabs(px(x, y, 0) - (sx + 3) / 6), 2e-3,
                         "pixel %d, %d: red's error against (x + 3) / 6", x, y);
                CHECK_LT(fabs(px(x, y, 1) - (sy + 3) / 6), 2e-3,
                         "pixel %d, %d: green's error against (y + 3) / 6", x, y);
                CHECK_LT(fabs(px(x, y, 2) - 0.25), 1e-4, "pixel %d, %d: blue's error against 0.25",
                         x, y);
            } else if (fabs(sx) > 3.1 || fabs(sy) > 3.1) {
                CHECK_EQ(px(x, y, 0), 0, "pixel %d, %d outside the quad: red", x, y);
                CHECK_EQ(px(x, y, 1), 0, "pixel %d, %d outside the quad: green", x, y);
                CHECK_EQ(px(x, y, 2), 0, "pixel %d, %d outside the quad: blue", x, y);
                assert_int_equal(zb[y * W + x], 0);
            }
        }
    /* From behind, the one-sided quad is not drawn at all. */
    {
        rad_camera_t back = cam;
        back.eye.z = RAD_REAL(-10);
        assert_int_equal(rad_render(&s, vrgb, &back, fb, zb, W, H), 0);
    }
}

static void test_depth_order(void **st)
{
    rad_scene_t s;
    rad_vec3_t far[4] = {V(-3, -3, 0), V(3, -3, 0), V(3, 3, 0), V(-3, 3, 0)};
    rad_vec3_t near[4] = {V(-1, -1, 2), V(1, -1, 2), V(1, 1, 2), V(-1, 1, 2)};
    const rad_rgb_t e1 = {RAD_REAL(1), 0, 0}, e2 = {0, RAD_REAL(1), 0};
    uint32_t v;
    (void)st;
    setup(&s);
    /* The near quad is added first, the far one second: the z-buffer, not the order,
     * decides. Emission is the radiosity before any shot. */
    assert_int_equal(rad_add_polygon(&s, near, 4, NULL, &e2), 0);
    assert_int_equal(rad_add_polygon(&s, far, 4, NULL, &e1), 1);
    assert_int_equal(rad_shade_vertices(&s, 0, vrgb, 1024), (int)s.n_vertices);
    /* Vertex shading: each vertex takes its own surface's colour only. */
    for (v = 0; v < s.n_vertices; v++) {
        int on_near = RAD_TO_DOUBLE(vx[v].z) > 1;
        assert_int_equal(vrgb[v].r, on_near ? 0 : RAD_REAL(1));
        assert_int_equal(vrgb[v].g, on_near ? RAD_REAL(1) : 0);
    }
    CHECK_INT_GT(rad_render(&s, vrgb, &cam, fb, zb, W, H), 0, "triangles drawn");
    CHECK_GT(px(W / 2, H / 2, 1), 0.99, "the centre (the near quad): green");
    CHECK_EQ(px(W / 2, H / 2, 0), 0, "the centre (the near quad): red");
    CHECK_GT(px(W / 2 + 12, H / 2, 0), 0.99, "beside the near quad (the far one): red");
    CHECK_EQ(px(W / 2 + 12, H / 2, 1), 0, "beside the near quad (the far one): green");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gouraud_orientation),
        cmocka_unit_test(test_depth_order),
    };
    return cmocka_run_group_tests_name("render", tests, NULL, NULL);
}
