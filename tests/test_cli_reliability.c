/* SPDX-License-Identifier: MIT */
/* rad_cli never destroys, never hangs, never diverges in silence: each case runs
 * build/rad_cli on one hostile input or condition and asserts the exact exit status,
 * the message, and what is (or is not) left on disk.
 *
 * The runs are children of fork: stdout and stderr go to files, and an alarm set in the
 * child before exec kills a run that hangs (status 128 + SIGALRM), so a regression
 * fails its test instead of stopping the suite. A full disk is RLIMIT_FSIZE in the child
 * with SIGXFSZ ignored: every write past the limit fails with EFBIG, as on a full disk.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "formats/file_io.h"
#include "formats/image.h"
#include "tmpdir.h"

#define CLI      "build/rad_cli"
#define CORNELL  "examples/cornell_box.obj"
/* Small and quick: every feature these cases look at survives it. */
#define SMALL    "--max-element", "0.1", "--res", "32", "--width", "32", "--height", "32"
#define HANG_S   120 /* a run still going after this is hung (a whole solve here takes < 1 s) */
#define MAX_ARGS 48

TMPDIR_GROUP("cli_reliability")

typedef struct {
    int status;      /* exit status, or 128 + the signal that ended the run */
    char *out, *err; /* what it printed */
} result_t;

static char *read_whole(const char *path)
{
    char *data, e[512];
    size_t n;
    if (fio_read_all(path, FIO_LIMIT_TEXT, &data, &n, e, sizeof e) < 0) fail_msg("%s", e);
    return data;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fputs(text, f) >= 0, 1);
    assert_int_equal(fclose(f), 0);
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* The runs' standard input (a test may set it, and puts it back). */
static const char *child_stdin = "/dev/null";

/* The child: its outputs into files, a hang bounded, the disk "full" past FSIZE bytes. */
static void child(const char *outp, const char *errp, long fsize, char **argv)
{
    int in = open(child_stdin, O_RDONLY), out = open(outp, O_WRONLY | O_CREAT | O_TRUNC, 0600),
        err = open(errp, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (in < 0 || out < 0 || err < 0 || dup2(in, 0) < 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0)
        _exit(126);
    if (fsize > 0) {
        struct rlimit rl;
        rl.rlim_cur = rl.rlim_max = (rlim_t)fsize;
        signal(SIGXFSZ, SIG_IGN);
        if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(126);
    }
    alarm(HANG_S);
    execv(argv[0], argv);
    _exit(127);
}

/* Runs rad_cli with ARGS (NULL-terminated); FSIZE > 0 fills the disk at that size. */
static void run(result_t *r, long fsize, const char *const *args)
{
    char outp[320], errp[320], *argv[MAX_ARGS + 2];
    int n = 0, st = 0;
    pid_t pid;
    if (access(CLI, X_OK) != 0) {
        print_message("%s is missing (make all): skipped\n", CLI);
        skip();
    }
    argv[n++] = (char *)CLI;
    for (; args[n - 1]; n++) {
        assert_in_range(n, 1, MAX_ARGS);
        argv[n] = (char *)args[n - 1];
    }
    argv[n] = NULL;
    snprintf(outp, sizeof outp, "%s", tmp_path("run.out"));
    snprintf(errp, sizeof errp, "%s", tmp_path("run.err"));
    pid = fork();
    CHECK_INT_GE(pid, 0, "fork");
    if (pid == 0) child(outp, errp, fsize, argv);
    assert_int_equal(waitpid(pid, &st, 0), pid);
    r->status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    r->out = read_whole(outp);
    r->err = read_whole(errp);
}

#define RUN(r, ...)             run((r), 0, (const char *const[]){__VA_ARGS__, NULL})
#define RUN_FULL(r, fsize, ...) run((r), (fsize), (const char *const[]){__VA_ARGS__, NULL})

static void done(result_t *r)
{
    free(r->out);
    free(r->err);
}

/* Exit STATUS and, when LINE is given, exactly that one line on stderr. */
static void expect(const result_t *r, int status, const char *line)
{
    if (r->status == status && (!line || strcmp(r->err, line) == 0)) return;
    fail_msg("exit %d, expected %d\nstderr:   %swanted:   %s\nstdout: %s", r->status, status,
             r->err, line ? line : "(any)\n", r->out);
}

/* Exit STATUS and one line on stderr starting with PREFIX and holding WORDS. */
static void expect_line(const result_t *r, int status, const char *prefix, const char *words)
{
    const char *nl = strchr(r->err, '\n');
    if (r->status == status && strncmp(r->err, prefix, strlen(prefix)) == 0 && nl &&
        nl[1] == '\0' && (!words || strstr(r->err, words)))
        return;
    fail_msg("exit %d, expected %d\nstderr: %swanted one line: %s...%s...\n", r->status, status,
             r->err, prefix, words ? words : "");
}

/* No file in the temporary folder starts with PREFIX (a temporary file left behind). */
static void none_starting(const char *prefix)
{
    DIR *d = opendir(tmpdir);
    struct dirent *de;
    assert_non_null(d);
    while ((de = readdir(d)) != NULL)
        if (strncmp(de->d_name, prefix, strlen(prefix)) == 0)
            fail_msg("left behind: %s", de->d_name);
    closedir(d);
}

static char *line_of(const char *fmt, const char *a, const char *b)
{
    static char buf[2048];
    snprintf(buf, sizeof buf, fmt, a, b);
    return buf;
}

/* ---- --views and --animate: bounded, never hung, comments to their end ----------- */

static void test_views_not_a_file(void **state)
{
    result_t r;
    const char *fifo = tmp_path("views.fifo");
    (void)state;
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("v.png"), "--views", tmpdir);
    expect(&r, 1, line_of("rad_cli: %s: is a directory\n", tmpdir, NULL)); /* it exited 0 */
    done(&r);
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("v.png"), "--animate", tmpdir);
    expect(&r, 1, line_of("rad_cli: %s: is a directory\n", tmpdir, NULL));
    done(&r);
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("v.png"), "--views", "/dev/zero");
    expect(&r, 1, "rad_cli: /dev/zero: not a regular file (a character device or terminal)\n");
    done(&r);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("v.png"), "--views",
        fifo); /* no writer: must not block */
    expect(&r, 1, line_of("rad_cli: %s: not a regular file (a FIFO or pipe)\n", fifo, NULL));
    done(&r);
    CHECK_THAT(!exists(tmp_path("v.png")), "no image after the failed runs");
}

/* Inputs that are not regular files are refused before the solve, at once: the scene
 * as a FIFO with no writer and with a writer waiting (it was waited on, then read), the
 * scene, --probe-file and --load-ff as devices (/dev/zero was read to each limit). Only
 * an explicit "-" reads standard input, and a scene from it needs -o. */
static void test_inputs_not_regular(void **state)
{
    result_t r;
    const char *fifo = tmp_path("scene.fifo");
    char want[600], *obj;
    pid_t writer;
    int st;
    (void)state;
    unlink(fifo);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    RUN(&r, fifo, SMALL, "-o", tmp_path("n.png"));
    expect(&r, 1, line_of("rad_cli: %s: not a regular file (a FIFO or pipe)\n", fifo, NULL));
    done(&r);
    writer = fork(); /* a writer waiting in its open, with a scene to give */
    CHECK_INT_GE(writer, 0, "fork");
    if (writer == 0) {
        int fd;
        signal(SIGPIPE, SIG_IGN);
        alarm(HANG_S);
        fd = open(fifo, O_WRONLY);
        _exit(fd >= 0 && write(fd, "v 0 0 0\n", 8) >= 0 ? 0 : 1);
    }
    RUN(&r, fifo, SMALL, "-o", tmp_path("n.png"));
    expect(&r, 1, line_of("rad_cli: %s: not a regular file (a FIFO or pipe)\n", fifo, NULL));
    done(&r);
    assert_int_equal(waitpid(writer, &st, 0), writer);
    RUN(&r, "/dev/null", SMALL, "-o", tmp_path("n.png"));
    expect(&r, 1, "rad_cli: /dev/null: not a regular file (a character device or terminal)\n");
    done(&r);
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("n.png"), "--load-ff", "/dev/zero");
    expect(&r, 1, "rad_cli: /dev/zero: not a regular file (a character device or terminal)\n");
    done(&r);
    CHECK_THAT(!exists(tmp_path("n.png")), "no image after the refused inputs");
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("n.png"), "--probe-file", "/dev/zero", "--probes-out",
        tmp_path("p.json"));
    expect(&r, 1, "rad_cli: /dev/zero: not a regular file (a character device or terminal)\n");
    done(&r);
    unlink(tmp_path("n.png"));
    /* "-": the scene from standard input (here a file; its mtllib from the current folder) */
    {
        char *at, *text;
        size_t n;
        assert_int_equal(fio_read_all(CORNELL, FIO_LIMIT_TEXT, &obj, &n, want, sizeof want), 0);
        at = strstr(obj, "mtllib cornell_box.mtl");
        text = malloc(n + 32);
        assert_non_null(at);
        assert_non_null(text);
        sprintf(text, "%.*smtllib examples/cornell_box.mtl%s", (int)(at - obj), obj,
                at + strlen("mtllib cornell_box.mtl"));
        write_file(tmp_path("stdin.obj"), text);
        free(text);
        free(obj);
    }
    child_stdin = tmp_path("stdin.obj");
    /* make check runs in a tree of links to the sources, where examples/ resolves
     * outside the current folder: allowed here, as reading stdin is what is tested */
    RUN(&r, "-", SMALL, "--allow-outside-paths", "-o", tmp_path("stdin.png"));
    expect(&r, 0, "");
    CHECK_THAT(exists(tmp_path("stdin.png")), "the scene read from standard input is rendered");
    done(&r);
    RUN(&r, "-", SMALL);
    child_stdin = "/dev/null";
    snprintf(
        want, sizeof want,
        "rad_cli: a scene on standard input (-) has no name to name outputs after: give -o FILE\n");
    CHECK_THAT(r.status == 2 && !strncmp(r.err, want, strlen(want)), "exit %d, stderr %.200s",
               r.status, r.err);
    done(&r);
    RUN(&r, "-", SMALL, "-o", tmp_path("n.png")); /* standard input a device: refused */
    expect(&r, 1, "rad_cli: -: standard input is a device: pipe or redirect a file into it\n");
    done(&r);
}

/* The old reader took a line in 4,095-byte pieces: a longer '#' comment ran its tail as
 * a view. Now the comment ends at its newline, and only the real view is written. */
static void test_views_long_comment(void **state)
{
    result_t r;
    char *text = malloc(8192);
    const char *path = tmp_path("long.views");
    (void)state;
    assert_non_null(text);
    memset(text, 'x', 4095);
    text[0] = '#';
    snprintf(text + 4095, 8192 - 4095, " 0 0.27 1.2 0 0.27 0 %s\n0 0.27 1.2 0 0.27 0 %s\n",
             tmp_path("tail.png"), tmp_path("real.png"));
    write_file(path, text);
    free(text);
    RUN(&r, CORNELL, SMALL, "--views", path, "--allow-outside-paths"); /* outputs in /tmp */
    expect(&r, 0, "");
    CHECK_THAT(exists(tmp_path("real.png")), "the real view is written");
    CHECK_THAT(!exists(tmp_path("tail.png")), "the comment's tail is not a view");
    done(&r);
    text = malloc(64);
    assert_non_null(text);
    memcpy(text, "0 0.27 1.2 0 0.27 0 a.png\n", 26);
    text[26] = '\0';
    {
        FILE *f = fopen(path, "wb"); /* a NUL byte after the first line */
        assert_non_null(f);
        assert_int_equal(fwrite(text, 1, 27, f), 27);
        assert_int_equal(fclose(f), 0);
    }
    free(text);
    RUN(&r, CORNELL, SMALL, "--views", path);
    expect(&r, 1, line_of("rad_cli: %s: not a text file (it holds a NUL byte)\n", path, NULL));
    done(&r);
}

/* A --probe-file is read before the solve: a malformed one fails with its line and no
 * solve (no image, no --stats: both came after the solve); points outside the scene's
 * box are counted in one warning naming the first, before the solve's output. */
static void test_probe_file_before_solve(void **state)
{
    result_t r;
    char pf[320], want[800];
    (void)state;
    strcpy(pf, tmp_path("probes.txt"));
    write_file(pf, "# probes\n-0.28 0.27 -0.28\n1 2\n");
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("pr.png"), "--probe-file", pf, "--probes-out",
        tmp_path("pr.json"), "--stats");
    expect(&r, 1, line_of("rad_cli: %s:3: a probe is three numbers, X Y Z\n", pf, NULL));
    CHECK_THAT(!*r.out, "no --stats (no solve): stdout '%s'", r.out);
    done(&r);
    CHECK_THAT(!exists(tmp_path("pr.png")) && !exists(tmp_path("pr.json")), "nothing written");
    write_file(pf, "-0.28 0.27 -0.28\n\n  # above the ceiling:\n-0.28 0.6 -0.28\n-0.1 0.1 "
                   "-0.1\n-0.28 -0.01 -0.28\n");
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("pr.png"), "--probe-file", pf, "--probes-out",
        tmp_path("pr.json"));
    snprintf(want, sizeof want,
             "rad_cli: warning: %s:4: 2 of 4 probes lie outside the scene's bounding box (-0.556 0 "
             "-0.5592 to 0 0.5488 0), the first here, -0.28 0.6 -0.28: they see the scene from "
             "outside\n",
             pf);
    CHECK_THAT(!strncmp(r.err, want, strlen(want)), "stderr starts\n%s\nwant\n%s", r.err, want);
    done(&r);
    unlink(tmp_path("pr.png"));
    unlink(tmp_path("pr.json"));
}

/* --lightmap-size: the atlas's memory said before it is laid out (38 bytes a texel:
 * lm_atlas's arrays, 30, and lm_build's ring, 8: 64 x 64 texels are 0.155648 MB), and
 * refused before the solve when over the memory budget (8192 x 8192: 2550.1 MB against
 * a RAD_MEMORY_BUDGET of 1 GB). */
static void test_lightmap_estimate(void **state)
{
    result_t r;
    char lm[320];
    (void)state;
    strcpy(lm, tmp_path("lm.png"));
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("lm_view.png"), "--lightmap", lm, "--lightmap-size",
        "64");
    CHECK_CONTAINS(r.err, "rad_cli: lightmap: 64 x 64 texels, about 0.2 MB\n", "rad_cli's stderr");
    CHECK_CONTAINS(
        r.err,
        "rad_cli: lightmap: 16 charts, 2660 texels covered: at most 2660 gathers at res 64\n",
        "rad_cli's stderr");
    expect(&r, 0, NULL);
    done(&r);
    unlink(lm);
    unlink(tmp_path("lm_view.png"));
    assert_int_equal(setenv("RAD_MEMORY_BUDGET", "1e9", 1), 0);
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("lm_view.png"), "--lightmap", lm, "--lightmap-size",
        "8192", "--stats");
    unsetenv("RAD_MEMORY_BUDGET");
    expect(&r, 1,
           line_of("rad_cli: %s: --lightmap-size 8192 needs about 2550.1 MB for its 8192 x 8192 "
                   "texels, over "
                   "the memory budget of 1000.0 MB (RAD_MEMORY_BUDGET): lower --lightmap-size\n",
                   lm, NULL));
    CHECK_THAT(!*r.out && !exists(lm) && !exists(tmp_path("lm_view.png")),
               "no solve, nothing written: stdout '%s'", r.out);
    done(&r);
}

/* Does the file PATH hold the N bytes of WHAT? */
static int holds(const char *path, const char *what, size_t n)
{
    char *d, e[512];
    size_t len, i;
    int found = 0;
    if (fio_read_all(path, FIO_LIMIT_TEXT, &d, &len, e, sizeof e) < 0) fail_msg("%s", e);
    for (i = 0; !found && i + n <= len; i++) found = !memcmp(d + i, what, n);
    free(d);
    return found;
}

/* A scene whose map_Kd leaves its folder (../secret.png) no longer copies that file into
 * its .glb (it was embedded byte for byte): one warning, the material's Kd; with
 * --allow-outside-paths it is read and embedded as before. */
static void test_texture_outside_not_embedded(void **state)
{
    unsigned char rgb[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    char obj[320], glb[320], secret[320], want[1200], e[512], *png, *root = fio_resolve(tmpdir);
    size_t n;
    result_t r;
    (void)state;
    assert_non_null(root);
    strcpy(obj, tmp_path("room/room.obj"));
    strcpy(glb, tmp_path("room.glb"));
    strcpy(secret, tmp_path("secret.png"));
    assert_int_equal(mkdir(tmp_path("room"), 0700), 0);
    write_file(
        obj,
        "mtllib room.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 2 -1\nv -1 2 1\nv 1 2 1\n"
        "v 1 2 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl floor\nf 1/1 4/4 3/3 2/2\nusemtl lamp\n"
        "f 5 6 7 8\n");
    write_file(tmp_path("room/room.mtl"),
               "newmtl floor\nKd 0 0 0\nmap_Kd ../secret.png\nnewmtl lamp\nKe 1 1 1\n");
    assert_int_equal(img_write_as(secret, "png", rgb, 2, 2, e, sizeof e), 0);
    assert_int_equal(fio_read_all(secret, FIO_LIMIT_TEXT, &png, &n, e, sizeof e), 0);
    RUN(&r, obj, SMALL, "-o", tmp_path("room.png"), "--export-gltf", glb);
    snprintf(want, sizeof want,
             "rad_cli: warning: %s:3: map_Kd: %s/../secret.png is outside the scene's folder "
             "%s/room; using Kd 0.5 0.5 0.5; --allow-outside-paths reads it\n",
             tmp_path("room/room.mtl"), tmp_path("room"), root);
    CHECK_THAT(r.status == 0 && !strncmp(r.err, want, strlen(want)),
               "exit %d, stderr\n%s\nwant first\n%s", r.status, r.err, want);
    done(&r);
    CHECK_THAT(!holds(glb, png, n), "%s does not hold the %zu bytes of %s", glb, n, secret);
    RUN(&r, obj, SMALL, "-o", tmp_path("room.png"), "--export-gltf", glb, "--allow-outside-paths");
    expect(&r, 0, NULL);
    done(&r);
    CHECK_THAT(holds(glb, png, n), "with the option %s holds %s", glb, secret);
    free(png);
    free(root);
}

/* ---- outputs checked before the solve ------------------------------------------ */

/* A copy of PATH's bytes, to see that a refused run left it as it was. */
static char *copy_of(const char *path)
{
    char *d, e[512];
    size_t n;
    if (fio_read_all(path, FIO_LIMIT_TEXT, &d, &n, e, sizeof e) < 0) fail_msg("%s", e);
    return d;
}

/* Runs ARGS, which must be refused with exactly LINE, leaving INPUT (if any) as it was. */
static void refused(const char *input, const char *line, const char *const *args)
{
    result_t r;
    char *before = input ? copy_of(input) : NULL, *want = strdup(line);
    assert_non_null(want);
    run(&r, 0, args);
    expect(&r, 1, want);
    done(&r);
    free(want);
    if (before) {
        char *after = copy_of(input);
        CHECK_THAT(!strcmp(before, after), "%s is unchanged", input);
        free(after);
        free(before);
    }
}
#define REFUSED(input, line, ...) refused((input), (line), (const char *const[]){__VA_ARGS__, NULL})

/* Outputs that would write over an input of the run, or over each other, are refused
 * before the solve, by file identity (a link, another spelling of the name, a file not
 * yet written named twice); --views may write only under the current folder. */
static void test_outputs_over_inputs(void **state)
{
    char obj[320], mtl[320], png[320], views[320], ff[320]; /* tmp_path's ring is reused */
    unsigned char rgb[12] = {200, 10, 10, 10, 200, 10, 10, 10, 200, 200, 200, 200};
    char e[512], text[1200], dotted[400];
    result_t r;
    (void)state;
    strcpy(obj, tmp_path("tex.obj"));
    strcpy(mtl, tmp_path("tex.mtl"));
    strcpy(png, tmp_path("tex.png"));
    strcpy(views, tmp_path("two.views"));
    strcpy(ff, tmp_path("tex.ff"));
    write_file(
        obj,
        "mtllib tex.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 2 -1\nv 1 2 -1\nv 1 2 1\n"
        "v -1 2 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl floor\nf 1/1 4/4 3/3 2/2\nusemtl lamp\n"
        "f 5 6 7 8\n");
    write_file(mtl, "newmtl floor\nKd 0.5 0.5 0.5\nmap_Kd tex.png\nnewmtl lamp\nKe 1 1 1\n");
    assert_int_equal(img_write_as(png, "png", rgb, 2, 2, e, sizeof e), 0);
    /* over the scene, its library and its texture (the same file under another name) */
    REFUSED(obj,
            line_of("rad_cli: %s: --export-ply would write over the scene %s (the same file): give "
                    "it another "
                    "name\n",
                    obj, obj),
            obj, SMALL, "-o", tmp_path("o.png"), "--export-ply", obj);
    REFUSED(mtl,
            line_of("rad_cli: %s: --dump-radiosity would write over the scene's material library "
                    "%s (the same "
                    "file): give it another name\n",
                    mtl, mtl),
            obj, SMALL, "-o", tmp_path("o.png"), "--dump-radiosity", mtl);
    snprintf(dotted, sizeof dotted, "%s/./tex.png", tmpdir);
    snprintf(text, sizeof text,
             "rad_cli: %s: the image of -o would write over the texture of material 'floor' "
             "(%s:3) %s (the same file): give it another name\n",
             dotted, mtl, png);
    REFUSED(NULL, text, obj, SMALL, "-o", dotted);
    assert_int_equal(symlink(obj, tmp_path("link.png")), 0); /* a link to the scene */
    REFUSED(obj,
            line_of("rad_cli: %s: the image of -o would write over the scene %s (the same file): "
                    "give it another "
                    "name\n",
                    tmp_path("link.png"), obj),
            obj, SMALL, "-o", tmp_path("link.png"));
    /* over the --views file and a --load-ff file */
    snprintf(text, sizeof text, "0 1 3 0 1 0 %s\n", tmp_path("v1.png"));
    write_file(views, text);
    REFUSED(views,
            line_of("rad_cli: %s: --export-gltf would write over the --views file %s (the same "
                    "file): give it "
                    "another name\n",
                    views, views),
            obj, SMALL, "--views", views, "--allow-outside-paths", "--export-gltf", views);
    RUN(&r, obj, SMALL, "-o", tmp_path("o.png"), "--save-ff", ff);
    expect(&r, 0, NULL);
    done(&r);
    REFUSED(NULL,
            line_of("rad_cli: %s: --dump-radiosity would write over the --load-ff file %s (the "
                    "same file): give "
                    "it another name\n",
                    ff, ff),
            obj, SMALL, "-o", tmp_path("o2.png"), "--load-ff", ff, "--dump-radiosity", ff);
    /* outputs over each other: two views to one (new) file, -o and --lightmap */
    snprintf(text, sizeof text, "0 1 3 0 1 0 %s\n0 1 3 0 1 0 %s/./v2.png\n", tmp_path("v2.png"),
             tmpdir);
    write_file(views, text);
    snprintf(dotted, sizeof dotted, "%s/./v2.png", tmpdir);
    snprintf(text, sizeof text,
             "rad_cli: %s: the image of %s:1 (--views) and the image of %s:2 (--views) write the "
             "same file: give one another name\n",
             dotted, views, views);
    REFUSED(NULL, text, obj, SMALL, "--views", views, "--allow-outside-paths");
    REFUSED(NULL,
            line_of("rad_cli: %s: the image of -o and --lightmap write the same file: give one "
                    "another name\n",
                    tmp_path("x.png"), NULL),
            obj, SMALL, "-o", tmp_path("x.png"), "--lightmap", tmp_path("x.png"));
    /* --views outside the current folder (the tests run in the repository; /tmp is outside) */
    snprintf(text, sizeof text, "# a view\n0 1 3 0 1 0 %s\n", tmp_path("v3.png"));
    write_file(views, text);
    REFUSED(
        NULL,
        line_of(
            "rad_cli: %s:2: %s is outside the current folder; --allow-outside-paths writes it\n",
            views, tmp_path("v3.png")),
        obj, SMALL, "--views", views);
    CHECK_THAT(!exists(tmp_path("x.png")) && !exists(tmp_path("v2.png")) &&
                   !exists(tmp_path("v3.png")) && !exists(tmp_path("o2.png")),
               "no output of the refused runs");
    RUN(&r, obj, SMALL, "--views", views, "--allow-outside-paths");
    expect(&r, 0, NULL); /* a warning: the lamp faces down, the floor up, little lands */
    CHECK_THAT(exists(tmp_path("v3.png")), "with the option the view is written");
    done(&r);
}

/* A name of LEN bytes in the temporary folder ending in EXT. */
static const char *long_name(size_t len, const char *ext)
{
    static char ring[16][600];
    static int k;
    char *p = ring[k++ % 16], base[300];
    size_t n = len - strlen(ext);
    memset(base, 'n', n);
    base[n] = '\0';
    snprintf(p, 600, "%s/%s%s", tmpdir, base, ext);
    return p;
}

/* Names of 246..255 bytes fit NAME_MAX but not with the temporary file's suffix: they
 * used to fail only after the solve. --stats prints after a solve: its silence on
 * stdout shows that none ran. */
static void test_long_names_refused_before_solve(void **state)
{
    const char *img = long_name(250, ".png"), *ok = long_name(244, ".png");
    const char *const cases[][4] = {
        {"-o", img, NULL, NULL},
        {"--export-ply", long_name(250, ".ply"), "-o", ok},
        {"--dump-radiosity", long_name(250, ".csv"), "-o", ok},
        {"--save-ff", long_name(250, ".ff"), "-o", ok},
    };
    size_t i;
    result_t r;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        RUN(&r, CORNELL, SMALL, "--stats", cases[i][0], cases[i][1],
            cases[i][2] ? cases[i][2] : "--quiet", cases[i][3] ? cases[i][3] : "--quiet");
        expect(&r, 1,
               line_of("rad_cli: %s: name too long for its temporary file (.tmpXXXXXX)\n",
                       cases[i][1], NULL));
        assert_string_equal(r.out, "");
        done(&r);
    }
    /* Names made from -o: the group's name or the frame number makes them too long. */
    RUN(&r, CORNELL, SMALL, "--stats", "-o", ok, "--light-group", "lamp=light", "--each-group");
    expect(&r, 1,
           line_of("rad_cli: %s: name too long for its temporary file (.tmpXXXXXX)\n",
                   long_name(249, ".lamp.png"), NULL));
    assert_string_equal(r.out, "");
    done(&r);
    write_file(tmp_path("frames.txt"), "0 0.27 1.2 0 0.27 0\n");
    RUN(&r, CORNELL, SMALL, "--stats", "-o", ok, "--animate", tmp_path("frames.txt"));
    expect(&r, 1,
           line_of("rad_cli: %s: name too long for its temporary file (.tmpXXXXXX)\n",
                   long_name(249, "_0000.png"), NULL));
    assert_string_equal(r.out, "");
    done(&r);
    CHECK_THAT(!exists(ok), "%s is not written", ok);
}

/* A camera the core refuses (an eye 1 km away) fails before the solve, and an existing
 * output stays as it was. */
static void test_camera_refused_before_solve(void **state)
{
    result_t r;
    char *after;
    const char *keep = tmp_path("keep.png");
    (void)state;
    write_file(keep, "not replaced\n");
    RUN(&r, CORNELL, SMALL, "--stats", "--camera", "1000,0.27,1.2,0,0.27,0", "-o", keep);
    expect_line(&r, 1, line_of("rad_cli: %s: cannot render this view", keep, NULL), NULL);
    assert_string_equal(r.out, "");
    after = read_whole(keep);
    assert_string_equal(after, "not replaced\n");
    free(after);
    done(&r);
}

/* ---- outputs written whole or not at all ---------------------------------------- */

/* A full disk while writing the CSV or the PLY: exit 1, the file named, the previous
 * file intact byte for byte, no temporary file left. */
static void test_full_disk_keeps_old_file(void **state)
{
    static const char *const opt[2] = {"--dump-radiosity", "--export-ply"}, *const ext[2] = {
                                                                                "old.csv",
                                                                                "old.ply"};
    int k;
    (void)state;
    for (k = 0; k < 2; k++) {
        result_t r;
        char *after;
        const char *path = tmp_path(ext[k]);
        write_file(path, "the previous file\n");
        /* 4 KiB: room for the 32 x 32 PNG (about 1.5 KB), not for the CSV (27 KB) or PLY (14 KB) */
        RUN_FULL(&r, 4096, CORNELL, SMALL, "-o", tmp_path("full.png"), opt[k], path);
        expect(&r, 1, line_of("rad_cli: %s: write error: File too large\n", path, NULL));
        after = read_whole(path);
        assert_string_equal(after, "the previous file\n");
        free(after);
        {
            char prefix[64];
            snprintf(prefix, sizeof prefix, "%s.tmp", ext[k]);
            none_starting(prefix);
        }
        done(&r);
    }
    {
        result_t r;
        RUN(&r, CORNELL, SMALL, "-o", tmp_path("full.png"), "--dump-radiosity", "/dev/full");
        expect(&r, 1, "rad_cli: /dev/full: write error: No space left on device\n");
        done(&r);
    }
}

/* ---- exit statuses: converged, not converged, saturated --------------------------- */

/* A closed unit box lit by its x = 0 face, walls of reflectance RHO; INWARD 0 turns every
 * wall to face outwards (the lamp still faces in). */
static const char *box_scene(const char *name, const char *rho, int inward)
{
    static char path[320];
    char text[1024], mtl[64];
    static const char *const in[5] = {"1 2 3 4", "5 8 7 6", "1 5 6 2", "2 6 7 3", "4 3 7 8"};
    static const char *const out[5] = {"4 3 2 1", "6 7 8 5", "2 6 5 1", "3 7 6 2", "8 7 3 4"};
    int i;
    size_t n;
    snprintf(mtl, sizeof mtl, "%s.mtl", name);
    n = (size_t)snprintf(text, sizeof text,
                         "mtllib %s\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\n"
                         "v 1 1 1\nv 0 1 1\nusemtl wall\n",
                         mtl);
    for (i = 0; i < 5; i++)
        n += (size_t)snprintf(text + n, sizeof text - n, "f %s\n", inward ? in[i] : out[i]);
    snprintf(text + n, sizeof text - n, "usemtl lamp\nf 1 4 8 5\n");
    snprintf(path, sizeof path, "%s", tmp_path(name));
    write_file(path, text);
    snprintf(text, sizeof text, "newmtl wall\nKd %s %s %s\nnewmtl lamp\nKd %s %s %s\nKe 1 1 1\n",
             rho, rho, rho, rho, rho, rho);
    write_file(tmp_path(mtl), text);
    return path;
}

static void test_exit_not_converged(void **state)
{
    result_t r;
    img_t im;
    char e[256];
    (void)state;
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("short.png"), "--max-shots", "2");
    expect_line(&r, 3, "rad_cli: " CORNELL ": not converged: the unshot fraction is ",
                "above --tol 0.001, at --max-shots 2; the outputs show that partial solution "
                "(raise --max-shots or --tol)");
    assert_int_equal(img_read(tmp_path("short.png"), &im, e, sizeof e),
                     0); /* written all the same */
    assert_int_equal(im.w, 32);
    img_free(&im);
    done(&r);
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("short.png"), "--max-shots", "2", "--light-group",
        "l=light");
    expect_line(&r, 3, "rad_cli: " CORNELL ": not converged: ", "(in a light group)");
    done(&r);
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("short.png"));
    expect(&r, 0, "");
    done(&r);
}

/* Reflectance 0.999 everywhere in a closed box: radiosity near 1000 times the emission,
 * past the 128 times the fixed core holds. */
static void test_exit_saturated(void **state)
{
    result_t r;
    const char *box = box_scene("bright.obj", "0.999", 1);
    (void)state;
    RUN(&r, box, "--res", "16", "--width", "16", "--height", "16", "--max-element", "0.25", "-o",
        tmp_path("bright.png"), "--quiet");
    expect_line(&r, 3, line_of("rad_cli: %s: ", box, NULL),
                "values saturated at the core's range, so some radiosities are clipped");
    CHECK_THAT(exists(tmp_path("bright.png")), "the saturated run still writes its image");
    done(&r);
}

/* ---- emissions the image can hold --------------------------------------------------- */

static void test_emission_limit(void **state)
{
    result_t r;
    (void)state;
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("e.png"), "--emit", "light=1e100,1,1");
    expect(&r, 1,
           "rad_cli: " CORNELL
           ": material 'light': emission 1e+100 is above the limit of 1e+30 (the image "
           "would overflow); scale every emission down: radiosity is linear in it\n");
    done(&r);
    /* It used to say 'must be finite and >= 0' there, and leak. */
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("e.png"), "--emit", "light=1e31,1,1", "--light-group",
        "l=light");
    expect(&r, 1,
           "rad_cli: " CORNELL
           ": material 'light': emission 1e+31 is above the limit of 1e+30 (the image "
           "would overflow); scale every emission down: radiosity is linear in it\n");
    done(&r);
    CHECK_THAT(!exists(tmp_path("e.png")), "no image from a refused emission");
    RUN(&r, CORNELL, SMALL, "-o", tmp_path("e.png"), "--emit", "light=1e30,1e30,1e30");
    expect(&r, 0, "");
    done(&r);
}

/* -o /dev/stdout (the Unix habit): the image goes down standard output, as PNG since the
 * name has no extension, byte for byte the file -o x.png writes; /dev/stdout itself is
 * left as it was (file_io writes it through the descriptor, never replaces it). */
static void test_image_to_stdout(void **state)
{
    result_t r;
    struct stat before, after;
    char *want = NULL, *got = NULL, e[512];
    size_t nwant = 0, ngot = 0;
    (void)state;
    CHECK_INT_EQ(lstat("/dev/stdout", &before), 0, "lstat /dev/stdout");
    RUN(&r, CORNELL, SMALL, "--quiet", "-o", tmp_path("x.png"));
    expect(&r, 0, "");
    done(&r);
    RUN(&r, CORNELL, SMALL, "--quiet", "-o", "/dev/stdout");
    expect(&r, 0, "");
    done(&r);
    if (fio_read_all(tmp_path("x.png"), FIO_LIMIT_IMAGE, &want, &nwant, e, sizeof e) < 0 ||
        fio_read_all(tmp_path("run.out"), FIO_LIMIT_IMAGE, &got, &ngot, e, sizeof e) < 0)
        fail_msg("%s", e);
    CHECK_INT_GT(ngot, 8, "bytes on standard output");
    CHECK_INT_EQ(ngot, nwant, "-o /dev/stdout's bytes against -o x.png's");
    CHECK_INT_EQ(memcmp(got, want, nwant), 0, "-o /dev/stdout's image against -o x.png's");
    free(want);
    free(got);
    CHECK_INT_EQ(lstat("/dev/stdout", &after), 0, "lstat /dev/stdout");
    CHECK_INT_EQ(after.st_ino, before.st_ino, "/dev/stdout's inode, kept");
    CHECK_INT_EQ(after.st_mode, before.st_mode, "/dev/stdout's kind and mode, kept");
}

/* ---- the default camera and the exposure ---------------------------------------------- */

/* The two images are the same, pixel for pixel. */
static void same_image(const char *pa, const char *pb)
{
    img_t a, b;
    char e[512];
    if (img_read(pa, &a, e, sizeof e) < 0) fail_msg("%s", e);
    if (img_read(pb, &b, e, sizeof e) < 0) fail_msg("%s", e);
    assert_int_equal(a.w, b.w);
    assert_int_equal(a.h, b.h);
    assert_memory_equal(a.rgb, b.rgb, (size_t)a.w * a.h * 3);
    img_free(&a);
    img_free(&b);
}

/* A polygon that is skipped (zero area) far from the box must not be framed: the default
 * image equals the one through the camera docs/cli.md describes for the box alone. The
 * skipped polygon is named by its line. */
static void test_default_camera_frames_meshed(void **state)
{
    result_t r;
    char *obj = read_whole(CORNELL), *text, cam[512], line[512];
    const char *scene = tmp_path("far.obj");
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, v[3], c[3], h[3], fit;
    double t = tan(22.5 * 3.14159265358979323846 / 180.0);
    const char *p;
    int k, lines = 0;
    (void)state;
    for (p = obj; *p; p++) lines += *p == '\n';
    for (p = obj; (p = strstr(p, "\nv ")) != NULL; p++) {
        assert_int_equal(sscanf(p + 3, "%lf %lf %lf", &v[0], &v[1], &v[2]), 3);
        for (k = 0; k < 3; k++) {
            lo[k] = v[k] < lo[k] ? v[k] : lo[k];
            hi[k] = v[k] > hi[k] ? v[k] : hi[k];
        }
    }
    text = malloc(strlen(obj) + 128);
    assert_non_null(text);
    sprintf(text, "%s\nv 30 0 0\nv 40 0 0\nv 50 0 0\nf -3 -2 -1\n", obj);
    write_file(scene, text);
    free(text);
    free(obj);
    text = read_whole("examples/cornell_box.mtl");
    write_file(tmp_path("cornell_box.mtl"), text);
    free(text);
    for (k = 0; k < 3; k++) {
        h[k] = 0.5 * (hi[k] - lo[k]);
        c[k] = 0.5 * (hi[k] + lo[k]);
    }
    /* docs/cli.md's default camera for a square image: along -Z, backed off until the
     * box's front face fills the frame with a 5% margin. */
    fit = h[1] > h[0] ? h[1] : h[0];
    snprintf(cam, sizeof cam, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", c[0], c[1],
             c[2] + h[2] + 1.05 * fit / t, c[0], c[1], c[2]);
    RUN(&r, scene, "--res", "16", "--width", "32", "--height", "32", "-o",
        tmp_path("far_default.png"));
    snprintf(line, sizeof line,
             "rad_cli: warning: %s:%d: skipped a degenerate polygon (degenerate polygon)\n", scene,
             lines + 5); /* the face after a blank line and three vertices */
    expect(&r, 0, line);
    done(&r);
    RUN(&r, scene, "--res", "16", "--width", "32", "--height", "32", "--camera", cam, "-o",
        tmp_path("far_cam.png"), "--quiet");
    expect(&r, 0, "");
    done(&r);
    same_image(tmp_path("far_default.png"), tmp_path("far_cam.png"));
}

static double stat_value(const char *out, const char *key)
{
    const char *p = strstr(out, key);
    if (!p) fail_msg("no '%s' in --stats:\n%s", key, out);
    return strtod(p + strlen(key), NULL);
}

/* Views of one run share one exposure (the first view's), which --stats prints: the
 * second view rendered alone at that exposure is the same image. */
static void test_exposure_shared_and_printed(void **state)
{
    result_t r;
    char x[64];
    double exposure;
    (void)state;
    RUN(&r, CORNELL, SMALL, "--stats", "--camera", "0,0.27,1.2,0,0.27,0", "-o", tmp_path("x1.png"),
        "--camera", "0.2,0.1,0.5,0,0.4,0,60", "-o", tmp_path("x2.png"));
    expect(&r, 0, "");
    exposure = stat_value(r.out, "\nexposure ");
    assert_non_null(strstr(r.out, " (automatic, from the first view)\n"));
    done(&r);
    snprintf(x, sizeof x, "%.17g", exposure);
    RUN(&r, CORNELL, SMALL, "--stats", "--camera", "0.2,0.1,0.5,0,0.4,0,60", "-o",
        tmp_path("x3.png"), "--exposure", x);
    expect(&r, 0, "");
    assert_non_null(strstr(r.out, " (--exposure)\n"));
    done(&r);
    same_image(tmp_path("x2.png"), tmp_path("x3.png"));
}

/* ---- light that leaves the scene: the room whose walls face outwards --------------- */

static void test_outward_room_warns(void **state)
{
    result_t r;
    const char *out = box_scene("outward.obj", "0.7", 0), *in;
    double share;
    (void)state;
    RUN(&r, out, "--res", "16", "--width", "16", "--height", "16", "--max-element", "0.25", "-o",
        tmp_path("o.png"), "--stats");
    expect(&r, 0,
           line_of("rad_cli: warning: %s: only 0%% of the emitted light reaches a face from its "
                   "front: the "
                   "rest leaves the scene or meets faces seen from behind (radiosity is one-sided: "
                   "wind faces "
                   "counter-clockwise seen from their lit side)\n",
                   out, NULL));
    share = stat_value(r.out, "emitted light reaching front faces ");
    /* Every wall faces away from the lamp: no front face is seen, whatever the rounding. */
    CHECK_EQ(share, 0.0, "share of the light landing in the outward room");
    done(&r);
    in = box_scene("inward.obj", "0.7", 1);
    RUN(&r, in, "--res", "16", "--width", "16", "--height", "16", "--max-element", "0.25", "-o",
        tmp_path("i.png"), "--stats");
    expect(&r, 0, "");
    share = stat_value(r.out, "emitted light reaching front faces ");
    /* A closed box: each row sums to one (the delta form factor table sums to exactly 1);
     * the printed 0.1% rounding is the bound. */
    CHECK_GE(share, 99.9, "percent of the emitted light landing in the closed box");
    done(&r);
}

/* ---- the documentation: --help and docs/cli.md's table ----------------------------- */

/* docs/cli.md's option table and --help name the same options, and --help states the
 * exit statuses and the default camera. */
static void test_help_matches_docs(void **state)
{
    result_t r;
    char *doc = read_whole("docs/cli.md"), *p;
    int n = 0;
    (void)state;
    RUN(&r, "--help");
    expect(&r, 0, "");
    assert_non_null(strstr(
        r.out, "Exit status: 0 success; 1 runtime or input error; 2 usage error; 3 outputs"));
    assert_non_null(strstr(r.out, "the default camera looks along -Z at the centre of"));
    for (p = doc; (p = strstr(p, "\n| `-")) != NULL; p++) {
        const char *end = strchr(p + 3, '|'), *q; /* the row's first column */
        for (q = p + 3; q && q < end; q = strchr(q + 1, '`')) {
            char opt[64];
            size_t len = strcspn(q + 1, " `,=");
            if (q[1] != '-') continue;
            if (len >= sizeof opt) fail_msg("docs/cli.md row: %.60s", p);
            memcpy(opt, q + 1, len);
            opt[len] = '\0';
            if (!strstr(r.out, opt)) fail_msg("docs/cli.md's option %s is not in --help", opt);
            n++;
            q = strchr(q + 1, '`'); /* past the closing backtick */
            if (!q) break;
        }
    }
    print_message("%d docs/cli.md options found in --help\n", n);
    assert_in_range(n, 25, 100);
    /* and the other way: every option --help lists has its row (its alias aside) */
    for (p = r.out; (p = strstr(p, "\n  -")) != NULL; p++) {
        char opt[64];
        size_t len = strcspn(p + 3, " ,\n");
        if (len >= sizeof opt - 1) fail_msg("--help line: %.60s", p);
        opt[0] = '`';
        memcpy(opt + 1, p + 3, len);
        opt[len + 1] = '\0';
        if (!strstr(doc, opt))
            fail_msg("--help's option %s has no row in docs/cli.md's table", opt + 1);
    }
    free(doc);
    done(&r);
}

/* --help's options come in sections, each under a heading (lines at the margin, the
 * last ending in ':') that says what its options do, in words: no heading without an
 * option under it, and no folder of the source ('/') in one. */
static void test_help_sections(void **state)
{
    result_t r;
    const char *p, *end;
    char heading[256] = "";
    size_t hl = 0;
    int sections = 0, in_section = -1, open = 0;
    (void)state;
    RUN(&r, "--help");
    expect(&r, 0, "");
    p = strstr(r.out, "\n\n"); /* the options: after the introduction, to the next blank line */
    assert_non_null(p);
    p += 2;
    end = strstr(p, "\n\n");
    assert_non_null(end);
    while (p < end) {
        const char *nl = strchr(p, '\n');
        size_t len = (size_t)(nl - p);
        if (p[0] == ' ') {
            if (open)
                fail_msg("--help: heading '%s' does not end in ':' before its options", heading);
            if (strncmp(p, "  -", 3) == 0) in_section++;
        } else {
            if (!open) {
                if (in_section == 0) fail_msg("--help: the section '%s' has no option", heading);
                hl = 0;
                open = 1;
            }
            if (hl + len + 2 > sizeof heading)
                fail_msg("--help: a heading longer than %zu bytes", sizeof heading);
            if (hl) heading[hl++] = ' ';
            memcpy(heading + hl, p, len);
            hl += len;
            heading[hl] = '\0';
            if (len && p[len - 1] == ':') {
                if (strchr(heading, '/'))
                    fail_msg("--help: the heading '%s' names a path", heading);
                open = 0;
                in_section = 0;
                sections++;
            }
        }
        p = nl + 1;
    }
    if (open) fail_msg("--help: heading '%s' does not end in ':'", heading);
    if (in_section == 0) fail_msg("--help: the last section, '%s', has no option", heading);
    print_message("--help: %d sections, each with options, no '/' in a heading\n", sections);
    assert_in_range(sections, 2, 32);
    done(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_views_not_a_file),
        cmocka_unit_test(test_inputs_not_regular),
        cmocka_unit_test(test_outputs_over_inputs),
        cmocka_unit_test(test_probe_file_before_solve),
        cmocka_unit_test(test_lightmap_estimate),
        cmocka_unit_test(test_texture_outside_not_embedded),
        cmocka_unit_test(test_views_long_comment),
        cmocka_unit_test(test_long_names_refused_before_solve),
        cmocka_unit_test(test_camera_refused_before_solve),
        cmocka_unit_test(test_full_disk_keeps_old_file),
        cmocka_unit_test(test_exit_not_converged),
        cmocka_unit_test(test_exit_saturated),
        cmocka_unit_test(test_emission_limit),
        cmocka_unit_test(test_default_camera_frames_meshed),
        cmocka_unit_test(test_exposure_shared_and_printed),
        cmocka_unit_test(test_outward_room_warns),
        cmocka_unit_test(test_help_matches_docs),
        cmocka_unit_test(test_help_sections),
        cmocka_unit_test(test_image_to_stdout),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
