/* SPDX-License-Identifier: MIT */
/* bench_peer — rad_bench's peer table: rad_cli against RenderPark's rpkCpp as whole
 * processes in turn (wall and processor time, peak memory through wait4), and each
 * rad_cli row solved again in this process for its accuracy per element against a
 * res-512 solve of the same mesh. See bench.h.
 */
/* wait4 (each child's own peak memory) is a BSD and Linux call, beyond POSIX. */
#define _DEFAULT_SOURCE
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench/bench.h"
#include "bench/plot.h"
#include "host/clock.h"
#include "host/defaults.h"

/* ---- the peer: whole processes, alternating ------------------------------------- */

#define PEER_RUNS 9

/* Runs ARGV (stdout and stderr to the file OUT, or /dev/null when OUT is NULL) and
 * waits for it: its wall time in SECS, and from wait4's rusage its processor time (user
 * + system) in CPU and its own peak resident memory in KB. Returns 0 when it ran and
 * exited with status 0. */
int bench_run_child(char *const argv[], const char *out, double *secs, double *cpu, long *kb)
{
    struct rusage ru;
    double t0 = host_now();
    int st;
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        int fd = out ? open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644) : open("/dev/null", O_WRONLY);
        if (fd >= 0) {
            dup2(fd, 1);
            dup2(fd, 2);
            close(fd);
        }
        execv(argv[0], argv);
        _exit(127);
    }
    if (wait4(pid, &st, 0, &ru) != pid) return -1;
    *secs = host_now() - t0;
    *cpu = ru.ru_utime.tv_sec + ru.ru_stime.tv_sec +
           1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
    *kb = ru.ru_maxrss;
    return WIFEXITED(st) && WEXITSTATUS(st) == 0 ? 0 : -1;
}

int bench_is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* PATH's folder (up to its last '/', or "." ) into OUT. */
void bench_dir_of(const char *path, char *out, size_t n)
{
    const char *sl = strrchr(path, '/');
    if (!sl)
        snprintf(out, n, ".");
    else
        snprintf(out, n, "%.*s", (int)(sl - path), path);
}

/* rad_cli's defaults (host/defaults.h): the emitters' shots at res 192, the others at 96, 48
 * and 24 as the unshot fraction falls below 1, 1/8 and 1/64 (chosen on
 * CornellBox-Original: more accurate than every shot at 128, about half its time; see
 * the peer table's accuracy column). */
#define DEF_FLOOR DEF_COARSE_FLOOR(DEF_RES)

const peer_row_t bench_peer_rows[PEER_CMDS] = {
    {0.01, 0, DEF_RES, DEF_COARSE, DEF_FLOOR, "--tol 0.01"},
    {0.001, 0, DEF_RES, DEF_COARSE, DEF_FLOOR, "--tol 0.001"},
    {0, 0, 0, 0, 0, NULL}, /* rpkCpp */
    {0.001, 0, 128, 0, 0, "--tol 0.001 --res 128 --coarse 0"},
    {0.001, 0.08, DEF_RES, DEF_COARSE, DEF_FLOOR, "--tol 0.001 --max-element 0.08"},
    {0.001, 0.08, 128, 0, 0, "--tol 0.001 --max-element 0.08 --res 128 --coarse 0"},
    {0.001, 0.08, 256, 2, DEF_COARSE_FLOOR(256),
     "--tol 0.001 --max-element 0.08 --res 256 --coarse 2"}};

/* The peer's scene beside it: converted from the OBJ SCENE with the shared converter
 * (SCENE's folder/../peers/obj2mgf.py) when it is missing. */
static int peer_scene(const char *scene, const char *mgf, peer_t *pr)
{
    char dir[512], conv[1024];
    double t, cpu;
    long kb;
    char *argv[] = {"/usr/bin/env", "python3", conv,          "-o", (char *)mgf,
                    "--channel",    "rgb",     (char *)scene, NULL};
    if (bench_is_file(mgf)) return 0;
    bench_dir_of(scene, dir, sizeof dir);
    snprintf(conv, sizeof conv, "%s/../peers/obj2mgf.py", dir);
    fprintf(stderr, "rad_bench: converting %s to %s ...\n", scene, mgf);
    if (!bench_is_file(conv) || bench_run_child(argv, NULL, &t, &cpu, &kb) < 0 ||
        !bench_is_file(mgf)) {
        snprintf(pr->why, sizeof pr->why, "the scene could not be converted to %s (with %s)", mgf,
                 conv);
        return -1;
    }
    return 0;
}

#define PEER_PATH 1024 /* bytes of a path peer_setup writes; the folder's half that */

/* What a run against the peer on SCENE needs: rpkCpp in $RAD_PEER_RPK, or ../peer-rpk
 * (its build/rpk, and SCENE converted into its cbo.mgf), and rad_cli beside SELF, their
 * paths into RPK, MGF and CLI and rad_cli's folder into DIR. 0, or -1 with the reason in
 * PR->why. */
static int peer_setup(const char *self, const char *scene, char *rpk, char *mgf, char *cli,
                      char *dir, peer_t *pr)
{
    const char *root = getenv("RAD_PEER_RPK");
    if (!root || !*root) root = "../peer-rpk";
    snprintf(rpk, PEER_PATH, "%s/build/rpk", root);
    snprintf(mgf, PEER_PATH, "%s/cbo.mgf", root);
    bench_dir_of(self, dir, PEER_PATH / 2);
    snprintf(cli, PEER_PATH, "%s/rad_cli", dir);
    if (!bench_is_file(rpk) || access(rpk, X_OK) != 0)
        snprintf(pr->why, sizeof pr->why,
                 "rpkCpp is not built (no %s; set RAD_PEER_RPK to its folder)", rpk);
    else if (!bench_is_file(cli))
        snprintf(pr->why, sizeof pr->why, "no %s", cli);
    else if (!bench_is_file(scene))
        snprintf(pr->why, sizeof pr->why, "no %s", scene);
    else
        return peer_scene(scene, mgf, pr);
    return -1;
}

/* rad_cli (beside this program) to 0.01 and 0.001 against rpkCpp's Galerkin solve,
 * whole processes in turn, PEER_RUNS rounds (peer_setup says where the peer is). */
void bench_peer(const char *self, const char *scene, peer_t *pr)
{
    char rpk[PEER_PATH], mgf[PEER_PATH], cli[PEER_PATH], dir[PEER_PATH / 2], png[PEER_PATH];
    char *cmd[PEER_CMDS][24], words[PEER_CMDS][128];
    char *rpk_cmd[] = {rpk,
                       "-force-onesided",
                       "-radiance-method",
                       "Galerkin",
                       "-raytracing-method",
                       "none",
                       "-iterations",
                       "30",
                       mgf,
                       NULL};
    double t[PEER_CMDS][PEER_RUNS], c[PEER_CMDS][PEER_RUNS], r[PEER_CMDS][PEER_RUNS],
        rc[PEER_CMDS][PEER_RUNS];
    int i, k;
    memset(pr, 0, sizeof *pr);
    if (peer_setup(self, scene, rpk, mgf, cli, dir, pr) < 0) return;
    snprintf(png, sizeof png, "%s/bench_peer.ppm", dir);
    for (k = 0; k < PEER_CMDS; k++) {
        char *w, *save = NULL;
        int j = 2;
        if (k == PEER_RPK) {
            memcpy(cmd[k], rpk_cmd, sizeof rpk_cmd);
            continue;
        }
        cmd[k][0] = cli;
        cmd[k][1] = (char *)scene;
        snprintf(words[k], sizeof words[k], "%s --width 64 --height 64 -o",
                 bench_peer_rows[k].flags);
        for (w = strtok_r(words[k], " ", &save); w; w = strtok_r(NULL, " ", &save)) cmd[k][j++] = w;
        cmd[k][j++] = png;
        cmd[k][j] = NULL;
    }
    fprintf(stderr, "rad_bench: rad_cli against rpkCpp, %d rounds ...\n", PEER_RUNS);
    for (i = 0; i < PEER_RUNS; i++)
        for (k = 0; k < PEER_CMDS; k++) {
            long kb;
            if (bench_run_child(cmd[k], NULL, &t[k][i], &c[k][i], &kb) < 0) {
                snprintf(pr->why, sizeof pr->why, "%s failed on %s", cmd[k][0],
                         k != PEER_RPK ? scene : mgf);
                return;
            }
            if (kb > pr->kb[k]) pr->kb[k] = kb;
        }
    remove(png);
    for (i = 0; i < PEER_RUNS; i++)
        for (k = 0; k < PEER_CMDS; k++) {
            r[k][i] = t[k][i] / t[PEER_RPK][i];
            rc[k][i] = c[k][i] / c[PEER_RPK][i];
        }
    for (k = 0; k < PEER_CMDS; k++) {
        pr->t[k] = bench_median(t[k], PEER_RUNS);
        pr->cpu[k] = bench_median(c[k], PEER_RUNS);
        pr->ratio[k] = bench_median(r[k], PEER_RUNS);
        pr->cpu_ratio[k] = bench_median(rc[k], PEER_RUNS);
    }
}

/* Per element, A against the reference REF of the same mesh: the relative error of
 * r + g + b (with the ambient term) over the elements of SC's non-emitting faces above
 * FLOOR[k] of the brightest of them, rms in RMS[k] and largest in MAX[k]. */
void bench_element_accuracy(const bscene *sc, sc_solver *ref, sc_solver *a, const double floor[2],
                            double *rms, double *mx)
{
    sc_stats st;
    double *b, top = 0, s2[2] = {0, 0};
    int e, k, i, n[2] = {0, 0}, ntag = 0;
    char *emits;
    for (i = 0; i < sc->n; i++)
        if (sc->polys[i].tag + 1 > ntag) ntag = sc->polys[i].tag + 1;
    sc_get_stats(ref, &st);
    b = malloc((size_t)st.elements * sizeof *b);
    emits = calloc((size_t)ntag + 1, 1);
    if (!b || !emits) exit(1);
    for (i = 0; i < sc->n; i++)
        if (bench_poly_emits(&sc->polys[i])) emits[sc->polys[i].tag] = 1;
    for (e = 0; e < st.elements; e++) {
        double x[3];
        sc_element_rgb(ref, e, 1, x);
        b[e] = x[0] + x[1] + x[2];
        if (!emits[sc_element_tag(ref, e)] && b[e] > top) top = b[e];
    }
    for (k = 0; k < 2; k++) mx[k] = 0;
    for (e = 0; e < st.elements; e++) {
        double x[3], d;
        if (emits[sc_element_tag(ref, e)]) continue;
        sc_element_rgb(a, e, 1, x);
        d = fabs((x[0] + x[1] + x[2]) / b[e] - 1);
        for (k = 0; k < 2; k++) {
            if (b[e] <= floor[k] * top) continue;
            s2[k] += d * d;
            n[k]++;
            if (d > mx[k]) mx[k] = d;
        }
    }
    for (k = 0; k < 2; k++) rms[k] = n[k] ? sqrt(s2[k] / n[k]) : 0;
    free(b);
    free(emits);
}

/* SC's solve at O to TOL (fixed build). */
sc_solver *bench_solved(const bscene *sc, const sc_opts *o, double tol)
{
    sc_solver *s = bench_fixed_solver(sc, sc->polys, o);
    sc_solve(s, 1000000, tol, NULL, NULL);
    return s;
}

/* O with peer row ROW's res and coarse shots (rad_cli's defaults, or a row's flags). */
sc_opts bench_row_opts(sc_opts o, const peer_row_t *row)
{
    o.res = row->res;
    o.coarse = row->coarse;
    o.coarse_res = row->coarse_res;
    return o;
}

/* Each rad_cli row of the peer table solved in this process (the same core, mesh and
 * settings, so the same bits) against a solve of its mesh at res 512 to 1e-4: the
 * accuracy column. */
void bench_peer_accuracy(const char *scene, peer_t *pr)
{
    static const double floor[2] = {0.1, 0.01};
    static const double edge[2] = {0, 0.08}; /* rad_cli's default, the bench's */
    bscene sc;
    int m, k;
    memset(&sc, 0, sizeof sc);
    sc.polys = bench_load_obj(scene, &sc.n, NULL);
    sc.name = scene;
    if (!sc.polys) return;
    for (m = 0; m < 2; m++) {
        sc_opts o = {0};
        sc_solver *ref;
        o.max_element = edge[m];
        o.res = 512;
        fprintf(stderr, "rad_bench: the res-512 reference (element edge %s) ...\n",
                m ? "0.08" : "default");
        ref = bench_solved(&sc, &o, 1e-4);
        for (k = 0; k < PEER_CMDS; k++) {
            sc_opts v = bench_row_opts(o, &bench_peer_rows[k]);
            sc_solver *a;
            sc_stats st;
            if (k == PEER_RPK || bench_peer_rows[k].edge != edge[m]) continue;
            a = bench_solved(&sc, &v, bench_peer_rows[k].tol);
            bench_element_accuracy(&sc, ref, a, floor, pr->rms[k], pr->max[k]);
            sc_get_stats(a, &st);
            pr->elements[k] = st.elements;
            pr->bytes[k] = st.pool_bytes + st.work_bytes;
            sc_destroy(a);
        }
        sc_destroy(ref);
    }
    free(sc.polys);
}

void bench_report_peers(report_t *rp, const peer_t *p, const brun *fx)
{
    bench_out(
        rp,
        "\nAgainst a peer on CornellBox-Original: RenderPark's hierarchical Galerkin radiosity "
        "(rpkCpp, "
        "`rpk -force-onesided -radiance-method Galerkin -raytracing-method none -iterations 30`, "
        "one core, about "
        "4,000 elements) beside `rad_cli --tol 0.01` (and 0.001) `--width 64 --height 64` (fixed "
        "build, default "
        "mesh), whole processes in turn, %d rounds: medians of wall and processor (user + system) "
        "time, the median of each round's ratio, and each program's peak resident memory over the "
        "rounds (wait4). ",
        PEER_RUNS);
    if (p->why[0]) {
        bench_out(rp, "Not measured: %s.\n", p->why);
    } else {
        int k;
        bench_out(rp, "The accuracy column: each rad row solved again in this process (the same "
                      "bits), per element "
                      "against a solve of its mesh at res 512 to an unshot fraction of 1e-4, "
                      "relative error of r + g + b "
                      "(with the ambient term) over the non-emitting elements above 10%% (and 1%%) "
                      "of the brightest: rms / "
                      "max. rad_cli's defaults: the emitters' shots at res 192, the others at 96, "
                      "48, 24 as the unshot "
                      "fraction falls below 1, 1/8, 1/64 (`--res 192 --coarse 1 --coarse-res 24`); "
                      "`--res 128 --coarse 0`: "
                      "every shot at 128, the defaults before; `--res 256 --coarse 2`: 256, then "
                      "128, 64, 32 below 2, 1/4, "
                      "1/32.\n\n"
                      "| program | elements | wall s | rad/rpkCpp | processor s | rad/rpkCpp | "
                      "peak memory MB | pools + "
                      "work MB | accuracy >10%%: rms / max | >1%%: rms / max |\n"
                      "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for (k = 0; k < PEER_CMDS; k++) {
            char a[32] = "", b[32] = "", n[32] = "", mb[32] = "", acc[2][48] = {"", ""},
                 nm[160] = "rpkCpp Galerkin";
            int j;
            if (k != PEER_RPK) {
                snprintf(nm, sizeof nm, "rad_cli %s", bench_peer_rows[k].flags);
                snprintf(a, sizeof a, "%.2f", p->ratio[k]);
                snprintf(b, sizeof b, "%.2f", p->cpu_ratio[k]);
            }
            if (k != PEER_RPK && p->elements[k]) {
                snprintf(n, sizeof n, "%d", p->elements[k]);
                snprintf(mb, sizeof mb, "%.2f", p->bytes[k] / 1048576.0);
                for (j = 0; j < 2; j++)
                    snprintf(acc[j], sizeof acc[j], "%.2f%% / %.2f%%", 100 * p->rms[k][j],
                             100 * p->max[k][j]);
            }
            bench_out(rp, "| %s | %s | %.3f | %s | %.3f | %s | %.1f | %s | %s | %s |\n", nm, n,
                      p->t[k], a, p->cpu[k], b, p->kb[k] / 1024.0, mb, acc[0], acc[1]);
        }
    }
    bench_out(rp,
              "\nIn this process (res 128, element edge 0.08, %d elements): %.3f s to an unshot "
              "fraction of 0.01 "
              "and %.3f s to 0.001, in %.2f MB of pools and work buffer.\n",
              fx->elements, fx->t[1], fx->total, fx->bytes / 1048576.0);
}

/* ---- the cost curve against the peer (rad_bench --curve) ------------------------- */

/* Per size, rad_cli's element edge (NULL: its default) and rpkCpp's link error
 * threshold and least element area, for about 4k, 16k, 64k and 250k elements each on
 * CornellBox-Original (measured: 3,998 / 4,358, 15,651 / 15,798, 65,605 / 62,526 and
 * 250,609 / 255,178). */
static const struct {
    const char *edge, *err, *area;
} curve_size[CURVE_SIZES] = {{NULL, "1e-5", "1e-6"},
                             {"0.0435", "8e-7", "8e-8"},
                             {"0.021", "6e-8", "6e-9"},
                             {"0.0105", "4e-9", "4e-10"}};

/* Per program: rad_cli's tolerance, or rpkCpp's iterations. rpkCpp has no convergence
 * test: 7 and 10 Jacobi iterations stand for rad's unshot fractions 0.01 and 0.001
 * (rho^k with rho = 0.467, the scene's reflected share in rad's solution). */
static const char *const curve_arg[CURVE_CMDS] = {"0.01", "7", "0.001", "10"};

/* The whole number after the last KEY in the first 1 MiB of file PATH, or -1 (rpkCpp
 * prints its element count after each iteration, the last one final). */
static long number_after(const char *path, const char *key)
{
    static char buf[1 << 20];
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    const char *at, *last = NULL;
    if (f) fclose(f);
    buf[n] = '\0';
    for (at = strstr(buf, key); at; at = strstr(at + 1, key)) last = at;
    return last ? strtol(last + strlen(key), NULL, 10) : -1;
}

void bench_curve(const char *self, const char *scene, int rounds, curve_t *cv)
{
    char rpk[PEER_PATH], mgf[PEER_PATH], cli[PEER_PATH], dir[PEER_PATH / 2], img[PEER_PATH],
        log[PEER_PATH];
    double t[CURVE_SIZES][CURVE_CMDS][CURVE_ROUNDS], r[CURVE_SIZES][2][CURVE_ROUNDS];
    peer_t pr;
    int z, k, i;
    memset(cv, 0, sizeof *cv);
    memset(&pr, 0, sizeof pr);
    cv->rounds = rounds;
    if (peer_setup(self, scene, rpk, mgf, cli, dir, &pr) < 0) {
        snprintf(cv->why, sizeof cv->why, "%s", pr.why);
        return;
    }
    snprintf(img, sizeof img, "%s/bench_curve.ppm", dir);
    snprintf(log, sizeof log, "%s/bench_curve.log", dir);
    for (i = 0; i < rounds; i++)
        for (z = 0; z < CURVE_SIZES; z++) {
            fprintf(stderr, "rad_bench: cost curve, round %d of %d, size %d of %d ...\n", i + 1,
                    rounds, z + 1, CURVE_SIZES);
            for (k = 0; k < CURVE_CMDS; k++) {
                char *rad_cmd[] = {cli,
                                   (char *)scene,
                                   "--tol",
                                   (char *)curve_arg[k],
                                   "--threads",
                                   "1",
                                   "--width",
                                   "64",
                                   "--height",
                                   "64",
                                   "--stats",
                                   "-o",
                                   img,
                                   curve_size[z].edge ? "--max-element" : NULL,
                                   (char *)curve_size[z].edge,
                                   NULL};
                char *rpk_cmd[] = {rpk,
                                   "-force-onesided",
                                   "-radiance-method",
                                   "Galerkin",
                                   "-raytracing-method",
                                   "none",
                                   "-iterations",
                                   (char *)curve_arg[k],
                                   "-gr-link-error-threshold",
                                   (char *)curve_size[z].err,
                                   "-gr-min-elem-area",
                                   (char *)curve_size[z].area,
                                   mgf,
                                   NULL};
                double wall;
                long kb, n;
                if (bench_run_child(k % 2 ? rpk_cmd : rad_cmd, log, &wall, &t[z][k][i], &kb) < 0) {
                    snprintf(cv->why, sizeof cv->why, "%s failed (its output: %s)",
                             k % 2 ? rpk : cli, log);
                    return;
                }
                n = number_after(log, k % 2 ? "Nr. elements: " : "elements ");
                if (n > 0) cv->elements[z][k % 2] = n;
                if (kb > cv->kb[z][k % 2]) cv->kb[z][k % 2] = kb;
            }
            r[z][0][i] = t[z][0][i] / t[z][1][i];
            r[z][1][i] = t[z][2][i] / t[z][3][i];
        }
    remove(img);
    remove(log);
    for (z = 0; z < CURVE_SIZES; z++) {
        for (k = 0; k < CURVE_CMDS; k++) cv->cpu[z][k] = bench_median(t[z][k], rounds);
        for (k = 0; k < 2; k++) cv->ratio[z][k] = bench_median(r[z][k], rounds);
    }
}

/* The least-squares slope of log Y on log X over N points. */
static double log_slope(const double *x, const double *y, int n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int i;
    for (i = 0; i < n; i++) {
        double a = log(x[i]), b = log(y[i]);
        sx += a;
        sy += b;
        sxx += a * a;
        sxy += a * b;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void bench_report_curve(report_t *rp, const curve_t *cv, const char *png)
{
    static const unsigned char col[CURVE_CMDS][3] = {
        {200, 30, 30}, {30, 120, 200}, {240, 120, 100}, {120, 180, 240}};
    static const char *const label[CURVE_CMDS] = {"rad to 0.01", "rpkCpp 7 iterations",
                                                  "rad to 0.001", "rpkCpp 10 iterations"};
    double x[CURVE_CMDS][CURVE_SIZES], y[CURVE_CMDS][CURVE_SIZES], slope[CURVE_CMDS];
    plot_series ser[CURVE_CMDS];
    plot_opts po;
    char err[256];
    int z, k;
    bench_out(rp,
              "CornellBox-Original refined to about 4k, 16k, 64k and 250k elements: rad_cli by "
              "`--max-element` (its default, 0.0435, 0.021, 0.0105; `--threads 1 --width 64 "
              "--height 64`), rpkCpp (`-force-onesided -radiance-method Galerkin "
              "-raytracing-method none`) by `-gr-link-error-threshold E -gr-min-elem-area E/10` "
              "with E = 1e-5, 8e-7, 6e-8, 4e-9. rpkCpp has no convergence test, so 7 and 10 "
              "Jacobi iterations stand for rad's unshot fractions 0.01 and 0.001 (rho^k with rho "
              "= 0.467, the scene's reflected share in rad's solution). Whole processes, one "
              "core, rad and rpkCpp in turn, %d rounds: medians of processor time (user + "
              "system), the median of each round's ratio, and each program's peak resident "
              "memory over the rounds (wait4). ",
              cv->rounds);
    if (cv->why[0]) {
        bench_out(rp, "Not measured: %s.\n", cv->why);
        return;
    }
    bench_out(rp, "Produced by `rad_bench --curve`.\n\n"
                  "| elements rad / rpk | rad 0.01 s | rpk 7 it s | rad/rpk | rad 0.001 s | "
                  "rpk 10 it s | rad/rpk | peak MB rad / rpk |\n"
                  "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (z = 0; z < CURVE_SIZES; z++) {
        bench_out(rp, "| %ld / %ld | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f / %.1f |\n",
                  cv->elements[z][0], cv->elements[z][1], cv->cpu[z][0], cv->cpu[z][1],
                  cv->ratio[z][0], cv->cpu[z][2], cv->cpu[z][3], cv->ratio[z][1],
                  cv->kb[z][0] / 1024.0, cv->kb[z][1] / 1024.0);
        for (k = 0; k < CURVE_CMDS; k++) {
            x[k][z] = (double)cv->elements[z][k % 2];
            y[k][z] = cv->cpu[z][k];
        }
    }
    for (k = 0; k < CURVE_CMDS; k++) {
        slope[k] = log_slope(x[k], y[k], CURVE_SIZES);
        ser[k].label = label[k];
        ser[k].x = x[k];
        ser[k].y = y[k];
        ser[k].n = CURVE_SIZES;
        memcpy(ser[k].rgb, col[k], 3);
    }
    bench_out(rp,
              "\nGrowth of processor time with elements (the least-squares slope of log time on "
              "log elements): rad %.2f (0.01) and %.2f (0.001), rpkCpp %.2f (7 iterations) and "
              "%.2f (10).\n\n![Cost curve](cost_curve.png)\n",
              slope[0], slope[2], slope[1], slope[3]);
    memset(&po, 0, sizeof po);
    po.title = "CornellBox-Original refined: processor seconds, one core";
    po.xlabel = "elements";
    po.ylabel = "seconds";
    po.log_x = po.log_y = 1;
    po.width = 800;
    po.height = 500;
    if (plot_write(png, ser, CURVE_CMDS, &po, err, sizeof err) < 0) fprintf(stderr, "%s\n", err);
}
