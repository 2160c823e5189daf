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

#define MAX_VALUE 1e30   /* coordinates beyond this are broken geometry, not a scene */
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
    const char *basedir;  /* for mtllib; NULL: mtllib is ignored with a warning */
    const char *file;     /* file being parsed, for messages */
    long line;            /* first physical line of the current statement */
    int cur;              /* OBJ: material of the next faces; MTL: the one being defined */
    size_t cap_verts, cap_indices, cap_faces, cap_mats;
} parser;

typedef int (*statement_fn)(parser *p, const char *kw, char *rest);

/* ---- messages ------------------------------------------------------------------ */

static void put_msg(char *out, size_t outlen, const char *fmt, ...) PRINTF_LIKE(3, 4);
static void put_msg(char *out, size_t outlen, const char *fmt, ...)
{
    va_list ap;
    if (!out || !outlen)
        return;
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
    if (p->err && p->errlen)
        located(p, p->err, p->errlen, fmt, ap);
    va_end(ap);
    return -1;
}

static void warn(parser *p, const char *fmt, ...) PRINTF_LIKE(2, 3);
static void warn(parser *p, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    p->sc->nwarnings++;
    if (!p->warn)
        return;
    va_start(ap, fmt);
    located(p, msg, sizeof msg, fmt, ap);
    va_end(ap);
    p->warn(p->ctx, msg);
}

static int line_int(const parser *p)
{
    return p->line > INT_MAX ? INT_MAX : (int)p->line;
}

/* ---- growing arrays ------------------------------------------------------------ */

/* Returns a block with room for need elements: p itself if it is big enough, else a
   doubled reallocation; NULL on failure (p is then still valid and owned by the caller). */
static void *reserve(void *p, size_t *cap, size_t need, size_t elem)
{
    size_t n = *cap ? *cap : 16;
    void *q;
    if (need <= *cap)
        return p;
    while (n < need) {
        if (n > SIZE_MAX / 2 / elem)
            return NULL;
        n *= 2;
    }
    q = realloc(p, n * elem);
    if (q)
        *cap = n;
    return q;
}

static int push_vert(parser *p, obj_vec3 v)
{
    obj_scene *sc = p->sc;
    obj_vec3 *q;
    if (sc->nverts == INT_MAX)
        return fail(p, "too many vertices");
    q = reserve(sc->verts, &p->cap_verts, (size_t)sc->nverts + 1, sizeof *q);
    if (!q)
        return fail(p, "out of memory");
    sc->verts = q;
    sc->verts[sc->nverts++] = v;
    return 0;
}

static int push_index(parser *p, int i)
{
    obj_scene *sc = p->sc;
    int *q;
    if (sc->nindices == INT_MAX)
        return fail(p, "too many face vertices");
    q = reserve(sc->indices, &p->cap_indices, (size_t)sc->nindices + 1, sizeof *q);
    if (!q)
        return fail(p, "out of memory");
    sc->indices = q;
    sc->indices[sc->nindices++] = i;
    return 0;
}

static int push_face(parser *p, int first, int count)
{
    obj_scene *sc = p->sc;
    obj_face *q;
    if (sc->nfaces == INT_MAX)
        return fail(p, "too many faces");
    q = reserve(sc->faces, &p->cap_faces, (size_t)sc->nfaces + 1, sizeof *q);
    if (!q)
        return fail(p, "out of memory");
    sc->faces = q;
    q += sc->nfaces++;
    q->material = p->cur;
    q->first = first;
    q->count = count;
    q->line = line_int(p);
    return 0;
}

static void material_defaults(obj_material *m)
{
    int i;
    for (i = 0; i < 3; i++) {
        m->kd[i] = DEFAULT_KD;
        m->ke[i] = 0.0;
    }
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
    if ((size_t)sc->nmaterials + 1 <= n / 2 && sc->mat_index)
        return 0;
    while ((size_t)sc->nmaterials + 1 > n / 2)
        n *= 2;
    if (!(t = malloc(n * sizeof *t)))
        return -1;
    for (i = 0; i < n; i++)
        t[i] = -1;
    free(sc->mat_index);
    sc->mat_index = t;
    sc->mat_slots = n;
    for (i = 0; i < (size_t)sc->nmaterials; i++)
        t[name_slot(sc, sc->materials[i].name)] = (int)i;
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
    if (m >= 0)
        return m;
    if (sc->nmaterials == INT_MAX)
        return fail(p, "too many materials");
    q = reserve(sc->materials, &p->cap_mats, (size_t)sc->nmaterials + 1, sizeof *q);
    if (!q)
        return fail(p, "out of memory");
    sc->materials = q; /* before grow_names, which reads the names */
    if (grow_names(sc) != 0)
        return fail(p, "out of memory");
    copy = malloc(len + 1);
    if (!copy)
        return fail(p, "out of memory");
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
    while (is_space((unsigned char)*c))
        c++;
    if (!*c)
        return NULL;
    start = c;
    while (*c && !is_space((unsigned char)*c))
        c++;
    if (*c)
        *c++ = '\0';
    *s = c;
    return start;
}

static char *trim(char *s)
{
    size_t n;
    while (is_space((unsigned char)*s))
        s++;
    n = strlen(s);
    while (n > 0 && is_space((unsigned char)s[n - 1]))
        n--;
    s[n] = '\0';
    return s;
}

static int is_one_of(const char *kw, const char *const *list)
{
    for (; *list; list++)
        if (!strcmp(kw, *list))
            return 1;
    return 0;
}

/* Plain decimals only: strtod alone would also take "nan", "inf", "infinity" and hex. */
static int is_decimal(const char *s)
{
    int digits = 0;
    if (*s == '+' || *s == '-')
        s++;
    for (; is_digit((unsigned char)*s); s++)
        digits++;
    if (*s == '.')
        for (s++; is_digit((unsigned char)*s); s++)
            digits++;
    if (!digits)
        return 0;
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-')
            s++;
        if (!is_digit((unsigned char)*s))
            return 0;
        while (is_digit((unsigned char)*s))
            s++;
    }
    return *s == '\0';
}

static int parse_number(parser *p, const char *tok, double *out)
{
    char *end;
    double v;
    if (!is_decimal(tok))
        return fail(p, "bad number '%.40s'", tok);
    v = strtod(tok, &end);
    if (*end != '\0')
        return fail(p, "bad number '%.40s'", tok);
    if (!(fabs(v) <= MAX_VALUE))
        return fail(p, "number out of range '%.40s' (limit 1e30)", tok);
    *out = v;
    return 0;
}

/* Reads [+-]digits at *s, saturating past INT_MAX (out of range anyway); -1 if none. */
static int read_int(const char **s, long long *v)
{
    const char *c = *s;
    long long x = 0;
    int neg = 0;
    if (*c == '+' || *c == '-')
        neg = *c++ == '-';
    if (!is_digit((unsigned char)*c))
        return -1;
    for (; is_digit((unsigned char)*c); c++)
        if (x <= INT_MAX)
            x = x * 10 + (*c - '0');
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
    while (n < rem && s[n] != '\n' && s[n] != '\r')
        n++;
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
        while (n > 0 && is_space((unsigned char)s[n - 1]))
            n--;
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

/* ---- MTL ----------------------------------------------------------------------- */

static int parse_newmtl(parser *p, char *rest)
{
    const char *name = trim(rest);
    obj_material *m;
    int i;
    if (!*name)
        return fail(p, "newmtl without a material name");
    if ((i = intern_material(p, name)) < 0)
        return -1;
    m = &p->sc->materials[i];
    if (m->defined)
        warn(p, "material '%.200s' defined again; the new definition wins", name);
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
        if (n == 3)
            return fail(p, "%s takes 1 or 3 values, got more", kw);
        if (parse_number(p, tok, &c[n]))
            return -1;
        if (c[n] < 0)
            return fail(p, "negative %s value '%.40s'", kw, tok);
        n++;
    }
    if (n != 1 && n != 3)
        return fail(p, "%s takes 1 or 3 values, got %d", kw, n);
    if (n == 1)
        c[1] = c[2] = c[0];
    memcpy(dst, c, sizeof c);
    return 0;
}

/* Valid MTL that says nothing about diffuse reflection or emission. */
static const char *const mtl_ignored[] = {
    "Ka", "Ks", "Ns", "Ni", "d", "Tr", "Tf", "illum", "sharpness", "bump", "disp", "decal",
    "refl", "norm", "Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor", NULL
};

static int mtl_statement(parser *p, const char *kw, char *rest)
{
    int colour = !strcmp(kw, "Kd") ? 1 : !strcmp(kw, "Ke") ? 2 : 0;
    if (!strcmp(kw, "newmtl"))
        return parse_newmtl(p, rest);
    if (colour) {
        obj_material *m;
        if (p->cur < 0)
            return fail(p, "%s before any newmtl", kw);
        m = &p->sc->materials[p->cur];
        return parse_colour(p, kw, rest, colour == 1 ? m->kd : m->ke);
    }
    if (!strncmp(kw, "map_", 4) || is_one_of(kw, mtl_ignored))
        return 0;
    p->sc->unknown_statements++;
    return 0;
}

static char *join_path(const char *dir, const char *name)
{
    size_t dl = name[0] == '/' ? 0 : strlen(dir), nl = strlen(name);
    int sep = dl > 0 && dir[dl - 1] != '/';
    char *s = malloc(dl + (size_t)sep + nl + 1);
    if (!s)
        return NULL;
    memcpy(s, dir, dl);
    if (sep)
        s[dl] = '/';
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
    if (fio_read_all(path, FIO_LIMIT_MTL, text, len, msg, sizeof msg) == 0)
        return 0;
    if (!strncmp(msg, path, pl) && !strncmp(msg + pl, ": ", 2))
        why = msg + pl + 2; /* fio's "PATH: " prefix: the warning names the library */
    if (!strncmp(why, "cannot open: ", 13))
        warn(p, "cannot open material library '%.200s': %s", name, why + 13);
    else
        warn(p, "cannot read material library '%.200s': %s", name, why);
    return 1;
}

/* Parses the library NAME, relative to the OBJ's folder; messages name it by path. */
static int load_mtl(parser *p, const char *name)
{
    const char *file = p->file;
    long line = p->line;
    int cur = p->cur, rc;
    char *text, *path = join_path(p->basedir, name);
    size_t len;
    if (!path)
        return fail(p, "out of memory");
    if (read_mtl_text(p, name, path, &text, &len)) {
        free(path);
        return 0;
    }
    p->file = path;
    p->cur = -1;
    rc = each_statement(p, text, len, mtl_statement);
    free(text);
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

static int parse_vertex(parser *p, char *rest)
{
    obj_vec3 v;
    double c[3];
    char *tok;
    int n = 0;
    /* Extra values (w, or the r g b some exporters add) must be numbers but are ignored. */
    while ((tok = next_token(&rest)) != NULL) {
        double x;
        if (parse_number(p, tok, &x))
            return -1;
        if (n < 3)
            c[n] = x;
        n++;
    }
    if (n < 3)
        return fail(p, "vertex needs 3 coordinates, got %d", n);
    v.x = c[0];
    v.y = c[1];
    v.z = c[2];
    return push_vert(p, v);
}

/* One face vertex: v, v/vt, v//vn or v/vt/vn; resolves v to a 0-based index. */
static int parse_face_vertex(parser *p, const char *tok, int *out)
{
    const char *c = tok;
    long long v, unused;
    int n = p->sc->nverts, vlen;
    if (read_int(&c, &v))
        goto bad;
    vlen = (int)(c - tok);
    if (*c == '/') {
        c++;
        if (*c != '/' && read_int(&c, &unused))
            goto bad;
        if (*c == '/') {
            c++;
            if (read_int(&c, &unused))
                goto bad;
        }
    }
    if (*c)
        goto bad;
    if (v == 0)
        return fail(p, "vertex index 0 (OBJ indices start at 1)");
    if (v > n || v < -(long long)n)
        return fail(p, "vertex index %.*s out of range (%d vertices defined so far)",
                    vlen > 40 ? 40 : vlen, tok, n);
    *out = (int)(v > 0 ? v - 1 : n + v);
    return 0;
bad:
    return fail(p, "bad face vertex '%.40s'", tok);
}

static int parse_face(parser *p, char *rest)
{
    int first = p->sc->nindices, count = 0, i = 0;
    char *tok;
    while ((tok = next_token(&rest)) != NULL) {
        if (parse_face_vertex(p, tok, &i) || push_index(p, i))
            return -1;
        count++;
    }
    if (count < 3)
        return fail(p, "face needs at least 3 vertices, got %d", count);
    if (p->cur < 0 && (p->cur = intern_material(p, OBJ_DEFAULT_MATERIAL)) < 0)
        return -1;
    return push_face(p, first, count);
}

static int parse_usemtl(parser *p, char *rest)
{
    const char *name = trim(rest);
    int m;
    if (!*name)
        return fail(p, "usemtl without a material name");
    if ((m = intern_material(p, name)) < 0)
        return -1;
    if (!p->sc->materials[m].use_line)
        p->sc->materials[m].use_line = line_int(p);
    p->cur = m;
    return 0;
}

/* Several names, unless the whole rest of the line names one file (with spaces). */
static int parse_mtllib(parser *p, char *rest)
{
    char *names = trim(rest), *tok;
    if (!*names)
        return fail(p, "mtllib without a file name");
    if (!p->basedir) {
        warn(p, "mtllib '%.200s' ignored: no directory to look in", names);
        return 0;
    }
    if (strpbrk(names, " \t\v\f\r") && mtl_exists(p, names))
        return load_mtl(p, names);
    while ((tok = next_token(&names)) != NULL)
        if (load_mtl(p, tok))
            return -1;
    return 0;
}

/* Valid OBJ that does not matter for radiosity. */
static const char *const obj_ignored[] = { "vt", "vn", "vp", "g", "o", "s", "l", "p", "mg", NULL };

static int obj_statement(parser *p, const char *kw, char *rest)
{
    if (!strcmp(kw, "v"))
        return parse_vertex(p, rest);
    if (!strcmp(kw, "f"))
        return parse_face(p, rest);
    if (!strcmp(kw, "usemtl"))
        return parse_usemtl(p, rest);
    if (!strcmp(kw, "mtllib"))
        return parse_mtllib(p, rest);
    if (!is_one_of(kw, obj_ignored))
        p->sc->unknown_statements++;
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
}

int obj_parse(const char *text, size_t len, const char *name, const char *basedir, obj_scene *sc,
              obj_warn_fn warn_fn, void *ctx, char *err, size_t errlen)
{
    parser p;
    memset(sc, 0, sizeof *sc);
    memset(&p, 0, sizeof p);
    p.sc = sc;
    p.warn = warn_fn;
    p.ctx = ctx;
    p.err = err;
    p.errlen = errlen;
    p.basedir = basedir;
    p.file = name ? name : "(memory)";
    p.cur = -1;
    put_msg(err, errlen, "%s", "");
    if (each_statement(&p, text, len, obj_statement)) {
        obj_free(sc);
        return -1;
    }
    finish(&p);
    return 0;
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
    char *text, *dir;
    size_t len;
    int rc;
    memset(sc, 0, sizeof *sc);
    if (fio_read_all(path, FIO_LIMIT_OBJ, &text, &len, err, errlen) != 0)
        return -1;
    dir = dir_of(path);
    if (!dir) {
        free(text);
        put_msg(err, errlen, "%s: out of memory", path);
        return -1;
    }
    rc = obj_parse(text, len, path, dir, sc, warn_fn, ctx, err, errlen);
    free(dir);
    free(text);
    return rc;
}

void obj_free(obj_scene *sc)
{
    int i;
    if (!sc)
        return;
    for (i = 0; i < sc->nmaterials; i++)
        free(sc->materials[i].name);
    free(sc->materials);
    free(sc->mat_index);
    free(sc->verts);
    free(sc->indices);
    free(sc->faces);
    memset(sc, 0, sizeof *sc);
}

int obj_find_material(const obj_scene *sc, const char *name)
{
    int i;
    if (sc->mat_index)
        return sc->mat_index[name_slot(sc, name)];
    for (i = 0; i < sc->nmaterials; i++) /* a scene made by hand, without the table */
        if (!strcmp(sc->materials[i].name, name))
            return i;
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
    obj_vec3 o = sc->verts[ix[0]], n = { 0, 0, 0 }, c;
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
        if (same_point(xy, j, a) || same_point(xy, j, b) || same_point(xy, j, c))
            continue;
        if (turn(xy, a, b, j) >= -eps && turn(xy, b, c, j) >= -eps && turn(xy, c, a, j) >= -eps)
            return 1;
    }
    return 0;
}

/* Picks the vertex to clip: an ear if there is one; else a vertex with no area (collinear
   or a spike), whose removal changes nothing; else the most convex vertex, so that broken
   (self-intersecting) polygons still get count-2 triangles. */
static int pick_ear(const double *xy, const int *next, const int *prev, int start,
                    int remaining, double eps)
{
    int i = start, k, flat = -1, best = start;
    double best_turn = -HUGE_VAL;
    for (k = 0; k < remaining; k++, i = next[i]) {
        double t = turn(xy, prev[i], i, next[i]);
        if (t > eps && !blocks_ear(xy, next, prev[i], i, next[i], eps))
            return i;
        if (flat < 0 && fabs(t) <= eps)
            flat = i;
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
    obj_vec3 z = vscale(normal, 1.0 / sqrt(vdot(normal, normal))), a = { 0, 0, 0 }, u, v;
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
    if (n > OBJ_MAX_FACE_VERTICES)
        return OBJ_TOO_MANY_VERTICES;
    if (n < 3)
        return -1;
    normal = obj_face_normal(sc, f);
    if (!(vdot(normal, normal) > 0))
        return -1;
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
