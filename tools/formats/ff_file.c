/* SPDX-License-Identifier: MIT */
/* ff_file — stored form factors on disk (see ff_file.h for the format). */
#include "formats/ff_file.h"

#include "formats/file_io.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define HEADER_BYTES  40u
#define TRAILER_BYTES 8u
static const unsigned char MAGIC[6] = {'R', 'A', 'D', 'F', 'F', '\0'};

uint64_t ff_file_fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= b[i];
        h *= 1099511628211ull;
    }
    return h;
}

uint64_t ff_file_fnv_u32(uint64_t h, uint32_t v)
{
    unsigned char b[4];
    b[0] = (unsigned char)v;
    b[1] = (unsigned char)(v >> 8);
    b[2] = (unsigned char)(v >> 16);
    b[3] = (unsigned char)(v >> 24);
    return ff_file_fnv(h, b, 4);
}

const char *ff_file_kind_name(unsigned kind)
{
    return kind == FF_FILE_KIND_FIXED ? "fixed" : kind == FF_FILE_KIND_FLOAT ? "float" : "unknown";
}

/* ---- little-endian fields ------------------------------------------------------ */

static void put16(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)v;
    p[1] = (unsigned char)(v >> 8);
}
static void put32(unsigned char *p, uint32_t v)
{
    put16(p, v);
    put16(p + 2, v >> 16);
}
static void put64(unsigned char *p, uint64_t v)
{
    put32(p, (uint32_t)v);
    put32(p + 4, (uint32_t)(v >> 32));
}
static uint32_t get16(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8;
}
static uint32_t get32(const unsigned char *p)
{
    return get16(p) | get16(p + 2) << 16;
}
static uint64_t get64(const unsigned char *p)
{
    return (uint64_t)get32(p) | (uint64_t)get32(p + 4) << 32;
}

/* File size for P patches and M entries (fits 64 bits for any 32-bit counts). */
static uint64_t file_bytes(uint32_t patches, uint32_t entries)
{
    return (uint64_t)HEADER_BYTES + 4u * ((uint64_t)patches + 1u) + 6u * (uint64_t)entries +
           TRAILER_BYTES;
}

static uint32_t id_at(const void *ids, unsigned id_bytes, uint32_t i)
{
    return id_bytes == 2 ? ((const uint16_t *)ids)[i] : ((const uint32_t *)ids)[i];
}

/* ---- writing ------------------------------------------------------------------- */

/* A buffered writer that hashes what it writes. */
typedef struct {
    FILE *fp;
    uint64_t hash;
    unsigned char buf[65536];
    size_t n;
    int failed; /* errno of the first failed write, 0 while none */
} writer_t;

static void w_flush(writer_t *w)
{
    if (w->n && !w->failed && fwrite(w->buf, 1, w->n, w->fp) != w->n)
        w->failed = errno ? errno : EIO;
    w->n = 0;
}

static void w_bytes(writer_t *w, const unsigned char *p, size_t n)
{
    w->hash = ff_file_fnv(w->hash, p, n);
    while (n) {
        size_t k = sizeof w->buf - w->n < n ? sizeof w->buf - w->n : n;
        memcpy(w->buf + w->n, p, k);
        w->n += k;
        p += k;
        n -= k;
        if (w->n == sizeof w->buf) w_flush(w);
    }
}

static void w_u32(writer_t *w, uint32_t v)
{
    unsigned char b[4];
    put32(b, v);
    w_bytes(w, b, 4);
}
static void w_u16(writer_t *w, uint32_t v)
{
    unsigned char b[2];
    put16(b, v);
    w_bytes(w, b, 2);
}

int ff_file_save(const char *path, const ff_file_info *info, const uint32_t *start, const void *ids,
                 unsigned id_bytes, const uint16_t *codes, char *err, size_t errlen)
{
    static writer_t w; /* 64 KB: not on the stack */
    unsigned char head[HEADER_BYTES], tail[TRAILER_BYTES];
    fio_out *o;
    uint32_t i;
    if (!info || !start || (info->entries && (!ids || !codes)) ||
        (id_bytes != 2 && id_bytes != 4) || info->res > 0xFFFFu || info->kind > 0xFFFFu ||
        start[info->patches] != info->entries) {
        fio_err(err, errlen, path, "invalid rows to save");
        return -1;
    }
    if (!(o = fio_out_open(path, err, errlen))) return -1;
    memset(&w, 0, sizeof w);
    w.fp = fio_out_stream(o);
    w.hash = FF_FILE_FNV_START;
    memset(head, 0, sizeof head);
    memcpy(head, MAGIC, sizeof MAGIC);
    put16(head + 6, FF_FILE_VERSION);
    put16(head + 8, info->kind);
    put16(head + 10, info->res);
    put32(head + 12, info->patches);
    put32(head + 16, info->elements);
    put32(head + 20, info->vertices);
    put32(head + 24, info->entries);
    put64(head + 32, info->fingerprint);
    w_bytes(&w, head, sizeof head);
    for (i = 0; i <= info->patches; i++) w_u32(&w, start[i]);
    for (i = 0; i < info->entries; i++) w_u32(&w, id_at(ids, id_bytes, i));
    for (i = 0; i < info->entries; i++) w_u16(&w, codes[i]);
    put64(tail, w.hash);
    w_bytes(&w, tail, sizeof tail);
    w_flush(&w);
    if (w.failed) {
        fio_out_abort(o);
        fio_err(err, errlen, path, "write error: %s", strerror(w.failed));
        return -1;
    }
    return fio_out_commit(o, err, errlen);
}

/* ---- reading ------------------------------------------------------------------- */

/* Bytes past the end its header gives that a file may have and still be read whole, so
 * that a botched copy or append is named by the checksum; a file longer than that is
 * not one of ours and is refused from its size, unread (a sparse 20 GB file costs an
 * fstat). */
#define EXTRA_BYTES 4096u

/* The checks the header alone allows, in the order of ff_file.h: magic, version, and a
 * file shorter than the header (GOT bytes of it came: the whole file when short). */
static int check_head(const char *path, const unsigned char *h, size_t got, char *err,
                      size_t errlen)
{
    if (memcmp(h, MAGIC, got < sizeof MAGIC ? got : sizeof MAGIC) != 0) {
        fio_err(err, errlen, path,
                "not a rad form factor file (bad magic: it should start with \"RADFF\")");
        return -1;
    }
    if (got >= 8 && get16(h + 6) != FF_FILE_VERSION) {
        fio_err(err, errlen, path, "unsupported format version %u (this program reads version %u)",
                get16(h + 6), FF_FILE_VERSION);
        return -1;
    }
    if (got < HEADER_BYTES) {
        fio_err(err, errlen, path, "truncated: %zu bytes, shorter than the %u-byte header", got,
                HEADER_BYTES);
        return -1;
    }
    return 0;
}

/* Reads the rest of the file after HEAD (a regular file of SIZE bytes, or a stream when
 * SIZE is -1) into a buffer that starts with HEAD; at most WANT + EXTRA_BYTES in all. */
static unsigned char *read_rest(FILE *fp, const char *path, const unsigned char *head,
                                long long size, size_t *total, char *err, size_t errlen)
{
    uint64_t want = file_bytes(get32(head + 12), get32(head + 24)), most = want + EXTRA_BYTES;
    uint64_t cap = size >= 0 ? (uint64_t)size : most + 1;
    unsigned char *buf;
    if (size >= 0 && (uint64_t)size > most) {
        fio_err(err, errlen, path,
                "corrupt: %lld bytes, its header (%u rows, %u entries) says %llu: not read", size,
                get32(head + 12), get32(head + 24), (unsigned long long)want);
        return NULL;
    }
    if (cap > (uint64_t)SIZE_MAX - 1u || !(buf = malloc((size_t)cap))) {
        fio_err(err, errlen, path, "out of memory for %llu bytes", (unsigned long long)cap);
        return NULL;
    }
    memcpy(buf, head, HEADER_BYTES);
    *total = HEADER_BYTES + fread(buf + HEADER_BYTES, 1, (size_t)cap - HEADER_BYTES, fp);
    if (ferror(fp) || (size >= 0 && *total != (uint64_t)size) || (size < 0 && *total > most)) {
        if (ferror(fp))
            fio_err(err, errlen, path, "read error: %s", strerror(errno));
        else if (size >= 0)
            fio_err(err, errlen, path, "read error: the file changed while read");
        else
            fio_err(err, errlen, path,
                    "corrupt: more bytes than its header (%u rows, %u entries) says (%llu)",
                    get32(head + 12), get32(head + 24), (unsigned long long)want);
        free(buf);
        return NULL;
    }
    return buf;
}

/* Reads PATH through fio_open_read: the header first and checked, then the rest. */
static unsigned char *read_ff(const char *path, size_t *size, char *err, size_t errlen)
{
    unsigned char head[HEADER_BYTES], *buf = NULL;
    struct stat st;
    size_t got;
    FILE *fp = fio_open_read(path, err, errlen);
    if (!fp) return NULL;
    got = fread(head, 1, sizeof head, fp);
    if (ferror(fp))
        fio_err(err, errlen, path, "read error: %s", strerror(errno));
    else if (check_head(path, head, got, err, errlen) == 0)
        buf = read_rest(fp, path, head,
                        fstat(fileno(fp), &st) == 0 && S_ISREG(st.st_mode) ? (long long)st.st_size
                                                                           : -1,
                        size, err, errlen);
    fclose(fp);
    return buf;
}

/* A code stands for a form factor in (0, 2^30] with a normalized mantissa. */
static int code_ok(uint32_t c)
{
    uint32_t e = c >> 11, m = c & 2047u;
    if (m == 0 || (e > 0 && m < 1024u)) return 0;
    return ((uint64_t)m << e) <= (1ull << 30);
}

int ff_file_load(const char *path, ff_file_t *f, char *err, size_t errlen)
{
    unsigned char *d;
    size_t size;
    uint64_t want;
    ff_file_info *in;
    const unsigned char *st, *id, *cd;
    uint32_t p, i;
    memset(f, 0, sizeof *f);
    if (!(d = read_ff(path, &size, err, errlen))) return -1;
    in = &f->info;
    in->kind = get16(d + 8);
    in->res = get16(d + 10);
    in->patches = get32(d + 12);
    in->elements = get32(d + 16);
    in->vertices = get32(d + 20);
    in->entries = get32(d + 24);
    in->fingerprint = get64(d + 32);
    want = file_bytes(in->patches, in->entries);
    /* A bad checksum is reported as truncation when the size explains it. */
    if ((uint64_t)size < want) {
        fio_err(err, errlen, path,
                "truncated: %zu bytes, its header (%u rows, %u entries) needs %llu", size,
                in->patches, in->entries, (unsigned long long)want);
        goto fail;
    }
    if (get64(d + size - TRAILER_BYTES) !=
        ff_file_fnv(FF_FILE_FNV_START, d, size - TRAILER_BYTES)) {
        fio_err(err, errlen, path, "checksum mismatch: the file is corrupt%s",
                (uint64_t)size > want ? " (or has bytes past its end)" : "");
        goto fail;
    }
    if ((uint64_t)size != want) {
        fio_err(err, errlen, path, "corrupt: %zu bytes, its header says %llu", size,
                (unsigned long long)want);
        goto fail;
    }
    if (get32(d + 28) != 0 || (in->kind != FF_FILE_KIND_FIXED && in->kind != FF_FILE_KIND_FLOAT)) {
        fio_err(err, errlen, path, "corrupt header (build kind %u)", in->kind);
        goto fail;
    }
    /* The structure, so that nothing in a file with a valid checksum can index out of
     * range or stand for a form factor no hemi-cube gives. */
    st = d + HEADER_BYTES;
    id = st + 4u * ((size_t)in->patches + 1u);
    cd = id + 4u * (size_t)in->entries;
    if (get32(st) != 0 || get32(st + 4u * (size_t)in->patches) != in->entries) {
        fio_err(err, errlen, path, "corrupt row table (the rows do not cover the %u entries)",
                in->entries);
        goto fail;
    }
    for (p = 0; p < in->patches; p++) {
        uint32_t a = get32(st + 4u * (size_t)p), b = get32(st + 4u * ((size_t)p + 1u));
        if (b < a || b > in->entries) {
            fio_err(err, errlen, path, "corrupt row table at row %u", p);
            goto fail;
        }
        for (i = a; i < b; i++) {
            uint32_t e = get32(id + 4u * (size_t)i);
            if (e >= in->elements || (i > a && e <= get32(id + 4u * ((size_t)i - 1u)))) {
                fio_err(err, errlen, path, "corrupt entry %u of row %u (element %u of %u)", i - a,
                        p, e, in->elements);
                goto fail;
            }
            if (!code_ok(get16(cd + 2u * (size_t)i))) {
                fio_err(err, errlen, path, "corrupt form factor code 0x%04x in row %u",
                        get16(cd + 2u * (size_t)i), p);
                goto fail;
            }
        }
    }
    f->data = d;
    f->size = size;
    return 0;
fail:
    free(d);
    memset(f, 0, sizeof *f);
    return -1;
}

int ff_file_match(const ff_file_t *f, const ff_file_info *want, const char *path, char *err,
                  size_t errlen)
{
    const ff_file_info *in = &f->info;
    if (in->kind != want->kind) {
        fio_err(
            err, errlen, path,
            "made by the %s build, this is the %s build (stored form factors do not cross builds)",
            ff_file_kind_name(in->kind), ff_file_kind_name(want->kind));
        return -1;
    }
    if (in->patches != want->patches || in->elements != want->elements ||
        in->vertices != want->vertices) {
        fio_err(err, errlen, path,
                "scene mismatch: made for %u patches, %u elements, %u vertices; this scene has %u, "
                "%u, %u "
                "(another scene, or other --max-element / --max-patch)",
                in->patches, in->elements, in->vertices, want->patches, want->elements,
                want->vertices);
        return -1;
    }
    if (in->fingerprint != want->fingerprint) {
        fio_err(err, errlen, path,
                "scene mismatch: the geometry fingerprint differs (%016llx, this scene %016llx): "
                "another scene "
                "or mesh with the same counts",
                (unsigned long long)in->fingerprint, (unsigned long long)want->fingerprint);
        return -1;
    }
    if (in->res != want->res) {
        fio_err(err, errlen, path, "computed at hemi-cube resolution %u, this run uses %u (--res)",
                in->res, want->res);
        return -1;
    }
    return 0;
}

void ff_file_rows(const ff_file_t *f, uint32_t *start, void *ids, unsigned id_bytes,
                  uint16_t *codes)
{
    const ff_file_info *in = &f->info;
    const unsigned char *st = f->data + HEADER_BYTES;
    const unsigned char *id = st + 4u * ((size_t)in->patches + 1u);
    const unsigned char *cd = id + 4u * (size_t)in->entries;
    uint32_t i;
    for (i = 0; i <= in->patches; i++) start[i] = get32(st + 4u * (size_t)i);
    for (i = 0; i < in->entries; i++) {
        uint32_t e = get32(id + 4u * (size_t)i);
        if (id_bytes == 2)
            ((uint16_t *)ids)[i] = (uint16_t)e;
        else
            ((uint32_t *)ids)[i] = e;
        codes[i] = (uint16_t)get16(cd + 2u * (size_t)i);
    }
}

void ff_file_free(ff_file_t *f)
{
    if (!f) return;
    free(f->data);
    memset(f, 0, sizeof *f);
}
