/* loader_int.h -- internals shared by loader.c (scene files) and obj.c
 * (Wavefront OBJ and MTL); not an API: scene.h is.  Every int function
 * returns -1 after writing "FILE:LINE: message" to the loader's err. */
#ifndef DEMO_LOADER_INT_H
#define DEMO_LOADER_INT_H

#include <stddef.h>
#include <stdio.h>

#include "scene.h"

#define LD_MAX_LINE 4095
/* Spaces and tabs separate tokens; stray \r, \v, \f too, so that strtod and
 * strtol, which skip leading white space, see a token exactly as split. */
#define LD_SEP " \t\r\v\f"
#define LD_MAX_TOK (LD_MAX_LINE / 2 + 1) /* one-character tokens */

typedef struct ld_reader {
    FILE *f;
    const char *path; /* as opened: what error messages name */
    int line;
    int ntok;
    char buf[LD_MAX_LINE + 2]; /* one spare character tells a \r from overflow */
    char *tok[LD_MAX_TOK];     /* tok[0] the keyword */
} ld_reader;

typedef struct ld_loader {
    scene *s;
    int cap_tris, cap_spheres, cap_mats;
    char **mtls; /* MTL files already read: a scene and its OBJ files may all
                    name the same one, which must not redefine its materials */
    int nmtls, cap_mtls;
    int have_cam, have_res, have_env, have_sun;
    char *err;
    size_t errlen;
} ld_loader;

/* Errors: ld_fail formats one at a line of r (returns -1). */
int ld_fail(ld_loader *L, const ld_reader *r, int line, const char *fmt, ...);
int ld_oom(ld_loader *L, const ld_reader *r);

/* p (*cap elements of size elem) grown to hold need, geometrically: the
 * new pointer, or NULL (p is then still valid). */
void *ld_grow(void *p, int *cap, int need, size_t elem);

/* Files: ld_read_line returns 1 for a line split into r->tok (possibly
 * none), 0 at the end, -1 on error.  ld_open_file returns -1 with errno
 * set and nothing reported; ld_open_named opens a file named at the
 * current line of `from` relative to its directory and reports failure
 * there; r->path is then malloc'd (the caller frees it). */
int ld_open_file(ld_reader *r, const char *path);
char *ld_relative_path(const char *from, const char *name);
int ld_open_named(ld_loader *L, const ld_reader *from, const char *name, ld_reader *r);
int ld_read_line(ld_loader *L, ld_reader *r);
void ld_close_file(ld_reader *r);

/* Arguments of the current line: their count in [lo, hi]; tokens
 * first..first+n-1 as finite floats; x[0..n-1] >= 0. */
int ld_nargs(ld_loader *L, const ld_reader *r, int lo, int hi);
int ld_nums(ld_loader *L, const ld_reader *r, int first, int n, float *out);
int ld_nonneg(ld_loader *L, const ld_reader *r, const float *x, int n);

/* Materials, global over all MTL files: index or -1. */
int ld_find_mat(const scene *s, const char *name);
int ld_add_mat(ld_loader *L, const ld_reader *r, const char *name);
int ld_use_mat(ld_loader *L, const ld_reader *r, const char *name);

/* The MTL or OBJ file `name` named at the current line of `from`. */
int ld_load_mtl(ld_loader *L, const ld_reader *from, const char *name);
int ld_load_obj(ld_loader *L, const ld_reader *from, const char *name);

#endif
