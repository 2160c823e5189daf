/* SPDX-License-Identifier: MIT */
/* obj — Wavefront OBJ + MTL loader for the host tools (uses malloc and stdio).
 *
 * Only what a radiosity scene and its export need is kept: vertex positions, texture
 * coordinates (vt) and normals (vn), polygonal faces with their object (o) and group (g),
 * and per material the diffuse reflectance (Kd), its texture (map_Kd) and the emission
 * (Ke). Everything else that is valid OBJ/MTL is accepted and ignored; unknown statements
 * are skipped and counted.
 * Errors are one line, "FILE:LINE: what is wrong"; warnings have the same form and go
 * to an optional callback.
 */
#ifndef RAD_TOOLS_OBJ_H
#define RAD_TOOLS_OBJ_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    double x, y, z;
} obj_vec3;
typedef struct {
    double u, v;
} obj_vec2;

/* A map_Kd statement. Of its options, -o and -s (offset and scale of u and v) and
 * -clamp are kept; the others (-blendu, -blendv, -bm, -boost, -cc, -imfchan, -mm,
 * -t, -texres, -type) are read and skipped. */
typedef struct {
    char *path; /* the file, joined to the MTL's folder; NULL: no texture */
    char *mtl;  /* the MTL file and line of the statement, for messages */
    int line;
    double offset[2]; /* texture coordinates used: (u, v) * scale + offset */
    double scale[2];
    int clamp;           /* 1: coordinates clamped to [0, 1]; 0: wrapped (repeat) */
    int outside;         /* internal to obj.c: PATH leaves the scene's folder (then NULL by
                           the end of the load, with a warning) */
    unsigned char *data; /* the image's bytes when the scene file holds them (a glTF's or
                            FBX's embedded texture, assimp_scene.h): PATH then only names
                            it, "SCENE#N" for messages and sharing; NULL: PATH is a file */
    size_t size;
} obj_map;

typedef struct {
    char *name;
    double kd[3];   /* diffuse reflectance (default 0.8 0.8 0.8 if the material has no Kd) */
    double ke[3];   /* emission (default 0) */
    double area;    /* total area of the faces using this material, filled by obj_load */
    int nfaces;     /* number of faces using it */
    int defined;    /* 1 if a newmtl defined it; 0 for "(default)" and undefined usemtl names */
    int use_line;   /* OBJ line of the first usemtl naming it, 0 if none */
    obj_map map_kd; /* diffuse texture (map_Kd); map_kd.path NULL if none */
} obj_material;

typedef struct {
    int material; /* index into materials; every face has one (see default material) */
    int first;    /* first entry in scene.indices */
    int count;    /* number of vertices, >= 3 */
    int line;     /* 1-based source line of the 'f' statement */
    int object;   /* index into names of the current 'o', -1 before any */
    int group;    /* index into names of the current 'g', -1 before any */
} obj_face;

/* A light of the scene file that is not a surface (OBJ has none; glTF's
 * KHR_lights_punctual, FBX, COLLADA and 3DS lights through assimp_scene.h), in the
 * file's units and placed in the scene by its node: TYPE OBJ_LIGHT_SUN (RGB its
 * irradiance on a plane facing it), OBJ_LIGHT_POINT or OBJ_LIGHT_SPOT (RGB its
 * intensity per steradian); DIR the way its light travels; a spot's cone by the cosines
 * of its outer and inner half angles. */
#define OBJ_LIGHT_SUN   1
#define OBJ_LIGHT_POINT 2
#define OBJ_LIGHT_SPOT  3
typedef struct {
    int type;
    char *name;
    double pos[3], dir[3], rgb[3];
    double cos_outer, cos_inner;
} obj_light;

/* A node of the scene file's hierarchy (glTF, FBX, COLLADA, 3DS through
 * assimp_scene.h; OBJ has none): its name, its parent (an index into nodes, before it;
 * -1: a root), its transform relative to the parent (LOCAL, column-major 4 x 4 as a
 * glTF node's matrix), its world transform (WORLD, rows of x' = M (x, y, z, 1): the
 * product from the root, by which its faces' vertices were moved) and the object
 * (index into names) of its faces, -1 when it has none. */
typedef struct {
    char *name;
    int parent, object;
    double local[16], world[3][4];
} obj_node;

typedef struct {
    obj_vec3 *verts;
    int nverts;
    int *indices;
    int nindices;        /* 0-based indices into verts, already resolved */
    int *uv_indices;     /* nindices entries: into uvs, -1 where a face gave no vt */
    int *normal_indices; /* nindices entries: into normals, -1 where no vn */
    obj_vec2 *uvs;
    int nuvs;      /* vt u v (a w is read and dropped) */
    obj_vec2 *uv2; /* NULL, or nindices entries: each corner's second UV set
                                        (a lightmap's: glTF TEXCOORD_1, assimp's
                                        mTextureCoords[1]; v up as vt), NaN where its mesh
                                        has none. OBJ has none. */
    obj_vec3 *normals;
    int nnormals; /* vn as given (not normalised) */
    char **names;
    int nnames; /* o and g names: an entry per statement that changes one */
    obj_face *faces;
    int nfaces;
    obj_material *materials;
    int nmaterials;
    char **libs;
    int nlibs; /* the material libraries read, as opened (joined paths) */
    obj_light *lights;
    int nlights; /* the file's lights (none from an OBJ) */
    obj_node *nodes;
    int nnodes;              /* the file's hierarchy (none from an OBJ) */
    long unknown_statements; /* statements skipped because unknown (counted for --stats) */
    long nwarnings;
    int *mat_index;
    size_t mat_slots; /* material names hashed (FNV-1a, open addressing):
                                         slot -> index or -1; NULL in a scene made by hand */
} obj_scene;

typedef void (*obj_warn_fn)(void *ctx, const char *msg); /* msg is "FILE:LINE: text" */

/* Most vertices of a face obj_triangulate clips (the parser loads any count). Ear
   clipping costs up to O(n^2) per clipped ear on a self-intersecting polygon (no ear:
   every vertex is tried against every other), O(n^3) in all, so a longer face is
   refused (OBJ_TOO_MANY_VERTICES) rather than left to run for minutes; at 1024 the worst
   case is about 10^9 steps, and 1024 is far above what modelling tools write. */
#define OBJ_MAX_FACE_VERTICES 1024
#define OBJ_TOO_MANY_VERTICES (-2)

/* Name of the material given to faces that come before any usemtl. */
#define OBJ_DEFAULT_MATERIAL "(default)"

/* What obj_load_opts may do beyond obj_load's defaults (all 0: obj_load). */
typedef struct {
    /* 1: mtllib and map_Kd files may lie outside the scene's folder (the OBJ's folder).
       0: such a file, after '..' and symbolic links are resolved, is not read: a warning
       "MTL:LINE: map_Kd: PATH is outside the scene's folder DIR; using Kd R G B;
       --allow-outside-paths reads it" and the material keeps its Kd (obj_map_fallback),
       or for mtllib "... library not read ...". A scene's files cannot then pull in
       ~/.ssh/id_rsa through a texture embedded in an exported .glb. */
    int allow_outside;
} obj_opts;

/* Loads PATH ("-": standard input, fio_read_stdin, whose folder is the current one);
   mtllib paths are relative to the OBJ's directory. Files are read whole
   through fio_read_all (file_io.h): an OBJ of at most FIO_LIMIT_OBJ bytes, a library of
   at most FIO_LIMIT_MTL (larger, or unreadable: a warning, like a missing one). Lines
   end in LF, CRLF or CR; a leading UTF-8 byte order mark is skipped. Returns 0, or -1 with a
   one-line message "FILE:LINE: what is wrong" (no trailing newline) in err. On error the
   scene is left empty (nothing to free, but obj_free is safe). warn may be NULL. */
int obj_load(const char *path, obj_scene *sc, obj_warn_fn warn, void *ctx, char *err,
             size_t errlen);
/* obj_load with OPTS (NULL: the defaults). */
int obj_load_opts(const char *path, const obj_opts *opts, obj_scene *sc, obj_warn_fn warn,
                  void *ctx, char *err, size_t errlen);
/* Same from memory (for fuzzing and tests); name is used in messages; basedir for mtllib
   and the folder files must stay in (may be NULL: then mtllib is a warning). text may hold any bytes (NUL is an error). */
int obj_parse(const char *text, size_t len, const char *name, const char *basedir, obj_scene *sc,
              obj_warn_fn warn, void *ctx, char *err, size_t errlen);
void obj_free(obj_scene *sc);
/* Triangulates face f (convex or concave, planar-ish polygon, any vertex count >= 3) by ear
   clipping in the polygon's best-fit plane (Newell normal). Writes 3*(count-2) vertex indices
   (into verts) to out, each triangle wound like the polygon, and returns the number of
   triangles (count-2), OBJ_TOO_MANY_VERTICES past OBJ_MAX_FACE_VERTICES, or -1 if the
   polygon is degenerate (zero Newell normal) or memory runs out. */
int obj_triangulate(const obj_scene *sc, const obj_face *f, int *out);
/* Index of the material called NAME, or -1: a hash lookup in a parsed scene (200,000
   materials parse in linear time), a linear search in one made by hand. */
int obj_find_material(const obj_scene *sc, const char *name);
/* A material whose texture cannot be used keeps its Kd, or gets OBJ_FALLBACK_KD grey if
   its Kd is all zero (exporters write Kd 0 0 0 beside map_Kd): never a black surface
   by accident. obj_load applies it to malformed map_Kd statements, the texture loader
   to files it cannot decode. Returns 1 if Kd was changed, else 0. */
#define OBJ_FALLBACK_KD 0.5
int obj_map_fallback(obj_material *m);
/* Polygon area (Newell) of face f. */
double obj_face_area(const obj_scene *sc, const obj_face *f);
/* Newell normal of face f: its length is twice the polygon's area. */
obj_vec3 obj_face_normal(const obj_scene *sc, const obj_face *f);

#ifdef __cplusplus
}
#endif

#endif
