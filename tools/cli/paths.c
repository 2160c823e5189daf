/* SPDX-License-Identifier: MIT */
/* rad_cli's outputs against its inputs and each other, by file identity, before the
 * solve: no run writes over its own scene, library, texture, --views file or stored
 * rows, nor writes two outputs to one file (the second would replace the first). */
#include "cli.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "formats/file_io.h"

/* A file the run reads or writes, and what it is to the run (for the message). */
typedef struct {
    const char *path;
    char *owned;    /* PATH when the list made it (frame and group names) */
    char what[200]; /* "the scene", "--export-ply", ... */
    int kind;       /* FILE_NONE: not compared (a device, a FIFO: written in place, never
                       replaced); FILE_OLD: a regular file (dev, ino); FILE_NEW: none yet (real) */
    dev_t dev;
    ino_t ino;
    char *real; /* fio_resolve(path) of a file not yet written */
} named_t;

enum { FILE_NONE, FILE_OLD, FILE_NEW };

typedef struct {
    named_t *v;
    int n, cap, failed;
} list_t;

static void add(list_t *l, const char *path, char *owned, const char *fmt, ...)
{
    named_t *e;
    struct stat st;
    va_list ap;
    if (!path) path = owned;
    if (!path || l->failed) {
        free(owned);
        return;
    }
    if (l->n == l->cap) {
        named_t *q = realloc(l->v, (size_t)(l->cap = l->cap ? 2 * l->cap : 32) * sizeof *q);
        if (!q) {
            l->failed = 1;
            free(owned);
            return;
        }
        l->v = q;
    }
    e = &l->v[l->n++];
    memset(e, 0, sizeof *e);
    e->path = path;
    e->owned = owned;
    va_start(ap, fmt);
    vsnprintf(e->what, sizeof e->what, fmt, ap);
    va_end(ap);
    if (stat(path, &st) == 0) { /* symbolic links followed: the file they lead to */
        e->kind = S_ISREG(st.st_mode) ? FILE_OLD : FILE_NONE;
        e->dev = st.st_dev;
        e->ino = st.st_ino;
    } else if ((e->real = fio_resolve(path)) != NULL) {
        e->kind = FILE_NEW;
    }
}

static int same(const named_t *a, const named_t *b)
{
    if (a->kind == FILE_OLD && b->kind == FILE_OLD) return a->dev == b->dev && a->ino == b->ino;
    return a->kind == FILE_NEW && b->kind == FILE_NEW && !strcmp(a->real, b->real);
}

static void free_list(list_t *l)
{
    int i;
    for (i = 0; i < l->n; i++) {
        free(l->v[i].owned);
        free(l->v[i].real);
    }
    free(l->v);
}

static void inputs(const opts_t *o, const obj_scene *sc, list_t *in)
{
    int i;
    if (strcmp(o->scene, "-")) add(in, o->scene, NULL, "the scene");
    for (i = 0; i < sc->nlibs; i++) add(in, sc->libs[i], NULL, "the scene's material library");
    for (i = 0; i < sc->nmaterials; i++)
        if (sc->materials[i].map_kd.path)
            add(in, sc->materials[i].map_kd.path, NULL,
                "the texture of material '%.60s' (%.60s:%d)", sc->materials[i].name,
                sc->materials[i].map_kd.mtl, sc->materials[i].map_kd.line);
    add(in, o->views_file, NULL, "the --views file");
    add(in, o->animate, NULL, "the --animate file");
    add(in, o->probe_file, NULL, "the --probe-file");
    add(in, o->load_ff, NULL, "the --load-ff file");
    for (i = 0; i < o->nlight_files; i++)
        add(in, o->light_files[i], NULL, "a --lights or --sky-hdr file");
}

static void outputs(const opts_t *o, list_t *out)
{
    int i, g;
    for (i = 0; !o->animate && !o->each_group && i < o->nviews; i++) {
        const view_t *v = &o->views[i];
        if (v->line)
            add(out, v->out, NULL, "the image of %.100s:%d (--views)", o->views_file, v->line);
        else if (v->out == o->default_out)
            add(out, v->out, NULL, "the default image (the scene's name + .png; -o sets it)");
        else
            add(out, v->out, NULL, "the image of -o");
    }
    for (i = 0; o->animate && i < o->nframes; i++)
        add(out, NULL, cli_frame_name(o, i), "frame %d of --animate (-o's name + _%04d)", i, i);
    for (g = 0; o->each_group && g < o->ngroups; g++)
        for (i = 0; i < o->nviews; i++)
            add(out, NULL, cli_insert_name(o->views[i].out, ".", o->groups[g].name),
                "the image of group %s (--each-group)", o->groups[g].name);
    add(out, o->ply, NULL, "--export-ply");
    add(out, o->csv, NULL, "--dump-radiosity");
    add(out, o->gltf, NULL, "--export-gltf");
    add(out, o->save_ff, NULL, "--save-ff");
    add(out, o->lightmap, NULL, "--lightmap");
    add(out, o->probes_out, NULL, "--probes-out");
}

int cli_check_collisions(const opts_t *o, const obj_scene *sc)
{
    list_t in = {NULL, 0, 0, 0}, out = {NULL, 0, 0, 0};
    int i, j, rc = 0;
    inputs(o, sc, &in);
    outputs(o, &out);
    if (in.failed || out.failed) {
        fprintf(stderr, PROG ": out of memory\n");
        rc = -1;
    }
    for (i = 0; rc == 0 && i < out.n; i++) {
        const named_t *a = &out.v[i];
        for (j = 0; rc == 0 && j < in.n; j++)
            if (same(a, &in.v[j])) {
                fprintf(stderr,
                        PROG
                        ": %s: %s would write over %s %s (the same file): give it another name\n",
                        a->path, a->what, in.v[j].what, in.v[j].path);
                rc = -1;
            }
        for (j = 0; rc == 0 && j < i; j++)
            if (same(a, &out.v[j])) {
                fprintf(stderr, PROG ": %s: %s and %s write the same file: give one another name\n",
                        a->path, out.v[j].what, a->what);
                rc = -1;
            }
    }
    free_list(&in);
    free_list(&out);
    return rc;
}
