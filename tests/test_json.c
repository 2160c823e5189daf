/* SPDX-License-Identifier: MIT */
/* Tests for tools/formats/json.c: the strict JSON reader of rad_cli's --lights files.
 * Good texts are parsed and every value asserted (types, numbers as strtod reads them,
 * strings decoded to their UTF-8 bytes, members in order); each bad text gives one
 * error at its LINE:COL with the words that say what is wrong, and nothing to free. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "check.h"
#include "formats/json.h"

static void parse_ok(json_doc *doc, const char *text)
{
    char err[256] = "";
    int rc = json_parse(doc, "t.json", text, strlen(text), err, sizeof err);
    if (rc != 0) fail_msg("json_parse of %s: %s", text, err);
}

/* A document of every type, nested, members in the file's order. */
static void test_values(void **state)
{
    static const char text[] =
        "\xEF\xBB\xBF { \"a\": [1, -0, 2.5e3, -1E-2, 0.1, 1e-400],\r\n"
        "  \"b\": {\"x\": true, \"y\": false, \"z\": null},\t\"c\": [], \"d\": {},\n"
        "  \"e\": \"\" } \n";
    const double nums[6] = {1, -0.0, 2500, -0.01, 0.1, 0};
    json_doc doc;
    const json_value *a, *b;
    size_t i;
    (void)state;
    parse_ok(&doc, text);
    CHECK_INT_EQ(doc.root.type, JSON_OBJECT, "the root's type");
    CHECK_INT_EQ(doc.root.n, 5, "the root's members");
    CHECK_THAT(strcmp(doc.root.items[0].key, "a") == 0 && strcmp(doc.root.items[4].key, "e") == 0,
               "members in order: %s .. %s", doc.root.items[0].key, doc.root.items[4].key);
    a = json_member(&doc.root, "a");
    assert_non_null(a);
    CHECK_INT_EQ(a->type, JSON_ARRAY, "a's type");
    CHECK_INT_EQ(a->n, 6, "a's items");
    for (i = 0; i < 6; i++) {
        CHECK_INT_EQ(a->items[i].type, JSON_NUMBER, "a[%zu]'s type", i);
        CHECK_EQ(a->items[i].number, nums[i], "a[%zu]", i);
    }
    CHECK_THAT(signbit(a->items[1].number), "-0 keeps its sign");
    b = json_member(&doc.root, "b");
    assert_non_null(b);
    CHECK_INT_EQ(json_member(b, "x")->type, JSON_TRUE, "b.x");
    CHECK_INT_EQ(json_member(b, "y")->type, JSON_FALSE, "b.y");
    CHECK_INT_EQ(json_member(b, "z")->type, JSON_NULL, "b.z");
    CHECK_INT_EQ(json_member(&doc.root, "c")->n, 0, "an empty array");
    CHECK_INT_EQ(json_member(&doc.root, "d")->type, JSON_OBJECT, "an empty object");
    CHECK_INT_EQ(json_member(&doc.root, "e")->len, 0, "an empty string");
    assert_null(json_member(&doc.root, "f"));
    assert_null(json_member(a, "a")); /* not an object */
    json_free(&doc);

    parse_ok(&doc, "  42 ");
    CHECK_INT_EQ(doc.root.type, JSON_NUMBER, "a bare number is a whole document");
    CHECK_EQ(doc.root.number, 42, "its value");
    json_free(&doc);
}

/* Escapes and UTF-8 decode to the bytes they stand for. */
static void test_strings(void **state)
{
    static const struct {
        const char *text, *bytes;
        size_t len;
    } cases[] = {
        {"\"a\\\"b\\\\c\\/d\\be\\ff\\ng\\rh\\ti\"", "a\"b\\c/d\be\ff\ng\rh\ti", 17},
        {"\"\\u0041\\u00e9\\u20AC\"", "A\xC3\xA9\xE2\x82\xAC", 6}, /* 1, 2, 3 bytes */
        {"\"\\uD83D\\uDE00\"", "\xF0\x9F\x98\x80", 4},             /* a surrogate pair */
        {"\"\\uDBFF\\uDFFF\"", "\xF4\x8F\xBF\xBF", 4},             /* U+10FFFF */
        {"\"\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80\"", "\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80",
         9},                     /* raw UTF-8 */
        {"\"\x7F\"", "\x7F", 1}, /* DEL is not a control */
    };
    size_t k;
    (void)state;
    for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        json_doc doc;
        parse_ok(&doc, cases[k].text);
        CHECK_INT_EQ(doc.root.type, JSON_STRING, "case %zu's type", k);
        CHECK_INT_EQ(doc.root.len, cases[k].len, "case %zu's length", k);
        assert_memory_equal(doc.root.string, cases[k].bytes, cases[k].len + 1);
        json_free(&doc);
    }
}

/* Each bad text: one error, at its place, saying what is wrong. */
static void test_errors(void **state)
{
    static const struct {
        const char *text, *says;
    } bad[] = {
        {"", "t.json:1:1: no JSON value: the file is empty"},
        {" \n\t ", "t.json:2:3: no JSON value"},
        {"[1, 2,]", "t.json:1:6: a ',' before ']'"},
        {"{\"a\": 1,}", "t.json:1:8: a ',' before '}'"},
        {"{\"a\": 1} x", "t.json:1:10: 'x' after the JSON value"},
        {"[1]]", "t.json:1:4: ']' after the JSON value"},
        {"{\"a\": 1, \"a\": 2}",
         "t.json:1:10: the name \"a\" given twice in one object (first at 1:2)"},
        {"{\"b\": 1,\n \"a\": {\"a\": 1}, \"b\": 3}",
         "t.json:2:17: the name \"b\" given twice in one object (first at 1:2)"},
        {"{\"a\\nb\\\"\": 1, \"a\\nb\\\"\": 2}",
         "t.json:1:15: the name \"a\\u000Ab\\\"\" given twice"}, /* quoted */
        {"[01]", "t.json:1:2: a number with a leading zero"},
        {"[-]", "t.json:1:2: a number wants a digit after its '-'"},
        {"[.5]", "t.json:1:2: expected a value"},
        {"[1.]", "t.json:1:2: a number wants a digit after its '.'"},
        {"[1e]", "t.json:1:2: a number wants a digit in its exponent"},
        {"[+1]", "t.json:1:2: expected a value"},
        {"[1e400]", "t.json:1:2: a number beyond a double's range"},
        {"[-1e400]", "t.json:1:2: a number beyond a double's range"},
        {"[NaN]",
         "t.json:1:2: expected a value (a number, a string, true, false, null, [ or {), found 'N'"},
        {"[tru]", "t.json:1:2: expected a value"},
        {"\"abc", "t.json:1:5: unexpected end of the file: the string opened at 1:1 is not closed"},
        {"\"a\tb\"", "t.json:1:3: a control character (U+0009) in a string"},
        {"\"a\\x\"", "t.json:1:3: an unknown escape \\x"},
        {"\"\\u12G4\"", "t.json:1:2: a \\u escape wants four hexadecimal digits"},
        {"\"\\u12\"", "t.json:1:2: a \\u escape wants four hexadecimal digits"},
        {"\"\\uD800\"", "t.json:1:2: a high surrogate \\uD800 without a low one"},
        {"\"\\uD800\\u0041\"", "t.json:1:2: a high surrogate \\uD800 without a low one"},
        {"\"\\uDC00\"", "t.json:1:2: a lone low surrogate \\uDC00"},
        {"\"\\u0000\"", "t.json:1:2: \\u0000 (NUL) in a string is not accepted"},
        {"\"\xC0\xAF\"", "t.json:1:2: not UTF-8: the byte 0xC0"},         /* overlong '/' */
        {"\"\xED\xA0\x80\"", "t.json:1:2: not UTF-8: the byte 0xED"},     /* an encoded surrogate */
        {"\"\xF4\x90\x80\x80\"", "t.json:1:2: not UTF-8: the byte 0xF4"}, /* above U+10FFFF */
        {"\"\xE2\x82\"", "t.json:1:2: not UTF-8: the byte 0xE2"},         /* cut short */
        {"[\xC3\xA9]", "t.json:1:2: expected a value (a number, a string, true, false, null, [ or "
                       "{), found the byte 0xC3"},
        {"\"\xC3\xA9\" x", "t.json:1:5: 'x' after the JSON value"}, /* columns count characters */
        {"{\"a\" 1}", "t.json:1:6: expected ':' after the name \"a\", found '1'"},
        {"{1: 2}", "t.json:1:2: expected a member's name in double quotes, found '1'"},
        {"[1 2]", "t.json:1:4: expected ',' or ']' in the array opened at 1:1, found '2'"},
        {"{\"a\": [1,\n 2}",
         "t.json:2:3: expected ',' or ']' in the array opened at 1:7, found '}'"},
        {"[1,", "t.json:1:4: unexpected end of the file: a value is missing"},
        {"{\"a\": 1",
         "t.json:1:8: expected ',' or '}' in the object opened at 1:1, found the end of the file"},
    };
    size_t k;
    (void)state;
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        json_doc doc;
        char err[256] = "";
        int rc = json_parse(&doc, "t.json", bad[k].text, strlen(bad[k].text), err, sizeof err);
        CHECK_INT_EQ(rc, -1, "json_parse of bad text %zu (%s)", k, bad[k].text);
        CHECK_THAT(strncmp(err, bad[k].says, strlen(bad[k].says)) == 0,
                   "bad text %zu (%s): said \"%s\", wanted \"%s...\"", k, bad[k].text, err,
                   bad[k].says);
        CHECK_THAT(!strchr(err, '\n'), "one line: %s", err);
        assert_null(doc.blocks); /* nothing to free */
    }
}

/* A NUL byte inside the text (strlen would stop there) is an error, not the end. */
static void test_nul_and_limits(void **state)
{
    static const char nul[] = "[1,\0 2]";
    char err[256] = "", *deep, *longnum;
    json_doc doc;
    int k;
    (void)state;
    CHECK_INT_EQ(json_parse(&doc, "t.json", nul, sizeof nul - 1, err, sizeof err), -1,
                 "a NUL inside the text");
    CHECK_CONTAINS(err, "t.json:1:4: expected a value", "a NUL inside the text");

    /* JSON_MAX_DEPTH arrays nest; one more is refused where it opens */
    deep = malloc(2 * JSON_MAX_DEPTH + 3);
    assert_non_null(deep);
    for (k = 0; k < JSON_MAX_DEPTH; k++) deep[k] = '[', deep[2 * JSON_MAX_DEPTH - 1 - k] = ']';
    deep[2 * JSON_MAX_DEPTH] = '\0';
    CHECK_INT_EQ(json_parse(&doc, "t.json", deep, strlen(deep), err, sizeof err), 0,
                 "%d nested arrays: %s", JSON_MAX_DEPTH, err);
    json_free(&doc);
    memmove(deep + 1, deep, 2 * JSON_MAX_DEPTH + 1);
    deep[0] = '[';
    strcat(deep, "]");
    CHECK_INT_EQ(json_parse(&doc, "t.json", deep, strlen(deep), err, sizeof err), -1,
                 "%d nested arrays", JSON_MAX_DEPTH + 1);
    CHECK_CONTAINS(err, "t.json:1:65: arrays and objects nested more than 64 deep",
                   "one array too deep");
    free(deep);

    /* a number of JSON_MAX_NUMBER characters reads; one more is refused */
    longnum = malloc(JSON_MAX_NUMBER + 2);
    assert_non_null(longnum);
    memset(longnum, '1', JSON_MAX_NUMBER);
    longnum[1] = '.';
    longnum[JSON_MAX_NUMBER] = '\0';
    CHECK_INT_EQ(json_parse(&doc, "t.json", longnum, strlen(longnum), err, sizeof err), 0,
                 "a number of %d characters: %s", JSON_MAX_NUMBER, err);
    CHECK_NEAR(doc.root.number, 1.0 + 1.0 / 9, 1e-15, "1.111...");
    json_free(&doc);
    strcat(longnum, "1");
    CHECK_INT_EQ(json_parse(&doc, "t.json", longnum, strlen(longnum), err, sizeof err), -1,
                 "a number of %d characters", JSON_MAX_NUMBER + 1);
    CHECK_CONTAINS(err, "a number longer than 400 characters", "a long number");
    free(longnum);
}

/* Duplicate names among many: found by sorting, the later one said. */
static void test_many_members(void **state)
{
    enum { N = 20000 };
    char *text = malloc(N * 16 + 16), *p, err[256] = "";
    json_doc doc;
    int k;
    (void)state;
    assert_non_null(text);
    p = text;
    *p++ = '{';
    for (k = 0; k < N; k++) p += sprintf(p, "%s\"k%d\":%d", k ? "," : "", k, k);
    strcpy(p, "}");
    CHECK_INT_EQ(json_parse(&doc, "t.json", text, strlen(text), err, sizeof err), 0,
                 "%d distinct members: %s", N, err);
    CHECK_INT_EQ(doc.root.n, N, "the members");
    CHECK_EQ(json_member(&doc.root, "k19999")->number, 19999, "the last member");
    json_free(&doc);
    sprintf(p, ",\"k777\":0}");
    CHECK_INT_EQ(json_parse(&doc, "t.json", text, strlen(text), err, sizeof err), -1,
                 "a name given again at the end");
    CHECK_CONTAINS(err,
                   "the name \"k777\" given twice in one object (first at 1:", "the repeated name");
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values),       cmocka_unit_test(test_strings),
        cmocka_unit_test(test_errors),       cmocka_unit_test(test_nul_and_limits),
        cmocka_unit_test(test_many_members),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
