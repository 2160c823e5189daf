/* SPDX-License-Identifier: MIT */
/* json — a strict JSON reader (RFC 8259) into a tree: rad_cli's --lights file (uses
 * malloc and libc).
 *
 * Accepted: one value (any type) with whitespace (space, tab, LF, CR) around it; an
 * optional UTF-8 byte order mark before it. Refused, each with one error: anything after
 * the value; text that is not UTF-8 (overlong forms, surrogates, code points above
 * U+10FFFF); a control character (below U+0020) inside a string; escapes other than
 * \" \\ \/ \b \f \n \r \t \uXXXX; a \u surrogate that is not a high one followed by a
 * low one (the pair decoded to one code point); \u0000 (names and strings stay C
 * strings); numbers outside the grammar (leading zeros, a bare '-', '.5', '1.', '+1')
 * or beyond a double's range (underflow reads as the nearest double, 0 at worst); a
 * number of more than JSON_MAX_NUMBER characters (RFC 8259 section 9 lets a reader
 * limit them); nesting (arrays and objects inside each other) deeper than
 * JSON_MAX_DEPTH; a name given twice in one object. Numbers are read as doubles by
 * strtod (the C locale's '.'), so "0.1" in a file is the double that "0.1" on a command
 * line is.
 *
 * Errors are one line, "NAME:LINE:COL: what is wrong", LINE and COL from 1, COL
 * counting characters (code points) of the line; json_error gives a caller's own
 * complaints about a value (a wrong type, an unknown name) the same form.
 */
#ifndef RAD_TOOLS_JSON_H
#define RAD_TOOLS_JSON_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define JSON_MAX_DEPTH  64  /* arrays and objects nested in each other */
#define JSON_MAX_NUMBER 400 /* characters of one number */

typedef enum {
    JSON_NULL,
    JSON_FALSE,
    JSON_TRUE,
    JSON_NUMBER,
    JSON_STRING,
    JSON_ARRAY,
    JSON_OBJECT
} json_type;

typedef struct json_value json_value;
struct json_value {
    json_type type;
    size_t at;          /* the byte offset of its first character in the text */
    double number;      /* JSON_NUMBER */
    const char *string; /* JSON_STRING: decoded UTF-8, NUL-terminated, LEN bytes */
    size_t len;
    size_t n;          /* JSON_ARRAY, JSON_OBJECT: the count of items or members */
    json_value *items; /* in the file's order */
    const char *key;   /* a member of an object: its name (decoded, NUL-terminated) */
    size_t key_at;     /* and the byte offset of the name's opening quote */
};

typedef struct {
    json_value root;
    const char *name, *text; /* the file's name (for errors) and text (the caller's) */
    size_t size;
    void *blocks; /* what the tree holds, freed by json_free */
} json_doc;

/* Parses TEXT (SIZE bytes; a NUL inside is an error) named NAME into DOC, which refers
 * to NAME and TEXT until json_free. Returns 0, or -1 with "NAME:LINE:COL: what" in err
 * and nothing to free. */
int json_parse(json_doc *doc, const char *name, const char *text, size_t size, char *err,
               size_t errlen);

/* Frees what json_parse allocated and zeroes DOC; NULL-safe. */
void json_free(json_doc *doc);

/* The member of object OBJ named KEY, or NULL (also when OBJ is not an object). */
const json_value *json_member(const json_value *obj, const char *key);

/* "NAME:LINE:COL: " + FMT into err, at byte offset AT of DOC's text. */
void json_error(const json_doc *doc, size_t at, char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* S (a string of the tree) for a message, into BUF (LEN bytes): control characters, '"'
 * and '\\' escaped as in JSON, cut with "..." to fit. Returns BUF. */
const char *json_quote(const char *s, char *buf, size_t len);

/* "a string", "a number", ...: TYPE's name for messages. */
const char *json_type_name(json_type type);

#ifdef __cplusplus
}
#endif

#endif
