/* obj.c -- Wavefront OBJ (triangles) and MTL (materials) files for the
 * scene loader (loader.c). */
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "loader_int.h"

/* Per-OBJ-file state: OBJ indices are local to their file. */
typedef struct objfile {
    float *v, *vn;
    int nv, nvn, nvt, cap_v, cap_vn;
    int mat; /* -1 until usemtl */
    int vi[LD_MAX_TOK], ni[LD_MAX_TOK];
} objfile;

/* MTL keys that carry nothing this tracer renders. */
static int mtl_ignored(const char *k)
{
    static const char *const keys[] = {"Ka",        "d",    "Tr",    "Tf",   "illum", "Ni",
                                       "sharpness", "disp", "decal", "refl", "norm",  "Pr",
                                       "Pm",        "Ps",   "Pc",    "Pcr",  "aniso", "anisor"};
    size_t i;
    if (strncmp(k, "map_", 4) == 0)
        return 1;
    for (i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (strcmp(k, keys[i]) == 0)
            return 1;
    return 0;
}

static int mtl_value(ld_loader *L, const ld_reader *r, material *m)
{
    const char *k = r->tok[0];
    float x[3];
    int n = strcmp(k, "Ns") == 0 ? 1 : strcmp(k, "bump") == 0 ? 2 : 3;
    if (ld_nargs(L, r, n, n) < 0 || ld_nums(L, r, 1, n, x) < 0 || ld_nonneg(L, r, x, n) < 0)
        return -1;
    if (strcmp(k, "Kd") == 0)
        memcpy(m->kd, x, sizeof m->kd);
    else if (strcmp(k, "Ks") == 0)
        memcpy(m->ks, x, sizeof m->ks);
    else if (strcmp(k, "Ke") == 0)
        memcpy(m->ke, x, sizeof m->ke);
    else if (n == 1)
        m->ns = x[0];
    else {
        m->bump = x[0];
        m->bump_freq = x[1];
    }
    return 0;
}

/* *cur: the material being defined, -1 before the first newmtl. */
static int mtl_statement(ld_loader *L, const ld_reader *r, int *cur)
{
    static const char *const keys[] = {"Kd", "Ks", "Ke", "Ns", "bump"};
    const char *k = r->tok[0];
    size_t i;
    if (strcmp(k, "newmtl") == 0) {
        if (ld_nargs(L, r, 1, 1) < 0 || (*cur = ld_add_mat(L, r, r->tok[1])) < 0)
            return -1;
        return 0;
    }
    if (mtl_ignored(k))
        return 0;
    for (i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (strcmp(k, keys[i]) == 0)
            break;
    if (i == sizeof keys / sizeof keys[0])
        return ld_fail(L, r, r->line, "unknown MTL statement \"%s\"", k);
    if (*cur < 0)
        return ld_fail(L, r, r->line, "%s before newmtl", k);
    return mtl_value(L, r, &L->s->mats[*cur]);
}

/* Reads the MTL file `name` named at the current line of `from`, unless
 * that file was read already. */
int ld_load_mtl(ld_loader *L, const ld_reader *from, const char *name)
{
    ld_reader r;
    char *path = ld_relative_path(from->path, name);
    char **mtls;
    int i, rc, cur = -1;
    if (!path)
        return ld_oom(L, from);
    for (i = 0; i < L->nmtls; i++)
        if (strcmp(L->mtls[i], path) == 0) {
            free(path);
            return 0;
        }
    if (!(mtls = ld_grow(L->mtls, &L->cap_mtls, L->nmtls + 1, sizeof *mtls))) {
        free(path);
        return ld_oom(L, from);
    }
    L->mtls = mtls;
    if (ld_open_file(&r, path) < 0) {
        int e = errno;
        free(path);
        return ld_fail(L, from, from->line, "cannot open \"%s\": %s", name, strerror(e));
    }
    L->mtls[L->nmtls++] = path; /* freed by scene_load */
    while ((rc = ld_read_line(L, &r)) > 0)
        if (r.ntok > 0 && mtl_statement(L, &r, &cur) < 0) {
            rc = -1;
            break;
        }
    ld_close_file(&r);
    return rc;
}

/* Resolves a 1-based or negative (relative) OBJ index against the n
 * elements defined so far; -1 if it refers to none of them. */
static int obj_index(long i, int n)
{
    if (i > 0 && i <= n)
        return (int)i - 1;
    if (i < 0 && i >= -(long)n)
        return n + (int)i;
    return -1;
}

/* Parses one integer of a face corner up to '/' or the end. */
static int ref_part(const char **p, long *out)
{
    char *end;
    if (**p == '\0' || **p == '/')
        return -1;
    errno = 0;
    *out = strtol(*p, &end, 10);
    if (end == *p || errno == ERANGE || (*end != '\0' && *end != '/'))
        return -1;
    *p = end;
    return 0;
}

/* A face corner "v", "v/vt", "v//vn" or "v/vt/vn" into vertex index *vi
 * and normal index *ni (-1: none). */
static int obj_corner(ld_loader *L, const ld_reader *r, const objfile *o, const char *t, int *vi,
                      int *ni)
{
    const char *p = t;
    long v, vt = 0, vn = 0;
    int bad = ref_part(&p, &v) < 0, has_vt = 0, has_vn = 0;
    if (!bad && *p == '/') {
        p++;
        if (*p != '/') {
            bad = ref_part(&p, &vt) < 0;
            has_vt = 1;
        }
        if (!bad && *p == '/') {
            p++;
            bad = ref_part(&p, &vn) < 0;
            has_vn = 1;
        }
    }
    if (bad || *p)
        return ld_fail(L, r, r->line, "f: bad vertex reference \"%s\"", t);
    if ((*vi = obj_index(v, o->nv)) < 0)
        return ld_fail(L, r, r->line, "f: vertex index %ld out of range (%d vertices so far)", v,
                       o->nv);
    if (has_vt && obj_index(vt, o->nvt) < 0)
        return ld_fail(L, r, r->line, "f: texture index %ld out of range (%d so far)", vt, o->nvt);
    *ni = -1;
    if (has_vn && (*ni = obj_index(vn, o->nvn)) < 0)
        return ld_fail(L, r, r->line, "f: normal index %ld out of range (%d normals so far)", vn,
                       o->nvn);
    return 0;
}

/* Faces before any usemtl get the built-in "default" material. */
static int obj_default_mat(ld_loader *L, const ld_reader *r)
{
    int m = ld_find_mat(L->s, "default");
    return m >= 0 ? m : ld_add_mat(L, r, "default");
}

static void obj_emit(const objfile *o, const int c[3], triangle *t)
{
    int k, has_n = 1;
    for (k = 0; k < 3; k++) {
        const float *n = o->ni[c[k]] >= 0 ? o->vn + 3 * o->ni[c[k]] : NULL;
        memcpy(t->v[k], o->v + 3 * o->vi[c[k]], sizeof t->v[k]);
        /* a zero normal (some exporters write them) cannot be shaded with */
        if (n && (n[0] != 0.0f || n[1] != 0.0f || n[2] != 0.0f))
            memcpy(t->n[k], n, sizeof t->n[k]);
        else
            has_n = 0;
    }
    if (!has_n)
        memset(t->n, 0, sizeof t->n);
    t->has_n = has_n;
    t->mat = o->mat;
}

/* A polygon of n >= 3 corners, fan-triangulated (0, i, i+1). */
static int obj_face(ld_loader *L, const ld_reader *r, objfile *o)
{
    scene *s = L->s;
    triangle *t;
    int i, n = r->ntok - 1;
    if (n < 3)
        return ld_fail(L, r, r->line, "f: a face needs at least 3 vertices, got %d", n);
    for (i = 0; i < n; i++)
        if (obj_corner(L, r, o, r->tok[i + 1], &o->vi[i], &o->ni[i]) < 0)
            return -1;
    if (o->mat < 0 && (o->mat = obj_default_mat(L, r)) < 0)
        return -1;
    if (s->ntris > INT_MAX - n ||
        !(t = ld_grow(s->tris, &L->cap_tris, s->ntris + n - 2, sizeof *t)))
        return ld_oom(L, r);
    s->tris = t;
    for (i = 1; i + 1 < n; i++) {
        int c[3];
        c[0] = 0;
        c[1] = i;
        c[2] = i + 1;
        obj_emit(o, c, &s->tris[s->ntris++]);
    }
    return 0;
}

/* v x y z [w] (w, a weight for rational curves, is ignored) and vn x y z,
 * kept unit length so that corners interpolate directions only. */
static int obj_vector(ld_loader *L, const ld_reader *r, objfile *o, int normal)
{
    float x[4], *a = normal ? o->vn : o->v;
    double len = 1.0;
    int i, n = normal ? o->nvn : o->nv;
    if (ld_nargs(L, r, 3, normal ? 3 : 4) < 0 || ld_nums(L, r, 1, r->ntok - 1, x) < 0)
        return -1;
    if (n >= INT_MAX / 3 ||
        !(a = ld_grow(a, normal ? &o->cap_vn : &o->cap_v, 3 * (n + 1), sizeof *a)))
        return ld_oom(L, r);
    if (normal) {
        o->vn = a;
        o->nvn++;
        len = sqrt((double)x[0] * x[0] + (double)x[1] * x[1] + (double)x[2] * x[2]);
        if (len == 0.0)
            len = 1.0; /* stays zero: obj_emit then treats the corner as without vn */
    } else {
        o->v = a;
        o->nv++;
    }
    for (i = 0; i < 3; i++)
        a[3 * n + i] = (float)(x[i] / len);
    return 0;
}

static int obj_statement(ld_loader *L, const ld_reader *r, objfile *o)
{
    static const char *const ignored[] = {"vt", "g", "o", "s", "l", "p"};
    const char *k = r->tok[0];
    size_t i;
    if (strcmp(k, "v") == 0 || strcmp(k, "vn") == 0)
        return obj_vector(L, r, o, k[1] == 'n');
    if (strcmp(k, "f") == 0)
        return obj_face(L, r, o);
    if (strcmp(k, "usemtl") == 0) {
        if (ld_nargs(L, r, 1, 1) < 0 || (o->mat = ld_use_mat(L, r, r->tok[1])) < 0)
            return -1;
        return 0;
    }
    if (strcmp(k, "mtllib") == 0) {
        if (ld_nargs(L, r, 1, LD_MAX_TOK) < 0)
            return -1;
        for (i = 1; i < (size_t)r->ntok; i++)
            if (ld_load_mtl(L, r, r->tok[i]) < 0)
                return -1;
        return 0;
    }
    if (strcmp(k, "vt") == 0)
        o->nvt += o->nvt < INT_MAX;
    for (i = 0; i < sizeof ignored / sizeof ignored[0]; i++)
        if (strcmp(k, ignored[i]) == 0)
            return 0;
    return ld_fail(L, r, r->line, "unknown OBJ statement \"%s\"", k);
}

int ld_load_obj(ld_loader *L, const ld_reader *from, const char *name)
{
    ld_reader r;
    objfile *o = calloc(1, sizeof *o);
    int rc;
    if (!o)
        return ld_oom(L, from);
    if (ld_open_named(L, from, name, &r) < 0) {
        free(o);
        return -1;
    }
    o->mat = -1;
    while ((rc = ld_read_line(L, &r)) > 0)
        if (r.ntok > 0 && obj_statement(L, &r, o) < 0) {
            rc = -1;
            break;
        }
    ld_close_file(&r);
    free((char *)r.path);
    free(o->v);
    free(o->vn);
    free(o);
    return rc;
}
