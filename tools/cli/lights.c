/* SPDX-License-Identifier: MIT */
/* rad_cli's lights: one table of each kind's fields (names, counts, ranges), read from
 * the options (--sun, --point, --spot, --sky, --sky-hdr: the fields' values in order,
 * comma-separated) and from a --lights file (JSON: a member a field), so that both say
 * the same light the same way, to the same bits; and --sky-hdr's map shot as the sky
 * dome's suns (tools/host/sky_map.h).
 */
#include "cli.h"

#include "formats/file_io.h"
#include "formats/hdr.h"
#include "formats/json.h"
#include "host/sky_map.h"
#include "rad/rad.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* What a field's values must be. */
enum { ANY, NONNEG, NONZERO, RANGE, RANGE_OPEN, WHOLE, POSITIVE, FILENAME };

typedef struct {
    const char *key; /* its name in a --lights file */
    int count;       /* its numbers (1 or 3; FILENAME: 1, a string) */
    int optional;    /* left out: NAN in the values (light_make's default) */
    int check;
    double lo, hi;    /* RANGE: [lo, hi]; RANGE_OPEN: (lo, hi]; WHOLE: an integer in [lo, hi] */
    const char *says; /* what it wants, for messages */
} field_t;

typedef struct {
    const char *type; /* a --lights entry's "type" */
    int nfields;
    field_t f[5];
} kind_t;

static const kind_t kinds[] = {
    [CLI_LIGHT_SUN] =
        {"sun",
         3,
         {{"direction", 3, 0, NONZERO, 0, 0, "the way the light travels, not zero"},
          {"irradiance", 3, 0, NONNEG, 0, 0, "the irradiance on a plane facing it, each >= 0"},
          {"angle", 1, 1, RANGE, 0, 14, "the sun's angular radius in degrees, 0..14"}}},
    [CLI_LIGHT_POINT] = {"point",
                         2,
                         {{"position", 3, 0, ANY, 0, 0, "a point"},
                          {"intensity", 3, 0, NONNEG, 0, 0,
                           "the intensity per steradian, each >= 0"}}},
    [CLI_LIGHT_SPOT] =
        {"spot",
         5,
         {{"position", 3, 0, ANY, 0, 0, "a point"},
          {"direction", 3, 0, NONZERO, 0, 0, "the way it points, not zero"},
          {"intensity", 3, 0, NONNEG, 0, 0, "the intensity per steradian, each >= 0"},
          {"angle", 1, 0, RANGE_OPEN, 0, 180, "the cone's half angle in degrees, in (0, 180]"},
          {"softness", 1, 1, RANGE, 0, 1, "the share of the angle that fades, 0..1"}}},
    [CLI_LIGHT_SKY] = {"sky",
                       3,
                       {{"radiance", 3, 0, NONNEG, 0, 0, "the zenith's radiance, each >= 0"},
                        {"horizon", 3, 1, NONNEG, 0, 0, "the horizon's radiance, each >= 0"},
                        {"directions", 1, 1, WHOLE, 3, SKY_MAP_MAX_DIRS,
                         "a whole number of directions, 3..768"}}},
    [CLI_LIGHT_SKY_HDR] =
        {"sky-hdr",
         3,
         {{"file", 1, 0, FILENAME, 0, 0, "a Radiance .hdr file's name"},
          {"directions", 1, 1, WHOLE, 3, SKY_MAP_MAX_DIRS, "a whole number of directions, 3..768"},
          {"scale", 1, 1, POSITIVE, 0, 0, "a factor on the map's radiance, > 0"}}},
};
#define NKINDS ((int)(sizeof kinds / sizeof kinds[0]))

int cli_light_values(int kind)
{
    int i, n = 0;
    for (i = 0; i < kinds[kind].nfields; i++) n += kinds[kind].f[i].count;
    return n;
}

static int value_ok(const field_t *f, const double *v)
{
    int a, zero = 1;
    if (f->check == FILENAME) return 1;
    if (f->optional && isnan(v[0])) return 1;
    for (a = 0; a < f->count; a++) {
        if (!isfinite(v[a])) return 0;
        if (v[a] != 0) zero = 0;
        switch (f->check) {
        case NONNEG:
            if (!(v[a] >= 0)) return 0;
            break;
        case RANGE:
            if (!(v[a] >= f->lo && v[a] <= f->hi)) return 0;
            break;
        case RANGE_OPEN:
            if (!(v[a] > f->lo && v[a] <= f->hi)) return 0;
            break;
        case WHOLE:
            if (!(v[a] >= f->lo && v[a] <= f->hi && v[a] == floor(v[a]))) return 0;
            break;
        case POSITIVE:
            if (!(v[a] > 0)) return 0;
            break;
        default: break;
        }
    }
    return !(f->check == NONZERO && zero);
}

int cli_light_check(int kind, const double *v)
{
    int i;
    for (i = 0; i < kinds[kind].nfields; i++) {
        if (!value_ok(&kinds[kind].f[i], v)) return i;
        v += kinds[kind].f[i].count;
    }
    return -1;
}

sc_light *cli_new_light(opts_t *o)
{
    if (o->nlights == o->max_lights) {
        int cap = o->max_lights ? 2 * o->max_lights : 16;
        sc_light *l;
        if (o->nlights >= CLI_MAX_LIGHTS)
            cli_die_usage("more lights than rad_cli takes (65535 in all)", NULL);
        l = realloc(o->lights, (size_t)cap * sizeof *l);
        if (!l) {
            fprintf(stderr, PROG ": out of memory\n");
            exit(CLI_EXIT_ERROR);
        }
        o->lights = l;
        o->max_lights = cap;
    }
    memset(&o->lights[o->nlights], 0, sizeof o->lights[0]);
    return &o->lights[o->nlights++];
}

void cli_light_make(opts_t *o, int kind, const double *v)
{
    sc_light *l = cli_new_light(o);
    int a;
    switch (kind) {
    case CLI_LIGHT_SUN:
        l->type = RAD_LIGHT_SUN;
        memcpy(l->dir, v, sizeof l->dir);
        memcpy(l->rgb, v + 3, sizeof l->rgb);
        l->radius = isnan(v[6]) ? 0 : tan(v[6] * PI / 180);
        break;
    case CLI_LIGHT_POINT:
        l->type = RAD_LIGHT_POINT;
        memcpy(l->pos, v, sizeof l->pos);
        memcpy(l->rgb, v + 3, sizeof l->rgb);
        break;
    case CLI_LIGHT_SPOT:
        l->type = RAD_LIGHT_SPOT;
        memcpy(l->pos, v, sizeof l->pos);
        memcpy(l->dir, v + 3, sizeof l->dir);
        memcpy(l->rgb, v + 6, sizeof l->rgb);
        l->cos_outer = cos(v[9] * PI / 180);
        l->cos_inner = cos(v[9] * (1 - (isnan(v[10]) ? 0 : v[10])) * PI / 180);
        break;
    default: /* CLI_LIGHT_SKY */
        l->type = RAD_LIGHT_SKY;
        for (a = 0; a < 3; a++) {
            l->rgb[a] = v[a];
            l->horizon[a] = isnan(v[3]) ? v[a] : v[3 + a]; /* no horizon: a uniform sky */
        }
        l->dirs = isnan(v[6]) ? 0 : (int)v[6];
        break;
    }
}

/* ---- --sky-hdr -------------------------------------------------------------------- */

int cli_add_sky_map(opts_t *o, const char *path, int dirs, double scale, char *err, size_t errlen)
{
    hdr_image im;
    sky_sun *suns;
    int n, i;
    if (hdr_read(path, &im, err, errlen) < 0) return -1;
    suns = malloc(SKY_MAP_MAX_DIRS * sizeof *suns);
    if (!suns) {
        hdr_free(&im);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    n = sky_map_suns(im.rgb, im.w, im.h, scale, dirs, suns);
    hdr_free(&im);
    if (n < 0) {
        free(suns);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (i = 0; i < n; i++) {
        sc_light *l = cli_new_light(o);
        l->type = RAD_LIGHT_SUN;
        l->dome = n;
        memcpy(l->dir, suns[i].dir, sizeof l->dir);
        memcpy(l->rgb, suns[i].e, sizeof l->rgb);
    }
    free(suns);
    return 0;
}

/* ---- --lights FILE ---------------------------------------------------------------- */

/* NAME relative to the folder of file PATH (NAME itself when absolute), malloc'd. */
static char *beside(const char *path, const char *name)
{
    const char *slash = strrchr(path, '/');
    size_t dir = name[0] == '/' || !slash ? 0 : (size_t)(slash - path) + 1;
    char *s = malloc(dir + strlen(name) + 1);
    if (!s) return NULL;
    memcpy(s, path, dir);
    strcpy(s + dir, name);
    return s;
}

typedef struct {
    const json_doc *doc;
    char *err;
    size_t errlen;
} reader_t;

/* Member M (of entry I) as field F's values into V. 0 after an error. */
static int member_values(const reader_t *rd, int i, const field_t *f, const json_value *m,
                         double *v)
{
    int a;
    if (f->check == FILENAME) {
        size_t c = 0;
        while (m->type == JSON_STRING && c < m->len && (unsigned char)m->string[c] >= 0x20) c++;
        if (m->type == JSON_STRING && m->len > 0 && c == m->len) return 1;
        json_error(rd->doc, m->at, rd->err, rd->errlen, "lights[%d].%s: wants %s, found %s", i,
                   f->key, f->says,
                   m->type != JSON_STRING ? json_type_name(m->type)
                   : m->len               ? "a control character in it"
                                          : "an empty string");
        return 0;
    }
    if (f->count == 1 && m->type == JSON_NUMBER) {
        v[0] = m->number;
        return 1;
    }
    if (f->count == 3 && m->type == JSON_ARRAY && m->n == 3) {
        for (a = 0; a < 3 && m->items[a].type == JSON_NUMBER; a++) v[a] = m->items[a].number;
        if (a == 3) return 1;
        json_error(rd->doc, m->items[a].at, rd->err, rd->errlen,
                   "lights[%d].%s[%d]: wants a number, found %s", i, f->key, a,
                   json_type_name(m->items[a].type));
    } else if (f->count == 3 && m->type == JSON_ARRAY) {
        json_error(rd->doc, m->at, rd->err, rd->errlen,
                   "lights[%d].%s: wants an array of 3 numbers, found %zu items", i, f->key, m->n);
    } else {
        json_error(rd->doc, m->at, rd->err, rd->errlen, "lights[%d].%s: wants %s, found %s", i,
                   f->key, f->count == 1 ? "a number" : "an array of 3 numbers",
                   json_type_name(m->type));
    }
    return 0;
}

/* The names a kind takes, for "unknown name" messages. */
static void field_names(const kind_t *k, char *buf, size_t len)
{
    int i;
    size_t used = 0;
    buf[0] = '\0';
    for (i = 0; i < k->nfields && used < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? ", " : "type, ", k->f[i].key);
}

/* Entry I of the file (E) into the run's lights. 0 after an error. */
static int read_entry(opts_t *o, const reader_t *rd, const char *path, int i, const json_value *e)
{
    const json_value *t = json_member(e, "type"), *file = NULL;
    double v[CLI_LIGHT_MAX_VALUES];
    const json_value *where[5] = {NULL, NULL, NULL, NULL, NULL};
    const kind_t *k;
    size_t m;
    int kind, f, off, bad;
    char names[160], name[72];
    if (e->type != JSON_OBJECT) {
        json_error(rd->doc, e->at, rd->err, rd->errlen, "lights[%d]: wants an object, found %s", i,
                   json_type_name(e->type));
        return 0;
    }
    for (kind = 0;
         t && t->type == JSON_STRING && kind < NKINDS && strcmp(t->string, kinds[kind].type);
         kind++)
        continue;
    if (!t || t->type != JSON_STRING || kind == NKINDS) {
        json_error(rd->doc, t ? t->at : e->at, rd->err, rd->errlen,
                   "lights[%d].type: wants \"sun\", \"point\", \"spot\", \"sky\" or \"sky-hdr\"%s",
                   i, t ? "" : " (missing)");
        return 0;
    }
    k = &kinds[kind];
    for (m = 0; m < e->n; m++) {
        const json_value *x = &e->items[m];
        if (x == t) continue;
        for (f = 0, off = 0; f < k->nfields && strcmp(x->key, k->f[f].key); f++)
            off += k->f[f].count;
        if (f == k->nfields) {
            field_names(k, names, sizeof names);
            json_error(rd->doc, x->key_at, rd->err, rd->errlen,
                       "lights[%d]: a %s has no \"%s\" (it takes %s)", i, k->type,
                       json_quote(x->key, name, sizeof name), names);
            return 0;
        }
        if (!member_values(rd, i, &k->f[f], x, v + off)) return 0;
        where[f] = x;
        if (k->f[f].check == FILENAME) file = x;
    }
    for (f = 0, off = 0; f < k->nfields; off += k->f[f].count, f++) {
        if (where[f]) continue;
        if (!k->f[f].optional) {
            json_error(rd->doc, e->at, rd->err, rd->errlen, "lights[%d]: a %s wants \"%s\" (%s)", i,
                       k->type, k->f[f].key, k->f[f].says);
            return 0;
        }
        for (m = 0; m < (size_t)k->f[f].count; m++) v[off + (int)m] = NAN;
    }
    bad = cli_light_check(kind, v);
    if (bad >= 0) {
        json_error(rd->doc, where[bad]->at, rd->err, rd->errlen, "lights[%d].%s: wants %s", i,
                   k->f[bad].key, k->f[bad].says);
        return 0;
    }
    if (kind != CLI_LIGHT_SKY_HDR) {
        cli_light_make(o, kind, v);
        return 1;
    }
    {
        char *map = beside(path, file->string), why[1024];
        int rc = map ? cli_add_sky_map(o, map, isnan(v[1]) ? 0 : (int)v[1],
                                       isnan(v[2]) ? 1.0 : v[2], why, sizeof why)
                     : -1;
        if (rc < 0)
            json_error(rd->doc, file->at, rd->err, rd->errlen, "lights[%d].file: %s", i,
                       map ? why : "out of memory");
        free(map);
        return rc == 0;
    }
}

int cli_read_lights(opts_t *o, const char *path, char *err, size_t errlen)
{
    char *text;
    size_t size, i;
    json_doc doc;
    reader_t rd;
    const json_value *list;
    char names[72];
    int ok = 1;
    if (fio_read_all(path, FIO_LIMIT_TEXT, &text, &size, err, errlen) < 0) return -1;
    if (json_parse(&doc, path, text, size, err, errlen) < 0) {
        free(text);
        return -1;
    }
    rd.doc = &doc;
    rd.err = err;
    rd.errlen = errlen;
    list = json_member(&doc.root, "lights");
    if (doc.root.type != JSON_OBJECT) {
        json_error(&doc, doc.root.at, err, errlen, "wants an object {\"lights\": [...]}, found %s",
                   json_type_name(doc.root.type));
        ok = 0;
    } else if (doc.root.n != (list ? 1u : 0u) || !list) {
        for (i = 0; i < doc.root.n && !strcmp(doc.root.items[i].key, "lights"); i++) continue;
        if (i < doc.root.n)
            json_error(&doc, doc.root.items[i].key_at, err, errlen,
                       "an unknown name \"%s\" (the file holds \"lights\")",
                       json_quote(doc.root.items[i].key, names, sizeof names));
        else
            json_error(&doc, doc.root.at, err, errlen, "\"lights\" is missing");
        ok = 0;
    } else if (list->type != JSON_ARRAY) {
        json_error(&doc, list->at, err, errlen, "lights: wants an array of lights, found %s",
                   json_type_name(list->type));
        ok = 0;
    }
    for (i = 0; ok && i < list->n; i++) ok = read_entry(o, &rd, path, (int)i, &list->items[i]);
    json_free(&doc);
    free(text);
    return ok ? 0 : -1;
}
