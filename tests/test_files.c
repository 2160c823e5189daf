/* SPDX-License-Identifier: MIT */
/* Tests for tools/formats/file_io.c and for the inputs and outputs of the readers and
 * writers that use it (OBJ/MTL, images, stored form factors): hostile files (FIFOs,
 * devices, directories, sparse giants, endless streams), outputs that are links,
 * devices or FIFOs, and a full disk. Anything that could hang runs in a child process
 * under alarm(): a regression then fails, naming the alarm, instead of stopping the
 * suite. The alarms only catch hangs (see HANG_SECONDS), never a measure of speed. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "formats/ff_file.h"
#include "formats/file_io.h"
#include "formats/image.h"
#include "formats/obj.h"
#include "host/polys.h"
#include "check.h"
#include "tmpdir.h"

TMPDIR_GROUP("files")

/* The alarm of every step that could hang. The slowest step, reading 1 GiB of /dev/zero,
 * takes about 2 s here and 20 s under valgrind (make check-valgrind sets
 * RAD_TEST_LIGHT), the others milliseconds: the alarm is 30 times that, so that it only
 * ever means "hung", even on a loaded machine. */
#define HANG_SECONDS (getenv("RAD_TEST_LIGHT") ? 600u : 60u)

/* ---- helpers ------------------------------------------------------------------- */

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

/* The whole of PATH (malloc'd, NUL after it) and its size; NULL if unreadable. */
static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    char *d;
    long len;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    len = ftell(f);
    rewind(f);
    d = malloc((size_t)len + 1);
    if (d && fread(d, 1, (size_t)len, f) != (size_t)len) {
        free(d);
        d = NULL;
    }
    fclose(f);
    if (d) {
        d[len] = '\0';
        *n = (size_t)len;
    }
    return d;
}

/* PATH made (or kept) and set to SIZE bytes with ftruncate: a hole, no disk used. */
static void make_sparse(const char *path, off_t size)
{
    int fd = open(path, O_WRONLY | O_CREAT, 0600);
    CHECK_INT_GE(fd, 0, "open: %s", strerror(errno));
    assert_int_equal(ftruncate(fd, size), 0);
    close(fd);
}

/* How many entries of the test folder's DIR (a subfolder name) there are, and whether
 * one of them has a temporary file's ".tmp" in its name. */
static int count_entries(const char *dir, int *tmp_seen)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    int n = 0;
    *tmp_seen = 0;
    assert_non_null(d);
    while ((e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        n++;
        if (strstr(e->d_name, ".tmp")) *tmp_seen = 1;
    }
    closedir(d);
    return n;
}

/* A fresh subfolder of the test folder. */
static const char *fresh_dir(const char *name)
{
    const char *d = tmp_path(name);
    remove_tree(d);
    assert_int_equal(mkdir(d, 0700), 0);
    return d;
}

/* What a step run in a child reports: its return code and its message. */
typedef struct {
    int rc;
    char msg[512];
} child_result;

typedef void (*child_fn)(void *arg, child_result *r);

/* Runs FN(ARG) in a child under alarm(HANG_SECONDS) and returns what it reported; a
 * child that is killed (the alarm: a hang) fails the test, naming the signal. */
static child_result in_child(child_fn fn, void *arg)
{
    child_result r;
    int fds[2], status;
    ssize_t got;
    pid_t pid;
    memset(&r, 0, sizeof r);
    assert_int_equal(pipe(fds), 0);
    fflush(NULL);
    pid = fork();
    CHECK_INT_GE(pid, 0, "fork: %s", strerror(errno));
    if (pid == 0) {
        static const int crashes[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
        size_t i;
        for (i = 0; i < sizeof crashes / sizeof crashes[0]; i++)
            signal(crashes[i], SIG_DFL); /* a crash ends the child, not CMocka's handler */
        close(fds[0]);
        alarm(HANG_SECONDS);
        fn(arg, &r);
        _exit(write(fds[1], &r, sizeof r) == (ssize_t)sizeof r ? 0 : 3);
    }
    close(fds[1]);
    got = read(fds[0], &r, sizeof r);
    close(fds[0]);
    assert_int_equal(waitpid(pid, &status, 0), pid);
    if (WIFSIGNALED(status)) {
        print_error("child killed by signal %d%s\n", WTERMSIG(status),
                    WTERMSIG(status) == SIGALRM ? " (the alarm: it hung)" : "");
        fail();
    }
    assert_int_equal(WEXITSTATUS(status), 0);
    assert_int_equal(got, (ssize_t)sizeof r);
    return r;
}

/* A fresh FIFO in the test folder, and a child running FN on its path. */
static child_result on_new_fifo(const char *name, child_fn fn)
{
    const char *p = tmp_path(name);
    unlink(p);
    assert_int_equal(mkfifo(p, 0600), 0);
    return in_child(fn, (void *)p);
}

/* ---- fio_read_all -------------------------------------------------------------- */

static void test_read_regular(void **state)
{
    const char *p = tmp_path("plain.txt");
    char err[256], *d;
    size_t n;
    (void)state;
    write_file(p, "abc\0def", 7);
    assert_int_equal(fio_read_all(p, 7, &d, &n, err, sizeof err), 0);
    assert_int_equal(n, 7);
    assert_memory_equal(d, "abc\0def", 8); /* the NUL after the last byte too */
    free(d);
    write_file(p, "", 0); /* an empty regular file is empty, not an error */
    assert_int_equal(fio_read_all(p, 7, &d, &n, err, sizeof err), 0);
    assert_int_equal(n, 0);
    assert_int_equal(d[0], '\0');
    free(d);
}

static void test_read_limit(void **state)
{
    const char *p = tmp_path("hundred.txt");
    char buf[100], err[256], *d = (char *)1;
    size_t n = 1;
    (void)state;
    memset(buf, 'x', sizeof buf);
    write_file(p, buf, sizeof buf);
    assert_int_equal(fio_read_all(p, 99, &d, &n, err, sizeof err), -1);
    assert_null(d);
    assert_int_equal(n, 0);
    CHECK_CONTAINS(err, "hundred.txt: larger than the limit of 99 bytes: 100 bytes", "the message");
    assert_int_equal(fio_read_all(p, 100, &d, &n, err, sizeof err), 0);
    assert_int_equal(n, 100);
    free(d);
}

static void read_path(void *arg, child_result *r)
{
    char *d = NULL;
    size_t n;
    r->rc = fio_read_all(arg, FIO_LIMIT_TEXT, &d, &n, r->msg, sizeof r->msg);
    free(d);
}

/* Devices are refused before a byte is read: /dev/zero no longer streams a gigabyte to
 * the limit, /dev/null is not an empty file. */
static void test_read_devices(void **state)
{
    child_result r;
    (void)state;
    r = in_child(read_path, "/dev/zero");
    assert_int_equal(r.rc, -1);
    assert_string_equal(r.msg, "/dev/zero: not a regular file (a character device or terminal)");
    r = in_child(read_path, "/dev/null");
    assert_int_equal(r.rc, -1);
    assert_string_equal(r.msg, "/dev/null: not a regular file (a character device or terminal)");
}

/* A FIFO that no one writes: the open must not block, and it is refused. */
static void test_read_fifo_no_writer(void **state)
{
    child_result r = on_new_fifo("nowriter.fifo", read_path);
    (void)state;
    assert_int_equal(r.rc, -1);
    CHECK_CONTAINS(r.msg, "nowriter.fifo: not a regular file (a FIFO or pipe)", "the message");
}

/* A FIFO with a writer waiting: refused all the same, at once (the writer's open
 * returns when ours does, its write then fails: nothing is read). */
static void test_read_fifo_with_writer(void **state)
{
    const char *p = tmp_path("writer.fifo");
    child_result r;
    int keep;
    (void)state;
    unlink(p);
    assert_int_equal(mkfifo(p, 0600), 0);
    /* A writer held open by this process (O_RDWR: Linux opens a FIFO so without waiting
     * for the other end), with bytes waiting: a forked writer would race the reader's
     * open, and under load block after it for good. */
    keep = open(p, O_RDWR);
    CHECK_INT_GE(keep, 0, "open of the FIFO for writing: %s", strerror(errno));
    CHECK_INT_EQ(write(keep, "v 1 2 3\n", 8), 8, "bytes written into the FIFO");
    r = in_child(read_path, (void *)p);
    close(keep);
    assert_int_equal(r.rc, -1);
    CHECK_CONTAINS(r.msg, "writer.fifo: not a regular file (a FIFO or pipe)", "the message");
}

/* Standard input, asked for by name: a pipe is read to its end, a regular file whole; a
 * device is refused. ARG: what the child's standard input is. */
static void read_stdin(void *arg, child_result *r)
{
    const char *what = arg;
    char *d = NULL;
    size_t n = 0;
    int fds[2];
    if (!strcmp(what, "pipe")) {
        if (pipe(fds) != 0 || write(fds[1], "v 1 2 3\n", 8) != 8) _exit(2);
        close(fds[1]);
        dup2(fds[0], 0);
    } else {
        int fd = open(what, O_RDONLY);
        if (fd < 0) _exit(2);
        dup2(fd, 0);
    }
    r->rc = fio_read_stdin(FIO_LIMIT_TEXT, &d, &n, r->msg, sizeof r->msg);
    if (r->rc == 0) snprintf(r->msg, sizeof r->msg, "%zu bytes: %s", n, d);
    free(d);
}

static void test_read_stdin(void **state)
{
    child_result r;
    (void)state;
    r = in_child(read_stdin, "pipe");
    assert_int_equal(r.rc, 0);
    assert_string_equal(r.msg, "8 bytes: v 1 2 3\n");
    write_file(tmp_path("stdin.obj"), "f 1 2 3\n", 8);
    r = in_child(read_stdin, (void *)tmp_path("stdin.obj"));
    assert_int_equal(r.rc, 0);
    assert_string_equal(r.msg, "8 bytes: f 1 2 3\n");
    r = in_child(read_stdin, "/dev/zero");
    assert_int_equal(r.rc, -1);
    assert_string_equal(r.msg, "-: standard input is a device: pipe or redirect a file into it");
}

static void test_read_directory(void **state)
{
    char err[256], *d;
    size_t n;
    FILE *f;
    (void)state;
    assert_int_equal(fio_read_all(tmpdir, 100, &d, &n, err, sizeof err), -1);
    CHECK_CONTAINS(err, ": is a directory", "the message");
    f = fio_open_read(tmpdir, err, sizeof err);
    assert_null(f);
    CHECK_CONTAINS(err, ": is a directory", "the message");
}

static void test_read_missing(void **state)
{
    char err[256], *d;
    size_t n;
    (void)state;
    assert_int_equal(fio_read_all(tmp_path("nothing.obj"), 100, &d, &n, err, sizeof err), -1);
    CHECK_CONTAINS(err, "nothing.obj: cannot open: No such file or directory", "the message");
}

/* 20 GB that are not there (ftruncate makes a hole): refused from its size alone. */
static void test_read_sparse_giant(void **state)
{
    const char *p = tmp_path("giant.obj");
    child_result r;
    (void)state;
    make_sparse(p, (off_t)20 * 1000 * 1000 * 1000);
    r = in_child(read_path, (void *)p);
    assert_int_equal(r.rc, -1);
    CHECK_CONTAINS(r.msg,
                   "giant.obj: larger than the limit of 16 MiB (16777216 bytes): "
                   "20000000000 bytes",
                   "the message");
    unlink(p);
}

/* ---- fio_out ------------------------------------------------------------------- */

/* Writes TEXT to PATH through fio_out; returns fio_out_commit's result (or -1 if the
 * open fails), the message in err. */
static int put_text(const char *path, const char *text, char *err, size_t errlen)
{
    fio_out *o = fio_out_open(path, err, errlen);
    if (!o) return -1;
    fputs(text, fio_out_stream(o));
    return fio_out_commit(o, err, errlen);
}

static void test_out_new_and_replace(void **state)
{
    const char *dir = fresh_dir("out_plain"), *p = tmp_path("out_plain/a.txt");
    char err[256], *d;
    size_t n;
    struct stat st;
    int tmp_seen;
    (void)state;
    assert_int_equal(put_text(p, "first", err, sizeof err), 0);
    d = slurp(p, &n);
    assert_non_null(d);
    assert_string_equal(d, "first");
    free(d);
    assert_int_equal(chmod(p, 0640), 0);
    assert_int_equal(put_text(p, "second", err, sizeof err), 0);
    d = slurp(p, &n);
    assert_string_equal(d, "second");
    free(d);
    assert_int_equal(stat(p, &st), 0);
    assert_int_equal(st.st_mode & 0777, 0640); /* the replaced file's permissions */
    assert_int_equal(count_entries(dir, &tmp_seen), 1);
    assert_int_equal(tmp_seen, 0);
}

/* fio_out_abort leaves the old file and no temporary file. */
static void test_out_abort(void **state)
{
    const char *dir = fresh_dir("out_abort"), *p = tmp_path("out_abort/a.txt");
    char err[256], *d;
    size_t n;
    fio_out *o;
    int tmp_seen;
    (void)state;
    write_file(p, "old", 3);
    o = fio_out_open(p, err, sizeof err);
    assert_non_null(o);
    fputs("new", fio_out_stream(o));
    fio_out_abort(o);
    d = slurp(p, &n);
    assert_string_equal(d, "old");
    free(d);
    assert_int_equal(count_entries(dir, &tmp_seen), 1);
    assert_int_equal(tmp_seen, 0);
}

/* A link is kept; the file it points to gets the new contents. */
static void test_out_symlink(void **state)
{
    const char *dir = fresh_dir("out_link"), *real = tmp_path("out_link/real.txt"),
               *link = tmp_path("out_link/link.txt");
    char err[256], *d, target[64];
    size_t n;
    ssize_t len;
    struct stat st;
    int tmp_seen;
    (void)state;
    write_file(real, "old", 3);
    assert_int_equal(symlink("real.txt", link), 0);
    assert_int_equal(fio_check_out(link, err, sizeof err), 0);
    assert_int_equal(put_text(link, "new", err, sizeof err), 0);
    assert_int_equal(lstat(link, &st), 0);
    CHECK_THAT(S_ISLNK(st.st_mode), "the link is kept: mode 0%o", (unsigned)st.st_mode);
    len = readlink(link, target, sizeof target - 1);
    assert_int_equal(len, 8);
    target[len] = '\0';
    assert_string_equal(target, "real.txt");
    d = slurp(real, &n);
    assert_string_equal(d, "new");
    free(d);
    assert_int_equal(count_entries(dir, &tmp_seen), 2);
    assert_int_equal(tmp_seen, 0);
}

static void test_out_dangling_symlink(void **state)
{
    const char *link = tmp_path("dangling.txt");
    char err[256];
    (void)state;
    unlink(link);
    assert_int_equal(symlink("no/such/file", link), 0);
    assert_int_equal(put_text(link, "x", err, sizeof err), -1);
    CHECK_CONTAINS(err, "dangling.txt: cannot write: a symbolic link to a missing file",
                   "the message");
    assert_int_equal(fio_check_out(link, err, sizeof err), -1);
}

/* A name of a descriptor (/dev/stdout's kind) is written through it: appended to a file
 * opened for appending, as "rad_cli -o /dev/stdout >> log" wants, not renamed over. */
static void test_out_descriptor(void **state)
{
    const char *p = tmp_path("log.txt");
    char err[256], name[64], *d;
    size_t n;
    int fd, rfd;
    (void)state;
    write_file(p, "old\n", 4);
    fd = open(p, O_WRONLY | O_APPEND);
    CHECK_INT_GE(fd, 0, "open: %s", strerror(errno));
    snprintf(name, sizeof name, "/dev/fd/%d", fd);
    assert_int_equal(fio_check_out(name, err, sizeof err), 0);
    assert_int_equal(put_text(name, "new\n", err, sizeof err), 0);
    snprintf(name, sizeof name, "/proc/self/fd/%d", fd);
    assert_int_equal(put_text(name, "more\n", err, sizeof err), 0);
    close(fd);
    d = slurp(p, &n);
    assert_non_null(d);
    assert_string_equal(d, "old\nnew\nmore\n");
    free(d);
    rfd = open(p, O_RDONLY);
    CHECK_INT_GE(rfd, 0, "open: %s", strerror(errno));
    snprintf(name, sizeof name, "/dev/fd/%d", rfd);
    assert_int_equal(fio_check_out(name, err, sizeof err), -1);
    snprintf(name, sizeof name, "cannot write: descriptor %d is open for reading only", rfd);
    CHECK_CONTAINS(err, name, "the message");
    close(rfd);
}

/* /dev/null is written in place: still the same character device afterwards. */
static void test_out_dev_null(void **state)
{
    struct stat before, after;
    char err[256];
    (void)state;
    assert_int_equal(stat("/dev/null", &before), 0);
    assert_int_equal(fio_check_out("/dev/null", err, sizeof err), 0);
    assert_int_equal(put_text("/dev/null", "gone", err, sizeof err), 0);
    assert_int_equal(stat("/dev/null", &after), 0);
    CHECK_THAT(S_ISCHR(after.st_mode), "/dev/null is still a character device: mode 0%o",
               (unsigned)after.st_mode);
    assert_int_equal(after.st_rdev, before.st_rdev);
    assert_int_equal(after.st_ino, before.st_ino);
}

/* /dev/full takes nothing: the error says why. */
static void test_out_dev_full(void **state)
{
    char err[256];
    fio_out *o;
    (void)state;
    o = fio_out_open("/dev/full", err, sizeof err);
    assert_non_null(o);
    fputs("anything", fio_out_stream(o));
    assert_int_equal(fio_out_commit(o, err, sizeof err), -1);
    assert_string_equal(err, "/dev/full: write error: No space left on device");
}

/* The reader of test_out_fifo_with_reader: reads RFD to its end and sends back the
 * byte count and a hash of the bytes. */
static void fifo_reader(int rfd, int res)
{
    unsigned char b[4096];
    unsigned long tally[2] = {0, 0};
    ssize_t k, i;
    struct pollfd pf;
    alarm(HANG_SECONDS);
    /* A FIFO no writer has opened yet reads as its end: wait for the first bytes (poll
     * reports no hang-up before a writer has come). */
    pf.fd = rfd;
    pf.events = POLLIN;
    while (poll(&pf, 1, -1) < 0 && errno == EINTR)
        ;
    fcntl(rfd, F_SETFL, fcntl(rfd, F_GETFL) & ~O_NONBLOCK);
    while ((k = read(rfd, b, sizeof b)) > 0)
        for (i = 0; i < k; i++) {
            tally[0]++;
            tally[1] = tally[1] * 31 + b[i];
        }
    _exit(write(res, tally, sizeof tally) == (ssize_t)sizeof tally ? 0 : 1);
}

/* The reader PID got N bytes hashing to WANT: what it sends back on RES (then closed). */
static void expect_reader(int res, pid_t pid, unsigned long n, unsigned long want)
{
    unsigned long tally[2] = {0, 0};
    int status;
    assert_int_equal(read(res, tally, sizeof tally), (ssize_t)sizeof tally);
    close(res);
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_int_equal(status, 0);
    assert_int_equal(tally[0], n);
    assert_int_equal(tally[1], want);
}

/* 200 KB, more than a pipe holds, through a FIFO to a reader in another process. */
#define FIFO_BYTES 200000
static void test_out_fifo_with_reader(void **state)
{
    const char *p = tmp_path("out.fifo");
    char err[256];
    unsigned char *data = malloc(FIFO_BYTES);
    unsigned long want = 0;
    int rfd, res[2];
    struct stat st;
    fio_out *o;
    pid_t pid;
    size_t i;
    (void)state;
    assert_non_null(data);
    for (i = 0; i < FIFO_BYTES; i++) {
        data[i] = (unsigned char)(i * 7 + i / 251);
        want = want * 31 + data[i];
    }
    unlink(p);
    assert_int_equal(mkfifo(p, 0600), 0);
    rfd = open(p, O_RDONLY | O_NONBLOCK); /* a reader exists before fio_out_open */
    CHECK_INT_GE(rfd, 0, "open: %s", strerror(errno));
    o = fio_out_open(p, err, sizeof err);
    assert_non_null(o);
    assert_int_equal(pipe(res), 0);
    fflush(NULL);
    pid = fork();
    CHECK_INT_GE(pid, 0, "fork: %s", strerror(errno));
    if (pid == 0) {
        fio_out_abort(o); /* else this child holds a writer open (and leaks O) */
        free(data);
        close(res[0]);
        fifo_reader(rfd, res[1]);
    }
    close(rfd);
    close(res[1]);
    assert_int_equal(fwrite(data, 1, FIFO_BYTES, fio_out_stream(o)), FIFO_BYTES);
    assert_int_equal(fio_out_commit(o, err, sizeof err), 0);
    expect_reader(res[0], pid, FIFO_BYTES, want);
    assert_int_equal(lstat(p, &st), 0);
    CHECK_THAT(S_ISFIFO(st.st_mode), "still the FIFO: mode 0%o", (unsigned)st.st_mode);
    free(data);
}

static void open_out_path(void *arg, child_result *r)
{
    fio_out *o = fio_out_open(arg, r->msg, sizeof r->msg);
    r->rc = o ? 0 : -1;
    fio_out_abort(o);
}

/* A FIFO no one reads: an error at once, not a wait for a reader. */
static void test_out_fifo_no_reader(void **state)
{
    child_result r = on_new_fifo("noreader.fifo", open_out_path);
    (void)state;
    assert_int_equal(r.rc, -1);
    CHECK_CONTAINS(r.msg, "noreader.fifo: cannot open: a FIFO with no reader", "the message");
}

static void test_out_directory(void **state)
{
    const char *dir = fresh_dir("out_dir");
    char err[256];
    int tmp_seen;
    (void)state;
    assert_int_equal(fio_check_out(dir, err, sizeof err), -1);
    CHECK_CONTAINS(err, "out_dir: is a directory", "the message");
    assert_null(fio_out_open(dir, err, sizeof err));
    CHECK_CONTAINS(err, "out_dir: is a directory", "the message");
    assert_int_equal(count_entries(dir, &tmp_seen), 0);
}

static void test_out_missing_folder(void **state)
{
    const char *p = tmp_path("no_such_folder/a.png");
    char err[256];
    (void)state;
    assert_int_equal(fio_check_out(p, err, sizeof err), -1);
    CHECK_CONTAINS(err, "a.png: cannot write into '", "the message");
    CHECK_CONTAINS(err, "no_such_folder': No such file or directory", "the message");
    assert_null(fio_out_open(p, err, sizeof err));
    CHECK_CONTAINS(err, "a.png: cannot create temporary file: No such file or directory",
                   "the message");
}

/* fio_check_out writes nothing. */
static void test_check_out_writes_nothing(void **state)
{
    const char *dir = fresh_dir("check"), *p = tmp_path("check/new.txt");
    char err[256];
    int tmp_seen;
    (void)state;
    assert_int_equal(fio_check_out(p, err, sizeof err), 0);
    assert_int_equal(count_entries(dir, &tmp_seen), 0);
}

/* ---- the readers: OBJ, MTL, images, stored form factors -------------------------- */

/* Warnings into a child_result: the first one's text, and how many came. */
static void first_warning(void *ctx, const char *msg)
{
    child_result *r = ctx;
    if (r->rc++ == 0) snprintf(r->msg, sizeof r->msg, "%s", msg);
}

static void load_obj(void *arg, child_result *r)
{
    obj_scene sc;
    r->rc = obj_load(arg, &sc, NULL, NULL, r->msg, sizeof r->msg);
    obj_free(&sc);
}

/* Loads an OBJ (which must load) and reports its warnings: count in rc, first in msg;
 * -100 - faces if the face count is not 1. Files outside its folder are read (these
 * tests are about the kinds of files: /dev/zero as a library). */
static void load_obj_warnings(void *arg, child_result *r)
{
    obj_scene sc;
    obj_opts o = {1};
    char err[512];
    if (obj_load_opts(arg, &o, &sc, first_warning, r, err, sizeof err) != 0) {
        r->rc = -1;
        snprintf(r->msg, sizeof r->msg, "%s", err);
        return;
    }
    if (sc.nfaces != 1) r->rc = -100 - sc.nfaces;
    obj_free(&sc);
}

static void load_ff(void *arg, child_result *r)
{
    ff_file_t f;
    r->rc = ff_file_load(arg, &f, r->msg, sizeof r->msg);
    ff_file_free(&f);
}

static void read_img(void *arg, child_result *r)
{
    img_t im;
    r->rc = img_read(arg, &im, r->msg, sizeof r->msg);
    img_free(&im);
}

#define TRIANGLE "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"

/* An OBJ in the test folder whose first line is mtllib LIB; returns its path. */
static const char *obj_with_mtllib(const char *name, const char *lib)
{
    char text[512];
    const char *p = tmp_path(name);
    int n = snprintf(text, sizeof text, "mtllib %s\n" TRIANGLE, lib);
    write_file(p, text, (size_t)n);
    return p;
}

/* FIFOs as the scene, a --load-ff file, an image and a material library: refused at
 * once, with no writer (nothing to wait for). */
static void test_fifo_inputs(void **state)
{
    const char *obj = obj_with_mtllib("fifo_lib.obj", "lib.fifo"), *f = tmp_path("lib.fifo");
    char want[600];
    child_result r;
    (void)state;
    r = on_new_fifo("scene.fifo", load_obj); /* the scene */
    assert_int_equal(r.rc, -1);
    snprintf(want, sizeof want, "%s: not a regular file (a FIFO or pipe)", tmp_path("scene.fifo"));
    assert_string_equal(r.msg, want);
    r = on_new_fifo("ff.fifo", load_ff); /* --load-ff */
    assert_int_equal(r.rc, -1);
    CHECK_CONTAINS(r.msg, "ff.fifo: not a regular file (a FIFO or pipe)", "the message");
    r = on_new_fifo("img.fifo", read_img);
    assert_int_equal(r.rc, -1);
    CHECK_CONTAINS(r.msg, "img.fifo: not a regular file (a FIFO or pipe)", "the message");
    unlink(f); /* an mtllib: a warning, the faces load with the default material */
    assert_int_equal(mkfifo(f, 0600), 0);
    r = in_child(load_obj_warnings, (void *)obj);
    assert_int_equal(r.rc, 1);
    snprintf(want, sizeof want,
             "%s:1: cannot read material library 'lib.fifo': not a regular file "
             "(a FIFO or pipe)",
             obj);
    assert_string_equal(r.msg, want);
}

/* /dev/zero as a scene, a material library and an image: refused unread (it was read to
 * each limit: 1 GiB, 64 MiB, 256 MiB). */
static void test_dev_zero_inputs(void **state)
{
    const char *obj = obj_with_mtllib("zero_lib.obj", "/dev/zero");
    char want[600];
    child_result r;
    (void)state;
    r = in_child(load_obj, "/dev/zero");
    assert_int_equal(r.rc, -1);
    assert_string_equal(r.msg, "/dev/zero: not a regular file (a character device or terminal)");
    r = in_child(load_obj_warnings, (void *)obj);
    assert_int_equal(r.rc, 1);
    snprintf(want, sizeof want,
             "%s:1: cannot read material library '/dev/zero': not a regular file "
             "(a character device or terminal)",
             obj);
    assert_string_equal(r.msg, want);
    r = in_child(read_img, "/dev/zero");
    assert_int_equal(r.rc, -1);
    assert_string_equal(r.msg, "/dev/zero: not a regular file (a character device or terminal)");
}

/* 20 GB of hole: a scene and an image are refused from their size; a form factor file
 * from its header (zeros: bad magic) or from the size its header implies. */
static void test_sparse_giants(void **state)
{
    const char *ff = tmp_path("giant.ff"), *img = tmp_path("giant.png"),
               *obj = tmp_path("giant2.obj");
    const off_t big = (off_t)20 * 1000 * 1000 * 1000;
    ff_file_info info;
    uint32_t start[2] = {0, 0};
    char err[256];
    child_result r;
    (void)state;
    make_sparse(obj, big);
    r = in_child(load_obj, (void *)obj);
    assert_int_equal(r.rc, -1);
    CHECK_CONTAINS(
        r.msg,
        "giant2.obj: larger than the limit of 1024 MiB (1073741824 bytes): 20000000000 bytes",
        "the message");
    make_sparse(img, big);
    r = in_child(read_img, (void *)img);
    CHECK_CONTAINS(
        r.msg, "giant.png: larger than the limit of 256 MiB (268435456 bytes): 20000000000 bytes",
        "the message");
    make_sparse(ff, big);
    r = in_child(load_ff, (void *)ff);
    assert_int_equal(r.rc, -1);
    CHECK_CONTAINS(r.msg, "giant.ff: not a rad form factor file (bad magic", "the message");
    memset(&info, 0, sizeof info); /* a valid file of one empty row, then 20 GB */
    info.kind = FF_FILE_KIND_FIXED;
    info.res = 8;
    info.patches = 1;
    assert_int_equal(ff_file_save(ff, &info, start, start, 4, NULL, err, sizeof err), 0);
    make_sparse(ff, big);
    r = in_child(load_ff, (void *)ff);
    assert_int_equal(r.rc, -1);
    CHECK_CONTAINS(
        r.msg,
        "giant.ff: corrupt: 20000000000 bytes, its header (1 rows, 0 entries) says 56: not read",
        "the message");
    unlink(ff);
    unlink(img);
    unlink(obj);
}

static void test_directory_inputs(void **state)
{
    const char *dir = fresh_dir("in_dir");
    char err[256], want[300];
    obj_scene sc;
    img_t im;
    ff_file_t f;
    (void)state;
    snprintf(want, sizeof want, "%s: is a directory", dir);
    assert_int_equal(obj_load(dir, &sc, NULL, NULL, err, sizeof err), -1);
    assert_string_equal(err, want);
    assert_int_equal(img_read(dir, &im, err, sizeof err), -1);
    assert_string_equal(err, want);
    assert_int_equal(ff_file_load(dir, &f, err, sizeof err), -1);
    assert_string_equal(err, want);
}

/* ---- the writers: images and stored form factors ------------------------------------ */

#define IW 64
#define IH 48
/* Noise, so that a PNG of it is larger than the 4096 bytes of test_writers_full_disk. */
static void noise(unsigned char *rgb)
{
    uint32_t x = 12345;
    size_t i;
    for (i = 0; i < IW * IH * 3; i++) {
        x = x * 1103515245u + 12345u;
        rgb[i] = (unsigned char)(x >> 24);
    }
}

/* A form factor file of PATCHES empty rows: 48 + 4 (PATCHES + 1) bytes. */
static int save_empty_rows(const char *path, uint32_t patches, char *err, size_t errlen)
{
    uint32_t *start = calloc(patches + 1, sizeof *start);
    ff_file_info info;
    int rc;
    assert_non_null(start);
    memset(&info, 0, sizeof info);
    info.kind = FF_FILE_KIND_FIXED;
    info.res = 8;
    info.patches = patches;
    rc = ff_file_save(path, &info, start, start, 4, NULL, err, errlen);
    free(start);
    return rc;
}

static void test_writers_symlink(void **state)
{
    const char *dir = fresh_dir("w_link");
    unsigned char rgb[IW * IH * 3];
    char err[256];
    struct stat st;
    img_t im;
    ff_file_t f;
    int tmp_seen;
    (void)state;
    noise(rgb);
    write_file(tmp_path("w_link/real.png"), "old", 3);
    assert_int_equal(symlink("real.png", tmp_path("w_link/link.png")), 0);
    assert_int_equal(img_write(tmp_path("w_link/link.png"), rgb, IW, IH, err, sizeof err), 0);
    assert_int_equal(lstat(tmp_path("w_link/link.png"), &st), 0);
    CHECK_THAT(S_ISLNK(st.st_mode), "the link is kept: mode 0%o", (unsigned)st.st_mode);
    assert_int_equal(img_read(tmp_path("w_link/real.png"), &im, err, sizeof err), 0);
    assert_memory_equal(im.rgb, rgb, sizeof rgb);
    img_free(&im);
    write_file(tmp_path("w_link/real.ff"), "old", 3);
    assert_int_equal(symlink("real.ff", tmp_path("w_link/link.ff")), 0);
    assert_int_equal(save_empty_rows(tmp_path("w_link/link.ff"), 3, err, sizeof err), 0);
    assert_int_equal(lstat(tmp_path("w_link/link.ff"), &st), 0);
    CHECK_THAT(S_ISLNK(st.st_mode), "the link is kept: mode 0%o", (unsigned)st.st_mode);
    assert_int_equal(ff_file_load(tmp_path("w_link/real.ff"), &f, err, sizeof err), 0);
    assert_int_equal(f.info.patches, 3);
    ff_file_free(&f);
    assert_int_equal(count_entries(dir, &tmp_seen), 4);
    assert_int_equal(tmp_seen, 0);
}

/* /dev/null (as itself for the form factors, through a .png link for the image, whose
 * format comes from the name) is still the same device afterwards; /dev/full says why
 * it takes nothing. */
static void test_writers_devices(void **state)
{
    unsigned char rgb[IW * IH * 3];
    char err[256];
    struct stat before, after;
    (void)state;
    noise(rgb);
    unlink(tmp_path("null.png"));
    unlink(tmp_path("full.png"));
    assert_int_equal(symlink("/dev/null", tmp_path("null.png")), 0);
    assert_int_equal(symlink("/dev/full", tmp_path("full.png")), 0);
    assert_int_equal(stat("/dev/null", &before), 0);
    assert_int_equal(img_write(tmp_path("null.png"), rgb, IW, IH, err, sizeof err), 0);
    assert_int_equal(save_empty_rows("/dev/null", 3, err, sizeof err), 0);
    assert_int_equal(stat("/dev/null", &after), 0);
    CHECK_THAT(S_ISCHR(after.st_mode), "/dev/null is still a character device: mode 0%o",
               (unsigned)after.st_mode);
    assert_int_equal(after.st_rdev, before.st_rdev);
    assert_int_equal(after.st_ino, before.st_ino);
    assert_int_equal(img_write(tmp_path("full.png"), rgb, IW, IH, err, sizeof err), -1);
    CHECK_CONTAINS(err, "full.png: write error: No space left on device", "the message");
    assert_int_equal(save_empty_rows("/dev/full", 3, err, sizeof err), -1);
    assert_string_equal(err, "/dev/full: write error: No space left on device");
}

/* An image through a FIFO to a reader in another process: the same bytes as the file. */
static void test_img_write_fifo(void **state)
{
    const char *p = tmp_path("img.ppm"), *ref = tmp_path("ref.ppm");
    unsigned char rgb[IW * IH * 3];
    unsigned long want = 0;
    char err[256], *d;
    size_t n, i;
    int rfd, res[2];
    pid_t pid;
    (void)state;
    noise(rgb);
    assert_int_equal(img_write(ref, rgb, IW, IH, err, sizeof err), 0);
    d = slurp(ref, &n);
    assert_non_null(d);
    for (i = 0; i < n; i++) want = want * 31 + (unsigned char)d[i];
    free(d);
    unlink(p);
    assert_int_equal(mkfifo(p, 0600), 0);
    rfd = open(p, O_RDONLY | O_NONBLOCK);
    CHECK_INT_GE(rfd, 0, "open: %s", strerror(errno));
    assert_int_equal(pipe(res), 0);
    fflush(NULL);
    pid = fork();
    CHECK_INT_GE(pid, 0, "fork: %s", strerror(errno));
    if (pid == 0) {
        close(res[0]);
        fifo_reader(rfd, res[1]);
    }
    close(res[1]);
    assert_int_equal(img_write(p, rgb, IW, IH, err, sizeof err), 0); /* rfd: a reader */
    close(rfd);
    expect_reader(res[0], pid, n, want);
}

/* What write_past_limit writes: 100,000 bytes through fio_out, an image (PNG or PPM
 * by the name), or a form factor file of 3000 rows (12 KB). */
enum { FULL_RAW, FULL_IMAGE, FULL_FF };
/* An image to /dev/fd/N (what "-o /dev/stdout" is), where the name has no extension:
 * img_write_as names the format; the bytes are those of the same image in a file. */
static void test_img_write_descriptor(void **state)
{
    const char *p = tmp_path("fd.out"), *ref = tmp_path("fd_ref.png");
    unsigned char rgb[IW * IH * 3];
    char err[256], name[64], *a, *b;
    size_t na, nb;
    int fd;
    (void)state;
    noise(rgb);
    assert_int_equal(img_write(ref, rgb, IW, IH, err, sizeof err), 0);
    fd = open(p, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    CHECK_INT_GE(fd, 0, "open: %s", strerror(errno));
    snprintf(name, sizeof name, "/dev/fd/%d", fd);
    assert_int_equal(img_write(name, rgb, IW, IH, err, sizeof err), -1);
    CHECK_CONTAINS(err, ": unknown image extension (use .png or .ppm)", "the message");
    assert_int_equal(img_write_as(name, "gif", rgb, IW, IH, err, sizeof err), -1);
    CHECK_CONTAINS(err, ": unknown image format 'gif' (use png or ppm)", "the message");
    assert_int_equal(img_write_as(name, "PNG", rgb, IW, IH, err, sizeof err), 0);
    close(fd);
    a = slurp(p, &na);
    b = slurp(ref, &nb);
    assert_non_null(a);
    assert_non_null(b);
    assert_int_equal(na, nb);
    assert_memory_equal(a, b, na);
    free(a);
    free(b);
}

typedef struct {
    const char *path;
    int kind;
} full_write;

static int write_raw(const char *path, char *err, size_t errlen)
{
    fio_out *o = fio_out_open(path, err, errlen);
    int i;
    if (!o) return -3;
    for (i = 0; i < 100000; i++) putc('n', fio_out_stream(o));
    return fio_out_commit(o, err, errlen);
}

static void write_past_limit(void *arg, child_result *r)
{
    const full_write *w = arg;
    unsigned char rgb[IW * IH * 3];
    struct rlimit rl;
    rl.rlim_cur = rl.rlim_max = 4096;
    signal(SIGXFSZ, SIG_IGN);
    noise(rgb);
    if (setrlimit(RLIMIT_FSIZE, &rl) != 0) {
        r->rc = 2;
        snprintf(r->msg, sizeof r->msg, "setrlimit: %s", strerror(errno));
        return;
    }
    r->rc = w->kind == FULL_FF      ? save_empty_rows(w->path, 3000, r->msg, sizeof r->msg)
            : w->kind == FULL_IMAGE ? img_write(w->path, rgb, IW, IH, r->msg, sizeof r->msg)
                                    : write_raw(w->path, r->msg, sizeof r->msg);
}

/* A full disk (RLIMIT_FSIZE at 4096 bytes, SIGXFSZ ignored, so writes fail with EFBIG)
 * under fio_out itself, a PNG of noise (about 9 KB), a PPM (9 KB) and a form factor
 * file (12 KB): each fails with the reason, the old file is byte for byte what it was,
 * no temporary file stays. */
static void test_writers_full_disk(void **state)
{
    static const char *const names[] = {"old.bin", "old.png", "old.ppm", "old.ff"};
    static const int kinds[] = {FULL_RAW, FULL_IMAGE, FULL_IMAGE, FULL_FF};
    const char *dir = fresh_dir("w_full");
    unsigned char old[2000];
    char *d, path[400];
    full_write w;
    child_result r;
    size_t n, i, k;
    int tmp_seen;
    (void)state;
    for (i = 0; i < sizeof old; i++) old[i] = (unsigned char)(i * 7);
    for (k = 0; k < 4; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        write_file(path, old, sizeof old);
        w.path = path;
        w.kind = kinds[k];
        r = in_child(write_past_limit, &w);
        assert_int_equal(r.rc, -1);
        CHECK_CONTAINS(r.msg, ": write error: File too large", "the message");
        CHECK_CONTAINS(r.msg, names[k], "the message");
        d = slurp(path, &n);
        assert_non_null(d);
        assert_int_equal(n, sizeof old);
        assert_memory_equal(d, old, sizeof old);
        free(d);
    }
    assert_int_equal(count_entries(dir, &tmp_seen), 4);
    assert_int_equal(tmp_seen, 0);
}

/* ---- the OBJ parser: many materials, huge faces, line ends, BOM --------------------- */

#define NMATS 200000

static void load_many_materials(void *arg, child_result *r)
{
    obj_scene sc;
    char name[32];
    int i;
    (void)arg;
    if ((r->rc = obj_load(tmp_path("mats.obj"), &sc, NULL, NULL, r->msg, sizeof r->msg)) != 0)
        return;
    r->rc = sc.nmaterials;
    for (i = 0; i < NMATS; i++) { /* every name at its index, with its own Kd */
        snprintf(name, sizeof name, "m%d", i);
        if (obj_find_material(&sc, name) != i ||
            sc.materials[i].kd[0] != (double)(i % 1000) / 1000) {
            snprintf(r->msg, sizeof r->msg, "%s found at %d, Kd %g", name,
                     obj_find_material(&sc, name), sc.materials[i].kd[0]);
            r->rc = -2;
            break;
        }
    }
    if (r->rc >= 0 &&
        (obj_find_material(&sc, "m200000") != -1 || sc.faces[0].material != NMATS - 1))
        r->rc = -3;
    obj_free(&sc);
}

/* 200,000 materials (84 s with a linear lookup): each found at its index. */
static void test_many_materials(void **state)
{
    FILE *m = fopen(tmp_path("mats.mtl"), "w");
    child_result r;
    int i;
    (void)state;
    assert_non_null(m);
    for (i = 0; i < NMATS; i++) fprintf(m, "newmtl m%d\nKd %g 0 0\n", i, (double)(i % 1000) / 1000);
    assert_int_equal(fclose(m), 0);
    write_file(tmp_path("mats.obj"),
               "mtllib mats.mtl\n"
               "usemtl m199999\n" TRIANGLE,
               strlen("mtllib mats.mtl\n"
                      "usemtl m199999\n" TRIANGLE));
    r = in_child(load_many_materials, NULL);
    if (r.rc != NMATS) print_error("rc %d: %s\n", r.rc, r.msg);
    assert_int_equal(r.rc, NMATS);
}

/* The OBJ text of one face of N vertices, on a star that crosses itself (vertex i at
 * angle i * (N/2 - 1) steps of 2 pi / N), into a malloc'd buffer. */
static char *star_face(int n, size_t *len)
{
    size_t cap = (size_t)n * 48 + 16, k = 0;
    char *t = malloc(cap);
    int i;
    assert_non_null(t);
    for (i = 0; i < n; i++) {
        double a = 6.283185307179586 * (double)((long long)i * (n / 2 - 1) % n) / n;
        k += (size_t)sprintf(t + k, "v %.9f %.9f 0\n", cos(a), sin(a));
    }
    k += (size_t)sprintf(t + k, "f");
    for (i = 1; i <= n; i++) k += (size_t)sprintf(t + k, " %d", i);
    t[k++] = '\n';
    *len = k;
    return t;
}

static void poly_warning(void *ctx, int line, const char *msg)
{
    child_result *r = ctx;
    snprintf(r->msg, sizeof r->msg, "line %d: %s", line, msg);
}

/* Clips the star of *ARG vertices: rc is what obj_triangulate returns; msg is
 * polys_from_obj' warning, if any. */
static void clip_star(void *arg, child_result *r)
{
    int n = *(int *)arg, np = 0, *tri = malloc(sizeof(int) * 3 * (size_t)n);
    size_t len;
    char *text = star_face(n, &len), err[256];
    obj_scene sc;
    sc_poly *p;
    if (obj_parse(text, len, "star.obj", NULL, &sc, NULL, NULL, err, sizeof err) != 0 || !tri) {
        r->rc = -100;
        snprintf(r->msg, sizeof r->msg, "%s", err);
    } else {
        r->rc = obj_triangulate(&sc, &sc.faces[0], tri);
        p = polys_from_obj(&sc, &np, poly_warning, r);
        free(p);
    }
    obj_free(&sc);
    free(text);
    free(tri);
}

/* 20,000 vertices on a self-intersecting star (62 s of ear clipping unbounded) are
 * refused at once with a warning naming the line; 1024 (the limit) are clipped. */
static void test_huge_face(void **state)
{
    int n = 20000;
    child_result r = in_child(clip_star, &n);
    char want[128];
    (void)state;
    assert_int_equal(r.rc, OBJ_TOO_MANY_VERTICES);
    snprintf(want, sizeof want, "line %d: skipped a face of more than %d vertices (split it)",
             n + 1, OBJ_MAX_FACE_VERTICES);
    assert_string_equal(r.msg, want);
    n = OBJ_MAX_FACE_VERTICES;
    r = in_child(clip_star, &n);
    assert_int_equal(r.rc, n - 2);
    assert_string_equal(r.msg, "");
}

/* One scene in each line-end convention, with and without a byte order mark: the same
 * material from the same library, the same faces on the same lines. */
static void test_line_ends_and_bom(void **state)
{
    static const char *const eols[] = {"\n", "\r\n", "\r"};
    static const char *const obj_lines[] = {
        "# scene", "mtllib le.mtl", "v 0 0 0", "v 1 0 0", "v 0 1 0",
        "v 1 1 0", "usemtl red",    "f 1 2 3", "f 2 4 3", NULL};
    static const char *const mtl_lines[] = {"newmtl red", "Kd 0.5 0.25 0.125", NULL};
    char text[512], err[256];
    obj_scene sc;
    int e, bom, i;
    size_t n;
    FILE *f;
    (void)state;
    for (e = 0; e < 3; e++)
        for (bom = 0; bom < 2; bom++) {
            child_result warns;
            memset(&warns, 0, sizeof warns);
            for (n = 0, i = 0; mtl_lines[i]; i++)
                n += (size_t)sprintf(text + n, "%s%s%s", bom && !i ? "\xEF\xBB\xBF" : "",
                                     mtl_lines[i], eols[e]);
            write_file(tmp_path("le.mtl"), text, n);
            for (n = 0, i = 0; obj_lines[i]; i++)
                n += (size_t)sprintf(text + n, "%s%s%s", bom && !i ? "\xEF\xBB\xBF" : "",
                                     obj_lines[i], eols[e]);
            f = fopen(tmp_path("le.obj"), "wb");
            assert_non_null(f);
            assert_int_equal(fwrite(text, 1, n, f), n);
            fclose(f);
            if (obj_load(tmp_path("le.obj"), &sc, first_warning, &warns, err, sizeof err) != 0)
                print_error("eol %d bom %d: %s\n", e, bom, err);
            if (warns.rc)
                print_error("eol %d bom %d: %d warnings, first: %s\n", e, bom, warns.rc, warns.msg);
            assert_int_equal(warns.rc, 0);
            assert_int_equal(sc.nfaces, 2);
            assert_int_equal(sc.faces[0].line, 8);
            assert_int_equal(sc.faces[1].line, 9);
            assert_int_equal(sc.nmaterials, 1);
            assert_int_equal(sc.materials[0].defined, 1);
            CHECK_THAT(sc.materials[0].kd[0] == 0.5 && sc.materials[0].kd[1] == 0.25 &&
                           sc.materials[0].kd[2] == 0.125,
                       "eol %d bom %d: Kd %g %g %g, the library's 0.5 0.25 0.125", e, bom,
                       sc.materials[0].kd[0], sc.materials[0].kd[1], sc.materials[0].kd[2]);
            assert_int_equal(sc.faces[1].material, 0);
            assert_int_equal(sc.unknown_statements, 0);
            obj_free(&sc);
        }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_read_regular),
        cmocka_unit_test(test_read_limit),
        cmocka_unit_test(test_read_devices),
        cmocka_unit_test(test_read_fifo_no_writer),
        cmocka_unit_test(test_read_fifo_with_writer),
        cmocka_unit_test(test_read_stdin),
        cmocka_unit_test(test_read_directory),
        cmocka_unit_test(test_read_missing),
        cmocka_unit_test(test_read_sparse_giant),
        cmocka_unit_test(test_out_new_and_replace),
        cmocka_unit_test(test_out_abort),
        cmocka_unit_test(test_out_symlink),
        cmocka_unit_test(test_out_dangling_symlink),
        cmocka_unit_test(test_out_descriptor),
        cmocka_unit_test(test_out_dev_null),
        cmocka_unit_test(test_out_dev_full),
        cmocka_unit_test(test_out_fifo_with_reader),
        cmocka_unit_test(test_out_fifo_no_reader),
        cmocka_unit_test(test_out_directory),
        cmocka_unit_test(test_out_missing_folder),
        cmocka_unit_test(test_check_out_writes_nothing),
        cmocka_unit_test(test_fifo_inputs),
        cmocka_unit_test(test_dev_zero_inputs),
        cmocka_unit_test(test_sparse_giants),
        cmocka_unit_test(test_directory_inputs),
        cmocka_unit_test(test_writers_symlink),
        cmocka_unit_test(test_writers_devices),
        cmocka_unit_test(test_img_write_fifo),
        cmocka_unit_test(test_img_write_descriptor),
        cmocka_unit_test(test_writers_full_disk),
        cmocka_unit_test(test_many_materials),
        cmocka_unit_test(test_huge_face),
        cmocka_unit_test(test_line_ends_and_bom),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
