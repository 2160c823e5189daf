/* SPDX-License-Identifier: MIT */
/* rad_cli's --views and --animate files, parsed from a buffer (tests/fuzz/fuzz_views.c
 * runs them on arbitrary bytes): no exit, no I/O, every error a line "NAME:LINE: what".
 */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SPACE         " \t\r\v\f"
#define MAX_INTENSITY 32768.0 /* --group-intensity's bound: [0, 32768) */

int cli_parse_list(const char *s, double *v, int n, int opt_last)
{
    int k = 0;
    for (;;) {
        char *end;
        if (k == n) return -1; /* more values than wanted */
        errno = 0;
        v[k] = strtod(s, &end);
        if (end == s || errno || !isfinite(v[k])) return -1;
        k++;
        if (*end == '\0') break;
        if (*end != ',') return -1;
        s = end + 1;
    }
    return (k == n || (opt_last && k == n - 1)) ? k : -1;
}

int cli_set_camera(sc_camera *c, const double *v, int k)
{
    double d[3], len2 = 0, side;
    int a;
    for (a = 0; a < 3; a++) {
        c->eye[a] = v[a];
        c->target[a] = v[3 + a];
        d[a] = v[3 + a] - v[a];
        len2 += d[a] * d[a];
    }
    c->fov_deg = k == 7 ? v[6] : 45.0;
    side = d[0] * d[0] + d[2] * d[2]; /* |d x y|^2 */
    c->up[0] = 0;
    c->up[1] = side > 1e-6 * len2 ? 1 : 0;
    c->up[2] = side > 1e-6 * len2 ? 0 : -1;
    return len2 > 0 && c->fov_deg >= 8.0 && c->fov_deg <= 170.0; /* the core's 1/16..16 */
}

group_t *cli_find_group(group_t *g, int n, const char *name, size_t len)
{
    int i;
    for (i = 0; i < n; i++)
        if (strlen(g[i].name) == len && strncmp(g[i].name, name, len) == 0) return &g[i];
    return NULL;
}

/* Cuts the next line out of *P (NUL in place of its '\n') and returns it; NULL at the end. */
static char *next_line(char **p, const char *end)
{
    char *line = *p, *nl;
    if (line >= end) return NULL;
    nl = memchr(line, '\n', (size_t)(end - line));
    if (nl) {
        *nl = '\0';
        *p = nl + 1;
    } else {
        *p = (char *)end;
    }
    return line;
}

/* A buffer that the line parsers can walk as C strings: no NUL before its end. */
static int check_text(const char *text, size_t len, const char *name, char *err, size_t errlen)
{
    if (memchr(text, '\0', len)) {
        snprintf(err, errlen, "%s: not a text file (it holds a NUL byte)", name);
        return -1;
    }
    return 0;
}

/* Nonzero when the line holds nothing or is a comment: it is then skipped to its end,
 * however long. */
static int blank_or_comment(const char *line)
{
    line += strspn(line, SPACE);
    return *line == '\0' || *line == '#';
}

/* Splits LINE into at most MAX tokens; returns how many there were (MAX + 1: more). */
static int tokens(char *line, char **tok, int max)
{
    char *save = NULL, *t;
    int n = 0;
    for (t = strtok_r(line, SPACE, &save); t; t = strtok_r(NULL, SPACE, &save)) {
        if (n == max) return max + 1;
        tok[n++] = t;
    }
    return n;
}

static int parse_number(const char *s, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*v);
}

/* "EX EY EZ LX LY LZ [FOV] OUTPUT": the camera, or 0. */
static int view_line(char *line, sc_camera *c, const char **out)
{
    char *tok[8];
    double v[7];
    int nt = tokens(line, tok, 8), k;
    if (nt < 7 || nt > 8) return 0;
    for (k = 0; k < nt - 1; k++)
        if (!parse_number(tok[k], &v[k])) return 0;
    *out = tok[nt - 1];
    return cli_set_camera(c, v, nt - 1);
}

int cli_views_parse(char *text, size_t len, const char *name, view_fn add, void *ctx, char *err,
                    size_t errlen)
{
    char *p = text, *line;
    int ln = 0, n = 0;
    if (check_text(text, len, name, err, errlen) < 0) return -1;
    while ((line = next_line(&p, text + len)) != NULL) {
        sc_camera c;
        const char *out;
        int rc;
        ln++;
        if (blank_or_comment(line)) continue;
        if (!view_line(line, &c, &out)) {
            snprintf(err, errlen, "%s:%d: expected EX EY EZ LX LY LZ [FOV] OUTPUT", name, ln);
            return -1;
        }
        {
            char why[600] = "";
            rc = add(ctx, &c, out, ln, why, sizeof why);
            if (rc) {
                snprintf(err, errlen, "%s:%d: %s", name, ln, why);
                return -1;
            }
        }
        n++;
    }
    return n;
}

/* "GROUP=R,G,B" of a frame into its intensities K; 0 or -1 with err. */
static int frame_intensity(const char *tok, const char *eq, group_t *groups, int ngroups,
                           double (*k)[3], const char *where, char *err, size_t errlen)
{
    group_t *gp = cli_find_group(groups, ngroups, tok, (size_t)(eq - tok));
    double v[3];
    if (!gp) {
        size_t used;
        int g;
        used = (size_t)snprintf(err, errlen, "%s: no light group named '%.*s' (", where,
                                (int)(eq - tok), tok);
        for (g = 0; g < ngroups && used < errlen; g++)
            used +=
                (size_t)snprintf(err + used, errlen - used, "%s%s", g ? ", " : "", groups[g].name);
        if (used < errlen)
            snprintf(err + used, errlen - used, "%s)", ngroups ? "" : "the scene has no emitter");
        return -1;
    }
    if (cli_parse_list(eq + 1, v, 3, 0) != 3 || !(v[0] >= 0 && v[1] >= 0 && v[2] >= 0) ||
        v[0] >= MAX_INTENSITY || v[1] >= MAX_INTENSITY || v[2] >= MAX_INTENSITY) {
        snprintf(err, errlen, "%s: %s: intensity wants R,G,B in [0, 32768)", where, tok);
        return -1;
    }
    memcpy(k[gp - groups], v, sizeof v);
    return 0;
}

/* One frame line into FR (its K allocated); 0, or -1 with err and nothing allocated. */
static int frame_line(char *line, group_t *groups, int ngroups, frame_t *fr, const char *where,
                      char *err, size_t errlen)
{
    char *tok, *save = NULL;
    double v[7];
    int nv = 0, g;
    fr->k = malloc((size_t)(ngroups ? ngroups : 1) * sizeof *fr->k);
    if (!fr->k) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (g = 0; g < ngroups; g++) memcpy(fr->k[g], groups[g].k, sizeof fr->k[g]);
    for (tok = strtok_r(line, SPACE, &save); tok; tok = strtok_r(NULL, SPACE, &save)) {
        char *eq = strchr(tok, '=');
        if (!eq && nv < 7 && parse_number(tok, &v[nv]))
            nv++;
        else if (eq && nv >= 6) {
            if (frame_intensity(tok, eq, groups, ngroups, fr->k, where, err, errlen) < 0) break;
        } else {
            snprintf(
                err, errlen,
                "%s: expected EX EY EZ LX LY LZ [FOV] [GROUP=R,G,B ...], eye and look-at apart, "
                "FOV 8..170",
                where);
            break;
        }
    }
    if (!tok && (nv < 6 || !cli_set_camera(&fr->cam, v, nv))) {
        snprintf(err, errlen,
                 "%s: expected EX EY EZ LX LY LZ [FOV] [GROUP=R,G,B ...], eye and look-at apart, "
                 "FOV 8..170",
                 where);
        tok = line;
    }
    if (tok) {
        free(fr->k);
        return -1;
    }
    return 0;
}

void cli_frames_free(frame_t *frames, int n)
{
    int i;
    for (i = 0; i < n; i++) free(frames[i].k);
    free(frames);
}

int cli_frames_parse(char *text, size_t len, const char *name, group_t *groups, int ngroups,
                     frame_t **frames, char *err, size_t errlen)
{
    char *p = text, *line;
    int ln = 0, n = 0, cap = 0;
    frame_t *fr = NULL;
    if (check_text(text, len, name, err, errlen) < 0) return -1;
    while ((line = next_line(&p, text + len)) != NULL) {
        char where[512];
        ln++;
        if (blank_or_comment(line)) continue;
        if (n == cap) {
            frame_t *nf = realloc(fr, (size_t)(cap = cap ? 2 * cap : 64) * sizeof *nf);
            if (!nf) {
                snprintf(err, errlen, "out of memory");
                cli_frames_free(fr, n);
                return -1;
            }
            fr = nf;
        }
        snprintf(where, sizeof where, "%.480s:%d", name, ln);
        if (frame_line(line, groups, ngroups, &fr[n], where, err, errlen) < 0) {
            cli_frames_free(fr, n);
            return -1;
        }
        n++;
    }
    if (n == 0) {
        snprintf(err, errlen,
                 "%s: no frames (one a line: EX EY EZ LX LY LZ [FOV] [GROUP=R,G,B ...])", name);
        free(fr);
        return -1;
    }
    *frames = fr;
    return n;
}
