/* SPDX-License-Identifier: MIT */
/* file_io — how every host tool reads its inputs and writes its outputs, so that no
 * input can hang or exhaust memory and no output can destroy what is not ours.
 *
 * Inputs: opened with O_NONBLOCK | O_NOCTTY (a FIFO with no writer cannot block the
 * open), then fstat'ed: only a regular file is read, whole, if it is at most the
 * caller's LIMIT bytes (checked against st_size before anything is read, so a sparse
 * 20 GB file costs nothing); a FIFO, pipe, terminal, device, socket or directory is
 * refused before a byte is read ("PATH: not a regular file (a FIFO or pipe)"), so that
 * no input waits on a writer or streams until the limit. The one stream read is
 * standard input, asked for by name (fio_read_stdin: rad_cli's scene "-"), never a
 * terminal.
 *
 * Outputs: fio_out_open picks how, from what PATH is now:
 *   - a regular file or nothing yet: a temporary file beside the target (in the target's
 *     folder, so rename is atomic), fsync'ed and renamed over the target by
 *     fio_out_commit; the old file stays intact until then, and is untouched if anything
 *     fails; the new file keeps the old one's permission bits (else 0666 & ~umask);
 *   - a symbolic link: followed (realpath); the file it points to is replaced as above,
 *     the link itself is kept;
 *   - a name of one of the process's descriptors (/dev/stdout, /dev/stderr, /dev/fd/N,
 *     /proc/self/fd/N): written through a copy of that descriptor, wherever the shell
 *     sent it, with its offset and flags (">> log" appends; nothing is renamed);
 *   - a device, FIFO or socket (/dev/null, a pipe): written in place,
 *     never replaced, never renamed; the open does not wait: a FIFO with no reader is
 *     an error ("cannot open: a FIFO with no reader");
 *   - a directory ("PATH: is a directory") or a dangling link: an error before anything
 *     is written; a folder that does not exist or cannot be written: mkstemp's error
 *     ("cannot create temporary file: No such file or directory").
 * Every write's error (ENOSPC included) is kept: fio_out_commit checks ferror, fflush,
 * fsync (regular files) and fclose, and fails without touching the target, saying why
 * ("PATH: write error: No space left on device").
 *
 * Errors are one line, "PATH: what is wrong", copied into a caller buffer (which may be
 * NULL or of length 0).
 */
#ifndef RAD_TOOLS_FILE_IO_H
#define RAD_TOOLS_FILE_IO_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Read limits of the tools, in bytes: one place so docs/precision.md's table stays true. */
#define FIO_LIMIT_OBJ   (1024u * 1024u * 1024u) /* an OBJ scene: 1 GiB */
#define FIO_LIMIT_MTL   (64u * 1024u * 1024u)   /* a material library: 64 MiB */
#define FIO_LIMIT_TEXT  (16u * 1024u * 1024u)   /* --views, --animate: 16 MiB */
#define FIO_LIMIT_IMAGE (256u * 1024u * 1024u)  /* an image or texture file: 256 MiB */

/* The memory the tools let one input take, in bytes: the environment's
 * RAD_MEMORY_BUDGET (a number of bytes; how tests try the refusals with small figures)
 * if set and positive, else half the physical memory (1 GiB when the system does not
 * say). The OBJ loader checks its scene against it before parsing, the stored rows
 * theirs before computing them. */
double fio_memory_budget(void);

/* "PATH: message" into err (NULL or errlen 0: nothing); the one form of every message
 * of the file format readers and writers. */
void fio_err(char *err, size_t errlen, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Reads the whole of regular file PATH (at most LIMIT bytes) into a malloc'd buffer
 * with a NUL after the last byte (*DATA, *SIZE bytes without the NUL). Returns 0, or -1
 * with err ("PATH: cannot open: No such file or directory", "PATH: is a directory",
 * "PATH: not a regular file (a FIFO or pipe)", "PATH: larger than the limit of 64 MiB
 * (67108864 bytes): N bytes"); *DATA is NULL and nothing is to free on error. */
int fio_read_all(const char *path, size_t limit, char **data, size_t *size, char *err,
                 size_t errlen);

/* Standard input read whole as fio_read_all reads a file, named "-" in messages: a
 * regular file or a pipe (read to its end, at most LIMIT bytes; an empty pipe is
 * "nothing to read"); anything else (a terminal, /dev/zero) is refused. 0, or -1 with err. */
int fio_read_stdin(size_t limit, char **data, size_t *size, char *err, size_t errlen);

/* Opens PATH for reading as above and returns a stdio stream (blocking mode restored),
 * or NULL with err. For readers that stream; the caller bounds what it reads. */
FILE *fio_open_read(const char *path, char *err, size_t errlen);

/* 0 when PATH can be written by fio_out_open (its folder exists and is writable, the
 * name and the temporary name fit PATH_MAX and NAME_MAX, it is not a directory), else
 * -1 with err. Writes nothing: the tools call it for every output before the solve. */
int fio_check_out(const char *path, char *err, size_t errlen);

/* Where PATH leads, as an absolute name without '.', '..' or symbolic links: realpath
 * of PATH if it exists, else realpath of its folder joined to its last component (a file
 * not yet written). malloc'd; NULL when neither resolves (the folder is missing). */
char *fio_resolve(const char *path);

/* 1 when PATH (resolved as fio_resolve) is DIR or lies under it (DIR resolved too,
 * compared at a component boundary: /a/bc is not under /a/b), 0 when it is elsewhere,
 * -1 when either cannot be resolved. */
int fio_within(const char *dir, const char *path);

typedef struct fio_out fio_out;

/* Opens PATH for writing as above. Returns the writer, or NULL with err. */
fio_out *fio_out_open(const char *path, char *err, size_t errlen);
/* The stream to write to (binary mode). */
FILE *fio_out_stream(fio_out *o);
/* Finishes: checks every write, fsyncs, closes and renames the temporary file into
 * place (or closes a device). Returns 0, or -1 with err, and then the target is as it
 * was before fio_out_open and no temporary file is left. Frees O either way. */
int fio_out_commit(fio_out *o, char *err, size_t errlen);
/* Gives up: removes the temporary file, leaves the target as it was, frees O. */
void fio_out_abort(fio_out *o);

#ifdef __cplusplus
}
#endif

#endif
