/* SPDX-License-Identifier: MIT */
/* obj — Wavefront OBJ + MTL loader for the host tools. See obj.h. */
#include "formats/obj.h"

#include "formats/file_io.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MAX_VALUE  1e30 /* coordinates beyond this are broken geometry, not a scene */
#define DEFAULT_KD 0.8

#if defined(__GNUC__)
#define PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define PRINTF_LIKE(f, a)
#endif

/* State shared by the OBJ file and the MTL files it pulls in. */
typedef struct {
    obj_scene *sc;
    obj_warn_fn warn;
    void *ctx;
    char *err;
    size_t errlen;
    const char *basedir; /* for mtllib; NULL: mtllib is ignored with a warning */
    int allow_outside;   /* obj_opts: files outside basedir are read */
    char *root;          /* basedir resolved (fio_resolve), for messages; lazily */
    const char *file;    /* file being parsed, for messages */
    long line;           /* first physical line of the current statement */
    int cur;             /* OBJ: material of the next faces; MTL: the one being defined */
    int object, group;   /* OBJ: names index of the current o and g, -1 before any */
    size_t cap_verts, cap_indices, cap_faces, cap_mats, cap_uvs, cap_normals, cap_names;
    size_t cap_uv_indices, cap_normal_indices;
} parser;

typedef int (*statement_fn)(parser *p, const char *kw, char *rest);

static char *join_path(const char *dir, const char *name);
static char *dir_of(const char *path);

/* ---- messages ------------------------------------------------------------------ */

static void put_msg(char *out, size_t outlen, const char *fmt, ...) PRINTF_LIKE(3, 4);
static void put_msg(char *out, size_t outlen, const char *fmt, ...)
{
    va_list ap;
    if (!out || !outlen) return;
    va_start(ap, fmt);
    vsnprintf(out, outlen, fmt, ap);
    va_end(ap);
}

static void located(const parser *p, char *out, size_t outlen, const char *fmt, va_list ap)
{
    char text[512];
    vsnprintf(text, sizeof text, fmt, ap);
    put_msg(out, outlen, "%s:%ld: %s", p->file, p->line, text);
}

/* Records the error for the current statement; returns -1 so callers can 'return fail()'. */
static int fail(parser *p, const char *fmt, ...) PRINTF_LIKE(2, 3);
static int fail(parser *p, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (p->err && p->errlen) located(p, p->err, p->errlen, fmt, ap);
    va_end(ap);
    return -1;
}

static void warn(parser *p, const char *fmt, ...) PRINTF_LIKE(2, 3);
static void warn(parser *p, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    p->sc->nwarnings++;
    if (!p->warn) return;
    va_start(ap, fmt);
    located(p, msg, sizeof msg, fmt, ap);
    va_end(ap);
    p->warn(p->ctx, msg);
}

static int line_int(const parser *p)
{
    return p->line > INT_MAX ? INT_MAX : (int)p->line;
}

/* ---- the scene's folder -------------------------------------------------------- */

/* Does PATH (a library or texture) leave the scene's folder, and may it not? A file
   that does not resolve (missing) is not outside: its reader says it is missing. */
static int outside(parser *p, const char *path)
{
    const char *dir = p->basedir && *p->basedir ? p->basedir : ".";
    if (p->allow_outside || fio_within(dir, path) != 0) return 0;
    if (!p->root) p->root = fio_resolve(dir);
    return 1;
}

/* The warning for PATH outside the folder: WHAT it is, DOING instead. */
static void warn_outside(parser *p, const char *what, const char *path, const char *doing)
{
    warn(p, "%s: %.300s is outside the scene's folder %.300s; %s; --allow-outside-paths reads it",
         what, path, p->root ? p->root : p->basedir, doing);
}

/* ---- growing arrays ------------------------------------------------------------ */

/* Returns a block with room for need elements: p itself if it is big enough, else a
   doubled reallocation; NULL on failure (p is then still valid and owned by the caller). */
static void *reserve(void *p, size_t *cap, size_t need, size_t elem)
{
    size_t n = *cap ? *cap : 16;
    void *q;
    if (need <= *cap) return p;
    while (n < need) {
        if (n > SIZE_MAX / 2 / elem) return NULL;
        n *= 2;
    }
    q = realloc(p, n * elem);
    if (q) *cap = n;
    return q;
}

/* ARR (N entries of ELEM bytes, room for *CAP) with room for one more: ARR itself or a
   reallocation; NULL after the error ("too many WHAT", out of memory), ARR still valid. */
static void *room_for_one(parser *p, void *arr, size_t *cap, int n, size_t elem, const char *what)
{
    void *q;
    if (n == INT_MAX) {
        fail(p, "too many %s", what);
        return NULL;
    }
    if (!(q = reserve(arr, cap, (size_t)n + 1, elem))) fail(p, "out of memory");
    return q;
}

/* Appends v to *arr (n entries, room for *cap): vertices and normals. */
static int push_vec3(parser *p, obj_vec3 **arr, int *n, size_t *cap, obj_vec3 v, const char *what)
{
    obj_vec3 *q = room_for_one(p, *arr, cap, *n, sizeof *q, what);
    if (!q) return -1;
    *arr = q;
    q[(*n)++] = v;
    return 0;
}

static int push_uv(parser *p, obj_vec2 t)
{
    obj_scene *sc = p->sc;
    obj_vec2 *q = room_for_one(p, sc->uvs, &p->cap_uvs, sc->nuvs, sizeof *q, "texture coordinates");
    if (!q) return -1;
    sc->uvs = q;
    sc->uvs[sc->nuvs++] = t;
    return 0;
}

/* One face vertex: its position, texture coordinate and normal indices (-1: none),
   kept in three arrays of nindices entries. */
static int push_index(parser *p, const int ix[3])
{
    obj_scene *sc = p->sc;
    size_t need = (size_t)sc->nindices + 1;
    int *q;
    if (sc->nindices == INT_MAX) return fail(p, "too many face vertices");
    if ((q = reserve(sc->indices, &p->cap_indices, need, sizeof *q)) != NULL) {
        sc->indices = q;
        if ((q = reserve(sc->uv_indices, &p->cap_uv_indices, need, sizeof *q)) != NULL) {
            sc->uv_indices = q;
            if ((q = reserve(sc->normal_indices, &p->cap_normal_indices, need, sizeof *q)))
                sc->normal_indices = q;
        }
    }
    if (!q) return fail(p, "out of memory");
    sc->indices[sc->nindices] = ix[0];
    sc->uv_indices[sc->nindices] = ix[1];
    sc->normal_indices[sc->nindices++] = ix[2];
    return 0;
}

static int push_face(parser *p, int first, int count)
{
    obj_scene *sc = p->sc;
    obj_face *q;
    if (sc->nfaces == INT_MAX) return fail(p, "too many faces");
    q = reserve(sc->faces, &p->cap_faces, (size_t)sc->nfaces + 1, sizeof *q);
    if (!q) return fail(p, "out of memory");
    sc->faces = q;
    q += sc->nfaces++;
    q->material = p->cur;
    q->first = first;
    q->count = count;
    q->line = line_int(p);
    q->object = p->object;
    q->group = p->group;
    return 0;
}

static char *copy_string(const char *s)
{
    size_t n = strlen(s) + 1;
    char *c = malloc(n);
    if (c) memcpy(c, s, n);
    return c;
}

static void map_defaults(obj_map *t)
{
    free(t->path);
    free(t->mtl);
    memset(t, 0, sizeof *t);
    t->scale[0] = t->scale[1] = 1.0;
}

static void material_defaults(obj_material *m)
{
    int i;
    for (i = 0; i < 3; i++) {
        m->kd[i] = DEFAULT_KD;
        m->ke[i] = 0.0;
    }
    map_defaults(&m->map_kd);
}

/* ---- material names: FNV-1a hashed, open addressing ------------------------------ */

static uint32_t name_hash(const char *s)
{
    uint32_t h = 2166136261u;
    for (; *s; s++) {
        h ^= (unsigned char)*s;
        h *= 16777619u;
    }
    return h;
}

/* The slot of NAME in the table: where it is, or the empty slot where it would go. The
 * table is at most half full (rehash below), so the probe ends. */
static size_t name_slot(const obj_scene *sc, const char *name)
{
    size_t mask = sc->mat_slots - 1, i = name_hash(name) & mask;
    while (sc->mat_index[i] >= 0 && strcmp(sc->materials[sc->mat_index[i]].name, name))
        i = (i + 1) & mask;
    return i;
}

/* Makes room for one more material in the table (doubling it past half full). */
static int grow_names(obj_scene *sc)
{
    size_t n = sc->mat_slots ? sc->mat_slots : 64, i;
    int *t;
    if ((size_t)sc->nmaterials + 1 <= n / 2 && sc->mat_index) return 0;
    while ((size_t)sc->nmaterials + 1 > n / 2) n *= 2;
    if (!(t = malloc(n * sizeof *t))) return -1;
    for (i = 0; i < n; i++) t[i] = -1;
    free(sc->mat_index);
    sc->mat_index = t;
    sc->mat_slots = n;
    for (i = 0; i < (size_t)sc->nmaterials; i++) t[name_slot(sc, sc->materials[i].name)] = (int)i;
    return 0;
}

/* Index of the material called name, created with default values if new; -1 on error. */
static int intern_material(parser *p, const char *name)
{
    obj_scene *sc = p->sc;
    obj_material *q;
    size_t len = strlen(name);
    char *copy;
    int m = obj_find_material(sc, name);
    if (m >= 0) return m;
    if (sc->nmaterials == INT_MAX) return fail(p, "too many materials");
    q = reserve(sc->materials, &p->cap_mats, (size_t)sc->nmaterials + 1, sizeof *q);
    if (!q) return fail(p, "out of memory");
    sc->materials = q; /* before grow_names, which reads the names */
    if (grow_names(sc) != 0) return fail(p, "out of memory");
    copy = malloc(len + 1);
    if (!copy) return fail(p, "out of memory");
    memcpy(copy, name, len + 1);
    q += sc->nmaterials;
    memset(q, 0, sizeof *q);
    q->name = copy;
    material_defaults(q);
    sc->mat_index[name_slot(sc, name)] = sc->nmaterials;
    return sc->nmaterials++;
}

/* ---- tokens and numbers -------------------------------------------------------- */

static int is_space(int c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

static int is_digit(int c)
{
    return c >= '0' && c <= '9';
}

/* Cuts the next whitespace-separated token out of *s (in place); NULL at the end. */
static char *next_token(char **s)
{
    char *c = *s, *start;
    while (is_space((unsigned char)*c)) c++;
    if (!*c) return NULL;
    start = c;
    while (*c && !is_space((unsigned char)*c)) c++;
    if (*c) *c++ = '\0';
    *s = c;
    return start;
}

static char *trim(char *s)
{
    size_t n;
    while (is_space((unsigned char)*s)) s++;
    n = strlen(s);
    while (n > 0 && is_space((unsigned char)s[n - 1])) n--;
    s[n] = '\0';
    return s;
}

static int is_one_of(const char *kw, const char *const *list)
{
    for (; *list; list++)
        if (!strcmp(kw, *list)) return 1;
    return 0;
}

/* Plain decimals only: strtod alone would also take "nan", "inf", "infinity" and hex. */
static int is_decimal(const char *s)
{
    int digits = 0;
    if (*s == '+' || *s == '-') s++;
    for (; is_digit((unsigned char)*s); s++) digits++;
    if (*s == '.')
        for (s++; is_digit((unsigned char)*s); s++) digits++;
    if (!digits) return 0;
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-') s++;
        if (!is_digit((unsigned char)*s)) return 0;
        while (is_digit((unsigned char)*s)) s++;
    }
    return *s == '\0';
}

static int parse_number(parser *p, const char *tok, double *out)
{
    char *end;
    double v;
    if (!is_decimal(tok)) return fail(p, "bad number '%.40s'", tok);
    v = strtod(tok, &end);
    if (*end != '\0') return fail(p, "bad number '%.40s'", tok);
    if (!(fabs(v) <= MAX_VALUE)) return fail(p, "number out of range '%.40s' (limit 1e30)", tok);
    *out = v;
    return 0;
}

/* Reads [+-]digits at *s, saturating past INT_MAX (out of range anyway); -1 if none. */
static int read_int(const char **s, long long *v)
{
    const char *c = *s;
    long long x = 0;
    int neg = 0;
    if (*c == '+' || *c == '-') neg = *c++ == '-';
    if (!is_digit((unsigned char)*c)) return -1;
    for (; is_digit((unsigned char)*c); c++)
        if (x <= INT_MAX) x = x * 10 + (*c - '0');
    *v = neg ? -x : x;
    *s = c;
    return 0;
}

/* ---- statements ---------------------------------------------------------------- */

/* Splits text into statements: physical lines joined by trailing backslashes, comments
   cut off, first token as keyword. p->line is the statement's first physical line. */
static int run_statement(parser *p, char *line, statement_fn fn)
{
    char *kw;
    size_t i;
    /* '#' starts a comment at the line start or after a blank, so "mat#1" stays a name. */
    for (i = 0; line[i]; i++)
        if (line[i] == '#' && (i == 0 || is_space((unsigned char)line[i - 1]))) {
            line[i] = '\0';
            break;
        }
    kw = next_token(&line);
    return kw ? fn(p, kw, line) : 0;
}

/* Length of the line at S (REM bytes left) up to its end: LF, CR or CRLF, all three
   being in use; *EOL gets the length of the line end (0 at the end of the text). */
static size_t line_length(const char *s, size_t rem, size_t *eol)
{
    size_t n = 0;
    while (n < rem && s[n] != '\n' && s[n] != '\r') n++;
    *eol = n == rem ? 0 : (s[n] == '\r' && n + 1 < rem && s[n + 1] == '\n') ? 2 : 1;
    return n;
}

/* A UTF-8 byte order mark some editors put first: not part of the first statement. */
static size_t bom_length(const char *text, size_t len)
{
    return len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3) ? 3 : 0;
}

static int each_statement(parser *p, const char *text, size_t len, statement_fn fn)
{
    char *buf = NULL, *q;
    size_t cap = 0, used = 0, pos = bom_length(text, len);
    long lineno = 0;
    int joining = 0, rc = 0;
    while (pos < len && rc == 0) {
        const char *s = text + pos;
        size_t eol, n = line_length(s, len - pos, &eol);
        pos += n + eol;
        if (!joining) {
            p->line = lineno + 1;
            used = 0;
        }
        lineno++;
        if (memchr(s, '\0', n)) {
            rc = fail(p, "binary data (NUL byte)");
            break;
        }
        while (n > 0 && is_space((unsigned char)s[n - 1])) n--;
        joining = n > 0 && s[n - 1] == '\\';
        n -= (size_t)joining;
        q = reserve(buf, &cap, used + n + 2, 1);
        if (!q) {
            rc = fail(p, "out of memory");
            break;
        }
        buf = q;
        memcpy(buf + used, s, n);
        used += n;
        if (joining) {
            buf[used++] = ' ';
            continue;
        }
        buf[used] = '\0';
        rc = run_statement(p, buf, fn);
    }
    if (rc == 0 && joining) { /* the file ended inside a continuation */
        buf[used] = '\0';
        rc = run_statement(p, buf, fn);
    }
    free(buf);
    return rc;
}

/* ---- the memory budget: a first, cheap pass --------------------------------------- */

/* Bytes the parsed scene keeps for the physical line S (N bytes): a vertex or normal
   (obj_vec3), a texture coordinate (obj_vec2), a face (obj_face) and its vertices (three
   int indices each); *NF counts the faces. Other statements keep little (names,
   materials: at most their own bytes, counted with the text). A face continued on the
   next line counts the vertices of its first line: the estimate is a lower bound. */
static double line_bytes(const char *s, size_t n, long *nf)
{
    size_t i = 0, k;
    double b = 0;
    while (i < n && is_space((unsigned char)s[i])) i++;
    for (k = i; k < n && !is_space((unsigned char)s[k]); k++)
        ;
    if (k - i == 1 && s[i] == 'v') return sizeof(obj_vec3);
    if (k - i == 2 && s[i] == 'v')
        return s[i + 1] == 't' ? sizeof(obj_vec2) : s[i + 1] == 'n' ? sizeof(obj_vec3) : 0;
    if (k - i != 1 || s[i] != 'f') return 0;
    (*nf)++;
    b = sizeof(obj_face);
    for (i = k; i < n && s[i] != '#'; i++)
        if (!is_space((unsigned char)s[i]) && is_space((unsigned char)s[i - 1]))
            b += 3 * sizeof(int);
    return b;
}

/* Refuses, before anything is parsed, a text whose scene would take more than
   fio_memory_budget: the text (kept while parsed) and what each line adds, summed line
   by line, so the error names the line where the budget runs out. 0 or -1. */
static int within_budget(parser *p, const char *text, size_t len)
{
    double budget = fio_memory_budget(), bytes = (double)len;
    size_t pos = bom_length(text, len);
    long line = 0, nf = 0;
    while (pos < len) {
        size_t eol, n = line_length(text + pos, len - pos, &eol);
        line++;
        bytes += line_bytes(text + pos, n, &nf);
        pos += n + eol;
        if (bytes > budget) {
            p->line = line;
            return fail(p,
                        "loading the scene up to this line needs more than the memory budget of "
                        "%.4g MB (%ld faces so far; %s): simplify or split the scene",
                        budget / 1e6, nf,
                        getenv("RAD_MEMORY_BUDGET")
                            ? "RAD_MEMORY_BUDGET"
                            : "half the physical memory; RAD_MEMORY_BUDGET sets it");
        }
    }
    return 0;
}

/* ---- MTL ----------------------------------------------------------------------- */

static int parse_newmtl(parser *p, char *rest)
{
    const char *name = trim(rest);
    obj_material *m;
    int i;
    if (!*name) return fail(p, "newmtl without a material name");
    if ((i = intern_material(p, name)) < 0) return -1;
    m = &p->sc->materials[i];
    if (m->defined) warn(p, "material '%.200s' defined again; the new definition wins", name);
    material_defaults(m);
    m->defined = 1;
    p->cur = i;
    return 0;
}

/* Kd / Ke: one value (grey) or three, each finite and >= 0. */
static int parse_colour(parser *p, const char *kw, char *rest, double *dst)
{
    double c[3];
    char *tok;
    int n = 0;
    while ((tok = next_token(&rest)) != NULL) {
        if (n == 3) return fail(p, "%s takes 1 or 3 values, got more", kw);
        if (parse_number(p, tok, &c[n])) return -1;
        if (c[n] < 0) return fail(p, "negative %s value '%.40s'", kw, tok);
        n++;
    }
    if (n != 1 && n != 3) return fail(p, "%s takes 1 or 3 values, got %d", kw, n);
    if (n == 1) c[1] = c[2] = c[0];
    memcpy(dst, c, sizeof c);
    return 0;
}

/* Texture map options (MTL specification) and what they take: -o, -s and -t 1 to 3
   numbers (u [v [w]]), -mm 2, -bm, -boost and -texres 1; -blendu, -blendv, -cc and
   -clamp on or off; -imfchan and -type one word. */
enum { MAP_NUMBERS, MAP_ON_OFF, MAP_WORD };

typedef struct {
    const char *name;
    int kind, min, max;
} map_option;

static const map_option map_options[] = {
    {"-blendu", MAP_ON_OFF, 1, 1}, {"-blendv", MAP_ON_OFF, 1, 1},
    {"-bm", MAP_NUMBERS, 1, 1},    {"-boost", MAP_NUMBERS, 1, 1},
    {"-cc", MAP_ON_OFF, 1, 1},     {"-clamp", MAP_ON_OFF, 1, 1},
    {"-imfchan", MAP_WORD, 1, 1},  {"-mm", MAP_NUMBERS, 2, 2},
    {"-o", MAP_NUMBERS, 1, 3},     {"-s", MAP_NUMBERS, 1, 3},
    {"-t", MAP_NUMBERS, 1, 3},     {"-texres", MAP_NUMBERS, 1, 1},
    {"-type", MAP_WORD, 1, 1},     {NULL, 0, 0, 0}};

static const map_option *find_map_option(const char *tok)
{
    const map_option *o;
    for (o = map_options; o->name; o++)
        if (!strcmp(tok, o->name)) return o;
    return NULL;
}

/* Is TOK a value option O can take (a number; on or off, kept as 1 or 0; any word)? */
static int map_value(const map_option *o, const char *tok, double *v)
{
    if (o->kind == MAP_NUMBERS && is_decimal(tok)) {
        *v = strtod(tok, NULL);
        return fabs(*v) <= MAX_VALUE;
    }
    if (o->kind == MAP_ON_OFF && (!strcmp(tok, "on") || !strcmp(tok, "off"))) {
        *v = tok[1] == 'n';
        return 1;
    }
    *v = 0;
    return o->kind == MAP_WORD;
}

/* Copies the next token of S (at most 63 characters, else "") into TOK without cutting
   it out; returns the text after it. */
static char *peek_token(char *s, char tok[64])
{
    size_t n = 0;
    while (is_space((unsigned char)*s)) s++;
    while (s[n] && !is_space((unsigned char)s[n])) n++;
    memcpy(tok, s, n < 64 ? n : 0);
    tok[n < 64 ? n : 0] = '\0';
    return s + n;
}

/* Reads option O's values from *REST into v. Returns the count read, or -1 (a warning
   given) when fewer than its minimum are there. */
static int map_option_values(parser *p, const map_option *o, char **rest, double v[3])
{
    int n = 0;
    while (n < o->max) {
        char tok[64], *after = peek_token(*rest, tok);
        if (!*tok || !map_value(o, tok, &v[n])) break; /* the file name, or the next option */
        *rest = after;
        n++;
    }
    if (n < o->min) {
        warn(p, "map_Kd %s needs %d value%s: statement ignored", o->name, o->min,
             o->min > 1 ? "s" : "");
        return -1;
    }
    return n;
}

/* Keeps the values of -o, -s and -clamp. */
static void map_apply(obj_map *t, const map_option *o, const double *v, int n)
{
    int offset = !strcmp(o->name, "-o");
    if (!strcmp(o->name, "-clamp")) t->clamp = v[0] > 0;
    if (offset || !strcmp(o->name, "-s")) {
        double *dst = offset ? t->offset : t->scale;
        dst[0] = v[0];
        dst[1] = n > 1 ? v[1] : offset ? 0.0 : 1.0;
    }
}

/* The file name as written: the rest of the statement (spaces kept); backslashes, as
   Windows exporters write them, become slashes. Joined to the MTL's folder. */
static char *map_path(const parser *p, char *name)
{
    char *dir = dir_of(p->file), *path, *c;
    for (c = name; *c; c++)
        if (*c == '\\') *c = '/';
    path = dir ? join_path(dir, name) : NULL;
    free(dir);
    return path;
}

/* map_Kd [options] FILE. A malformed statement is a warning, not an error: the material
   keeps its Kd (0.5 grey if Kd is 0, see obj_map_fallback). */
static int parse_map_kd(parser *p, char *rest)
{
    obj_map *t = &p->sc->materials[p->cur].map_kd;
    char tok[64], *after;
    map_defaults(t);
    t->line = line_int(p);
    if (!(t->mtl = copy_string(p->file))) return fail(p, "out of memory");
    while ((after = peek_token(rest, tok)), tok[0] == '-') {
        const map_option *o = find_map_option(tok);
        double v[3];
        int n;
        if (!o) break; /* a file whose name starts with '-' */
        rest = after;
        if ((n = map_option_values(p, o, &rest, v)) < 0) return 0;
        map_apply(t, o, v, n);
    }
    if (!*(rest = trim(rest))) {
        warn(p, "map_Kd without a file name: ignored");
        return 0;
    }
    if (!(t->path = map_path(p, rest))) return fail(p, "out of memory");
    t->outside = outside(p, t->path); /* warned of by finish, once Kd is known */
    return 0;
}

/* Valid MTL that says nothing about diffuse reflection or emission. */
static const char *const mtl_ignored[] = {
    "Ka",    "Ks",   "Ns",   "Ni", "d",  "Tr", "Tf", "illum", "sharpness", "bump",   "disp",
    "decal", "refl", "norm", "Pr", "Pm", "Ps", "Pc", "Pcr",   "aniso",     "anisor", NULL};

static int mtl_statement(parser *p, const char *kw, char *rest)
{
    int colour = !strcmp(kw, "Kd") ? 1 : !strcmp(kw, "Ke") ? 2 : 0;
    if (!strcmp(kw, "newmtl")) return parse_newmtl(p, rest);
    if (colour) {
        obj_material *m;
        if (p->cur < 0) return fail(p, "%s before any newmtl", kw);
        m = &p->sc->materials[p->cur];
        return parse_colour(p, kw, rest, colour == 1 ? m->kd : m->ke);
    }
    if (!strcmp(kw, "map_Kd")) {
        if (p->cur < 0) return fail(p, "%s before any newmtl", kw);
        return parse_map_kd(p, rest);
    }
    if (!strncmp(kw, "map_", 4) || is_one_of(kw, mtl_ignored)) return 0;
    p->sc->unknown_statements++;
    return 0;
}

static char *join_path(const char *dir, const char *name)
{
    size_t dl = name[0] == '/' ? 0 : strlen(dir), nl = strlen(name);
    int sep = dl > 0 && dir[dl - 1] != '/';
    char *s = malloc(dl + (size_t)sep + nl + 1);
    if (!s) return NULL;
    memcpy(s, dir, dl);
    if (sep) s[dl] = '/';
    memcpy(s + dl + (size_t)sep, name, nl + 1);
    return s;
}

/* Reads the library NAME (at PATH) whole: 0, or 1 after a warning (a library that
   cannot be read is like a missing one: its materials stay undefined). */
static int read_mtl_text(parser *p, const char *name, const char *path, char **text, size_t *len)
{
    char msg[600];
    const char *why = msg;
    size_t pl = strlen(path);
    if (fio_read_all(path, FIO_LIMIT_MTL, text, len, msg, sizeof msg) == 0) return 0;
    if (!strncmp(msg, path, pl) && !strncmp(msg + pl, ": ", 2))
        why = msg + pl + 2; /* fio's "PATH: " prefix: the warning names the library */
    if (!strncmp(why, "cannot open: ", 13))
        warn(p, "cannot open material library '%.200s': %s", name, why + 13);
    else
        warn(p, "cannot read material library '%.200s': %s", name, why);
    return 1;
}

/* Adds PATH to the libraries read (sc->libs). 0 or -1 (out of memory). */
static int keep_lib(parser *p, const char *path)
{
    obj_scene *sc = p->sc;
    char **q = sc->nlibs < INT_MAX ? realloc(sc->libs, ((size_t)sc->nlibs + 1) * sizeof *q) : NULL;
    if (!q) return -1;
    sc->libs = q;
    if (!(q[sc->nlibs] = copy_string(path))) return -1;
    sc->nlibs++;
    return 0;
}

/* Parses the library NAME, relative to the OBJ's folder; messages name it by path. */
static int load_mtl(parser *p, const char *name)
{
    const char *file = p->file;
    long line = p->line;
    int cur = p->cur, rc;
    char *text, *path = join_path(p->basedir, name);
    size_t len;
    if (!path) return fail(p, "out of memory");
    if (outside(p, path)) {
        warn_outside(p, "mtllib", path, "library not read");
        free(path);
        return 0;
    }
    if (read_mtl_text(p, name, path, &text, &len)) {
        free(path);
        return 0;
    }
    p->file = path;
    p->cur = -1;
    rc = each_statement(p, text, len, mtl_statement);
    free(text);
    if (rc == 0 && keep_lib(p, path) < 0) rc = fail(p, "out of memory");
    free(path);
    p->file = file;
    p->line = line;
    p->cur = cur;
    return rc;
}

/* Is there a file (of any kind) called NAME in the OBJ's folder? */
static int mtl_exists(const parser *p, const char *name)
{
    struct stat st;
    char *path = join_path(p->basedir, name);
    int yes = path && stat(path, &st) == 0;
    free(path);
    return yes;
}

/* ---- OBJ ----------------------------------------------------------------------- */

/* Reads between MIN and MAX numbers (more must still be numbers, and are ignored); NEED
   says how many in the message. Returns the count kept or -1. */
static int parse_numbers(parser *p, const char *kw, const char *need, char *rest, double *c,
                         int min, int max)
{
    char *tok;
    int n = 0;
    while ((tok = next_token(&rest)) != NULL) {
        double x;
        if (parse_number(p, tok, &x)) return -1;
        if (n < max) c[n] = x;
        n++;
    }
    if (n < min) return fail(p, "%s needs %s, got %d", kw, need, n);
    return n < max ? n : max;
}

/* v x y z or vn x y z. Extra values (w, or the r g b some exporters add) must be
   numbers but are ignored. */
static int parse_vec3(parser *p, int normal, char *rest)
{
    obj_scene *sc = p->sc;
    obj_vec3 v;
    double c[3];
    if (parse_numbers(p, normal ? "vn" : "vertex", "3 coordinates", rest, c, 3, 3) < 0) return -1;
    v.x = c[0];
    v.y = c[1];
    v.z = c[2];
    if (normal) return push_vec3(p, &sc->normals, &sc->nnormals, &p->cap_normals, v, "normals");
    return push_vec3(p, &sc->verts, &sc->nverts, &p->cap_verts, v, "vertices");
}

/* vt u [v [w]]: v defaults to 0 (the OBJ specification); w is dropped. */
static int parse_uv(parser *p, char *rest)
{
    obj_vec2 t;
    double c[2] = {0, 0};
    if (parse_numbers(p, "vt", "at least 1 coordinate", rest, c, 1, 2) < 0) return -1;
    t.u = c[0];
    t.v = c[1];
    return push_uv(p, t);
}

/* Resolves a 1-based (or negative, relative) OBJ index V, written as the LEN characters
   at TEXT, against the N entries defined so far; WHAT[0] and WHAT[1] name one and many. */
static int resolve_index(parser *p, long long v, const char *text, int len, int n,
                         const char *const what[2], int *out)
{
    if (v == 0) return fail(p, "%s index 0 (OBJ indices start at 1)", what[0]);
    if (v > n || v < -(long long)n)
        return fail(p, "%s index %.*s out of range (%d %s defined so far)", what[0],
                    len > 40 ? 40 : len, text, n, what[1]);
    *out = (int)(v > 0 ? v - 1 : n + v);
    return 0;
}

/* A vt or vn index that does not resolve is not an error (the positions are whole, and
   such files loaded before texture coordinates were read): the part is dropped with a
   warning, once per face (*WARNED). */
static void resolve_part(parser *p, long long v, int n, const char *what, int *out, int *warned)
{
    if (v != 0 && v <= n && v >= -(long long)n) {
        *out = (int)(v > 0 ? v - 1 : n + v);
        return;
    }
    if (!*warned) warn(p, "%s index %lld out of range (%d defined so far): ignored", what, v, n);
    *warned = 1;
}

/* One face vertex: v, v/vt, v//vn or v/vt/vn; resolves each part to a 0-based index
   into ix[0..2], -1 for a part not given. */
static int parse_face_vertex(parser *p, const char *tok, int ix[3], int *warned)
{
    static const char *const what[3][2] = {{"vertex", "vertices"},
                                           {"texture coordinate", "texture coordinates"},
                                           {"normal", "normals"}};
    const obj_scene *sc = p->sc;
    const int n[3] = {sc->nverts, sc->nuvs, sc->nnormals};
    const char *c = tok;
    int k;
    ix[0] = ix[1] = ix[2] = -1;
    for (k = 0; k < 3; k++) {
        const char *start = c;
        long long v;
        if (k > 0) {
            if (*c != '/') break;
            start = ++c;
            if (k == 1 && *c == '/') continue; /* v//vn */
        }
        if (read_int(&c, &v)) return fail(p, "bad face vertex '%.40s'", tok);
        if (k > 0)
            resolve_part(p, v, n[k], what[k][0], &ix[k], warned);
        else if (resolve_index(p, v, start, (int)(c - start), n[k], what[k], &ix[k]))
            return -1;
    }
    if (*c) return fail(p, "bad face vertex '%.40s'", tok);
    return 0;
}

/* A face has texture coordinates (normals) at all its vertices or at none. */
static void whole_parts(int *uv, int *normal, int count)
{
    int k, has_uv = 1, has_normal = 1;
    for (k = 0; k < count; k++) {
        has_uv &= uv[k] >= 0;
        has_normal &= normal[k] >= 0;
    }
    for (k = 0; k < count; k++) {
        uv[k] = has_uv ? uv[k] : -1;
        normal[k] = has_normal ? normal[k] : -1;
    }
}

static int parse_face(parser *p, char *rest)
{
    obj_scene *sc = p->sc;
    int first = sc->nindices, count = 0, ix[3], warned = 0;
    char *tok;
    while ((tok = next_token(&rest)) != NULL) {
        if (parse_face_vertex(p, tok, ix, &warned) || push_index(p, ix)) return -1;
        count++;
    }
    if (count < 3) return fail(p, "face needs at least 3 vertices, got %d", count);
    whole_parts(sc->uv_indices + first, sc->normal_indices + first, count);
    if (p->cur < 0 && (p->cur = intern_material(p, OBJ_DEFAULT_MATERIAL)) < 0) return -1;
    return push_face(p, first, count);
}

static int parse_usemtl(parser *p, char *rest)
{
    const char *name = trim(rest);
    int m;
    if (!*name) return fail(p, "usemtl without a material name");
    if ((m = intern_material(p, name)) < 0) return -1;
    if (!p->sc->materials[m].use_line) p->sc->materials[m].use_line = line_int(p);
    p->cur = m;
    return 0;
}

/* Several names, unless the whole rest of the line names one file (with spaces). */
static int parse_mtllib(parser *p, char *rest)
{
    char *names = trim(rest), *tok;
    if (!*names) return fail(p, "mtllib without a file name");
    if (!p->basedir) {
        warn(p, "mtllib '%.200s' ignored: no directory to look in", names);
        return 0;
    }
    if (strpbrk(names, " \t\v\f\r") && mtl_exists(p, names)) return load_mtl(p, names);
    while ((tok = next_token(&names)) != NULL)
        if (load_mtl(p, tok)) return -1;
    return 0;
}

/* o NAME / g NAME: the faces that follow belong to it (*CUR: a names index). A name
   equal to the current one adds nothing; names are otherwise not looked up, so one name
   may appear more than once (readers that group faces compare the strings). No name:
   the faces belong to none (-1). */
static int parse_name(parser *p, char *rest, int *cur)
{
    obj_scene *sc = p->sc;
    const char *name = trim(rest);
    char **q;
    if (!*name) {
        *cur = -1;
        return 0;
    }
    if (*cur >= 0 && !strcmp(sc->names[*cur], name)) return 0;
    if (!(q = room_for_one(p, sc->names, &p->cap_names, sc->nnames, sizeof *q,
                           "object and group names")))
        return -1;
    sc->names = q;
    if (!(q[sc->nnames] = copy_string(name))) return fail(p, "out of memory");
    *cur = sc->nnames++;
    return 0;
}

/* Valid OBJ that does not matter for radiosity. */
static const char *const obj_ignored[] = {"vp", "s", "l", "p", "mg", NULL};

static int obj_statement(parser *p, const char *kw, char *rest)
{
    if (!strcmp(kw, "v")) return parse_vec3(p, 0, rest);
    if (!strcmp(kw, "vt")) return parse_uv(p, rest);
    if (!strcmp(kw, "vn")) return parse_vec3(p, 1, rest);
    if (!strcmp(kw, "o")) return parse_name(p, rest, &p->object);
    if (!strcmp(kw, "g")) return parse_name(p, rest, &p->group);
    if (!strcmp(kw, "f")) return parse_face(p, rest);
    if (!strcmp(kw, "usemtl")) return parse_usemtl(p, rest);
    if (!strcmp(kw, "mtllib")) return parse_mtllib(p, rest);
    if (!is_one_of(kw, obj_ignored)) p->sc->unknown_statements++;
    return 0;
}

/* Warns about undefined materials (only now: an mtllib may follow the usemtl) and sums
   face areas per material. */
static void finish(parser *p)
{
    obj_scene *sc = p->sc;
    int i;
    for (i = 0; i < sc->nmaterials; i++) {
        const obj_material *m = &sc->materials[i];
        if (!m->defined && m->use_line) {
            p->line = m->use_line;
            warn(p, "usemtl '%.200s': material not defined, using Kd %.1f", m->name, DEFAULT_KD);
        }
    }
    for (i = 0; i < sc->nfaces; i++) {
        obj_material *m = &sc->materials[sc->faces[i].material];
        m->area += obj_face_area(sc, &sc->faces[i]);
        m->nfaces++;
    }
    for (i = 0; i < sc->nmaterials; i++) {
        obj_material *m = &sc->materials[i];
        char doing[128];
        if (m->map_kd.line && (!m->map_kd.path || m->map_kd.outside)) obj_map_fallback(m);
        if (!m->map_kd.outside) continue;
        p->file = m->map_kd.mtl;
        p->line = m->map_kd.line;
        snprintf(doing, sizeof doing, "using Kd %.3g %.3g %.3g", m->kd[0], m->kd[1], m->kd[2]);
        warn_outside(p, "map_Kd", m->map_kd.path, doing);
        free(m->map_kd.path);
        m->map_kd.path = NULL;
        m->map_kd.outside = 0;
    }
}

int obj_map_fallback(obj_material *m)
{
    int i;
    if (m->kd[0] != 0 || m->kd[1] != 0 || m->kd[2] != 0) return 0;
    for (i = 0; i < 3; i++) m->kd[i] = OBJ_FALLBACK_KD;
    return 1;
}

static int parse_text(const char *text, size_t len, const char *name, const char *basedir,
                      const obj_opts *opts, obj_scene *sc, obj_warn_fn warn_fn, void *ctx,
                      char *err, size_t errlen)
{
    parser p;
    int rc = 0;
    memset(sc, 0, sizeof *sc);
    memset(&p, 0, sizeof p);
    p.allow_outside = opts && opts->allow_outside;
    p.sc = sc;
    p.warn = warn_fn;
    p.ctx = ctx;
    p.err = err;
    p.errlen = errlen;
    p.basedir = basedir;
    p.file = name ? name : "(memory)";
    p.cur = -1;
    p.object = p.group = -1;
    put_msg(err, errlen, "%s", "");
    if (within_budget(&p, text, len) || each_statement(&p, text, len, obj_statement)) {
        obj_free(sc);
        rc = -1;
    } else {
        finish(&p);
    }
    free(p.root);
    return rc;
}

int obj_parse(const char *text, size_t len, const char *name, const char *basedir, obj_scene *sc,
              obj_warn_fn warn_fn, void *ctx, char *err, size_t errlen)
{
    return parse_text(text, len, name, basedir, NULL, sc, warn_fn, ctx, err, errlen);
}

/* Directory part of path ("" for a bare name), for mtllib. */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path) + (slash == path) : 0;
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, path, n);
        d[n] = '\0';
    }
    return d;
}

int obj_load(const char *path, obj_scene *sc, obj_warn_fn warn_fn, void *ctx, char *err,
             size_t errlen)
{
    return obj_load_opts(path, NULL, sc, warn_fn, ctx, err, errlen);
}

int obj_load_opts(const char *path, const obj_opts *opts, obj_scene *sc, obj_warn_fn warn_fn,
                  void *ctx, char *err, size_t errlen)
{
    char *text, *dir;
    size_t len;
    int rc;
    memset(sc, 0, sizeof *sc);
    if (path && !strcmp(path, "-") ? fio_read_stdin(FIO_LIMIT_OBJ, &text, &len, err, errlen)
                                   : fio_read_all(path, FIO_LIMIT_OBJ, &text, &len, err, errlen))
        return -1;
    dir = dir_of(path); /* "-": "", the current folder */
    if (!dir) {
        free(text);
        put_msg(err, errlen, "%s: out of memory", path);
        return -1;
    }
    rc = parse_text(text, len, path, dir, opts, sc, warn_fn, ctx, err, errlen);
    free(dir);
    free(text);
    return rc;
}

void obj_free(obj_scene *sc)
{
    int i;
    if (!sc) return;
    for (i = 0; i < sc->nmaterials; i++) {
        free(sc->materials[i].name);
        free(sc->materials[i].map_kd.path);
        free(sc->materials[i].map_kd.mtl);
        free(sc->materials[i].map_kd.data);
    }
    for (i = 0; i < sc->nnames; i++) free(sc->names[i]);
    for (i = 0; i < sc->nlights; i++) free(sc->lights[i].name);
    free(sc->lights);
    for (i = 0; i < sc->nnodes; i++) free(sc->nodes[i].name);
    free(sc->nodes);
    for (i = 0; i < sc->nlibs; i++) free(sc->libs[i]);
    free(sc->libs);
    free(sc->names);
    free(sc->materials);
    free(sc->mat_index);
    free(sc->verts);
    free(sc->indices);
    free(sc->uv_indices);
    free(sc->normal_indices);
    free(sc->uvs);
    free(sc->uv2);
    free(sc->normals);
    free(sc->faces);
    memset(sc, 0, sizeof *sc);
}

int obj_find_material(const obj_scene *sc, const char *name)
{
    int i;
    if (sc->mat_index) return sc->mat_index[name_slot(sc, name)];
    for (i = 0; i < sc->nmaterials; i++) /* a scene made by hand, without the table */
        if (!strcmp(sc->materials[i].name, name)) return i;
    return -1;
}

/* ---- geometry ------------------------------------------------------------------ */

static obj_vec3 vsub(obj_vec3 a, obj_vec3 b)
{
    obj_vec3 r;
    r.x = a.x - b.x;
    r.y = a.y - b.y;
    r.z = a.z - b.z;
    return r;
}

static obj_vec3 vcross(obj_vec3 a, obj_vec3 b)
{
    obj_vec3 r;
    r.x = a.y * b.z - a.z * b.y;
    r.y = a.z * b.x - a.x * b.z;
    r.z = a.x * b.y - a.y * b.x;
    return r;
}

static double vdot(obj_vec3 a, obj_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static obj_vec3 vscale(obj_vec3 a, double s)
{
    obj_vec3 r;
    r.x = a.x * s;
    r.y = a.y * s;
    r.z = a.z * s;
    return r;
}

/* Newell's normal written as a fan of cross products around the first vertex: the same
   vector, but relative coordinates keep precision for polygons far from the origin. */
obj_vec3 obj_face_normal(const obj_scene *sc, const obj_face *f)
{
    const int *ix = sc->indices + f->first;
    obj_vec3 o = sc->verts[ix[0]], n = {0, 0, 0}, c;
    int i;
    for (i = 1; i + 1 < f->count; i++) {
        c = vcross(vsub(sc->verts[ix[i]], o), vsub(sc->verts[ix[i + 1]], o));
        n.x += c.x;
        n.y += c.y;
        n.z += c.z;
    }
    return n;
}

double obj_face_area(const obj_scene *sc, const obj_face *f)
{
    obj_vec3 n = obj_face_normal(sc, f);
    return 0.5 * sqrt(vdot(n, n));
}

/* Twice the signed area of 2-D triangle (a, b, c): > 0 when counter-clockwise. */
static double turn(const double *xy, int a, int b, int c)
{
    return (xy[2 * b] - xy[2 * a]) * (xy[2 * c + 1] - xy[2 * a + 1]) -
           (xy[2 * b + 1] - xy[2 * a + 1]) * (xy[2 * c] - xy[2 * a]);
}

static int same_point(const double *xy, int a, int b)
{
    return xy[2 * a] == xy[2 * b] && xy[2 * a + 1] == xy[2 * b + 1];
}

/* Does any other remaining vertex lie in or on triangle (a, b, c)? Copies of a corner
   (polygons with bridged holes repeat vertices) do not count. */
static int blocks_ear(const double *xy, const int *next, int a, int b, int c, double eps)
{
    int j;
    for (j = next[c]; j != a; j = next[j]) {
        if (same_point(xy, j, a) || same_point(xy, j, b) || same_point(xy, j, c)) continue;
        if (turn(xy, a, b, j) >= -eps && turn(xy, b, c, j) >= -eps && turn(xy, c, a, j) >= -eps)
            return 1;
    }
    return 0;
}

/* Picks the vertex to clip: an ear if there is one; else a vertex with no area (collinear
   or a spike), whose removal changes nothing; else the most convex vertex, so that broken
   (self-intersecting) polygons still get count-2 triangles. */
static int pick_ear(const double *xy, const int *next, const int *prev, int start, int remaining,
                    double eps)
{
    int i = start, k, flat = -1, best = start;
    double best_turn = -HUGE_VAL;
    for (k = 0; k < remaining; k++, i = next[i]) {
        double t = turn(xy, prev[i], i, next[i]);
        if (t > eps && !blocks_ear(xy, next, prev[i], i, next[i], eps)) return i;
        if (flat < 0 && fabs(t) <= eps) flat = i;
        if (t > best_turn) {
            best_turn = t;
            best = i;
        }
    }
    return flat >= 0 ? flat : best;
}

/* Coordinates in the plane through the first vertex, with axes u, v such that u x v is
   the normal: the polygon then runs counter-clockwise. Returns the largest |coordinate|. */
static double project(const obj_scene *sc, const int *ix, int n, obj_vec3 normal, double *xy)
{
    obj_vec3 z = vscale(normal, 1.0 / sqrt(vdot(normal, normal))), a = {0, 0, 0}, u, v;
    double extent = 0;
    int i;
    if (fabs(z.x) < 0.6)
        a.x = 1; /* any axis well away from the normal */
    else
        a.y = 1;
    u = vsub(a, vscale(z, vdot(a, z)));
    u = vscale(u, 1.0 / sqrt(vdot(u, u)));
    v = vcross(z, u);
    for (i = 0; i < n; i++) {
        obj_vec3 d = vsub(sc->verts[ix[i]], sc->verts[ix[0]]);
        xy[2 * i] = vdot(d, u);
        xy[2 * i + 1] = vdot(d, v);
        extent = fmax(extent, fmax(fabs(xy[2 * i]), fabs(xy[2 * i + 1])));
    }
    return extent;
}

int obj_triangulate(const obj_scene *sc, const obj_face *f, int *out)
{
    const int *ix = sc->indices + f->first;
    int n = f->count, tris = 0, remaining, cur = 0, i, *next, *prev;
    obj_vec3 normal;
    double *xy, eps;
    if (n > OBJ_MAX_FACE_VERTICES) return OBJ_TOO_MANY_VERTICES;
    if (n < 3) return -1;
    normal = obj_face_normal(sc, f);
    if (!(vdot(normal, normal) > 0)) return -1;
    xy = malloc((size_t)n * 2 * sizeof *xy);
    next = malloc((size_t)n * 2 * sizeof *next);
    if (!xy || !next) {
        free(xy);
        free(next);
        return -1;
    }
    prev = next + n;
    eps = project(sc, ix, n, normal, xy);
    eps = eps * eps * 1e-12; /* cross products below this are rounding noise */
    for (i = 0; i < n; i++) {
        next[i] = (i + 1) % n;
        prev[i] = (i + n - 1) % n;
    }
    for (remaining = n; remaining > 3; remaining--) {
        int e = pick_ear(xy, next, prev, cur, remaining, eps);
        out[3 * tris] = ix[prev[e]];
        out[3 * tris + 1] = ix[e];
        out[3 * tris + 2] = ix[next[e]];
        tris++;
        next[prev[e]] = next[e];
        prev[next[e]] = prev[e];
        cur = next[e];
    }
    out[3 * tris] = ix[prev[cur]];
    out[3 * tris + 1] = ix[cur];
    out[3 * tris + 2] = ix[next[cur]];
    free(xy);
    free(next);
    return tris + 1;
}
