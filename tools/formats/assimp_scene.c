/* SPDX-License-Identifier: MIT */
/* assimp_scene — other scene formats through assimp's C API (see assimp_scene.h). */
#include "formats/assimp_scene.h"

#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/file_io.h"

/* 1 if PATH ends in "." EXT, in any case. */
static int has_ext(const char *path, const char *ext)
{
    const char *dot = path ? strrchr(path, '.') : NULL;
    size_t i;
    if (!dot || strchr(dot, '/')) return 0;
    for (i = 0; ext[i]; i++)
        if (tolower((unsigned char)dot[1 + i]) != ext[i]) return 0;
    return dot[1 + i] == '\0';
}

int assimp_scene_wants(const char *path)
{
    return !(path && !strcmp(path, "-")) && !has_ext(path, "obj");
}

#ifndef RAD_HAVE_ASSIMP

int assimp_scene_available(void)
{
    return 0;
}

int assimp_scene_load(const char *path, const obj_opts *opts, obj_scene *sc, obj_warn_fn warn,
                      void *ctx, char *err, size_t errlen)
{
    FILE *f;
    (void)opts;
    (void)warn;
    (void)ctx;
    memset(sc, 0, sizeof *sc);
    /* what is wrong with the file itself first (missing, a FIFO, a folder) */
    if (!(f = fio_open_read(path, err, errlen))) return -1;
    fclose(f);
    fio_err(err, errlen, path,
            "this rad_cli reads only .obj: it was built without assimp, which reads glTF, "
            "FBX, COLLADA and 3DS (apt-get install libassimp-dev, then make again)");
    return -1;
}

#else

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

int assimp_scene_available(void)
{
    return 1;
}

/* ---- files: every one assimp opens, read whole through file_io ------------------- */

typedef struct {
    char *data;
    size_t size, pos;
} mem_file;

static size_t mf_read(struct aiFile *f, char *buf, size_t size, size_t count)
{
    mem_file *m = (mem_file *)f->UserData;
    size_t left = m->size - m->pos, n;
    if (size == 0) return 0;
    n = count < left / size ? count : left / size;
    memcpy(buf, m->data + m->pos, n * size);
    m->pos += n * size;
    return n;
}

static size_t mf_write(struct aiFile *f, const char *buf, size_t size, size_t count)
{
    (void)f;
    (void)buf;
    (void)size;
    (void)count;
    return 0;
}

static size_t mf_tell(struct aiFile *f)
{
    return ((mem_file *)f->UserData)->pos;
}

static size_t mf_size(struct aiFile *f)
{
    return ((mem_file *)f->UserData)->size;
}

static enum aiReturn mf_seek(struct aiFile *f, size_t off, enum aiOrigin how)
{
    mem_file *m = (mem_file *)f->UserData;
    size_t base = how == aiOrigin_SET ? 0 : how == aiOrigin_CUR ? m->pos : m->size;
    if (how != aiOrigin_SET && how != aiOrigin_CUR && how != aiOrigin_END) return aiReturn_FAILURE;
    if (off > m->size - base) return aiReturn_FAILURE;
    m->pos = base + off;
    return aiReturn_SUCCESS;
}

static void mf_flush(struct aiFile *f)
{
    (void)f;
}

/* The scene's folder and whether files may come from outside it, and the first
 * refusal, kept for the error message (assimp's own says only that it could not open
 * the file). */
typedef struct {
    const char *scene;
    char dir[4096];
    int allow_outside;
    char why[8800];
} io_state;

/* The folder of PATH with its slash ("dir/"), or "" for a bare name. */
static size_t dir_len(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? (size_t)(s - path) + 1 : 0;
}

/* 1 when PATH leads out of the scene's folder and that is not allowed (a file that does
 * not resolve is not outside: its reader says it is missing). */
static int outside(const io_state *st, const char *path)
{
    return !st->allow_outside && fio_within(st->dir, path) == 0;
}

static struct aiFile *mf_open(struct aiFileIO *io, const char *path, const char *mode)
{
    io_state *st = (io_state *)io->UserData;
    struct aiFile *f;
    mem_file *m;
    char err[512];
    if (!mode || strchr(mode, 'w') || strchr(mode, 'a') || strchr(mode, '+')) return NULL;
    if (outside(st, path)) {
        if (!st->why[0])
            snprintf(st->why, sizeof st->why,
                     "%s: %s is outside the scene's folder %s; --allow-outside-paths reads it",
                     st->scene, path, st->dir);
        return NULL;
    }
    f = calloc(1, sizeof *f);
    m = calloc(1, sizeof *m);
    if (!f || !m || fio_read_all(path, FIO_LIMIT_OBJ, &m->data, &m->size, err, sizeof err) < 0) {
        if (f && m && !st->why[0]) /* err names PATH; the scene's name first if another */
            snprintf(st->why, sizeof st->why, "%s%s%s", strcmp(path, st->scene) ? st->scene : "",
                     strcmp(path, st->scene) ? ": " : "", err);
        free(f);
        free(m);
        return NULL;
    }
    f->ReadProc = mf_read;
    f->WriteProc = mf_write;
    f->TellProc = mf_tell;
    f->FileSizeProc = mf_size;
    f->SeekProc = mf_seek;
    f->FlushProc = mf_flush;
    f->UserData = (aiUserData)m;
    return f;
}

static void mf_close(struct aiFileIO *io, struct aiFile *f)
{
    (void)io;
    if (!f) return;
    free(((mem_file *)f->UserData)->data);
    free(f->UserData);
    free(f);
}

/* ---- the scene ------------------------------------------------------------------- */

typedef struct {
    obj_scene *sc;
    const struct aiScene *ai;
    int half_angles; /* spot cones given as half angles (glTF), else full (assimp's rule) */
    char *placed;    /* per assimp light: placed by its node */
    int cap_verts, cap_idx, cap_uvi, cap_ni, cap_uvs, cap_normals, cap_names, cap_faces, cap_uv2,
        cap_nodes;
    long uv2_corners; /* corners given a second UV set */
    int *mat_of;      /* assimp material -> obj material */
} build;

/* Grows *P (of *CAP elements of SIZE bytes) to hold NEED; 0, or -1 when NEED passes
 * INT_MAX / 2 (the obj_scene's int counts) or memory runs out. */
static int grow(void **p, int *cap, long need, size_t size)
{
    long n = *cap ? *cap : 64;
    void *q;
    if (need <= *cap) return 0;
    if (need > INT_MAX / 2) return -1;
    while (n < need) n *= 2;
    q = realloc(*p, (size_t)n * size);
    if (!q) return -1;
    *p = q;
    *cap = (int)n;
    return 0;
}

static char *dup_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

typedef struct {
    double m[3][4]; /* rows: x' = m[0][0] x + m[0][1] y + m[0][2] z + m[0][3] */
} xform;

static xform xf_mul(const xform *a, const struct aiMatrix4x4 *b)
{
    const double bm[3][4] = {
        {b->a1, b->a2, b->a3, b->a4}, {b->b1, b->b2, b->b3, b->b4}, {b->c1, b->c2, b->c3, b->c4}};
    xform r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 4; j++)
            r.m[i][j] = a->m[i][0] * bm[0][j] + a->m[i][1] * bm[1][j] + a->m[i][2] * bm[2][j] +
                        (j == 3 ? a->m[i][3] : 0.0);
    return r;
}

static double xf_det(const xform *t)
{
    const double(*m)[4] = t->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* Normals go through the cofactor matrix (det times the inverse transpose), times the
 * sign of det so that a mirror keeps them pointing out of the same side. */
static obj_vec3 xf_normal(const xform *t, double sign, const struct aiVector3D *n)
{
    const double(*m)[4] = t->m;
    double c[3][3];
    obj_vec3 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            c[i][j] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
        }
    r.x = sign * (c[0][0] * n->x + c[0][1] * n->y + c[0][2] * n->z);
    r.y = sign * (c[1][0] * n->x + c[1][1] * n->y + c[1][2] * n->z);
    r.z = sign * (c[2][0] * n->x + c[2][1] * n->y + c[2][2] * n->z);
    return r;
}

static int add_mesh(build *b, const struct aiMesh *me, const xform *t, int object)
{
    obj_scene *sc = b->sc;
    const double det = xf_det(t), sign = det < 0 ? -1.0 : 1.0;
    const int v0 = sc->nverts, t0 = sc->nuvs, n0 = sc->nnormals;
    const int has_uv = me->mTextureCoords[0] != NULL, has_n = me->mNormals != NULL;
    const int has_uv2 = me->mTextureCoords[1] != NULL;
    unsigned i, k;
    long nv = (long)sc->nverts + me->mNumVertices;
    if (grow((void **)&sc->verts, &b->cap_verts, nv, sizeof *sc->verts) ||
        (has_uv && grow((void **)&sc->uvs, &b->cap_uvs, (long)sc->nuvs + me->mNumVertices,
                        sizeof *sc->uvs)) ||
        (has_n && grow((void **)&sc->normals, &b->cap_normals,
                       (long)sc->nnormals + me->mNumVertices, sizeof *sc->normals)))
        return -1;
    for (i = 0; i < me->mNumVertices; i++) {
        const struct aiVector3D *p = &me->mVertices[i];
        obj_vec3 *v = &sc->verts[sc->nverts++];
        v->x = t->m[0][0] * p->x + t->m[0][1] * p->y + t->m[0][2] * p->z + t->m[0][3];
        v->y = t->m[1][0] * p->x + t->m[1][1] * p->y + t->m[1][2] * p->z + t->m[1][3];
        v->z = t->m[2][0] * p->x + t->m[2][1] * p->y + t->m[2][2] * p->z + t->m[2][3];
        if (has_uv) {
            sc->uvs[sc->nuvs].u = me->mTextureCoords[0][i].x;
            sc->uvs[sc->nuvs++].v = me->mTextureCoords[0][i].y;
        }
        if (has_n) sc->normals[sc->nnormals++] = xf_normal(t, sign, &me->mNormals[i]);
    }
    for (i = 0; i < me->mNumFaces; i++) {
        const struct aiFace *f = &me->mFaces[i];
        long ni = (long)sc->nindices + f->mNumIndices;
        obj_face *of;
        if (f->mNumIndices < 3) {
            sc->unknown_statements++;
            continue;
        }
        if (grow((void **)&sc->faces, &b->cap_faces, (long)sc->nfaces + 1, sizeof *sc->faces))
            return -1;
        if (grow((void **)&sc->indices, &b->cap_idx, ni, sizeof(int)) ||
            grow((void **)&sc->uv_indices, &b->cap_uvi, ni, sizeof(int)) ||
            grow((void **)&sc->normal_indices, &b->cap_ni, ni, sizeof(int)) ||
            grow((void **)&sc->uv2, &b->cap_uv2, ni, sizeof *sc->uv2))
            return -1;
        of = &sc->faces[sc->nfaces++];
        of->material = b->mat_of[me->mMaterialIndex];
        of->first = sc->nindices;
        of->count = (int)f->mNumIndices;
        of->line = 0;
        of->object = object;
        of->group = -1;
        for (k = 0; k < f->mNumIndices; k++) {
            /* a mirror reverses the order, so the winding's front stays the normals' */
            unsigned j = sign < 0 ? f->mNumIndices - 1 - k : k, vi = f->mIndices[j];
            if (vi >= me->mNumVertices) return -1; /* aiProcess_ValidateDataStructure's */
            sc->indices[sc->nindices] = v0 + (int)vi;
            sc->uv_indices[sc->nindices] = has_uv ? t0 + (int)vi : -1;
            sc->normal_indices[sc->nindices] = has_n ? n0 + (int)vi : -1;
            sc->uv2[sc->nindices].u = has_uv2 ? me->mTextureCoords[1][vi].x : NAN;
            sc->uv2[sc->nindices].v = has_uv2 ? me->mTextureCoords[1][vi].y : NAN;
            b->uv2_corners += has_uv2;
            sc->nindices++;
        }
        sc->materials[of->material].nfaces++;
    }
    return 0;
}

static int add_name(build *b, const struct aiString *s)
{
    obj_scene *sc = b->sc;
    char *d;
    if (s->length == 0) return -1;
    if (grow((void **)&sc->names, &b->cap_names, (long)sc->nnames + 1, sizeof *sc->names))
        return -2;
    d = dup_str(s->data);
    if (!d) return -2;
    sc->names[sc->nnames] = d;
    return sc->nnames++;
}

/* Assimp light I placed by transform T (of its node, or the identity) into the scene's
 * next entry; a light of another kind (ambient, area) is left out, counted. */
static int add_light(build *b, unsigned i, const xform *t)
{
    const struct aiLight *l = b->ai->mLights[i];
    obj_light *o = &b->sc->lights[b->sc->nlights];
    const struct aiVector3D *p = &l->mPosition, *d = &l->mDirection;
    double len, half = b->half_angles ? 1.0 : 0.5;
    int k;
    b->placed[i] = 1;
    memset(o, 0, sizeof *o);
    o->type = l->mType == aiLightSource_DIRECTIONAL ? OBJ_LIGHT_SUN
              : l->mType == aiLightSource_POINT     ? OBJ_LIGHT_POINT
              : l->mType == aiLightSource_SPOT      ? OBJ_LIGHT_SPOT
                                                    : 0;
    if (!o->type) {
        b->sc->unknown_statements++;
        return 0;
    }
    for (k = 0; k < 3; k++) {
        o->pos[k] = t->m[k][0] * p->x + t->m[k][1] * p->y + t->m[k][2] * p->z + t->m[k][3];
        o->dir[k] = t->m[k][0] * d->x + t->m[k][1] * d->y + t->m[k][2] * d->z;
    }
    len = sqrt(o->dir[0] * o->dir[0] + o->dir[1] * o->dir[1] + o->dir[2] * o->dir[2]);
    for (k = 0; k < 3; k++) o->dir[k] = len > 0 ? o->dir[k] / len : (k == 2 ? -1.0 : 0.0);
    o->rgb[0] = l->mColorDiffuse.r;
    o->rgb[1] = l->mColorDiffuse.g;
    o->rgb[2] = l->mColorDiffuse.b;
    if (o->type == OBJ_LIGHT_SPOT) {
        o->cos_outer = cos(half * l->mAngleOuterCone);
        o->cos_inner = cos(half * l->mAngleInnerCone);
        if (o->cos_inner < o->cos_outer) o->cos_inner = o->cos_outer;
    }
    o->name = dup_str(l->mName.data);
    if (!o->name) return -1;
    b->sc->nlights++;
    return 0;
}

/* NODE (world transform T, parent PARENT, its faces' OBJECT) as the scene's next
 * obj_node; its index, or -1 out of memory. */
static void local_matrix(const struct aiNode *node, double local[16])
{
    const struct aiMatrix4x4 *m = &node->mTransformation;
    const double c[16] = {m->a1, m->b1, m->c1, m->d1, m->a2, m->b2, m->c2, m->d2,
                          m->a3, m->b3, m->c3, m->d3, m->a4, m->b4, m->c4, m->d4};
    memcpy(local, c, sizeof c);
}

static int add_node(build *b, const struct aiNode *node, const xform *t, int parent, int object)
{
    obj_scene *sc = b->sc;
    double local[16];
    obj_node *n;
    local_matrix(node, local);
    if (grow((void **)&sc->nodes, &b->cap_nodes, (long)sc->nnodes + 1, sizeof *sc->nodes))
        return -1;
    n = &sc->nodes[sc->nnodes];
    n->name = dup_str(node->mName.data);
    if (!n->name) return -1;
    n->parent = parent;
    n->object = object;
    memcpy(n->local, local, sizeof local);
    memcpy(n->world, t->m, sizeof n->world);
    return sc->nnodes++;
}

/* 1 for the root assimp adds above a file's several roots (glTF's "ROOT", FBX's
 * "RootNode"): no mesh, the identity. Left out of the scene's nodes. */
static int added_root(const struct aiNode *node, int depth)
{
    double m[16];
    int k;
    local_matrix(node, m);
    for (k = 0; k < 16; k++)
        if (m[k] != (k % 5 == 0)) return 0; /* the diagonal 1, the rest 0 */
    return depth == 0 && !node->mNumMeshes;
}

/* Depth first from NODE with its parents' transform T and obj_node PARENT (-1: none);
 * DEPTH bounds a cyclic or absurd hierarchy (assimp's validation refuses cycles; this
 * is belt and braces). */
static int walk(build *b, const struct aiNode *node, const xform *parent, int depth, int up)
{
    xform t = xf_mul(parent, &node->mTransformation);
    int object = -1, me = up;
    unsigned i;
    if (depth > 1000) return -1;
    if (node->mNumMeshes) {
        object = add_name(b, &node->mName);
        if (object == -2) return -1;
    }
    if (!added_root(node, depth) && (me = add_node(b, node, &t, up, object)) < 0) return -1;
    for (i = 0; i < b->ai->mNumLights; i++) /* a light is placed by the node of its name */
        if (!b->placed[i] && !strcmp(b->ai->mLights[i]->mName.data, node->mName.data) &&
            add_light(b, i, &t) < 0)
            return -1;
    for (i = 0; i < node->mNumMeshes; i++) {
        unsigned mi = node->mMeshes[i];
        if (mi >= b->ai->mNumMeshes || add_mesh(b, b->ai->mMeshes[mi], &t, object) < 0) return -1;
    }
    for (i = 0; i < node->mNumChildren; i++)
        if (walk(b, node->mChildren[i], &t, depth + 1, me) < 0) return -1;
    return 0;
}

static void warnf(obj_warn_fn warn, void *ctx, obj_scene *sc, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    sc->nwarnings++;
    if (!warn) return;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    warn(ctx, msg);
}

static int get_rgb(const struct aiMaterial *m, const char *key, unsigned type, unsigned idx,
                   double rgb[3])
{
    struct aiColor4D c;
    if (aiGetMaterialColor(m, key, type, idx, &c) != aiReturn_SUCCESS) return 0;
    rgb[0] = c.r;
    rgb[1] = c.g;
    rgb[2] = c.b;
    return 1;
}

/* The embedded texture a material's texture name TEX means: "*N" (glTF, and what
 * assimp names others), or the file name an embedded texture keeps (FBX); -1: a file. */
static int embedded(const build *b, const struct aiString *tex)
{
    unsigned i;
    if (tex->data[0] == '*') {
        char *end;
        long n = strtol(tex->data + 1, &end, 10);
        return *end == '\0' && end > tex->data + 1 && n >= 0 && n < (long)b->ai->mNumTextures
                   ? (int)n
                   : -2;
    }
    for (i = 0; i < b->ai->mNumTextures; i++)
        if (b->ai->mTextures[i]->mFilename.length &&
            !strcmp(b->ai->mTextures[i]->mFilename.data, tex->data))
            return (int)i;
    return -1;
}

/* Material OM's map from embedded texture K (-2: a "*N" past the file's textures): its
 * bytes copied, named "SCENE/texture K (embedded)" (a path under a file: never a file
 * that could be read instead). A texture of raw texels, not a file's bytes, is not read:
 * a warning, and the colour. 0, or -1 without memory. */
static int embed_map(build *b, obj_material *om, const char *path, int k, obj_warn_fn warn,
                     void *ctx)
{
    const struct aiTexture *t = k >= 0 ? b->ai->mTextures[k] : NULL;
    size_t n = strlen(path) + 40;
    if (!t || t->mHeight != 0) {
        obj_map_fallback(om);
        warnf(warn, ctx, b->sc, "%s: material %s: %s; using its colour %g %g %g", path, om->name,
              t ? "its embedded texture holds raw texels, which rad does not read"
                : "its texture names none of the file's embedded textures",
              om->kd[0], om->kd[1], om->kd[2]);
        return 0;
    }
    om->map_kd.path = malloc(n);
    om->map_kd.data = malloc(t->mWidth ? t->mWidth : 1);
    if (!om->map_kd.path || !om->map_kd.data) return -1;
    snprintf(om->map_kd.path, n, "%s/texture %d (embedded)", path, k);
    memcpy(om->map_kd.data, t->pcData, t->mWidth);
    om->map_kd.size = t->mWidth;
    return 0;
}

static int add_material(build *b, const io_state *st, const char *path, unsigned i,
                        obj_warn_fn warn, void *ctx)
{
    const struct aiMaterial *m = b->ai->mMaterials[i];
    obj_scene *sc = b->sc;
    obj_material *om = &sc->materials[sc->nmaterials];
    struct aiString name, tex;
    char buf[1100];
    float strength = 1.0f;
    unsigned n = 1;
    if (aiGetMaterialString(m, AI_MATKEY_NAME, &name) != aiReturn_SUCCESS || name.length == 0)
        snprintf(buf, sizeof buf, "material%u", i);
    else
        snprintf(buf, sizeof buf, "%s", name.data);
    while (obj_find_material(sc, buf) >= 0) { /* unique names, for --emit and --light-group */
        char base[1024];
        snprintf(base, sizeof base, "%s", name.length ? name.data : "material");
        snprintf(buf, sizeof buf, "%s#%u", base, n++);
    }
    memset(om, 0, sizeof *om);
    om->name = dup_str(buf);
    om->map_kd.scale[0] = om->map_kd.scale[1] = 1.0;
    if (!om->name) return -1;
    sc->nmaterials++; /* freed by obj_free from here on */
    om->defined = 1;
    om->kd[0] = om->kd[1] = om->kd[2] = 0.8;
    if (!get_rgb(m, AI_MATKEY_BASE_COLOR, om->kd)) get_rgb(m, AI_MATKEY_COLOR_DIFFUSE, om->kd);
    if (get_rgb(m, AI_MATKEY_COLOR_EMISSIVE, om->ke) &&
        aiGetMaterialFloatArray(m, AI_MATKEY_EMISSIVE_INTENSITY, &strength, NULL) ==
            aiReturn_SUCCESS) {
        om->ke[0] *= strength;
        om->ke[1] *= strength;
        om->ke[2] *= strength;
    }
    if (aiGetMaterialTexture(m, aiTextureType_BASE_COLOR, 0, &tex, NULL, NULL, NULL, NULL, NULL,
                             NULL) != aiReturn_SUCCESS &&
        aiGetMaterialTexture(m, aiTextureType_DIFFUSE, 0, &tex, NULL, NULL, NULL, NULL, NULL,
                             NULL) != aiReturn_SUCCESS)
        return 0;
    om->map_kd.mtl = dup_str(path); /* messages name the scene; line 1: the map exists */
    om->map_kd.line = 1;
    if (!om->map_kd.mtl) return -1;
    if (embedded(b, &tex) >= 0) return embed_map(b, om, path, embedded(b, &tex), warn, ctx);
    {
        size_t d = tex.data[0] == '/' ? 0 : dir_len(path), t = strlen(tex.data);
        om->map_kd.path = malloc(d + t + 1);
        if (!om->map_kd.path) return -1;
        memcpy(om->map_kd.path, path, d);
        memcpy(om->map_kd.path + d, tex.data, t + 1);
    }
    if (outside(st, om->map_kd.path)) {
        obj_map_fallback(om);
        warnf(warn, ctx, sc,
              "%s: material %s: texture %s is outside the scene's folder %s; using its colour "
              "%g %g %g; --allow-outside-paths reads it",
              path, om->name, om->map_kd.path, st->dir, om->kd[0], om->kd[1], om->kd[2]);
        free(om->map_kd.path);
        om->map_kd.path = NULL;
    }
    return 0;
}

int assimp_scene_load(const char *path, const obj_opts *opts, obj_scene *sc, obj_warn_fn warn,
                      void *ctx, char *err, size_t errlen)
{
    static const unsigned flags = aiProcess_ValidateDataStructure | aiProcess_JoinIdenticalVertices;
    io_state st;
    struct aiFileIO io = {mf_open, mf_close, NULL};
    struct aiPropertyStore *props;
    const struct aiScene *ai;
    build b;
    xform id = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
    unsigned i;
    memset(sc, 0, sizeof *sc);
    memset(&b, 0, sizeof b);
    memset(&st, 0, sizeof st);
    st.scene = path;
    st.allow_outside = opts && opts->allow_outside;
    if (dir_len(path) >= sizeof st.dir) {
        fio_err(err, errlen, path, "path too long");
        return -1;
    }
    if (dir_len(path))
        memcpy(st.dir, path, dir_len(path));
    else
        st.dir[0] = '.';
    io.UserData = (aiUserData)&st;
    props = aiCreatePropertyStore();
    if (!props) {
        fio_err(err, errlen, path, "out of memory");
        return -1;
    }
    aiSetImportPropertyInteger(props, AI_CONFIG_FBX_CONVERT_TO_M, 1);
    ai = aiImportFileExWithProperties(path, flags, &io, props);
    aiReleasePropertyStore(props);
    if (!ai) {
        if (st.why[0] && err && errlen) /* mf_open's words, which name the scene */
            snprintf(err, errlen, "%s", st.why);
        else if (!st.why[0])
            fio_err(err, errlen, path, "not readable as a scene: %s", aiGetErrorString());
        return -1;
    }
    if (!ai->mRootNode || ai->mNumMeshes == 0) {
        aiReleaseImport(ai);
        fio_err(err, errlen, path, "no meshes in the file");
        return -1;
    }
    b.sc = sc;
    b.ai = ai;
    b.half_angles = has_ext(path, "gltf") || has_ext(path, "glb");
    b.placed = calloc(ai->mNumLights + 1u, 1);
    sc->lights = calloc(ai->mNumLights + 1u, sizeof *sc->lights);
    if (!b.placed || !sc->lights) goto nomem;
    b.mat_of = calloc(ai->mNumMaterials ? ai->mNumMaterials : 1, sizeof *b.mat_of);
    sc->materials = calloc(ai->mNumMaterials ? ai->mNumMaterials : 1, sizeof *sc->materials);
    if (!b.mat_of || !sc->materials) goto nomem;
    for (i = 0; i < ai->mNumMeshes; i++) /* ValidateDataStructure checks it too */
        if (ai->mMeshes[i]->mMaterialIndex >= ai->mNumMaterials) {
            aiReleaseImport(ai);
            free(b.mat_of);
            obj_free(sc);
            fio_err(err, errlen, path, "mesh %u names material %u of %u", i,
                    ai->mMeshes[i]->mMaterialIndex, ai->mNumMaterials);
            return -1;
        } else {
            b.mat_of[ai->mMeshes[i]->mMaterialIndex] = 1;
        }
    /* only the materials some mesh uses (importers add a default one that none may) */
    for (i = 0; i < ai->mNumMaterials; i++) {
        if (!b.mat_of[i]) continue;
        b.mat_of[i] = sc->nmaterials;
        if (add_material(&b, &st, path, i, warn, ctx) < 0) goto nomem;
    }
    if (walk(&b, ai->mRootNode, &id, 0, -1) < 0) goto nomem;
    for (i = 0; i < ai->mNumLights; i++) /* no node of its name: as the file gives it */
        if (!b.placed[i] && add_light(&b, i, &id) < 0) goto nomem;
    aiReleaseImport(ai);
    free(b.mat_of);
    free(b.placed);
    if (!b.uv2_corners) { /* no mesh has a second set */
        free(sc->uv2);
        sc->uv2 = NULL;
    }
    for (i = 0; i < (unsigned)sc->nfaces; i++)
        sc->materials[sc->faces[i].material].area += obj_face_area(sc, &sc->faces[i]);
    if (sc->nfaces == 0) {
        obj_free(sc);
        fio_err(err, errlen, path, "no faces of three or more vertices in the file");
        return -1;
    }
    return 0;
nomem:
    aiReleaseImport(ai);
    free(b.mat_of);
    free(b.placed);
    obj_free(sc);
    fio_err(err, errlen, path, "out of memory, or more than %d vertices or indices", INT_MAX / 2);
    return -1;
}

#endif
