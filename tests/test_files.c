/* Tests for tools/formats/file_io.c and for the inputs and outputs of the readers and
 * writers that use it (OBJ/MTL, images, stored form factors): hostile files (FIFOs,
 * devices, directories, sparse giants, endless streams), outputs that are links,
 * devices or FIFOs, and a full disk. Anything that could hang runs in a child process
 * under alarm(): a regression then fails with "timed out" instead of stopping the
 * suite. The alarms only catch hangs: each is at least 10x what the step takes here
 * (milliseconds), never a measure of speed. */
#include <errno.h>
#include <fcntl.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "formats/file_io.h"
#include "tmpdir.h"

TMPDIR_GROUP("files")

#define HANG_SECONDS 20 /* steps here take milliseconds: 20 s only means "hung" */

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
    if (!f)
        return NULL;
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

/* Fails, printing both, unless HAYSTACK contains NEEDLE. */
static void expect_text(const char *haystack, const char *needle)
{
    if (!strstr(haystack, needle)) {
        print_error("message \"%s\" lacks \"%s\"\n", haystack, needle);
        fail();
    }
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
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        n++;
        if (strstr(e->d_name, ".tmp"))
            *tmp_seen = 1;
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
    assert_true(pid >= 0);
    if (pid == 0) {
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
    expect_text(err, "hundred.txt: larger than the limit of 99 bytes: 100 bytes");
    assert_int_equal(fio_read_all(p, 100, &d, &n, err, sizeof err), 0);
    assert_int_equal(n, 100);
    free(d);
}

static void read_zero(void *arg, child_result *r)
{
    char *d;
    size_t n;
    r->rc = fio_read_all("/dev/zero", *(size_t *)arg, &d, &n, r->msg, sizeof r->msg);
}

/* An endless stream stops at the limit: 1 MiB here (the tools' limits are in the
 * tests of each reader). */
static void test_read_dev_zero(void **state)
{
    size_t limit = 1048576;
    child_result r = in_child(read_zero, &limit);
    (void)state;
    assert_int_equal(r.rc, -1);
    assert_string_equal(r.msg, "/dev/zero: larger than the limit of 1 MiB (1048576 bytes)");
}

static void read_path(void *arg, child_result *r)
{
    char *d = NULL;
    size_t n;
    r->rc = fio_read_all(arg, FIO_LIMIT_TEXT, &d, &n, r->msg, sizeof r->msg);
    free(d);
}

/* A FIFO that no one writes: the open must not block, and nothing is an error. */
static void test_read_fifo_no_writer(void **state)
{
    child_result r = on_new_fifo("nowriter.fifo", read_path);
    (void)state;
    assert_int_equal(r.rc, -1);
    expect_text(r.msg, "nowriter.fifo: nothing to read (a FIFO with no writer");
}

/* A FIFO with a writer is read to its end. */
static void test_read_fifo_with_writer(void **state)
{
    const char *p = tmp_path("writer.fifo");
    char err[256], *d;
    size_t n;
    pid_t pid;
    int status;
    struct timespec ms = { 0, 1000000 };
    (void)state;
    unlink(p);
    assert_int_equal(mkfifo(p, 0600), 0);
    fflush(NULL);
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) { /* the writer's open blocks until our reader opens */
        int fd;
        alarm(HANG_SECONDS);
        fd = open(p, O_WRONLY);
        _exit(fd >= 0 && write(fd, "v 1 2 3\n", 8) == 8 ? 0 : 1);
    }
    /* Our open does not wait for the writer: read until its data comes. */
    do {
        n = 0;
        d = NULL;
        if (fio_read_all(p, 100, &d, &n, err, sizeof err) == 0)
            break;
        expect_text(err, "nothing to read");
        nanosleep(&ms, NULL);
    } while (1);
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_int_equal(n, 8);
    assert_string_equal(d, "v 1 2 3\n");
    free(d);
}

static void test_read_directory(void **state)
{
    char err[256], *d;
    size_t n;
    FILE *f;
    (void)state;
    assert_int_equal(fio_read_all(tmpdir, 100, &d, &n, err, sizeof err), -1);
    expect_text(err, ": is a directory");
    f = fio_open_read(tmpdir, err, sizeof err);
    assert_null(f);
    expect_text(err, ": is a directory");
}

static void test_read_missing(void **state)
{
    char err[256], *d;
    size_t n;
    (void)state;
    assert_int_equal(fio_read_all(tmp_path("nothing.obj"), 100, &d, &n, err, sizeof err), -1);
    expect_text(err, "nothing.obj: cannot open: No such file or directory");
}

/* 20 GB that are not there (ftruncate makes a hole): refused from its size alone. */
static void test_read_sparse_giant(void **state)
{
    const char *p = tmp_path("giant.obj");
    child_result r;
    int fd;
    (void)state;
    fd = open(p, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    assert_true(fd >= 0);
    assert_int_equal(ftruncate(fd, (off_t)20 * 1000 * 1000 * 1000), 0);
    close(fd);
    r = in_child(read_path, (void *)p);
    assert_int_equal(r.rc, -1);
    expect_text(r.msg, "giant.obj: larger than the limit of 16 MiB (16777216 bytes): "
                       "20000000000 bytes");
    unlink(p);
}

/* ---- fio_out ------------------------------------------------------------------- */

/* Writes TEXT to PATH through fio_out; returns fio_out_commit's result (or -1 if the
 * open fails), the message in err. */
static int put_text(const char *path, const char *text, char *err, size_t errlen)
{
    fio_out *o = fio_out_open(path, err, errlen);
    if (!o)
        return -1;
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
    assert_true(S_ISLNK(st.st_mode));
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
    expect_text(err, "dangling.txt: cannot write: a symbolic link to a missing file");
    assert_int_equal(fio_check_out(link, err, sizeof err), -1);
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
    assert_true(S_ISCHR(after.st_mode));
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
    unsigned long tally[2] = { 0, 0 };
    ssize_t k, i;
    alarm(HANG_SECONDS);
    fcntl(rfd, F_SETFL, fcntl(rfd, F_GETFL) & ~O_NONBLOCK);
    while ((k = read(rfd, b, sizeof b)) > 0)
        for (i = 0; i < k; i++) {
            tally[0]++;
            tally[1] = tally[1] * 31 + b[i];
        }
    _exit(write(res, tally, sizeof tally) == (ssize_t)sizeof tally ? 0 : 1);
}

/* 200 KB, more than a pipe holds, through a FIFO to a reader in another process. */
#define FIFO_BYTES 200000
static void test_out_fifo_with_reader(void **state)
{
    const char *p = tmp_path("out.fifo");
    char err[256];
    unsigned char *data = malloc(FIFO_BYTES);
    unsigned long want = 0, tally[2] = { 0, 0 };
    int rfd, res[2], status;
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
    assert_true(rfd >= 0);
    o = fio_out_open(p, err, sizeof err);
    assert_non_null(o);
    assert_int_equal(pipe(res), 0);
    fflush(NULL);
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        close(fileno(fio_out_stream(o))); /* else this child holds a writer open */
        close(res[0]);
        fifo_reader(rfd, res[1]);
    }
    close(rfd);
    close(res[1]);
    assert_int_equal(fwrite(data, 1, FIFO_BYTES, fio_out_stream(o)), FIFO_BYTES);
    assert_int_equal(fio_out_commit(o, err, sizeof err), 0);
    assert_int_equal(read(res[0], tally, sizeof tally), (ssize_t)sizeof tally);
    close(res[0]);
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_int_equal(status, 0);
    assert_int_equal(tally[0], FIFO_BYTES);
    assert_int_equal(tally[1], want);
    assert_int_equal(lstat(p, &st), 0);
    assert_true(S_ISFIFO(st.st_mode)); /* still the FIFO */
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
    expect_text(r.msg, "noreader.fifo: cannot open: a FIFO with no reader");
}

static void test_out_directory(void **state)
{
    const char *dir = fresh_dir("out_dir");
    char err[256];
    int tmp_seen;
    (void)state;
    assert_int_equal(fio_check_out(dir, err, sizeof err), -1);
    expect_text(err, "out_dir: is a directory");
    assert_null(fio_out_open(dir, err, sizeof err));
    expect_text(err, "out_dir: is a directory");
    assert_int_equal(count_entries(dir, &tmp_seen), 0);
}

static void test_out_missing_folder(void **state)
{
    const char *p = tmp_path("no_such_folder/a.png");
    char err[256];
    (void)state;
    assert_int_equal(fio_check_out(p, err, sizeof err), -1);
    expect_text(err, "a.png: cannot write in folder ");
    expect_text(err, "no_such_folder: No such file or directory");
    assert_null(fio_out_open(p, err, sizeof err));
    expect_text(err, "a.png: cannot create temporary file: No such file or directory");
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

/* A full disk, simulated by a file size limit (SIGXFSZ ignored, so writes fail with
 * EFBIG): the commit fails, the old file is intact, no temporary file is left. */
typedef struct {
    const char *path;
    size_t bytes;
} big_write;

static void write_past_fsize(void *arg, child_result *r)
{
    const big_write *b = arg;
    struct rlimit rl;
    fio_out *o;
    size_t i;
    rl.rlim_cur = rl.rlim_max = 4096;
    signal(SIGXFSZ, SIG_IGN);
    if (setrlimit(RLIMIT_FSIZE, &rl) != 0) {
        r->rc = 2;
        snprintf(r->msg, sizeof r->msg, "setrlimit: %s", strerror(errno));
        return;
    }
    if (!(o = fio_out_open(b->path, r->msg, sizeof r->msg))) {
        r->rc = 3;
        return;
    }
    for (i = 0; i < b->bytes; i++)
        putc('n', fio_out_stream(o));
    r->rc = fio_out_commit(o, r->msg, sizeof r->msg);
}

static void test_out_full_disk(void **state)
{
    const char *dir = fresh_dir("full"), *p = tmp_path("full/keep.bin");
    unsigned char old[3000];
    big_write b;
    child_result r;
    char *d;
    size_t n, i;
    int tmp_seen;
    (void)state;
    for (i = 0; i < sizeof old; i++)
        old[i] = (unsigned char)(i * 13);
    write_file(p, old, sizeof old);
    b.path = p;
    b.bytes = 100000;
    r = in_child(write_past_fsize, &b);
    assert_int_equal(r.rc, -1);
    expect_text(r.msg, "keep.bin: write error: File too large");
    d = slurp(p, &n);
    assert_non_null(d);
    assert_int_equal(n, sizeof old);
    assert_memory_equal(d, old, sizeof old);
    free(d);
    assert_int_equal(count_entries(dir, &tmp_seen), 1);
    assert_int_equal(tmp_seen, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_read_regular),
        cmocka_unit_test(test_read_limit),
        cmocka_unit_test(test_read_dev_zero),
        cmocka_unit_test(test_read_fifo_no_writer),
        cmocka_unit_test(test_read_fifo_with_writer),
        cmocka_unit_test(test_read_directory),
        cmocka_unit_test(test_read_missing),
        cmocka_unit_test(test_read_sparse_giant),
        cmocka_unit_test(test_out_new_and_replace),
        cmocka_unit_test(test_out_abort),
        cmocka_unit_test(test_out_symlink),
        cmocka_unit_test(test_out_dangling_symlink),
        cmocka_unit_test(test_out_dev_null),
        cmocka_unit_test(test_out_dev_full),
        cmocka_unit_test(test_out_fifo_with_reader),
        cmocka_unit_test(test_out_fifo_no_reader),
        cmocka_unit_test(test_out_directory),
        cmocka_unit_test(test_out_missing_folder),
        cmocka_unit_test(test_check_out_writes_nothing),
        cmocka_unit_test(test_out_full_disk),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
