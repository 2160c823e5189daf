/* SPDX-License-Identifier: MIT */
/* libFuzzer harness: the strict JSON reader (tools/formats/json.c, rad_cli's --lights
 * files) on arbitrary bytes.
 *
 * Input: the file's bytes, whole.
 *
 * Checked: the reader never crashes, reads outside the buffer or leaks; on failure the
 * error is one line starting "lights.json:LINE:COL: " with LINE and COL inside the text
 * and the document is left empty; on success every value's offset lies inside the text,
 * numbers are finite, strings are well-formed UTF-8 of their stated length with no NUL,
 * an object's names are distinct, the nesting is at most JSON_MAX_DEPTH, and the tree
 * written back as JSON (numbers to 17 digits, strings escaped) parses again to the same
 * tree.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/json.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(c)                                                                              \
    do {                                                                                      \
        if (!(c)) {                                                                           \
            fprintf(stderr, "fuzz_json: check failed: %s (%s:%d)\n", #c, __FILE__, __LINE__); \
            abort();                                                                          \
        }                                                                                     \
    } while (0)

#define NAME "lights.json"

typedef struct {
    char *s;
    size_t n, cap;
} buf_t;

static void put(buf_t *b, const char *s, size_t n)
{
    if (b->n + n + 1 > b->cap) {
        b->cap = 2 * (b->n + n + 1);
        b->s = realloc(b->s, b->cap);
        CHECK(b->s);
    }
    memcpy(b->s + b->n, s, n);
    b->n += n;
    b->s[b->n] = '\0';
}

/* Well-formed UTF-8 (json.h's rules) of LEN bytes, no NUL. */
static int utf8_ok(const unsigned char *s, size_t len)
{
    size_t i = 0;
    while (i < len) {
        unsigned c = s[i], n, k, cp;
        if (c == 0) return 0;
        if (c < 0x80) {
            i++;
            continue;
        }
        n = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 0;
        if (n == 0 || i + n > len) return 0;
        cp = c & (0x7F >> n);
        for (k = 1; k < n; k++) {
            if ((s[i + k] & 0xC0) != 0x80) return 0;
            cp = (cp << 6) | (s[i + k] & 0x3F);
        }
        if ((n == 2 && cp < 0x80) || (n == 3 && cp < 0x800) || (n == 4 && cp < 0x10000) ||
            cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
            return 0;
        i += n;
    }
    return 1;
}

static void put_string(buf_t *b, const char *s)
{
    put(b, "\"", 1);
    for (; *s; s++) {
        char e[8];
        if (*s == '"' || *s == '\\') {
            e[0] = '\\';
            e[1] = *s;
            put(b, e, 2);
        } else if ((unsigned char)*s < 0x20) {
            snprintf(e, sizeof e, "\\u%04x", (unsigned char)*s);
            put(b, e, 6);
        } else {
            put(b, s, 1);
        }
    }
    put(b, "\"", 1);
}

/* V checked (inside a text of SIZE bytes, at DEPTH) and written to B. */
static void walk(const json_value *v, size_t size, int depth, buf_t *b)
{
    size_t i, j;
    char num[40];
    CHECK(v->at < size);
    CHECK(depth <= JSON_MAX_DEPTH);
    switch (v->type) {
    case JSON_NULL: put(b, "null", 4); break;
    case JSON_TRUE: put(b, "true", 4); break;
    case JSON_FALSE: put(b, "false", 5); break;
    case JSON_NUMBER:
        CHECK(isfinite(v->number));
        put(b, num, (size_t)snprintf(num, sizeof num, "%.17g", v->number));
        break;
    case JSON_STRING:
        CHECK(v->string && strlen(v->string) == v->len);
        CHECK(utf8_ok((const unsigned char *)v->string, v->len));
        put_string(b, v->string);
        break;
    case JSON_ARRAY:
    case JSON_OBJECT:
        CHECK(depth < JSON_MAX_DEPTH);
        CHECK(v->n == 0 || v->items);
        put(b, v->type == JSON_ARRAY ? "[" : "{", 1);
        for (i = 0; i < v->n; i++) {
            const json_value *x = &v->items[i];
            if (i) put(b, ",", 1);
            if (v->type == JSON_OBJECT) {
                CHECK(x->key && x->key_at < size &&
                      utf8_ok((const unsigned char *)x->key, strlen(x->key)));
                for (j = 0; j < i && v->n <= 64; j++) CHECK(strcmp(v->items[j].key, x->key) != 0);
                CHECK(json_member(v, x->key) != NULL);
                put_string(b, x->key);
                put(b, ":", 1);
            }
            walk(x, size, depth + 1, b);
        }
        put(b, v->type == JSON_ARRAY ? "]" : "}", 1);
        break;
    }
}

/* The same tree: types, numbers, strings, names and order. */
static void same(const json_value *a, const json_value *b)
{
    size_t i;
    CHECK(a->type == b->type);
    if (a->type == JSON_NUMBER) CHECK(a->number == b->number);
    if (a->type == JSON_STRING)
        CHECK(a->len == b->len && memcmp(a->string, b->string, a->len) == 0);
    if (a->type != JSON_ARRAY && a->type != JSON_OBJECT) return;
    CHECK(a->n == b->n);
    for (i = 0; i < a->n; i++) {
        if (a->type == JSON_OBJECT) CHECK(strcmp(a->items[i].key, b->items[i].key) == 0);
        same(&a->items[i], &b->items[i]);
    }
}

/* "lights.json:LINE:COL: ..." on one line, LINE and COL inside TEXT (SIZE bytes). */
static void check_error(const char *err, const char *text, size_t size)
{
    int line = 0, col = 0, k = 0;
    size_t lines = 1, i;
    for (i = 0; i < size; i++) lines += text[i] == '\n';
    CHECK(strncmp(err, NAME ":", sizeof NAME) == 0);
    CHECK(sscanf(err + sizeof NAME, "%d:%d: %n", &line, &col, &k) == 2 && k > 0);
    CHECK(line >= 1 && (size_t)line <= lines && col >= 1 && (size_t)col <= size + 1);
    CHECK(!strchr(err, '\n'));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1), err[512];
    json_doc doc, again;
    buf_t b = {NULL, 0, 0};
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    err[0] = '\0';
    if (json_parse(&doc, NAME, text, size, err, sizeof err) != 0) {
        check_error(err, text, size);
        CHECK(doc.blocks == NULL);
        free(text);
        return 0;
    }
    walk(&doc.root, size, 0, &b);
    CHECK(json_parse(&again, NAME, b.s, b.n, err, sizeof err) == 0);
    same(&doc.root, &again.root);
    json_free(&again);
    json_free(&doc);
    free(b.s);
    free(text);
    return 0;
}
