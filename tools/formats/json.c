/* SPDX-License-Identifier: MIT */
/* json — a strict JSON reader (RFC 8259). See json.h.
 *
 * Recursive descent, one value a call, depth bounded by JSON_MAX_DEPTH. A container's
 * values are parsed one at a time into a growing stack shared by all levels (an inner
 * container's values sit above the outer's and leave before the outer's next value),
 * then copied into an array of their own when the container closes. Everything the
 * tree holds is a block of one list (DOC->blocks), freed at once. Duplicate names are
 * found by sorting an object's members by name (then place): n log n, so that an
 * object of a million members does not take a million squared comparisons.
 */
#include "formats/json.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A block of the tree's memory: this header, then the caller's bytes (aligned as any
 * of these types). */
typedef union block {
    union block *next;
    double d;
    long long ll;
    void *p;
} block_t;

typedef struct {
    json_doc *doc;
    const unsigned char *t;
    size_t n, p;
    json_value *stack; /* values of the open containers */
    size_t top, cap;
    int depth;
    char *err;
    size_t errlen;
    int failed;
} parser_t;

/* ---- positions and errors ---------------------------------------------------------- */

static void where(const char *text, size_t at, int *line, int *col)
{
    size_t i;
    *line = 1;
    *col = 1;
    for (i = 0; i < at; i++) {
        const unsigned char c = (unsigned char)text[i];
        if (c == '\n') {
            ++*line;
            *col = 1;
        } else if ((c & 0xC0u) != 0x80u) { /* not a UTF-8 continuation byte */
            ++*col;
        }
    }
}

static void verror(const json_doc *doc, size_t at, char *err, size_t errlen, const char *fmt,
                   va_list ap)
{
    int line, col, k;
    if (!err || errlen == 0) return;
    where(doc->text, at < doc->size ? at : doc->size, &line, &col);
    k = snprintf(err, errlen, "%s:%d:%d: ", doc->name, line, col);
    if (k >= 0 && (size_t)k < errlen) vsnprintf(err + k, errlen - (size_t)k, fmt, ap);
}

void json_error(const json_doc *doc, size_t at, char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    verror(doc, at, err, errlen, fmt, ap);
    va_end(ap);
}

/* The first failure is the one said; later calls keep it. Returns 0 for "return fail(...)". */
static int fail(parser_t *ps, size_t at, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static int fail(parser_t *ps, size_t at, const char *fmt, ...)
{
    va_list ap;
    if (ps->failed) return 0;
    ps->failed = 1;
    va_start(ap, fmt);
    verror(ps->doc, at, ps->err, ps->errlen, fmt, ap);
    va_end(ap);
    return 0;
}

/* "L:C" of offset AT, for "opened at" notes. */
static void at_text(const parser_t *ps, size_t at, char *buf, size_t len)
{
    int line, col;
    where(ps->doc->text, at, &line, &col);
    snprintf(buf, len, "%d:%d", line, col);
}

/* What stands at the parser's place, for "expected X, found Y". */
static void found(const parser_t *ps, char *buf, size_t len)
{
    if (ps->p >= ps->n)
        snprintf(buf, len, "the end of the file");
    else if (ps->t[ps->p] >= 0x21 && ps->t[ps->p] < 0x7F)
        snprintf(buf, len, "'%c'", ps->t[ps->p]);
    else
        snprintf(buf, len, "the byte 0x%02X", ps->t[ps->p]);
}

/* ---- memory ------------------------------------------------------------------------ */

static void *take(parser_t *ps, size_t size)
{
    block_t *b = size < ((size_t)-1) / 2 ? malloc(sizeof *b + size) : NULL;
    if (!b) {
        fail(ps, ps->p, "out of memory");
        return NULL;
    }
    b->next = ps->doc->blocks;
    ps->doc->blocks = b;
    return b + 1;
}

static int push(parser_t *ps, const json_value *v)
{
    if (ps->top == ps->cap) {
        size_t cap = ps->cap ? 2 * ps->cap : 64;
        json_value *s = cap < ((size_t)-1) / sizeof *s ? realloc(ps->stack, cap * sizeof *s) : NULL;
        if (!s) return fail(ps, v->at, "out of memory");
        ps->stack = s;
        ps->cap = cap;
    }
    ps->stack[ps->top++] = *v;
    return 1;
}

/* The values above BASE into V's own array, popped. */
static int pop_into(parser_t *ps, size_t base, json_value *v)
{
    v->n = ps->top - base;
    v->items = NULL;
    if (v->n) {
        v->items = take(ps, v->n * sizeof *v->items);
        if (!v->items) return 0;
        memcpy(v->items, ps->stack + base, v->n * sizeof *v->items);
    }
    ps->top = base;
    return 1;
}

/* ---- the grammar ------------------------------------------------------------------- */

static void skip_ws(parser_t *ps)
{
    while (ps->p < ps->n && (ps->t[ps->p] == ' ' || ps->t[ps->p] == '\t' || ps->t[ps->p] == '\n' ||
                             ps->t[ps->p] == '\r'))
        ps->p++;
}

/* The length of the well-formed UTF-8 sequence at S (AVAIL bytes there), 0 if none
 * (Unicode's table 3-7: no overlong forms, no surrogates, nothing above U+10FFFF). */
static size_t utf8_len(const unsigned char *s, size_t avail)
{
    unsigned char lo = 0x80, hi = 0xBF;
    size_t len, i;
    if (s[0] < 0x80) return 1;
    if (s[0] >= 0xC2 && s[0] <= 0xDF)
        len = 2;
    else if (s[0] >= 0xE0 && s[0] <= 0xEF)
        len = 3;
    else if (s[0] >= 0xF0 && s[0] <= 0xF4)
        len = 4;
    else
        return 0;
    if (s[0] == 0xE0) lo = 0xA0;
    if (s[0] == 0xED) hi = 0x9F;
    if (s[0] == 0xF0) lo = 0x90;
    if (s[0] == 0xF4) hi = 0x8F;
    if (avail < len) return 0;
    for (i = 1; i < len; i++, lo = 0x80, hi = 0xBF)
        if (s[i] < lo || s[i] > hi) return 0;
    return len;
}

static int hex4(const unsigned char *s, unsigned long *v)
{
    int i;
    *v = 0;
    for (i = 0; i < 4; i++) {
        unsigned d;
        if (s[i] >= '0' && s[i] <= '9')
            d = (unsigned)(s[i] - '0');
        else if (s[i] >= 'a' && s[i] <= 'f')
            d = (unsigned)(s[i] - 'a' + 10);
        else if (s[i] >= 'A' && s[i] <= 'F')
            d = (unsigned)(s[i] - 'A' + 10);
        else
            return 0;
        *v = *v * 16u + d;
    }
    return 1;
}

static size_t put_utf8(unsigned char *o, unsigned long c)
{
    if (c < 0x80) {
        o[0] = (unsigned char)c;
        return 1;
    }
    if (c < 0x800) {
        o[0] = (unsigned char)(0xC0 | (c >> 6));
        o[1] = (unsigned char)(0x80 | (c & 0x3F));
        return 2;
    }
    if (c < 0x10000) {
        o[0] = (unsigned char)(0xE0 | (c >> 12));
        o[1] = (unsigned char)(0x80 | ((c >> 6) & 0x3F));
        o[2] = (unsigned char)(0x80 | (c & 0x3F));
        return 3;
    }
    o[0] = (unsigned char)(0xF0 | (c >> 18));
    o[1] = (unsigned char)(0x80 | ((c >> 12) & 0x3F));
    o[2] = (unsigned char)(0x80 | ((c >> 6) & 0x3F));
    o[3] = (unsigned char)(0x80 | (c & 0x3F));
    return 4;
}

/* The \u escape at the parser's place (after "\u"): one code point, a surrogate pair
 * joined, into *C. */
static int unicode_escape(parser_t *ps, size_t esc, unsigned long *c)
{
    unsigned long lo;
    if (ps->n - ps->p < 4 || !hex4(ps->t + ps->p, c))
        return fail(ps, esc, "a \\u escape wants four hexadecimal digits");
    ps->p += 4;
    if (*c >= 0xDC00 && *c <= 0xDFFF) return fail(ps, esc, "a lone low surrogate \\u%04lX", *c);
    if (*c >= 0xD800 && *c <= 0xDBFF) {
        if (ps->n - ps->p < 6 || ps->t[ps->p] != '\\' || ps->t[ps->p + 1] != 'u' ||
            !hex4(ps->t + ps->p + 2, &lo) || lo < 0xDC00 || lo > 0xDFFF)
            return fail(ps, esc,
                        "a high surrogate \\u%04lX without a low one (\\uDC00..\\uDFFF) after it",
                        *c);
        ps->p += 6;
        *c = 0x10000 + ((*c - 0xD800) << 10) + (lo - 0xDC00);
    }
    if (*c == 0) return fail(ps, esc, "\\u0000 (NUL) in a string is not accepted");
    return 1;
}

/* The string at the parser's place (its opening quote), decoded into *S (LEN bytes). */
static int string(parser_t *ps, const char **s, size_t *len)
{
    const size_t open = ps->p;
    size_t end = ps->p + 1, k = 0;
    unsigned char *o;
    char at[32];
    while (end < ps->n && ps->t[end] != '"') end += ps->t[end] == '\\' ? 2 : 1;
    if (end >= ps->n) {
        at_text(ps, open, at, sizeof at);
        return fail(ps, ps->n, "unexpected end of the file: the string opened at %s is not closed",
                    at);
    }
    o = take(ps, end - open);
    if (!o) return 0;
    for (ps->p = open + 1; ps->p < end;) {
        const unsigned char c = ps->t[ps->p];
        if (c < 0x20)
            return fail(ps, ps->p,
                        "a control character (U+%04X) in a string: write it as an escape", c);
        if (c == '\\') {
            const size_t esc = ps->p;
            static const char from[] = "\"\\/bfnrt", to[] = "\"\\/\b\f\n\r\t";
            const char *e = ps->t[ps->p + 1] ? strchr(from, ps->t[ps->p + 1]) : NULL;
            ps->p += 2;
            if (e) {
                o[k++] = (unsigned char)to[e - from];
            } else if (ps->t[esc + 1] == 'u') {
                unsigned long cp;
                if (!unicode_escape(ps, esc, &cp)) return 0;
                k += put_utf8(o + k, cp);
            } else if (ps->t[esc + 1] >= 0x21 && ps->t[esc + 1] < 0x7F) {
                return fail(ps, esc,
                            "an unknown escape \\%c (\\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX)",
                            ps->t[esc + 1]);
            } else {
                return fail(ps, esc,
                            "an unknown escape (\\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX)");
            }
        } else {
            size_t u = utf8_len(ps->t + ps->p, end - ps->p);
            if (!u) return fail(ps, ps->p, "not UTF-8: the byte 0x%02X", c);
            memcpy(o + k, ps->t + ps->p, u);
            k += u;
            ps->p += u;
        }
    }
    o[k] = '\0';
    ps->p = end + 1;
    *s = (const char *)o;
    *len = k;
    return 1;
}

static int digits(parser_t *ps)
{
    size_t p0 = ps->p;
    while (ps->p < ps->n && ps->t[ps->p] >= '0' && ps->t[ps->p] <= '9') ps->p++;
    return ps->p > p0;
}

/* -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)? at the parser's place, into V. */
static int number(parser_t *ps, json_value *v)
{
    const size_t p0 = ps->p;
    char buf[JSON_MAX_NUMBER + 1];
    if (ps->t[ps->p] == '-') ps->p++;
    if (ps->p < ps->n && ps->t[ps->p] == '0') {
        ps->p++;
        if (ps->p < ps->n && ps->t[ps->p] >= '0' && ps->t[ps->p] <= '9')
            return fail(ps, p0, "a number with a leading zero");
    } else if (!digits(ps)) {
        return fail(ps, p0, "a number wants a digit after its '-'");
    }
    if (ps->p < ps->n && ps->t[ps->p] == '.') {
        ps->p++;
        if (!digits(ps)) return fail(ps, p0, "a number wants a digit after its '.'");
    }
    if (ps->p < ps->n && (ps->t[ps->p] == 'e' || ps->t[ps->p] == 'E')) {
        ps->p++;
        if (ps->p < ps->n && (ps->t[ps->p] == '+' || ps->t[ps->p] == '-')) ps->p++;
        if (!digits(ps)) return fail(ps, p0, "a number wants a digit in its exponent");
    }
    if (ps->p - p0 > JSON_MAX_NUMBER)
        return fail(ps, p0, "a number longer than %d characters", JSON_MAX_NUMBER);
    memcpy(buf, ps->t + p0, ps->p - p0);
    buf[ps->p - p0] = '\0';
    errno = 0;
    v->number = strtod(buf, NULL);
    if (!isfinite(v->number)) return fail(ps, p0, "a number beyond a double's range (1.8e308)");
    v->type = JSON_NUMBER;
    return 1;
}

static int literal(parser_t *ps, json_value *v)
{
    static const struct {
        const char *word;
        json_type type;
    } words[3] = {{"true", JSON_TRUE}, {"false", JSON_FALSE}, {"null", JSON_NULL}};
    char what[32];
    int i;
    for (i = 0; i < 3; i++) {
        size_t len = strlen(words[i].word);
        if (ps->n - ps->p >= len && memcmp(ps->t + ps->p, words[i].word, len) == 0) {
            ps->p += len;
            v->type = words[i].type;
            return 1;
        }
    }
    found(ps, what, sizeof what);
    return fail(ps, ps->p,
                "expected a value (a number, a string, true, false, null, [ or {), found %s", what);
}

static int value(parser_t *ps, json_value *v);

/* The end of a container's value: ',' (1, another follows), CLOSE (0) or an error (-1). */
static int next_or_close(parser_t *ps, char close, const char *what, size_t open)
{
    char at[32], seen[32];
    skip_ws(ps);
    if (ps->p < ps->n && ps->t[ps->p] == ',') {
        ps->p++;
        skip_ws(ps);
        if (ps->p < ps->n && ps->t[ps->p] == close)
            return fail(ps, ps->p - 1, "a ',' before '%c' (no value follows it)", close) - 1;
        return 1;
    }
    if (ps->p < ps->n && ps->t[ps->p] == close) {
        ps->p++;
        return 0;
    }
    at_text(ps, open, at, sizeof at);
    found(ps, seen, sizeof seen);
    return fail(ps, ps->p, "expected ',' or '%c' in the %s opened at %s, found %s", close, what, at,
                seen) -
           1;
}

/* Past a container's opening bracket: 0 when CLOSE follows at once (taken), else 1. */
static int opens(parser_t *ps, char close)
{
    ps->p++;
    skip_ws(ps);
    if (ps->p < ps->n && ps->t[ps->p] == close) {
        ps->p++;
        return 0;
    }
    return 1;
}

static int array(parser_t *ps, json_value *v)
{
    const size_t open = ps->p, base = ps->top;
    int more = opens(ps, ']');
    v->type = JSON_ARRAY;
    while (more > 0) {
        json_value item;
        if (!value(ps, &item) || !push(ps, &item)) return 0;
        more = next_or_close(ps, ']', "array", open);
    }
    return more == 0 && pop_into(ps, base, v);
}

static int by_name(const void *a, const void *b)
{
    const json_value *x = *(const json_value *const *)a, *y = *(const json_value *const *)b;
    int c = strcmp(x->key, y->key);
    return c ? c : x->key_at < y->key_at ? -1 : 1;
}

/* A name given twice in object V: the second said, with where the first is. */
static int unique_names(parser_t *ps, const json_value *v)
{
    const json_value **order;
    size_t i;
    int ok = 1;
    if (v->n < 2) return 1;
    order = malloc(v->n * sizeof *order);
    if (!order) return fail(ps, v->at, "out of memory");
    for (i = 0; i < v->n; i++) order[i] = &v->items[i];
    qsort(order, v->n, sizeof *order, by_name);
    for (i = 1; i < v->n && ok; i++)
        if (strcmp(order[i - 1]->key, order[i]->key) == 0) {
            char at[32], name[72];
            at_text(ps, order[i - 1]->key_at, at, sizeof at);
            ok = fail(ps, order[i]->key_at,
                      "the name \"%s\" given twice in one object (first at %s)",
                      json_quote(order[i]->key, name, sizeof name), at);
        }
    free(order);
    return ok;
}

static int object(parser_t *ps, json_value *v)
{
    const size_t open = ps->p, base = ps->top;
    int more = opens(ps, '}');
    v->type = JSON_OBJECT;
    while (more > 0) {
        json_value m;
        const char *key;
        size_t klen, kat = ps->p;
        char seen[32], name[72];
        if (ps->p >= ps->n || ps->t[ps->p] != '"') {
            found(ps, seen, sizeof seen);
            return fail(ps, ps->p, "expected a member's name in double quotes, found %s", seen);
        }
        if (!string(ps, &key, &klen)) return 0;
        skip_ws(ps);
        if (ps->p >= ps->n || ps->t[ps->p] != ':') {
            found(ps, seen, sizeof seen);
            return fail(ps, ps->p, "expected ':' after the name \"%s\", found %s",
                        json_quote(key, name, sizeof name), seen);
        }
        ps->p++;
        if (!value(ps, &m)) return 0;
        m.key = key;
        m.key_at = kat;
        if (!push(ps, &m)) return 0;
        more = next_or_close(ps, '}', "object", open);
    }
    return more == 0 && pop_into(ps, base, v) && unique_names(ps, v);
}

static int value(parser_t *ps, json_value *v)
{
    int ok;
    memset(v, 0, sizeof *v);
    skip_ws(ps);
    v->at = ps->p;
    if (ps->p >= ps->n) return fail(ps, ps->p, "unexpected end of the file: a value is missing");
    switch (ps->t[ps->p]) {
    case '[':
    case '{':
        if (ps->depth >= JSON_MAX_DEPTH)
            return fail(ps, ps->p, "arrays and objects nested more than %d deep", JSON_MAX_DEPTH);
        ps->depth++;
        ok = ps->t[ps->p] == '[' ? array(ps, v) : object(ps, v);
        ps->depth--;
        return ok;
    case '"': v->type = JSON_STRING; return string(ps, &v->string, &v->len);
    case '-':
    case '0':
    case '1':
    case '2':
    case '3':
    case '4':
    case '5':
    case '6':
    case '7':
    case '8':
    case '9': return number(ps, v);
    default: return literal(ps, v);
    }
}

int json_parse(json_doc *doc, const char *name, const char *text, size_t size, char *err,
               size_t errlen)
{
    parser_t ps;
    memset(doc, 0, sizeof *doc);
    doc->name = name;
    doc->text = text;
    doc->size = size;
    memset(&ps, 0, sizeof ps);
    ps.doc = doc;
    ps.t = (const unsigned char *)text;
    ps.n = size;
    ps.err = err;
    ps.errlen = errlen;
    if (size >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) ps.p = 3; /* a byte order mark */
    skip_ws(&ps);
    if (ps.p >= ps.n)
        fail(&ps, ps.p, "no JSON value: the file is empty");
    else if (value(&ps, &doc->root)) {
        skip_ws(&ps);
        if (ps.p < ps.n) {
            char seen[32];
            found(&ps, seen, sizeof seen);
            fail(&ps, ps.p, "%s after the JSON value (a file holds one value)", seen);
        }
    }
    free(ps.stack);
    if (ps.failed) {
        json_free(doc);
        return -1;
    }
    return 0;
}

void json_free(json_doc *doc)
{
    block_t *b;
    if (!doc) return;
    b = doc->blocks;
    while (b) {
        block_t *next = b->next;
        free(b);
        b = next;
    }
    memset(doc, 0, sizeof *doc);
}

const json_value *json_member(const json_value *obj, const char *key)
{
    size_t i;
    if (!obj || obj->type != JSON_OBJECT) return NULL;
    for (i = 0; i < obj->n; i++)
        if (strcmp(obj->items[i].key, key) == 0) return &obj->items[i];
    return NULL;
}

const char *json_quote(const char *s, char *buf, size_t len)
{
    size_t k = 0;
    const size_t room = len > 8 ? len - 8 : 0; /* for an escape, "..." and the NUL */
    if (len == 0) return buf;
    while (*s && k < room) {
        const unsigned char c = (unsigned char)*s;
        size_t n = c < 0x80 ? 1 : c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : 2;
        if (c < 0x20 || c == 0x7F || c == '"' || c == '\\') {
            k += (size_t)(c == '"' || c == '\\' ? snprintf(buf + k, len - k, "\\%c", c)
                                                : snprintf(buf + k, len - k, "\\u%04X", c));
            s++;
            continue;
        }
        if (k + n > room) break;
        memcpy(buf + k, s, n); /* the reader's strings are whole UTF-8 sequences */
        k += n;
        s += n;
    }
    if (*s && k + 4 <= len) {
        memcpy(buf + k, "...", 3);
        k += 3;
    }
    buf[k < len ? k : len - 1] = '\0';
    return buf;
}

const char *json_type_name(json_type type)
{
    switch (type) {
    case JSON_NULL: return "null";
    case JSON_FALSE: return "false";
    case JSON_TRUE: return "true";
    case JSON_NUMBER: return "a number";
    case JSON_STRING: return "a string";
    case JSON_ARRAY: return "an array";
    default: return "an object";
    }
}
