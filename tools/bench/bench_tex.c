/* SPDX-License-Identifier: MIT */
/* bench_tex — rad_bench's textures table: a generated room with a PNG map on each face,
 * rad_cli with the maps, with --no-textures and on the maps' means as Kd, whole
 * processes in turn. See bench.h.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench/bench.h"
#include "formats/image.h"
#include "formats/texture.h"
#include "host/polys.h"

/* ---- textures: loading and sampling them, whole processes ---------------------------- */

#define TEX_RUNS 9
#define TEX_SIDE 512 /* texels a side of each generated map */
#define TEX_MAPS 7   /* six walls and the block */

typedef struct {
    char why[256];             /* empty when measured; else why not */
    int elements, shots[3];    /* textures, --no-textures, the textures' means as Kd */
    double t[2][3], cpu[2][3]; /* medians per view size (64, 512 square), variant as above */
    double ratio[2][2], cpu_ratio[2][2]; /* the maps over the other two: median per round */
} texbench_t;

/* A map of TEX_SIDE^2: bricks of 64 x 32 in a hue of its own, mortar lines, noise. */
static int write_map(const char *path, int m)
{
    unsigned char *rgb = malloc((size_t)TEX_SIDE * TEX_SIDE * 3);
    int x, y, k, rc;
    if (!rgb) return -1;
    for (y = 0; y < TEX_SIDE; y++)
        for (x = 0; x < TEX_SIDE; x++) {
            unsigned h =
                (unsigned)x * 73856093u ^ (unsigned)y * 19349663u ^ (unsigned)m * 83492791u;
            int mortar = y % 32 < 2 || (x + (y / 32 % 2) * 32) % 64 < 2;
            for (k = 0; k < 3; k++)
                rgb[3 * ((size_t)y * TEX_SIDE + x) + k] =
                    (unsigned char)(mortar ? 200
                                           : 60 + 25 * ((m + k) % 5) + (int)((h >> (8 * k)) % 40));
        }
    rc = img_write(path, rgb, TEX_SIDE, TEX_SIDE, NULL, 0);
    free(rgb);
    return rc;
}

/* DIR/room.obj: a room of 2 m with a block and a lamp, each wall and the block with a
 * map of its own (walls' UVs 0..2: the map twice across), mtllib MTL. */
static int write_room(const char *dir, const char *name, const char *mtl)
{
    static const double grey[3] = {0.5, 0.5, 0.5}, lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    static const double blo[3] = {-0.5, -1, -0.4}, bhi[3] = {0.1, -0.2, 0.3};
    static const double lamp[4][3] = {
        {-0.3, 0.98, -0.3}, {0.3, 0.98, -0.3}, {0.3, 0.98, 0.3}, {-0.3, 0.98, 0.3}};
    sc_poly p[12];
    char path[600];
    FILE *f;
    int n = 0, i, k;
    bench_add_box(p, &n, lo, hi, 1, -1, grey);
    bench_add_box(p, &n, blo, bhi, 0, 2, grey);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (!(f = fopen(path, "w"))) return -1;
    fprintf(f, "mtllib %s\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\nvt 1 0\nvt 1 1\nvt 0 1\n", mtl);
    for (i = 0; i <= n; i++) {
        for (k = 0; k < 4; k++)
            fprintf(f, "v %.17g %.17g %.17g\n", i < n ? p[i].v[k][0] : lamp[k][0],
                    i < n ? p[i].v[k][1] : lamp[k][1], i < n ? p[i].v[k][2] : lamp[k][2]);
        if (i == n)
            fprintf(f, "usemtl lamp\nf -4 -3 -2 -1\n");
        else if (i < 6)
            fprintf(f, "usemtl m%d\nf -4/1 -3/2 -2/3 -1/4\n", i);
        else
            fprintf(f, "usemtl m6\nf -4/1 -3/5 -2/6 -1/7\n");
    }
    return fclose(f);
}

/* DIR/kd.mtl: each material's Kd the reflectance rad gives its textured face (the
 * same bits reach the core), so that solve is the textured one without the maps. */
static int write_kd_mtl(const char *dir, const char *obj)
{
    obj_scene sc;
    tex_image maps[TEX_MAPS + 1];
    sc_poly *p;
    char path[600];
    FILE *f;
    int n, i, m;
    if (obj_load(obj, &sc, NULL, NULL, path, sizeof path) < 0) return -1;
    if (sc.nmaterials > TEX_MAPS + 1 || tex_load_materials(&sc, maps, NULL, NULL, 1) != TEX_MAPS) {
        obj_free(&sc);
        return -1;
    }
    p = polys_from_obj_tex(&sc, maps, &n, NULL, NULL);
    snprintf(path, sizeof path, "%s/kd.mtl", dir);
    f = p ? fopen(path, "w") : NULL;
    for (m = 0; f && m < sc.nmaterials; m++)
        for (i = 0; i < n; i++)
            if (sc.faces[p[i].tag].material == m) {
                fprintf(f, "newmtl %s\nKd %.17g %.17g %.17g\nKe %.17g %.17g %.17g\n",
                        sc.materials[m].name, p[i].rho[0], p[i].rho[1], p[i].rho[2], p[i].emit[0],
                        p[i].emit[1], p[i].emit[2]);
                break;
            }
    for (m = 0; m < sc.nmaterials; m++) tex_free(&maps[m]);
    free(p);
    obj_free(&sc);
    return f && fclose(f) == 0 ? 0 : -1;
}

static int make_tex_scene(const char *dir)
{
    char path[600];
    FILE *f;
    int m;
    snprintf(path, sizeof path, "%s/room.mtl", dir);
    if (!(f = fopen(path, "w"))) return -1;
    for (m = 0; m < TEX_MAPS; m++) fprintf(f, "newmtl m%d\nKd 0 0 0\nmap_Kd map%d.png\n", m, m);
    fprintf(f, "newmtl lamp\nKd 0 0 0\nKe 12 12 12\n");
    if (fclose(f) != 0) return -1;
    for (m = 0; m < TEX_MAPS; m++) {
        snprintf(path, sizeof path, "%s/map%d.png", dir, m);
        if (write_map(path, m) < 0) return -1;
    }
    snprintf(path, sizeof path, "%s/room.obj", dir);
    if (write_room(dir, "room.obj", "room.mtl") < 0 || write_room(dir, "room_kd.obj", "kd.mtl") < 0)
        return -1;
    return write_kd_mtl(dir, path);
}

/* The three variants' shots and elements, solved here at rad_cli's settings. */
static void tex_shots(const char *dir, texbench_t *tb)
{
    static const char *const obj[3] = {"room.obj", "room.obj", "room_kd.obj"};
    int v;
    for (v = 0; v < 3; v++) {
        obj_scene sc;
        tex_image maps[TEX_MAPS + 1];
        /* rad_cli's */
        sc_opts o =
            bench_row_opts((sc_opts){.max_element = 0.08, .max_patch = 0.32}, &bench_peer_rows[1]);
        char path[600], err[256];
        sc_poly *p;
        sc_solver *s;
        sc_stats st;
        int n, m;
        snprintf(path, sizeof path, "%s/%s", dir, obj[v]);
        if (obj_load(path, &sc, NULL, NULL, err, sizeof err) < 0) continue;
        if (v == 0) tex_load_materials(&sc, maps, NULL, NULL, 1);
        p = v == 0 ? polys_from_obj_tex(&sc, maps, &n, NULL, NULL)
                   : polys_from_obj(&sc, &n, NULL, NULL);
        if (v == 1)
            for (m = 0; p && m < n; m++) /* --no-textures: Kd 0 shows 0.5 grey (obj_map_fallback) */
                if (p[m].emit[0] == 0) p[m].rho[0] = p[m].rho[1] = p[m].rho[2] = 0.5;
        s = p ? sc_create(p, n, &o, NULL, NULL, err, sizeof err) : NULL;
        if (s) {
            tb->shots[v] = sc_solve(s, 1000000, 0.001, NULL, NULL);
            sc_get_stats(s, &st);
            tb->elements = st.elements;
            sc_destroy(s);
        }
        if (v == 0)
            for (m = 0; m < sc.nmaterials; m++) tex_free(&maps[m]);
        free(p);
        obj_free(&sc);
    }
}

/* rad_cli with the maps, with --no-textures, and on the maps' means as Kd, whole
 * processes in turn, TEX_RUNS rounds, views of 64 and 512 square. */
static void tex_bench(const char *self, texbench_t *tb)
{
    static const char *const files[] = {"room.obj", "room_kd.obj", "room.mtl", "kd.mtl",
                                        "view.png"};
    char dir[64] = "/tmp/rad_bench_tex.XXXXXX", cli[1024], here[512], room[600], kd[600], png[600];
    char w[2][8] = {"64", "512"};
    double t[2][3][TEX_RUNS], c[2][3][TEX_RUNS], r[2][2][TEX_RUNS], rc[2][2][TEX_RUNS];
    int i, k, v, m;
    long kb;
    memset(tb, 0, sizeof *tb);
    bench_dir_of(self, here, sizeof here);
    snprintf(cli, sizeof cli, "%s/rad_cli", here);
    if (!bench_is_file(cli)) {
        snprintf(tb->why, sizeof tb->why, "no %.200s", cli);
        return;
    }
    if (!mkdtemp(dir) || make_tex_scene(dir) < 0) {
        snprintf(tb->why, sizeof tb->why, "the scene could not be written");
        return;
    }
    snprintf(room, sizeof room, "%s/room.obj", dir);
    snprintf(kd, sizeof kd, "%s/room_kd.obj", dir);
    snprintf(png, sizeof png, "%s/view.png", dir);
    fprintf(stderr, "rad_bench: textures, %d rounds ...\n", TEX_RUNS);
    tex_shots(dir, tb);
    for (i = 0; i < TEX_RUNS && !tb->why[0]; i++)
        for (k = 0; k < 2; k++)
            for (v = 0; v < 3; v++) {
                char *cmd[16] = {cli,
                                 v == 2 ? kd : room,
                                 "--max-element",
                                 "0.08",
                                 "--width",
                                 w[k],
                                 "--height",
                                 w[k],
                                 "-o",
                                 png,
                                 v == 1 ? "--no-textures" : NULL,
                                 NULL};
                if (bench_run_child(cmd, NULL, &t[k][v][i], &c[k][v][i], &kb) < 0)
                    snprintf(tb->why, sizeof tb->why, "rad_cli failed");
            }
    for (m = 0; m < TEX_MAPS; m++) {
        snprintf(png, sizeof png, "%s/map%d.png", dir, m);
        remove(png);
    }
    for (m = 0; m < 5; m++) {
        snprintf(png, sizeof png, "%s/%s", dir, files[m]);
        remove(png);
    }
    rmdir(dir);
    if (tb->why[0]) return;
    for (k = 0; k < 2; k++) {
        for (i = 0; i < TEX_RUNS; i++)
            for (v = 0; v < 2; v++) {
                r[k][v][i] = t[k][0][i] / t[k][v + 1][i];
                rc[k][v][i] = c[k][0][i] / c[k][v + 1][i];
            }
        for (v = 0; v < 3; v++) {
            tb->t[k][v] = bench_median(t[k][v], TEX_RUNS);
            tb->cpu[k][v] = bench_median(c[k][v], TEX_RUNS);
        }
        for (v = 0; v < 2; v++) {
            tb->ratio[k][v] = bench_median(r[k][v], TEX_RUNS);
            tb->cpu_ratio[k][v] = bench_median(rc[k][v], TEX_RUNS);
        }
    }
}

void bench_report_textures(report_t *rp, const char *self)
{
    static const char *const nm[3] = {"with the maps", "`--no-textures` (Kd 0: 0.5 grey)",
                                      "the maps' means as Kd (the faces' means)"};
    texbench_t tb;
    int k, v;
    tex_bench(self, &tb);
    bench_out(
        rp,
        "\nTextures: a generated room of 2 m (six walls and a block, each with a %d x %d PNG "
        "map_Kd of its "
        "own, the walls' twice across; a lamp), `rad_cli --max-element 0.08` (fixed build, its "
        "defaults: res 192, "
        "coarse shots), whole processes in turn, %d rounds: medians of wall and processor (user + "
        "system) time and of "
        "each round's ratio (the run with the maps over this one). The maps change the light, so "
        "`--no-textures` solves another scene; the third run gives every face the reflectance the "
        "maps give it as "
        "Kd: the solve without loading or sampling a map, but for the maps' run giving each "
        "element the mean of "
        "its own footprint (the light moves within a face; the shots differ by a few). ",
        TEX_SIDE, TEX_SIDE, TEX_RUNS);
    if (tb.why[0]) {
        bench_out(rp, "Not measured: %s.\n", tb.why);
        return;
    }
    bench_out(
        rp,
        "%d elements.\n\n| run | shots to 0.001 | view | wall s | ratio | processor s | ratio |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n",
        tb.elements);
    for (v = 0; v < 3; v++)
        for (k = 0; k < 2; k++) {
            char a[2][32] = {"", ""};
            if (v > 0) {
                snprintf(a[0], sizeof a[0], "%.2f", tb.ratio[k][v - 1]);
                snprintf(a[1], sizeof a[1], "%.2f", tb.cpu_ratio[k][v - 1]);
            }
            bench_out(rp, "| %s | %d | %s | %.3f | %s | %.3f | %s |\n", k ? "" : nm[v], tb.shots[v],
                      k ? "512" : "64", tb.t[k][v], a[0], tb.cpu[k][v], a[1]);
        }
}
