/* SPDX-License-Identifier: MIT */
/* Comparisons that say, when they fail, what the test measured and what it had to meet.
 *
 * CHECK_LE(measured, bound, what...) fails unless measured <= bound, and then prints
 *
 *     WHAT: measured M, required <= B
 *
 * and the file and line. WHAT is a printf format and its arguments (at least the format):
 * the requirement in the project's own words, with what varies in a loop (an element, a
 * pixel) among its arguments, evaluated only on failure; a literal % is written %%. Each
 * macro evaluates each of its operands once, in order, so a call with side effects can
 * stand in the measured place.
 *
 * CHECK_LE, _LT, _GE, _GT, _EQ compare doubles (a float or an integer below 2^53
 * converts exactly); CHECK_NEAR(measured, expected, tol, what...) requires
 * fabs(measured - expected) <= tol and prints all three and the difference. CHECK_INT_*
 * compare as intmax_t and print in decimal (a negative RAD_ERR_* code reads as itself):
 * for signed or small unsigned integers. A 64-bit checksum or bit pattern uses CMocka's
 * assert_int_equal, exact over all 64 bits; pointers assert_non_null, strings
 * assert_string_equal, bytes assert_memory_equal. CHECK_CONTAINS(text, part, what...)
 * and CHECK_LACKS require PART in TEXT (or not) and print both. CHECK_THAT(cond,
 * what...) is for a condition none of these express (128-bit products, a line that must
 * start a text): WHAT's arguments then carry the values.
 *
 * Include after <cmocka.h>. */
#ifndef RAD_TESTS_CHECK_H
#define RAD_TESTS_CHECK_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define CHECK_CMP_(type, fmt, measured, op, bound, ...)                                        \
    do {                                                                                       \
        const type check_m_ = (type)(measured);                                                \
        const type check_b_ = (type)(bound);                                                   \
        if (!(check_m_ op check_b_)) {                                                         \
            print_error(__VA_ARGS__);                                                          \
            print_error(": measured " fmt ", required " #op " " fmt "\n", check_m_, check_b_); \
            fail();                                                                            \
        }                                                                                      \
    } while (0)

#define CHECK_LE(m, b, ...) CHECK_CMP_(double, "%.9g", m, <=, b, __VA_ARGS__)
#define CHECK_LT(m, b, ...) CHECK_CMP_(double, "%.9g", m, <, b, __VA_ARGS__)
#define CHECK_GE(m, b, ...) CHECK_CMP_(double, "%.9g", m, >=, b, __VA_ARGS__)
#define CHECK_GT(m, b, ...) CHECK_CMP_(double, "%.9g", m, >, b, __VA_ARGS__)
#define CHECK_EQ(m, b, ...) CHECK_CMP_(double, "%.17g", m, ==, b, __VA_ARGS__)

#define CHECK_INT_LE(m, b, ...) CHECK_CMP_(intmax_t, "%jd", m, <=, b, __VA_ARGS__)
#define CHECK_INT_LT(m, b, ...) CHECK_CMP_(intmax_t, "%jd", m, <, b, __VA_ARGS__)
#define CHECK_INT_GE(m, b, ...) CHECK_CMP_(intmax_t, "%jd", m, >=, b, __VA_ARGS__)
#define CHECK_INT_GT(m, b, ...) CHECK_CMP_(intmax_t, "%jd", m, >, b, __VA_ARGS__)
#define CHECK_INT_EQ(m, b, ...) CHECK_CMP_(intmax_t, "%jd", m, ==, b, __VA_ARGS__)
#define CHECK_INT_NE(m, b, ...) CHECK_CMP_(intmax_t, "%jd", m, !=, b, __VA_ARGS__)

#define CHECK_TEXT_(text, part, found, ...)                                                 \
    do {                                                                                    \
        const char *check_t_ = (text);                                                      \
        const char *check_p_ = (part);                                                      \
        if ((strstr(check_t_, check_p_) != NULL) != (found)) {                              \
            print_error(__VA_ARGS__);                                                       \
            print_error(": \"%s\" %s in:\n%s\n", check_p_, (found) ? "not found" : "found", \
                        check_t_);                                                          \
            fail();                                                                         \
        }                                                                                   \
    } while (0)

#define CHECK_CONTAINS(text, part, ...) CHECK_TEXT_(text, part, 1, __VA_ARGS__)
#define CHECK_LACKS(text, part, ...)    CHECK_TEXT_(text, part, 0, __VA_ARGS__)

#define CHECK_THAT(cond, ...)         \
    do {                              \
        if (!(cond)) {                \
            print_error(__VA_ARGS__); \
            print_error("\n");        \
            fail();                   \
        }                             \
    } while (0)

#define CHECK_NEAR(measured, expected, tol, ...)                                                   \
    do {                                                                                           \
        const double check_m_ = (measured);                                                        \
        const double check_e_ = (expected);                                                        \
        const double check_t_ = (tol);                                                             \
        if (!(fabs(check_m_ - check_e_) <= check_t_)) {                                            \
            print_error(__VA_ARGS__);                                                              \
            print_error(": measured %.17g, expected %.17g, off by %.3g, allowed %.3g\n", check_m_, \
                        check_e_, fabs(check_m_ - check_e_), check_t_);                            \
            fail();                                                                                \
        }                                                                                          \
    } while (0)

#endif
