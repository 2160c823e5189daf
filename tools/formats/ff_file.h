/* SPDX-License-Identifier: MIT */
/* ff_file — stored form factors on disk: the rows of rad_rows_t (rad.h) in a small,
 * versioned, checksummed binary file, so a scene's visibility (every patch's hemi-cube
 * row) is computed once and reused to relight it (host tools only: malloc, stdio).
 *
 * Format, version 1. Every number is little-endian; offsets in bytes.
 *
 *   off  size     field
 *     0  6        magic "RADFF\0"
 *     6  2        format version (1)
 *     8  2        build kind: 1 = fixed (librad, Q16.16 geometry), 2 = float twin
 *    10  2        hemi-cube resolution the rows were rendered at
 *    12  4        patches P (rows)
 *    16  4        elements N
 *    20  4        vertices V
 *    24  4        entries M (non-zero form factors over all rows)
 *    28  4        reserved, 0
 *    32  8        geometry fingerprint: FNV-1a 64 of the meshed scene as the core
 *                 holds it (see the glue, tools/host/scene_rows.c: counts, every vertex
 *                 coordinate's bits, every element's vertex indices, patch and surface,
 *                 every patch's surface and element range)
 *    40  4(P+1)   row starts: row p is entries start[p] .. start[p+1]-1;
 *                 start[0] = 0, non-decreasing, start[P] = M
 *     .  4M       element ids (< N, increasing within a row)
 *     .  2M       form factor codes: 5-bit exponent e, 11-bit mantissa m, the Q2.30
 *                 form factor m << e (e > 0: m >= 1024), non-zero and <= 2^30
 *     .  8        FNV-1a 64 of every byte before it
 *
 * So a file is 48 + 4 (P + 1) + 6 M bytes. The codes are the core's own
 * (rad_ff_from_code): both builds store the same 16-bit codes, but the float twin
 * meshes and renders with float geometry, so its rows (and its fingerprint, hashed over
 * float bits) differ in the last bits. A file therefore loads only in the build that
 * wrote it: a mismatch is an error naming both (by design, not by limitation of the
 * format: the two builds are kept apart so that comparing them means something).
 *
 * Written and read through file_io: a regular file is replaced atomically (a temporary
 * file beside it, then rename), a link's target is replaced, a device or FIFO written
 * in place. Reading takes the 40-byte header first and checks, in this order: the
 * magic, the version, the file's size against the header's counts before reading the
 * rest (a file more than 4096 bytes longer is refused unread), then truncation or bytes
 * past the end, the checksum, then the rows' structure; the caller then compares the
 * header with its scene (ff_file_match). Every error is one line "PATH: what is wrong".
 */
#ifndef RAD_TOOLS_FF_FILE_H
#define RAD_TOOLS_FF_FILE_H

#include <stddef.h>
#include <stdint.h>

#define FF_FILE_VERSION    1
#define FF_FILE_KIND_FIXED 1
#define FF_FILE_KIND_FLOAT 2

typedef struct {
    unsigned kind; /* FF_FILE_KIND_* */
    unsigned res;  /* hemi-cube resolution */
    uint32_t patches, elements, vertices, entries;
    uint64_t fingerprint;
} ff_file_info;

/* A file read and checked, held in memory until ff_file_free. */
typedef struct {
    ff_file_info info;
    unsigned char *data; /* the whole file */
    size_t size;
} ff_file_t;

/* FNV-1a 64: start with FF_FILE_FNV_START, feed bytes. */
#define FF_FILE_FNV_START 1469598103934665603ull
uint64_t ff_file_fnv(uint64_t h, const void *p, size_t n);
/* Feeds V as 4 little-endian bytes. */
uint64_t ff_file_fnv_u32(uint64_t h, uint32_t v);

/* Writes rows: START (patches + 1 offsets), IDS (entries ids, each ID_BYTES = 2 or 4
 * bytes wide in memory, host order), CODES (entries). Returns 0 or -1 with a message. */
int ff_file_save(const char *path, const ff_file_info *info, const uint32_t *start, const void *ids,
                 unsigned id_bytes, const uint16_t *codes, char *err, size_t errlen);

/* Reads and checks PATH (magic, version, size, checksum, structure). Returns 0, or -1
 * with a message (nothing to free). */
int ff_file_load(const char *path, ff_file_t *f, char *err, size_t errlen);

/* 0 when F was made for the scene WANT describes (same build kind, resolution, counts
 * and fingerprint), else -1 with a message naming PATH and what differs. */
int ff_file_match(const ff_file_t *f, const ff_file_info *want, const char *path, char *err,
                  size_t errlen);

/* Copies the rows out of F into caller arrays sized from f->info (as for ff_file_save). */
void ff_file_rows(const ff_file_t *f, uint32_t *start, void *ids, unsigned id_bytes,
                  uint16_t *codes);

void ff_file_free(ff_file_t *f);

/* "fixed" or "float". */
const char *ff_file_kind_name(unsigned kind);

#endif
