/* SPDX-License-Identifier: MIT */
/* libFuzzer harness: rad_cli's --views and --animate parsers (tools/cli/views.c) on
 * arbitrary bytes.
 *
 * Input: one byte choosing the parser (even: cli_views_parse, odd: cli_frames_parse), then the
 * file's text. The frames parser knows two light groups, "lamp" and "other", with
 * intensities (1,1,1) and (0.5,0.5,0.5), as rad_cli has them after --light-group.
 *
 * Checked: the parsers never crash, read outside the buffer or leak; on success every
 * view has a finite camera with eye and look-at apart, a field of view in 8..170 and an
 * output name that is a non-empty token inside the buffer; every frame the same camera
 * rules and intensities in [0, 32768); on failure the message is one line that starts
 * with the file's name.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(c)                                                                               \
    do {                                                                                       \
        if (!(c)) {                                                                            \
            fprintf(stderr, "fuzz_views: check failed: %s (%s:%d)\n", #c, __FILE__, __LINE__); \
            abort();                                                                           \
        }                                                                                      \
    } while (0)

#define NAME "views.txt"

typedef struct {
    const char *lo, *hi; /* the buffer */
    int n;
} ctx_t;

static void check_camera(const sc_camera *c)
{
    double d2 = 0;
    int a;
    for (a = 0; a < 3; a++) {
        CHECK(isfinite(c->eye[a]) && isfinite(c->target[a]));
        d2 += (c->target[a] - c->eye[a]) * (c->target[a] - c->eye[a]);
    }
    CHECK(d2 > 0);
    CHECK(c->fov_deg >= 8.0 && c->fov_deg <= 170.0);
}

static int on_view(void *vctx, const sc_camera *cam, const char *out, int line, char *why,
                   size_t whylen)
{
    ctx_t *c = vctx;
    check_camera(cam);
    CHECK(out >= c->lo && out < c->hi && *out);
    CHECK(!strpbrk(out, " \t\r\n"));
    CHECK(line > c->n);
    snprintf(why, whylen, "too many views");
    return ++c->n > MAX_VIEWS; /* as rad_cli: too many views stop the parse */
}

static void check_error(const char *err)
{
    CHECK(strncmp(err, NAME, strlen(NAME)) == 0);
    CHECK(!strchr(err, '\n'));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text, err[4096];
    int n;
    if (size < 1) return 0;
    text = malloc(size); /* the text and the NUL the file reader puts after it */
    CHECK(text != NULL);
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    err[0] = '\0';
    if (data[0] % 2 == 0) {
        ctx_t c;
        c.lo = text;
        c.hi = text + size - 1;
        c.n = 0;
        n = cli_views_parse(text, size - 1, NAME, on_view, &c, err, sizeof err);
        if (n < 0)
            check_error(err);
        else
            CHECK(n == c.n);
    } else {
        group_t groups[2];
        frame_t *fr = NULL;
        int i, g, k;
        memset(groups, 0, sizeof groups);
        strcpy(groups[0].name, "lamp");
        strcpy(groups[1].name, OTHER_GROUP);
        for (k = 0; k < 3; k++) {
            groups[0].k[k] = 1.0;
            groups[1].k[k] = 0.5;
        }
        n = cli_frames_parse(text, size - 1, NAME, groups, 2, &fr, err, sizeof err);
        if (n < 0) check_error(err);
        for (i = 0; i < n; i++) {
            check_camera(&fr[i].cam);
            for (g = 0; g < 2; g++)
                for (k = 0; k < 3; k++) CHECK(fr[i].k[g][k] >= 0 && fr[i].k[g][k] < 32768);
        }
        if (n >= 0) cli_frames_free(fr, n);
    }
    free(text);
    return 0;
}
