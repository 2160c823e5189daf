/* SPDX-License-Identifier: MIT */
/* file_io — how the host tools read inputs and write outputs. See file_io.h. */
/* realpath is XSI: the tools otherwise ask for POSIX 2008 only. */
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700
#endif
#include "formats/file_io.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#ifndef NAME_MAX
#define NAME_MAX 255
#endif
#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

#define TMP_SUFFIX ".tmpXXXXXX"
#define READ_CHUNK 65536u /* first buffer of a stream of unknown size; then doubled */

struct fio_out {
    FILE *fp;
    char *path;   /* as the caller named it, for messages */
    char *target; /* what the temporary file is renamed to; NULL when written in place */
    char *tmp;    /* the temporary file; NULL when written in place */
    mode_t mode;  /* permission bits the new file gets; written in place: the st_mode */
};

void fio_err(char *err, size_t errlen, const char *path, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    if (!err || !errlen) return;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(err, errlen, "%s: %s", path ? path : "(null)", msg);
}

double fio_memory_budget(void)
{
    const char *env = getenv("RAD_MEMORY_BUDGET");
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    double v = env ? strtod(env, NULL) : 0;
    if (v > 0) return v;
    return pages > 0 && size > 0 ? 0.5 * (double)pages * (double)size : 1073741824.0;
}

/* "64 MiB (67108864 bytes)" for a whole number of MiB, else "N bytes". */
static void limit_text(char *out, size_t n, size_t limit)
{
    if (limit >= 1048576u && limit % 1048576u == 0)
        snprintf(out, n, "%zu MiB (%zu bytes)", limit / 1048576u, limit);
    else
        snprintf(out, n, "%zu bytes", limit);
}

/* ---- inputs -------------------------------------------------------------------- */

/* What a file that is not regular is, for messages. */
static const char *kind_of(mode_t m)
{
    return S_ISDIR(m)    ? "is a directory"
           : S_ISFIFO(m) ? "not a regular file (a FIFO or pipe)"
           : S_ISCHR(m)  ? "not a regular file (a character device or terminal)"
           : S_ISBLK(m)  ? "not a regular file (a block device)"
           : S_ISSOCK(m) ? "not a regular file (a socket)"
                         : "not a regular file";
}

/* Opens PATH without blocking (a FIFO with no writer), refuses any kind but a regular
 * file before a byte is read, then restores blocking reads. Returns the descriptor (*ST
 * filled) or -1 with err. */
static int open_in(const char *path, struct stat *st, char *err, size_t errlen)
{
    int fd, fl;
    if (!path) {
        fio_err(err, errlen, path, "no path given");
        return -1;
    }
    fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) {
        fio_err(err, errlen, path, "cannot open: %s", strerror(errno));
        return -1;
    }
    if (fstat(fd, st) != 0) {
        fio_err(err, errlen, path, "cannot stat: %s", strerror(errno));
    } else if (!S_ISREG(st->st_mode)) {
        fio_err(err, errlen, path, "%s", kind_of(st->st_mode));
    } else if ((fl = fcntl(fd, F_GETFL)) < 0 || fcntl(fd, F_SETFL, fl & ~O_NONBLOCK) < 0) {
        fio_err(err, errlen, path, "cannot read: %s", strerror(errno));
    } else {
        return fd;
    }
    close(fd);
    return -1;
}

/* Makes room for more bytes in *BUF: capacity doubled, at most LIMIT + 1 (one past the
 * limit is how read_fd sees "too large"); one byte more is kept for the NUL. */
static int grow(char **buf, size_t *cap, size_t limit)
{
    size_t want = *cap > (limit + 1) / 2 ? limit + 1 : *cap * 2;
    char *q = realloc(*buf, want + 1);
    if (!q) {
        errno = ENOMEM;
        return -1;
    }
    *buf = q;
    *cap = want;
    return 0;
}

/* Reads FD to its end into *BUF (capacity *CAP), stopping once more than LIMIT bytes
 * have come. Returns the byte count (above LIMIT means "too large"), or -1 with errno. */
static long long read_fd(int fd, size_t limit, char **buf, size_t *cap)
{
    size_t len = 0;
    for (;;) {
        ssize_t got;
        if (len == *cap && grow(buf, cap, limit) != 0) return -1;
        got = read(fd, *buf + len, *cap - len);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) return -1;
        if (got == 0 || (len += (size_t)got) > limit) return (long long)len;
    }
}

/* Reads FD (of kind ST, named PATH in messages) as fio_read_all. */
static int read_whole(int fd, const struct stat *st, const char *path, size_t limit, char **data,
                      size_t *size, char *err, size_t errlen)
{
    char lim[64], *buf;
    size_t cap;
    long long n;
    int fifo = S_ISFIFO(st->st_mode);
    limit = limit < SIZE_MAX / 2 ? limit : SIZE_MAX / 2; /* so that limit + 2 fits */
    limit_text(lim, sizeof lim, limit);
    if (S_ISREG(st->st_mode) && (uintmax_t)st->st_size > limit) {
        fio_err(err, errlen, path, "larger than the limit of %s: %lld bytes", lim,
                (long long)st->st_size);
        return -1;
    }
    /* A regular file's size is known: one buffer, and one more read to see the end. */
    cap = S_ISREG(st->st_mode) ? (size_t)st->st_size + 1 : READ_CHUNK;
    cap = cap > limit + 1 ? limit + 1 : cap;
    if (!(buf = malloc(cap + 1))) {
        fio_err(err, errlen, path, "out of memory for %zu bytes", cap);
        return -1;
    }
    n = read_fd(fd, limit, &buf, &cap);
    if (n < 0)
        fio_err(err, errlen, path, "cannot read: %s", strerror(errno));
    else if ((size_t)n > limit)
        fio_err(err, errlen, path, "larger than the limit of %s", lim);
    else if (n == 0 && fifo)
        fio_err(err, errlen, path, "nothing to read (an empty pipe)");
    if (n < 0 || (size_t)n > limit || (n == 0 && fifo)) {
        free(buf);
        return -1;
    }
    buf[n] = '\0';
    *data = buf;
    *size = (size_t)n;
    return 0;
}

int fio_read_all(const char *path, size_t limit, char **data, size_t *size, char *err,
                 size_t errlen)
{
    struct stat st;
    int fd, rc;
    *data = NULL;
    *size = 0;
    if ((fd = open_in(path, &st, err, errlen)) < 0) return -1;
    rc = read_whole(fd, &st, path, limit, data, size, err, errlen);
    close(fd);
    return rc;
}

int fio_read_stdin(size_t limit, char **data, size_t *size, char *err, size_t errlen)
{
    struct stat st;
    *data = NULL;
    *size = 0;
    if (fstat(0, &st) != 0) {
        fio_err(err, errlen, "-", "standard input: %s", strerror(errno));
        return -1;
    }
    if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) { /* a terminal, /dev/zero, ... */
        fio_err(err, errlen, "-", "standard input is %s: pipe or redirect a file into it",
                isatty(0)             ? "a terminal"
                : S_ISCHR(st.st_mode) ? "a device"
                : S_ISDIR(st.st_mode) ? "a directory"
                                      : "not a file or pipe");
        return -1;
    }
    return read_whole(0, &st, "-", limit, data, size, err, errlen);
}

FILE *fio_open_read(const char *path, char *err, size_t errlen)
{
    struct stat st;
    FILE *fp;
    int fd = open_in(path, &st, err, errlen);
    if (fd < 0) return NULL;
    if (!(fp = fdopen(fd, "rb"))) {
        fio_err(err, errlen, path, "cannot read: %s", strerror(errno));
        close(fd);
    }
    return fp;
}

/* ---- where a path leads ---------------------------------------------------------- */

char *fio_resolve(const char *path)
{
    const char *slash, *base;
    char *dir, *real, *out;
    size_t n;
    if (!path || !*path) return NULL;
    if ((real = realpath(path, NULL)) != NULL) return real;
    slash = strrchr(path, '/');
    base = slash ? slash + 1 : path;
    if (!*base || !strcmp(base, ".") || !strcmp(base, ".."))
        return NULL; /* a folder's name that does not resolve */
    n = slash ? (size_t)(slash - path) + (slash == path) : 1;
    if (!(dir = malloc(n + 1))) return NULL;
    memcpy(dir, slash ? path : ".", n);
    dir[n] = '\0';
    real = realpath(dir, NULL);
    free(dir);
    if (!real) return NULL;
    n = strlen(real);
    if ((out = malloc(n + strlen(base) + 2)) != NULL)
        sprintf(out, "%s%s%s", real, real[n - 1] == '/' ? "" : "/", base);
    free(real);
    return out;
}

int fio_within(const char *dir, const char *path)
{
    char *d = realpath(dir && *dir ? dir : ".", NULL), *p = fio_resolve(path);
    size_t n = d ? strlen(d) : 0;
    int rc = -1;
    if (d && p) /* the root "/" holds everything; else DIR itself or DIR + '/' + ... */
        rc = !strcmp(d, "/") || (!strncmp(p, d, n) && (p[n] == '\0' || p[n] == '/'));
    free(d);
    free(p);
    return rc;
}

/* ---- outputs ------------------------------------------------------------------- */

/* The name a regular file ST at PATH is replaced under: PATH itself, or the file a
 * symbolic link PATH leads to. malloc'd, or NULL with err. */
static char *replaced_name(const char *path, const struct stat *st, char *err, size_t errlen)
{
    struct stat lst, rst;
    char *target;
    if (lstat(path, &lst) != 0 || !S_ISLNK(lst.st_mode))
        target = strdup(path);
    else if (!(target = realpath(path, NULL))) {
        fio_err(err, errlen, path, "cannot follow the symbolic link: %s", strerror(errno));
        return NULL;
    } else if (stat(target, &rst) != 0 || rst.st_dev != st->st_dev || rst.st_ino != st->st_ino) {
        /* e.g. /dev/stdout onto a deleted file: there is no name to replace */
        fio_err(err, errlen, path, "cannot write: the link's target has no name to replace");
        free(target);
        return NULL;
    }
    if (!target) fio_err(err, errlen, path, "out of memory");
    return target;
}

/* How PATH is written: by a temporary file renamed over TARGET (*TARGET malloc'd, the
 * link resolved, *MODE its permission bits) or in place (*TARGET NULL, *MODE the
 * st_mode). 0, or -1 with err. Writes nothing. */
static int plan_out(const char *path, char **target, mode_t *mode, char *err, size_t errlen)
{
    struct stat st, lst;
    mode_t um;
    int e;
    *target = NULL;
    if (!path || !*path) {
        fio_err(err, errlen, path, "no path given");
        return -1;
    }
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            fio_err(err, errlen, path, "is a directory");
            return -1;
        }
        *mode = S_ISREG(st.st_mode) ? st.st_mode & 0777 : st.st_mode;
        if (!S_ISREG(st.st_mode))
            return 0; /* a device, FIFO or socket: in place (the kind for messages) */
        return (*target = replaced_name(path, &st, err, errlen)) ? 0 : -1;
    }
    e = errno;
    if (lstat(path, &lst) == 0) { /* a link stat cannot follow */
        fio_err(err, errlen, path, "cannot write: %s",
                e == ENOENT ? "a symbolic link to a missing file" : strerror(e));
        return -1;
    }
    /* A new file (mkstemp names what is wrong with its folder, if anything). */
    um = umask(022); /* umask is read by setting it: restored at once */
    umask(um);
    *mode = 0666 & ~um;
    if (!(*target = strdup(path))) {
        fio_err(err, errlen, path, "out of memory");
        return -1;
    }
    return 0;
}

/* Length of the last component of PATH. */
static size_t base_len(const char *path)
{
    const char *slash = strrchr(path, '/');
    return strlen(slash ? slash + 1 : path);
}

/* The folder of PATH ("." for a bare name), malloc'd. */
static char *folder_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path) + (slash == path) : 1;
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, slash ? path : ".", n);
        d[n] = '\0';
    }
    return d;
}

/* The temporary name of TARGET and its folder can be made: 0, or -1 with err. */
static int check_target(const char *path, const char *target, char *err, size_t errlen)
{
    struct stat st;
    char *dir;
    int rc = -1;
    if (strlen(target) + sizeof TMP_SUFFIX > PATH_MAX ||
        base_len(target) + sizeof TMP_SUFFIX - 1 > NAME_MAX) {
        fio_err(err, errlen, path, "name too long for its temporary file (%s)", TMP_SUFFIX);
        return -1;
    }
    if (!(dir = folder_of(target)))
        fio_err(err, errlen, path, "out of memory");
    else if (stat(dir, &st) != 0) /* the words of rad_cli's own check before file_io */
        fio_err(err, errlen, path, "cannot write into '%s': %s", dir, strerror(errno));
    else if (!S_ISDIR(st.st_mode))
        fio_err(err, errlen, path, "cannot write into '%s': %s", dir, strerror(ENOTDIR));
    else if (access(dir, W_OK | X_OK) != 0)
        fio_err(err, errlen, path, "cannot write into '%s': %s", dir, strerror(errno));
    else
        rc = 0;
    free(dir);
    return rc;
}

/* The descriptor PATH names, if it names one of this process's: /dev/stdout,
 * /dev/stderr, /dev/fd/N or /proc/self/fd/N; else -1. Such an output is written through
 * a copy of the descriptor, so that it goes where the shell sent it, with the shell's
 * offset and flags (">>" appends; a rename would have replaced the file). */
static int named_fd(const char *path)
{
    static const char *const dirs[] = {"/dev/fd/", "/proc/self/fd/"};
    const char *d = NULL;
    char *end;
    long n;
    size_t i;
    if (!strcmp(path, "/dev/stdout")) return 1;
    if (!strcmp(path, "/dev/stderr")) return 2;
    for (i = 0; i < 2 && !d; i++)
        if (!strncmp(path, dirs[i], strlen(dirs[i]))) d = path + strlen(dirs[i]);
    if (!d || *d < '0' || *d > '9') return -1;
    errno = 0;
    n = strtol(d, &end, 10);
    return *end || errno || n > INT_MAX ? -1 : (int)n;
}

/* FD, open for writing: 0, or -1 with err. */
static int fd_writable(const char *path, int fd, char *err, size_t errlen)
{
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0) {
        fio_err(err, errlen, path, "cannot write: %s", strerror(errno));
        return -1;
    }
    if ((fl & O_ACCMODE) == O_RDONLY) {
        fio_err(err, errlen, path, "cannot write: descriptor %d is open for reading only", fd);
        return -1;
    }
    return 0;
}

int fio_check_out(const char *path, char *err, size_t errlen)
{
    char *target;
    mode_t mode;
    int rc;
    if (path && named_fd(path) >= 0) return fd_writable(path, named_fd(path), err, errlen);
    if (plan_out(path, &target, &mode, err, errlen) != 0) return -1;
    if (!target) {
        if (access(path, W_OK) == 0) return 0;
        fio_err(err, errlen, path, "cannot write: %s", strerror(errno));
        return -1;
    }
    rc = check_target(path, target, err, errlen);
    free(target);
    return rc;
}

static void out_free(fio_out *o)
{
    free(o->path);
    free(o->target);
    free(o->tmp);
    free(o);
}

/* In place: O_NONBLOCK so that a FIFO with no reader is an error (ENXIO), not a hang. */
static int open_in_place(fio_out *o, char *err, size_t errlen)
{
    int fd = open(o->path, O_WRONLY | O_NONBLOCK | O_NOCTTY), fl;
    if (fd < 0) {
        fio_err(err, errlen, o->path, "cannot open: %s",
                errno == ENXIO && S_ISFIFO(o->mode) ? "a FIFO with no reader" : strerror(errno));
        return -1;
    }
    if ((fl = fcntl(fd, F_GETFL)) < 0 || fcntl(fd, F_SETFL, fl & ~O_NONBLOCK) < 0 ||
        !(o->fp = fdopen(fd, "wb"))) {
        fio_err(err, errlen, o->path, "cannot write: %s", strerror(errno));
        close(fd);
        return -1;
    }
    return 0;
}

/* Through a copy of descriptor FD (named_fd). */
static int open_dup(fio_out *o, int fd, char *err, size_t errlen)
{
    int d;
    if (fd_writable(o->path, fd, err, errlen) != 0) return -1;
    if ((d = dup(fd)) < 0 || !(o->fp = fdopen(d, "wb"))) {
        fio_err(err, errlen, o->path, "cannot write: %s", strerror(errno));
        if (d >= 0) close(d);
        return -1;
    }
    return 0;
}

/* mkstemp's own error names what is wrong with the folder (missing, not a folder, not
 * writable, a name too long), so nothing is checked before it. */
static int open_tmp(fio_out *o, char *err, size_t errlen)
{
    int fd;
    if (!(o->tmp = malloc(strlen(o->target) + sizeof TMP_SUFFIX))) {
        fio_err(err, errlen, o->path, "out of memory");
        return -1;
    }
    strcpy(o->tmp, o->target);
    strcat(o->tmp, TMP_SUFFIX);
    if ((fd = mkstemp(o->tmp)) < 0) {
        fio_err(err, errlen, o->path, "cannot create temporary file: %s", strerror(errno));
        return -1;
    }
    if (!(o->fp = fdopen(fd, "wb"))) {
        fio_err(err, errlen, o->path, "cannot write: %s", strerror(errno));
        close(fd);
        unlink(o->tmp);
        return -1;
    }
    return 0;
}

fio_out *fio_out_open(const char *path, char *err, size_t errlen)
{
    fio_out *o = calloc(1, sizeof *o);
    int rc;
    if (!o || !path || !(o->path = strdup(path))) {
        fio_err(err, errlen, path, path ? "out of memory" : "no path given");
        free(o);
        return NULL;
    }
    if (named_fd(path) >= 0)
        rc = open_dup(o, named_fd(path), err, errlen);
    else if (plan_out(path, &o->target, &o->mode, err, errlen) != 0)
        rc = -1;
    else
        rc = o->target ? open_tmp(o, err, errlen) : open_in_place(o, err, errlen);
    if (rc != 0) {
        out_free(o);
        return NULL;
    }
    return o;
}

FILE *fio_out_stream(fio_out *o)
{
    return o ? o->fp : NULL;
}

/* The error of the stream's writes: a failed write leaves its data in the buffer, so a
 * second flush fails again and gives a fresh errno (errno itself may have been reused
 * since the caller's write). */
static int stream_error(FILE *fp)
{
    int e = errno;
    clearerr(fp);
    if (fflush(fp) != 0) e = errno;
    return e ? e : EIO;
}

/* Flushes, syncs (regular files) and closes o->fp; 0 or an errno value. */
static int finish_stream(fio_out *o)
{
    int e = 0, fd = fileno(o->fp);
    if (ferror(o->fp))
        e = stream_error(o->fp);
    else if (fflush(o->fp) != 0)
        e = errno;
    else if (o->tmp && (fchmod(fd, o->mode) != 0 || fsync(fd) != 0))
        e = errno; /* the data is on disk before the rename makes it visible */
    if (fclose(o->fp) != 0 && !e) e = errno;
    o->fp = NULL;
    return e;
}

int fio_out_commit(fio_out *o, char *err, size_t errlen)
{
    int e;
    if (!o) {
        fio_err(err, errlen, NULL, "no output to commit");
        return -1;
    }
    e = finish_stream(o);
    if (e)
        fio_err(err, errlen, o->path, "write error: %s", strerror(e));
    else if (o->tmp && rename(o->tmp, o->target) != 0)
        fio_err(err, errlen, o->path, "cannot rename the temporary file into place: %s",
                strerror(e = errno ? errno : EIO));
    if (e && o->tmp) unlink(o->tmp);
    out_free(o);
    return e ? -1 : 0;
}

void fio_out_abort(fio_out *o)
{
    if (!o) return;
    if (o->fp) fclose(o->fp);
    if (o->tmp) unlink(o->tmp);
    out_free(o);
}
