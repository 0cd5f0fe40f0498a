/*
 * fuzz_scene.c -- the demo's parsers (scene file, OBJ, MTL) on fuzzed
 * text.  The input is split at its first two zero bytes into three files
 * written to a private temporary folder: s.scene, a.obj and a.mtl (so a
 * scene may say "obj a.obj" and "mtllib a.mtl", and the OBJ "mtllib
 * a.mtl").  Then scene_load(), and on success a BVH over the result.
 * Inputs naming files outside the folder are skipped (escapes()).
 *
 * Invariants (abort() on violation): the loader returns 0 or -1; a failure
 * leaves the scene empty and says "FILE:LINE: message" with FILE one of
 * the three; a success has every triangle and sphere naming a material
 * that exists, finite vertices, positive radii, and a BVH that builds.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bvh.h"
#include "fuzz_input.h"
#include "scene.h"

static int fin(float x)
{
    return x == x && x - x == 0.0f;
}

static const char *folder(void)
{
    static char dir[64];
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/irc-fuzz-scene-XXXXXX");
        if (!mkdtemp(dir))
            abort();
    }
    return dir;
}

static void put(const char *path, const uint8_t *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    check(f != NULL);
    if (n)
        check(fwrite(p, 1, n, f) == n);
    fclose(f);
}

/* err starts with one of the three paths, a colon, digits, a colon. */
static int located(const char *err, char paths[3][128])
{
    int k;
    for (k = 0; k < 3; k++) {
        size_t l = strlen(paths[k]);
        if (!strncmp(err, paths[k], l) && err[l] == ':') {
            const char *q = err + l + 1;
            if (*q < '0' || *q > '9')
                return 0;
            while (*q >= '0' && *q <= '9')
                q++;
            return *q == ':' && q[1] == ' ' && q[2];
        }
    }
    return 0;
}

/* The loader's token separators (loader_int.h, LD_SEP). */
static int sep(uint8_t c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* A file named on an "obj" or "mtllib" line outside the folder (a name
 * with '/' or starting with '.') could be /dev/stdin and wait forever:
 * such inputs are skipped.  A name starts after any of the loader's
 * separators ("mtllib \f." named the folder itself, whose read error
 * names no file of the three). */
static int escapes(const uint8_t *p, size_t n)
{
    size_t i = 0;
    while (i < n) {
        size_t e = i, k;
        while (e < n && p[e] != '\n' && p[e] != 0)
            e++;
        k = i;
        while (k < e && sep(p[k]))
            k++;
        if ((e - k > 4 && !memcmp(p + k, "obj", 3)) || (e - k > 7 && !memcmp(p + k, "mtllib", 6))) {
            size_t q;
            for (q = k; q < e; q++)
                if (p[q] == '/' || (p[q] == '.' && sep(p[q - 1])))
                    return 1;
        }
        i = e + 1;
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *names[3] = {"s.scene", "a.obj", "a.mtl"};
    char paths[3][128], err[512];
    size_t start = 0, i;
    int part = 0, k, st;
    scene s;
    if (escapes(data, size))
        return 0;
    for (k = 0; k < 3; k++)
        snprintf(paths[k], sizeof paths[k], "%s/%s", folder(), names[k]);
    for (i = 0; i <= size && part < 3; i++)
        if (i == size || (data[i] == 0 && part < 2)) {
            put(paths[part++], data + start, i - start);
            start = i + 1;
        }
    while (part < 3)
        put(paths[part++], data, 0);
    memset(&s, 0x5a, sizeof s);
    err[0] = 0;
    st = scene_load(paths[0], &s, err, sizeof err);
    check(st == 0 || st == -1);
    if (getenv("FUZZ_TRACE"))
        fprintf(stderr, "%s\n", st < 0 ? err : "loaded");
    if (st < 0) {
        check(located(err, paths));
        check(s.tris == NULL && s.spheres == NULL && s.mats == NULL);
        return 0;
    }
    for (i = 0; i < (size_t)s.ntris; i++) {
        check(s.tris[i].mat >= 0 && s.tris[i].mat < s.nmats);
        for (k = 0; k < 9; k++)
            check(fin(s.tris[i].v[k / 3][k % 3]));
    }
    for (i = 0; i < (size_t)s.nspheres; i++)
        check(s.spheres[i].mat >= 0 && s.spheres[i].mat < s.nmats && s.spheres[i].r > 0.0f &&
              fin(s.spheres[i].r));
    check(s.cam.width > 0 && s.cam.height > 0);
    {
        bvh b;
        check(bvh_build(&b, &s) == 0);
        bvh_free(&b);
    }
    scene_free(&s);
    return 0;
}
