/* SPDX-License-Identifier: MIT */
/* rad_cli — load an OBJ/MTL scene, solve its radiosity, render views, write images.
 *
 * Built twice from the files of tools/cli/ (see cli.h): rad_cli (the fixed-point core)
 * and rad_cli_float (the float twin, for comparisons). Exit status: 0 success, 1 runtime
 * or input error, 2 usage, 3 outputs written but not converged or saturated.
 */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "formats/assimp_scene.h"
#include "formats/file_io.h"
#include "host/clock.h"
#include "bake/gltf_export.h"
#include "host/polys.h"
#include "host/tex_render.h"
#include "rad/rad.h"
#include "progress.h"

/* ---- load: the scene, --emit, the light groups, the views and frames ------------- */

static void obj_warning(void *ctx, const char *msg)
{
    const opts_t *o = ctx;
    if (!o->quiet) fprintf(stderr, PROG ": warning: %s\n", msg);
}

static void poly_warning(void *ctx, int line, const char *msg)
{
    const opts_t *o = ctx;
    fprintf(stderr, PROG ": warning: %s:%d: %s\n", o->scene, line, msg);
}

/* The glue's warnings name a polygon by its tag, the OBJ face index: shown as its line. */
static void glue_warning(void *ctx, int tag, const char *msg)
{
    const run_t *r = ctx;
    fprintf(stderr, PROG ": warning: %s:%d: %s\n", r->o->scene,
            tag >= 0 && tag < r->sc.nfaces ? r->sc.faces[tag].line : 0, msg);
}

static int apply_emit(const opts_t *o, obj_scene *sc)
{
    int i;
    for (i = 0; i < o->nemit; i++) {
        const char *eq = strrchr(o->emit[i], '=');
        char name[512];
        double v[3];
        int m;
        size_t len = (size_t)(eq - o->emit[i]);
        if (len >= sizeof name) len = sizeof name - 1;
        memcpy(name, o->emit[i], len);
        name[len] = '\0';
        cli_parse_list(eq + 1, v, 3, 0);
        m = obj_find_material(sc, name);
        if (m < 0) {
            fprintf(stderr,
                    PROG ": %s: --emit: no material named '%s' (--list-materials shows them)\n",
                    o->scene, name);
            return -1;
        }
        memcpy(sc->materials[m].ke, v, sizeof v);
    }
    return 0;
}

/* Emissions the outputs can hold (CLI_EMIT_LIMIT), after --emit: 0 or -1. */
static int check_emissions(const opts_t *o, const obj_scene *sc)
{
    int m, c;
    for (m = 0; m < sc->nmaterials; m++)
        for (c = 0; c < 3 && sc->materials[m].nfaces > 0; c++)
            if (sc->materials[m].ke[c] > CLI_EMIT_LIMIT) {
                fprintf(
                    stderr,
                    PROG
                    ": %s: material '%s': emission %g is above the limit of %g (the image would "
                    "overflow); scale every emission down: radiosity is linear in it\n",
                    o->scene, sc->materials[m].name, sc->materials[m].ke[c], CLI_EMIT_LIMIT);
                return -1;
            }
    return 0;
}

static void list_materials(const obj_scene *sc)
{
    int i;
    printf("%-24s %-26s %-26s %10s %6s\n", "material", "Kd", "Ke", "area", "faces");
    for (i = 0; i < sc->nmaterials; i++) {
        const obj_material *m = &sc->materials[i];
        char kd[64], ke[64];
        snprintf(kd, sizeof kd, "%.4g %.4g %.4g", m->kd[0], m->kd[1], m->kd[2]);
        snprintf(ke, sizeof ke, "%.4g %.4g %.4g", m->ke[0], m->ke[1], m->ke[2]);
        printf("%-24s %-26s %-26s %10.4g %6d\n", m->name, kd, ke, m->area, m->nfaces);
    }
}

static int emits(const obj_material *m)
{
    return m->nfaces > 0 && (m->ke[0] > 0 || m->ke[1] > 0 || m->ke[2] > 0);
}

/* Light I's name for --light-group: an option's light by its kind and number among
 * the lights of that option (sun1, sky1, point2, spot1, in the order given), a scene
 * file's light by its name (light1, light2, ... when it has none). */
static void light_name(const run_t *r, int i, char *name, size_t len)
{
    static const char *const kind[] = {"light", "sun", "point", "spot", "sky"};
    int j, n = 1, t = r->lights[i].type;
    if (i < r->o->nlights) {
        for (j = 0; j < i; j++) n += r->lights[j].type == t;
        snprintf(name, len, "%s%d", kind[t >= 1 && t <= 4 ? t : 0], n);
    } else if (r->sc.lights[i - r->o->nlights].name && r->sc.lights[i - r->o->nlights].name[0]) {
        snprintf(name, len, "%s", r->sc.lights[i - r->o->nlights].name);
    } else {
        snprintf(name, len, "light%d", i - r->o->nlights + 1);
    }
}

static int find_light(const run_t *r, const char *name)
{
    char ln[512];
    int i;
    for (i = 0; i < r->nlights; i++) {
        light_name(r, i, ln, sizeof ln);
        if (strcmp(ln, name) == 0) return i;
    }
    return -1;
}

/* Light L into group G of --light-group's list (LOF: light -> group); 0 or -1. */
static int group_light(run_t *r, int g, int l, int *lof, const char *name)
{
    const opts_t *o = r->o;
    if (lof[l] >= 0 && lof[l] != g) {
        fprintf(stderr, PROG ": %s: --light-group %s: light '%s' is already in group '%s'\n",
                o->scene, o->groups[g].name, name, o->groups[lof[l]].name);
        return -1;
    }
    lof[l] = g;
    return 0;
}

/* Material and light names of --light-group's list into OF[material] = G and
 * LOF[light] = G; 0 or -1. */
static int group_materials(run_t *r, int g, int *of, int *lof)
{
    const opts_t *o = r->o;
    const obj_scene *sc = &r->sc;
    const char *p = o->groups[g].mats;
    while (*p) {
        const char *q = strchr(p, ',');
        size_t len = q ? (size_t)(q - p) : strlen(p);
        char name[512];
        int m, l;
        if (len >= sizeof name) len = sizeof name - 1;
        memcpy(name, p, len);
        name[len] = '\0';
        m = obj_find_material(sc, name);
        l = find_light(r, name);
        if (m >= 0 && l >= 0) {
            fprintf(stderr, PROG ": %s: --light-group %s: '%s' names both a material and a light\n",
                    o->scene, o->groups[g].name, name);
            return -1;
        }
        if (l >= 0) {
            if (group_light(r, g, l, lof, name) < 0) return -1;
            p += len;
            if (*p == ',') p++;
            continue;
        }
        if (m < 0) {
            fprintf(
                stderr,
                PROG
                ": %s: --light-group %s: no material or light named '%s' (--list-materials shows "
                "the materials; lights are sun1, sky1, point1, spot1, ... in the order given, or a "
                "scene file light's name)\n",
                o->scene, o->groups[g].name, name);
            return -1;
        }
        if (of[m] >= 0 && of[m] != g) {
            fprintf(stderr, PROG ": %s: --light-group %s: material '%s' is already in group '%s'\n",
                    o->scene, o->groups[g].name, name, o->groups[of[m]].name);
            return -1;
        }
        of[m] = g;
        if (!emits(&sc->materials[m]) && !o->quiet)
            fprintf(stderr,
                    PROG ": warning: %s: --light-group %s: material '%s' emits no light (Ke 0 0 0; "
                         "--emit sets it)\n",
                    o->scene, o->groups[g].name, name);
        p += len;
        if (*p == ',') p++;
    }
    return 0;
}

/* The group "other" (index OTHER - 1, or none: 0) gets its --group-intensity. */
static int other_intensity(run_t *r, int other)
{
    opts_t *o = r->o;
    int i;
    for (i = 0; i < o->ngint; i++) {
        const char *eq = strrchr(o->gint[i], '=');
        if ((size_t)(eq - o->gint[i]) != strlen(OTHER_GROUP) ||
            strncmp(o->gint[i], OTHER_GROUP, strlen(OTHER_GROUP)) != 0)
            continue;
        if (!other) {
            fprintf(stderr,
                    PROG
                    ": %s: --group-intensity other: every emitting material is in a --light-group, "
                    "so there is no group 'other'\n",
                    o->scene);
            return -1;
        }
        cli_parse_list(eq + 1, o->groups[other - 1].k, 3, 0);
    }
    return 0;
}

/* Material -> group (-1: none, or it emits nothing) and light -> group, after --emit.
 * Adds the group "other" for emitting materials and lights in no group, and applies
 * its --group-intensity. */
static int resolve_groups(run_t *r)
{
    opts_t *o = r->o;
    const obj_scene *sc = &r->sc;
    int *of = malloc((size_t)(sc->nmaterials ? sc->nmaterials : 1) * sizeof *of), g, m, other = 0;
    int *lof = malloc((size_t)(r->nlights + 1) * sizeof *lof);
    r->group_of = of;
    r->light_group_of = lof;
    if (!of || !lof) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    for (m = 0; m < sc->nmaterials; m++) of[m] = -1;
    for (m = 0; m < r->nlights; m++) lof[m] = -1;
    for (g = 0; g < o->nuser_groups; g++)
        if (group_materials(r, g, of, lof) < 0) return -1;
    for (m = 0; m < sc->nmaterials + r->nlights; m++) {
        int *in = m < sc->nmaterials ? &of[m] : &lof[m - sc->nmaterials];
        if (*in >= 0 || (m < sc->nmaterials && !emits(&sc->materials[m]))) continue;
        if (!other) {
            group_t *og = &o->groups[o->ngroups];
            memset(og, 0, sizeof *og);
            strcpy(og->name, OTHER_GROUP);
            og->mats = "";
            og->k[0] = og->k[1] = og->k[2] = 1.0;
            other = ++o->ngroups;
        }
        *in = other - 1;
    }
    if (other_intensity(r, other) < 0) return -1;
    /* Emitting materials outside the user's groups are all in "other": unused if none. */
    for (m = 0; m < sc->nmaterials; m++)
        if (!emits(&sc->materials[m])) of[m] = -1;
    return 0;
}

static int read_text(const char *path, char **text, size_t *len)
{
    char err[1024];
    if (fio_read_all(path, FIO_LIMIT_TEXT, text, len, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    return 0;
}

/* A view of the --views file: its output under the current folder unless
 * --allow-outside-paths (a file from elsewhere must not write ~/.bashrc). */
static int add_file_view(void *ctx, const sc_camera *cam, const char *out, int line, char *why,
                         size_t whylen)
{
    opts_t *o = ctx;
    if (o->nviews >= MAX_VIEWS) {
        snprintf(why, whylen, "too many views (%d)", MAX_VIEWS);
        return 1;
    }
    if (!o->allow_outside && fio_within(".", out) == 0) {
        snprintf(why, whylen,
                 "%.300s is outside the current folder; --allow-outside-paths writes it", out);
        return 1;
    }
    cli_add_view(o, cam, out);
    o->views[o->nviews - 1].line = line;
    return 0;
}

static int read_views(opts_t *o)
{
    char err[1024];
    size_t len;
    if (read_text(o->views_file, &o->views_text, &len) < 0) return -1;
    if (cli_views_parse(o->views_text, len, o->views_file, add_file_view, o, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    return 0;
}

static int read_frames(opts_t *o)
{
    char err[4096];
    size_t len;
    int n;
    if (read_text(o->animate, &o->frames_text, &len) < 0) return -1;
    n = cli_frames_parse(o->frames_text, len, o->animate, o->groups, o->ngroups, &o->frames, err,
                         sizeof err);
    if (n < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    o->nframes = n;
    return 0;
}

/* map_Kd textures: each that fails is one warning and its material keeps Kd. */
static int load_textures(run_t *r)
{
    r->maps = calloc((size_t)r->sc.nmaterials + 1, sizeof *r->maps);
    if (!r->maps) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    if (tex_load_materials(&r->sc, r->maps, obj_warning, r->o, r->o->threads) > 0) {
        r->ot.sc = &r->sc;
        r->ot.maps = r->maps;
    }
    return 0;
}

/* The lights: --sun, --point and --spot's, then the scene file's (obj_scene.lights,
 * unless --no-file-lights). 0 or -1 (said). */
static int gather_lights(run_t *r)
{
    const opts_t *o = r->o;
    int i, nfile = o->no_file_lights ? 0 : r->sc.nlights;
    r->lights = calloc((size_t)(o->nlights + nfile) + 1, sizeof *r->lights);
    if (!r->lights) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    for (i = 0; i < o->nlights; i++) r->lights[r->nlights++] = o->lights[i];
    for (i = 0; i < nfile; i++) {
        const obj_light *l = &r->sc.lights[i];
        sc_light *d = &r->lights[r->nlights++];
        d->type = l->type == OBJ_LIGHT_SUN     ? RAD_LIGHT_SUN
                  : l->type == OBJ_LIGHT_POINT ? RAD_LIGHT_POINT
                                               : RAD_LIGHT_SPOT;
        memcpy(d->pos, l->pos, sizeof d->pos);
        memcpy(d->dir, l->dir, sizeof d->dir);
        memcpy(d->rgb, l->rgb, sizeof d->rgb);
        d->cos_outer = l->cos_outer;
        d->cos_inner = l->cos_inner;
    }
    return 0;
}

/* The scene and everything that names its materials. 1: done (--list-materials). */
/* Faces wound against their vn turned round (warned with the count), or with
 * --two-sided every face doubled back to back (both sides there: nothing to turn). */
static int orient_faces(run_t *r)
{
    const opts_t *o = r->o;
    double area = 0.0;
    int n;
    if (o->two_sided) {
        if (polys_two_sided(&r->sc) == 0) return 0;
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    n = polys_orient_by_normals(&r->sc, &area);
    if (n > 0 && !o->quiet)
        fprintf(stderr,
                PROG ": warning: %s: %d faces (%.1f%% of the area) were wound against their vn "
                     "normals and were "
                     "flipped (a face is lit on one side; --two-sided lights both)\n",
                o->scene, n, 100.0 * area);
    return 0;
}

static int load_step(run_t *r)
{
    opts_t *o = r->o;
    char err[1024];
    obj_opts lo = {0};
    int i, emitters = 0;
    lo.allow_outside = o->allow_outside;
    if ((assimp_scene_wants(o->scene) ? assimp_scene_load : obj_load_opts)(
            o->scene, &lo, &r->sc, o->quiet ? NULL : obj_warning, o, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    r->have_scene = 1;
    if (orient_faces(r) < 0) return -1;
    if (apply_emit(o, &r->sc) < 0) return -1;
    if (!o->no_textures && !o->list && load_textures(r) < 0) return -1;
    for (i = 0; o->no_textures && i < r->sc.nmaterials; i++)
        if (r->sc.materials[i].map_kd.line) obj_map_fallback(&r->sc.materials[i]); /* Kd 0: grey */
    if (o->list) {
        list_materials(&r->sc);
        return 1;
    }
    if (r->sc.nfaces == 0) {
        fprintf(stderr, PROG ": %s: the scene has no faces\n", o->scene);
        return -1;
    }
    if (check_emissions(o, &r->sc) < 0) return -1;
    if (gather_lights(r) < 0) return -1;
    for (i = 0; i < r->sc.nmaterials; i++)
        if (emits(&r->sc.materials[i])) emitters++;
    if (!emitters && !r->nlights && !o->quiet)
        fprintf(
            stderr,
            PROG
            ": warning: %s: no material emits light (Ke), so the image is black; set one with "
            "--emit NAME=R,G,B (--list-materials shows them), or add --sun, --point or --spot\n",
            o->scene);
    if (r->groups_mode && resolve_groups(r) < 0) return -1;
    if (o->animate && read_frames(o) < 0) return -1;
    return 0;
}

/* ---- build: the mesh, and the default camera from what was meshed ---------------- */

/* The bounding box of the OBJ faces that have elements: what was meshed, in the OBJ's
 * own coordinates (a skipped polygon far away must not shrink the picture). 0: none. */
static int meshed_box(const run_t *r, double lo[3], double hi[3])
{
    const obj_scene *sc = &r->sc;
    char *used = calloc((size_t)sc->nfaces + 1, 1);
    int e, f, k, a, any = 0;
    if (!used) return 0;
    for (e = 0; e < r->st.elements; e++) {
        int tag = sc_element_tag(r->s, e);
        if (tag >= 0 && tag < sc->nfaces) used[tag] = 1;
    }
    for (a = 0; a < 3; a++) {
        lo[a] = HUGE_VAL;
        hi[a] = -HUGE_VAL;
    }
    for (f = 0; f < sc->nfaces; f++)
        for (k = 0; used[f] && k < sc->faces[f].count; k++) {
            const double *v = &sc->verts[sc->indices[sc->faces[f].first + k]].x;
            for (a = 0; a < 3; a++) {
                if (v[a] < lo[a]) lo[a] = v[a];
                if (v[a] > hi[a]) hi[a] = v[a];
            }
            any = 1;
        }
    free(used);
    return any;
}

/* Looks along -Z at the centre of the meshed box, from in front of it, +Y up, 45
 * degrees, backed off until the box's front face fits the frame with a 5% margin (the
 * docs/cli.md and --help say so). */
static int default_camera(const run_t *r, sc_camera *c)
{
    double lo[3], hi[3], half[3], ctr[3], t = tan(22.5 * 3.14159265358979323846 / 180.0), fit;
    double aspect = (double)r->o->width / r->o->height;
    int a;
    if (!meshed_box(r, lo, hi)) return -1;
    for (a = 0; a < 3; a++) {
        half[a] = 0.5 * (hi[a] - lo[a]);
        ctr[a] = 0.5 * (hi[a] + lo[a]);
    }
    fit = half[1] > half[0] / aspect ? half[1] : half[0] / aspect;
    for (a = 0; a < 3; a++) {
        c->eye[a] = ctr[a];
        c->target[a] = ctr[a];
        c->up[a] = 0;
    }
    c->eye[2] = ctr[2] + half[2] + 1.05 * fit / t;
    c->up[1] = 1;
    c->fov_deg = 45.0;
    return 0;
}

/* Every face with an area becomes at least one element: more than the solver holds is
 * refused now, before its polygons are made (a 100 MB file of "f 1 2 3" took 3.3 GB
 * to reach the same refusal in sc_create). 0 or -1. */
static int check_face_count(const run_t *r)
{
    sc_opts so;
    long limit, n = 0;
    int f;
    memset(&so, 0, sizeof so);
    limit = sc_element_limit(&so);
    for (f = 0; f < r->sc.nfaces; f++)
        if (obj_face_area(&r->sc, &r->sc.faces[f]) > 0 && ++n > limit) {
            fprintf(
                stderr,
                PROG
                ": %s:%d: face %ld with an area: more than the %ld elements the solver holds (each "
                "face is at least one element): simplify or split the scene\n",
                r->o->scene, r->sc.faces[f].line, n, limit);
            return -1;
        }
    return 0;
}

static int build_step(run_t *r)
{
    opts_t *o = r->o;
    char err[1024];
    int npolys, i;
    sc_camera def;
    sc_poly *polys;
    if (check_face_count(r) < 0) return -1;
    polys = polys_from_obj_tex(&r->sc, r->ot.maps, &npolys, o->quiet ? NULL : poly_warning, o);
    if (!polys) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    r->t_load = host_now();
    memset(&r->so, 0, sizeof r->so);
    r->so.max_patch = o->max_patch;
    r->so.max_element = o->max_element;
    cli_shot_settings(o, r->rows_mode, &r->so);
    r->so.no_overshoot = o->no_overshoot;
    r->so.lights = r->lights;
    r->so.nlights = r->nlights;
    r->s = sc_create(polys, npolys, &r->so, o->quiet ? NULL : glue_warning, r, err, sizeof err);
    r->polys = polys; /* kept for --export-gltf */
    r->npolys = npolys;
    if (!r->s) {
        fprintf(stderr, PROG ": %s: %s\n", o->scene, err);
        return -1;
    }
    /* each element of a textured face: the texture's mean over its own footprint */
    if (r->ot.maps && sc_texture_elements(r->s, &r->sc, r->ot.maps, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s: %s\n", o->scene, err);
        return -1;
    }
    r->t_mesh = host_now();
    sc_get_stats(r->s, &r->st);
    if (default_camera(r, &def) < 0) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    for (i = 0; i < o->nviews; i++)
        if (!o->views[i].has_cam) o->views[i].cam = def;
    return cli_check_cameras(r->s, o);
}

/* ---- outputs --------------------------------------------------------------------- */

static int render_frames(run_t *r)
{
    const opts_t *o = r->o;
    int i, rc = 0;
    for (i = 0; rc == 0 && i < o->nframes; i++) {
        char *path = cli_frame_name(o, i);
        rc = cli_mix_groups(r, r->sol, (const double(*)[3])o->frames[i].k, o->ngroups);
        if (rc == 0) rc = cli_render_view(r->s, o, &o->frames[i].cam, path, r->ambient, &r->ot);
        free(path);
    }
    if (rc == 0)
        rc = cli_mix_groups(r, r->sol, (const double(*)[3])r->ks,
                            o->ngroups); /* for the CSV and PLY */
    return rc;
}

/* The exposure of the whole mix, so each group shows its share of the light. */
static int render_each_group(run_t *r)
{
    const opts_t *o = r->o;
    int g, i, rc = cli_render_view(r->s, o, &o->views[0].cam, NULL, r->ambient, &r->ot);
    for (g = 0; rc == 0 && g < o->ngroups; g++) {
        rc = cli_mix_groups(r, &r->sol[g], (const double(*)[3]) & r->ks[g], 1);
        for (i = 0; rc == 0 && i < o->nviews; i++) {
            char *path = cli_insert_name(o->views[i].out, ".", o->groups[g].name);
            rc = cli_render_view(r->s, o, &o->views[i].cam, path, r->ambient, &r->ot);
            free(path);
        }
    }
    if (rc == 0) rc = cli_mix_groups(r, r->sol, (const double(*)[3])r->ks, o->ngroups);
    return rc;
}

/* --gather's vertices for --export-ply and --export-gltf, once, with progress. */
static int gather_vertices(run_t *r)
{
    progress_t pg;
    int rc;
    progress_begin(&pg, "gathering vertices", r->o->quiet);
    sc_fgather_progress(r->ot.fg, progress_fraction, &pg);
    rc = sc_fgather_vertices(r->ot.fg, NULL, NULL);
    sc_fgather_progress(r->ot.fg, NULL, NULL);
    r->t_vertices = progress_end(&pg);
    if (rc < 0) fprintf(stderr, PROG ": out of memory for the final gather\n");
    return rc;
}

static int output_step(run_t *r)
{
    const opts_t *o = r->o;
    double t;
    int i, rc = 0;
    r->ot.img = malloc((size_t)o->width * o->height * 3 * sizeof *r->ot.img);
    r->ot.rgb8 = malloc((size_t)o->width * o->height * 3);
    if (!r->ot.img || !r->ot.rgb8) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    if (o->gather_res && !(r->ot.fg = sc_fgather_new(r->s, r->polys, r->npolys, o->gather_res,
                                                     o->threads, r->ambient))) {
        fprintf(stderr, PROG ": out of memory for the final gather\n");
        return -1;
    }
    if (o->animate)
        rc = render_frames(r);
    else if (o->each_group)
        rc = render_each_group(r);
    else
        for (i = 0; rc == 0 && i < o->nviews; i++)
            rc = cli_render_view(r->s, o, &o->views[i].cam, o->views[i].out, r->ambient, &r->ot);
    if (rc == 0 && r->ot.fg && (o->ply || o->gltf)) rc = gather_vertices(r);
    if (rc == 0 && o->csv) rc = cli_write_csv(o->csv, r->s, &r->sc, r->ambient, &r->st, &r->ot);
    t = host_now();
    if (rc == 0 && o->ply)
        rc = cli_write_ply(o->ply, r->s, r->ot.fg, r->ambient, o->ply_linear, r->ot.exposure,
                           &r->st);
    r->t_ply = host_now() - t;
    if (rc == 0 && o->gltf && !o->lightmap)
        rc = cli_write_gltf(r, NULL, obj_warning); /* else after the bake */
    return rc < 0 ? -1 : 0;
}

/* ---- --stats ----------------------------------------------------------------------- */

static void print_rows_stats(const run_t *r)
{
    const opts_t *o = r->o;
    const sc_stats *st = &r->st;
    sc_rows_stats rst;
    int g;
    sc_get_rows_stats(r->s, &rst);
    printf("form factor rows: %d %s%s, %lu entries, %zu bytes (%.0f bytes per patch), %s\n",
           rst.rows, o->load_ff ? "loaded from " : "computed", o->load_ff ? o->load_ff : "",
           rst.entries, rst.bytes, rst.rows ? (double)rst.bytes / rst.rows : 0.0,
           o->save_ff ? "saved" : "not saved");
    printf("solve from rows: %s, %lu polygons rendered during the solve (%s)\n",
           o->gauss_seidel ? "gauss-seidel" : "shoot", st->raster_calls - r->raster_before_solve,
           r->nlights ? "the lights' direct shots: no hemi-cube" : "no hemi-cube");
    if (r->groups_mode) {
        printf("light groups %d:", o->ngroups);
        for (g = 0; g < o->ngroups; g++)
            printf(" %s (%g,%g,%g)", o->groups[g].name, o->groups[g].k[0], o->groups[g].k[1],
                   o->groups[g].k[2]);
        printf("\n");
    }
    if (o->gauss_seidel && rst.matrix_bytes)
        printf("gauss-seidel matrix %zu bytes\n", rst.matrix_bytes);
}

/* Every stage's time on one line: those of the outputs asked for after the views'. */
static void print_times(const run_t *r)
{
    const opts_t *o = r->o;
    printf("time: load %.3fs  mesh %.3fs", r->t_load - r->t0, r->t_mesh - r->t_load);
    if (r->rows_mode) printf("  rows %.3fs", r->t_rows);
    if (o->lightmap || o->probes || o->probe_file) printf("  layout %.3fs", r->t_layout);
    printf("  solve %.3fs  render %.3fs  write %.3fs",
           r->t_solve - r->t_mesh - r->t_layout - r->t_rows, r->ot.t_render, r->ot.t_write);
    if (r->ot.fg && (o->ply || o->gltf)) printf("  vertex gathers %.3fs", r->t_vertices);
    if (o->csv) printf("  csv %.3fs", r->ot.t_csv);
    if (o->ply) printf("  ply %.3fs", r->t_ply);
    if (o->lightmap) printf("  lightmap %.3fs", r->t_lightmap);
    if (o->probes || o->probe_file) printf("  probes %.3fs", r->t_probes);
    if (o->gltf) printf("  gltf %.3fs", r->ot.t_gltf);
    printf("\n");
}

static void print_stats(const run_t *r)
{
    const opts_t *o = r->o;
    const sc_stats *st = &r->st;
    printf("surfaces %d (split quads %d, skipped %d, reflectances clamped %d)\n", st->surfaces,
           st->split, st->skipped, st->clamped);
    printf("patches %d  elements %d  vertices %d\n", st->patches, st->elements, st->vertices);
    if (r->rows_mode && o->gauss_seidel)
        printf("shots 0  gauss-seidel sweeps %d  saturations %lu\n", r->work, st->saturations);
    else
        printf("shots %d  unshot fraction %.6f  saturations %lu\n",
               r->rows_mode ? r->work : st->shots, st->unshot, st->saturations);
    printf("hemi-cube: resolution %d, %lu polygons, %llu pixels\n", r->so.res, st->raster_calls,
           st->raster_pixels);
    printf("overshoot back-offs %lu\n", st->backoffs);
    if (r->ot.fg)
        printf("final gather: resolution %d, %ld pixel gathers\n", o->gather_res, r->ot.gathers);
    printf("coarse shots %lu (below an unshot fraction of %g, down to res %d)\n", st->coarse_shots,
           r->so.coarse, r->so.coarse_res);
    if (r->rows_mode) print_rows_stats(r);
    printf("unknown statements skipped %ld, warnings %ld\n", r->sc.unknown_statements,
           r->sc.nwarnings);
    printf("exposure %.9g (%s%s)\n", r->ot.exposure,
           o->exposure > 0 ? "--exposure" : "automatic, from the first view",
           o->ply && !o->ply_linear ? "; also --export-ply's sRGB colours" : "");
    if (r->landing >= 0)
        printf("emitted light reaching front faces %.1f%% (the rest leaves the scene or meets back "
               "faces)\n",
               100 * r->landing);
    print_times(r);
    cli_print_export_stats(o, &r->ot);
    printf("memory: pools %zu bytes, work buffer %zu bytes\n", st->pool_bytes, st->work_bytes);
}

/* ---- what the run says after its outputs ---------------------------------------------- */

/* Most of the emitted light lost at its first bounce: a flat, dark picture with no
 * error, so a warning says why. */
#define LANDING_WARN 0.5

static void balance_step(run_t *r)
{
    r->landing = cli_emitted_share_landing(r);
    if (r->landing >= 0 && r->landing < LANDING_WARN && !r->o->quiet)
        fprintf(
            stderr,
            PROG
            ": warning: %s: only %.0f%% of the emitted light reaches a face from its front: the "
            "rest "
            "leaves the scene or meets faces seen from behind (radiosity is one-sided: wind faces "
            "counter-clockwise seen from their lit side)\n",
            r->o->scene, 100 * r->landing);
}

/* CLI_EXIT_WARNED with one line each when the solve stopped short or saturated. */
static int verdict(const run_t *r)
{
    const opts_t *o = r->o;
    int rc = CLI_EXIT_OK;
    if (r->unconverged && o->gauss_seidel) {
        fprintf(stderr,
                PROG
                ": %s: not converged: Gauss-Seidel stopped at its sweep limit above --tol %g; the "
                "outputs show that partial solution (raise --tol)\n",
                o->scene, o->tol);
        rc = CLI_EXIT_WARNED;
    } else if (r->unconverged) {
        fprintf(
            stderr,
            PROG
            ": %s: not converged: the unshot fraction is %g, above --tol %g, at --max-shots %d%s; "
            "the outputs show that partial solution (raise --max-shots or --tol)\n",
            o->scene, r->st.unshot, o->tol, o->max_shots,
            r->groups_mode ? " (in a light group)" : "");
        rc = CLI_EXIT_WARNED;
    }
    if (r->st.saturations) {
        fprintf(stderr,
                PROG
                ": %s: %lu values saturated at the core's range, so some radiosities are clipped "
                "(reflectances near 1 keep more light than it holds: lower them)\n",
                o->scene, r->st.saturations);
        rc = CLI_EXIT_WARNED;
    }
    return rc;
}

/* ---- main -------------------------------------------------------------------------- */

static void free_run(run_t *r)
{
    int g;
    if (r->sol)
        for (g = 0; g < r->o->ngroups; g++) sc_solution_free(r->sol[g]);
    free(r->sol);
    free(r->ks);
    free(r->group_of);
    free(r->light_group_of);
    free(r->ot.img);
    free(r->ot.rgb8);
    sc_fgather_free(r->ot.fg);
    cli_bake_free(r);
    if (r->s) sc_destroy(r->s);
    free(r->polys);
    free(r->lights);
    for (g = 0; r->maps && g < r->sc.nmaterials; g++) tex_free(&r->maps[g]);
    free(r->maps);
    if (r->have_scene) obj_free(&r->sc);
    cli_free_opts(r->o);
}

/* The views: --views' file, or the default view; every output name checked. */
static int views_step(opts_t *o)
{
    if (o->views_file && read_views(o) < 0) return -1;
    if (o->nviews == 0) {
        o->default_out = cli_default_output(o->scene);
        if (!o->default_out) {
            fprintf(stderr, PROG ": out of memory\n");
            return -1;
        }
        cli_add_view(o, NULL, o->default_out);
    }
    if ((o->probes || o->probe_file) && !o->probes_out &&
        !(o->probes_out = o->probes_default = cli_probes_output(o->scene))) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    if (!o->list) cli_check_outputs(o);
    return 0;
}

int main(int argc, char **argv)
{
    static opts_t o;
    run_t r;
    int rc, solved;
    memset(&r, 0, sizeof r);
    r.o = &o;
    r.t0 = host_now();
    cli_parse_args(argc, argv, &o);
    r.ambient = !o.no_ambient;
    r.rows_mode = o.save_ff || o.load_ff || o.gauss_seidel || o.nuser_groups || o.animate;
    r.groups_mode = o.nuser_groups || o.animate;
    rc = views_step(&o);
    if (rc == 0) rc = load_step(&r);
    if (rc > 0) { /* --list-materials: done */
        free_run(&r);
        return CLI_EXIT_OK;
    }
    if (rc == 0) cli_check_group_outputs(&o);
    if (rc == 0) rc = cli_check_collisions(&o, &r.sc);
    if (rc == 0) rc = build_step(&r);
    if (rc == 0) rc = cli_bake_prepare(&r);
    if (rc == 0) rc = cli_solve_step(&r);
    solved = rc == 0;
    if (rc == 0) rc = output_step(&r);
    if (rc == 0) rc = cli_bake_step(&r);
    if (rc == 0) rc = cli_bake_export_gltf(&r, obj_warning);
    if (solved) balance_step(&r);
    if (o.stats && solved) print_stats(&r);
    if (rc == 0) rc = verdict(&r);
    free_run(&r);
    return rc < 0 ? CLI_EXIT_ERROR : rc;
}
