/* t_loader.c -- the demo's scene loader (demo/loader.c, demo/obj.c): every
 * malformed file in tests/data/bad fails at exactly the expected FILE:LINE
 * and leaves the scene empty; the good files and the four shipped scenes
 * load with the expected contents.  Uses the shared harness:
 *   cc -std=c99 -Idemo -Itests demo/loader.c demo/obj.c tests/t_loader.c tests/harness.c \
 *       -o t_loader -lm
 *   t_loader [ROOT [TEST...]]   ROOT the project's root (default: the current
 *                               directory, or found from the program's own
 *                               path); the tests named (by prefix), or all. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "scene.h"
#include "test.h"

#define TESTS(X)                                                                           \
    X(test_bad_files) X(test_missing_message) X(test_good_crlf) X(test_big) X(test_cornell) \
    X(test_fig5) X(test_fig15) X(test_sh) X(test_placed) X(test_real)
TESTS(TEST_DECL)

static int near(double a, double b, double tol)
{
    return fabs(a - b) <= tol;
}

static int is_empty(const scene *s)
{
    return !s->tris && !s->ntris && !s->spheres && !s->nspheres && !s->mats && !s->nmats;
}

/* ------------------------------------------------------------ bad files */

typedef struct bad_case {
    const char *file;  /* under tests/data/bad */
    const char *where; /* "FILE:LINE", FILE under tests/data/bad */
    const char *says;  /* part of the message */
} bad_case;

static const bad_case bad_cases[] = {
    {"s_unknown.scene", "s_unknown.scene:3", "unknown scene statement \"lights\""},
    {"s_camera_args.scene", "s_camera_args.scene:1", "camera: expected 10 arguments, got 9"},
    {"s_res_args.scene", "s_res_args.scene:2", "resolution: expected 2 arguments, got 1"},
    {"s_number.scene", "s_number.scene:1", "bad number \"40x\""},
    {"s_nan.scene", "s_nan.scene:1", "bad number \"nan\""},
    {"s_inf.scene", "s_inf.scene:3", "bad number \"inf\""},
    {"s_float_range.scene", "s_float_range.scene:2", "bad number \"1e39\""},
    {"s_res_int.scene", "s_res_int.scene:2", "bad integer \"8.5\""},
    {"s_res_zero.scene", "s_res_zero.scene:2", "not in 1..16384"},
    {"s_res_big.scene", "s_res_big.scene:2", "not in 1..16384"},
    {"s_res_neg.scene", "s_res_neg.scene:2", "not in 1..16384"},
    {"s_fov0.scene", "s_fov0.scene:1", "field of view"},
    {"s_fov180.scene", "s_fov180.scene:1", "field of view"},
    {"s_look_eye.scene", "s_look_eye.scene:1", "the point looked at is the eye"},
    {"s_up_parallel.scene", "s_up_parallel.scene:1", "up is parallel"},
    {"s_up_zero.scene", "s_up_zero.scene:1", "up is parallel"},
    {"s_radius0.scene", "s_radius0.scene:4", "radius"},
    {"s_radius_neg.scene", "s_radius_neg.scene:4", "radius"},
    {"s_undef_mat.scene", "s_undef_mat.scene:2", "material \"nosuch\" is not defined"},
    {"s_mat_later.scene", "s_mat_later.scene:2", "material \"m\" is not defined"},
    {"s_sphere_args.scene", "s_sphere_args.scene:2", "sphere: expected 5 arguments"},
    {"s_no_camera.scene", "s_no_camera.scene:4", "missing camera"},
    {"s_no_res.scene", "s_no_res.scene:2", "missing resolution"},
    {"s_empty.scene", "s_empty.scene:1", "missing camera"},
    {"s_missing_obj.scene", "s_missing_obj.scene:3",
     "cannot open \"missing.obj\": No such file or directory"},
    {"s_missing_mtl.scene", "s_missing_mtl.scene:3", "cannot open \"nothere/missing.mtl\""},
    {"s_long.scene", "s_long.scene:2", "line longer than 4095"},
    {"s_long_crlf.scene", "s_long_crlf.scene:3", "line longer than 4095"},
    {"s_dup_camera.scene", "s_dup_camera.scene:3", "camera given twice"},
    {"s_env_kind.scene", "s_env_kind.scene:3", "\"constant\" or \"gaussian\""},
    {"s_env_dir0.scene", "s_env_dir0.scene:3", "non-zero"},
    {"s_env_args.scene", "s_env_args.scene:3", "expected 11 arguments"},
    {"s_crlf_bad.scene", "s_crlf_bad.scene:4", "unknown scene statement \"bogus\""},
    {"s_nul.scene", "s_nul.scene:2", "NUL byte"},
    {"s_dup_mat_files.scene", "other.mtl:4", "material \"m\" defined twice"},
    {"o_unknown.scene", "o_unknown.obj:5", "unknown OBJ statement \"vp\""},
    {"o_face2.scene", "o_face2.obj:4", "at least 3 vertices, got 2"},
    {"o_index0.scene", "o_index0.obj:4", "vertex index 0 out of range"},
    {"o_index_range.scene", "o_index_range.obj:4", "vertex index 4 out of range"},
    {"o_index_later.scene", "o_index_later.obj:4", "vertex index 4 out of range"},
    {"o_rel_range.scene", "o_rel_range.obj:4", "vertex index -4 out of range"},
    {"o_vn_range.scene", "o_vn_range.obj:5", "normal index 2 out of range"},
    {"o_vn0.scene", "o_vn0.obj:5", "normal index 0 out of range"},
    {"o_vn_rel_range.scene", "o_vn_rel_range.obj:5", "normal index -2 out of range"},
    {"o_vt_range.scene", "o_vt_range.obj:5", "texture index 2 out of range"},
    {"o_usemtl_undef.scene", "o_usemtl_undef.obj:7", "material \"nosuch\" is not defined"},
    {"o_usemtl_args.scene", "o_usemtl_args.obj:4", "usemtl: expected 1 argument, got 0"},
    {"o_number.scene", "o_number.obj:2", "bad number \"0x\""},
    {"o_nan.scene", "o_nan.obj:3", "bad number \"NaN\""},
    {"o_v_args.scene", "o_v_args.obj:2", "v: expected 3 to 4 arguments, got 2"},
    {"o_vn_args.scene", "o_vn_args.obj:4", "vn: expected 3 arguments, got 2"},
    {"o_bad_ref.scene", "o_bad_ref.obj:4", "bad vertex reference \"1/\""},
    {"o_bad_ref2.scene", "o_bad_ref2.obj:6", "bad vertex reference \"1/1/1/1\""},
    {"o_bad_ref3.scene", "o_bad_ref3.obj:4", "bad vertex reference \"3a\""},
    {"o_index_huge.scene", "o_index_huge.obj:4", "bad vertex reference"},
    {"o_missing_mtl.scene", "o_missing_mtl.obj:5", "cannot open \"gone.mtl\""},
    {"o_long.scene", "o_long.obj:4", "line longer than 4095"},
    {"m_unknown.scene", "m_unknown.mtl:3", "unknown MTL statement \"Kx\""},
    {"m_dup.scene", "m_dup.mtl:5", "material \"a\" defined twice"},
    {"m_args.scene", "m_args.mtl:2", "Kd: expected 3 arguments, got 2"},
    {"m_number.scene", "m_number.mtl:2", "bad number \"1e999\""},
    {"m_before.scene", "m_before.mtl:2", "Ke before newmtl"},
    {"m_bump_args.scene", "m_bump_args.mtl:2", "bump: expected 2 arguments, got 1"},
    {"m_name_long.scene", "m_name_long.mtl:1", "longer than 63"},
    {"m_negative.scene", "m_negative.mtl:2", "negative"},
    {"m_newmtl_args.scene", "m_newmtl_args.mtl:1", "newmtl: expected 1 argument, got 0"},
    {"m_crlf.scene", "m_crlf.mtl:4", "unknown MTL statement \"bogus\""},
    {"s_sun_dir0.scene", "s_sun_dir0.scene:3", "sun: the direction must be a non-zero vector"},
    {"s_sun_neg.scene", "s_sun_neg.scene:3", "sun: negative value -1"},
    {"s_sun_twice.scene", "s_sun_twice.scene:4", "sun given twice"},
    {"s_obj_scale0.scene", "s_obj_scale0.scene:3", "obj: scale 0 must be positive"},
    {"s_obj_args.scene", "s_obj_args.scene:3", "obj: expected a file, or a file, a scale and a move"},
    {"s_obj_overflow.scene", "s_obj_overflow.scene:3", "obj: a moved vertex is not finite"},
};

/* One malformed file; every message names it. */
static void test_bad(const bad_case *c)
{
    char path[256], where[256], err[512];
    scene s;
    size_t n;
    int rc;
    snprintf(path, sizeof path, "tests/data/bad/%s", c->file);
    snprintf(where, sizeof where, "tests/data/bad/%s:", c->where);
    n = strlen(where);
    where[n - 1] = '\0';
    memset(&s, 0xab, sizeof s); /* the loader must empty it */
    rc = scene_load(path, &s, err, sizeof err);
    CHECK(rc == -1, "bad/%s: loaded (rc %d)", c->file, rc);
    if (rc == 0) {
        scene_free(&s);
    } else {
        /* exactly FILE:LINE, then ": " */
        CHECK(strncmp(err, where, n - 1) == 0 && strncmp(err + n - 1, ": ", 2) == 0,
              "bad/%s: error \"%s\", expected at %s", c->file, err, where);
        CHECK(strstr(err, c->says) != NULL, "bad/%s: error \"%s\" does not say \"%s\"", c->file,
              err, c->says);
        CHECK(is_empty(&s), "bad/%s: scene not left empty", c->file);
    }
    if (rc == -1)
        printf("  %s\n", err);
}

TEST(test_bad_files)
{
    size_t i;
    for (i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++)
        test_bad(&bad_cases[i]);
}

TEST(test_missing_message)
{
    char err[512];
    scene s;
    const char *want = "tests/data/bad/s_missing_obj.scene:3: cannot open \"missing.obj\": "
                       "No such file or directory";
    CHECK(scene_load("tests/data/bad/s_missing_obj.scene", &s, err, sizeof err) == -1, "loaded");
    CHECK(strcmp(err, want) == 0, "\"%s\"", err);
    CHECK(scene_load("tests/data/bad/no-such.scene", &s, err, sizeof err) == -1, "loaded");
    CHECK(strncmp(err, "tests/data/bad/no-such.scene:0: cannot open", 43) == 0, "\"%s\"", err);
    CHECK(is_empty(&s), "not empty");
    /* a directory opens but cannot be read */
    CHECK(scene_load("tests/data/bad", &s, err, sizeof err) == -1, "loaded a directory");
    CHECK(strncmp(err, "tests/data/bad:1: ", 18) == 0, "\"%s\"", err);
    /* a short buffer gets a truncated message, no overflow */
    CHECK(scene_load("tests/data/bad/s_missing_obj.scene", &s, err, 12) == -1, "loaded");
    CHECK(strlen(err) == 11, "\"%s\"", err);
    CHECK(scene_load("tests/data/bad/s_missing_obj.scene", &s, NULL, 0) == -1, "loaded");
}

/* ------------------------------------------------------------ good files */

static void tri_normal(const triangle *t, float n[3])
{
    float a[3], b[3], l;
    int i;
    for (i = 0; i < 3; i++) {
        a[i] = t->v[1][i] - t->v[0][i];
        b[i] = t->v[2][i] - t->v[0][i];
    }
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (i = 0; i < 3; i++)
        n[i] /= l;
}

static int load(const char *path, scene *s)
{
    char err[512];
    if (scene_load(path, s, err, sizeof err) == 0)
        return 0;
    CHECK(0, "%s", err);
    return -1;
}

static int mat_named(const scene *s, const char *name)
{
    int i;
    for (i = 0; i < s->nmats; i++)
        if (strcmp(s->mats[i].name, name) == 0)
            return i;
    return -1;
}

TEST(test_good_crlf)
{
    /* tris of sub/mesh.obj: material, has_n (see the file) */
    static const char *const mats[12] = {"default", "a", "a", "a", "b", "b",
                                         "b",       "a", "a", "a", "a", "a"};
    static const int has_n[12] = {0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1};
    scene s;
    int i;
    const material *a, *b;
    if (load("tests/data/good/crlf.scene", &s) < 0)
        return;
    CHECK(s.ntris == 12, "%d triangles", s.ntris);
    CHECK(s.nmats == 3, "%d materials (the MTL named twice must be read once)", s.nmats);
    for (i = 0; i < s.ntris && i < 12; i++) {
        CHECK(strcmp(s.mats[s.tris[i].mat].name, mats[i]) == 0, "tri %d: %s", i,
              s.mats[s.tris[i].mat].name);
        CHECK(s.tris[i].has_n == has_n[i], "tri %d has_n %d", i, s.tris[i].has_n);
    }
    if (s.ntris == 12) {
        /* the pentagon -5..-1 fans from vertex 1: (1,2,3) (1,3,4) (1,4,5) */
        CHECK(s.tris[3].v[0][0] == 0 && s.tris[3].v[1][0] == 0 && s.tris[3].v[1][1] == 1 &&
                  s.tris[3].v[2][0] == -0.5f && s.tris[3].v[2][1] == 0.5f,
              "pentagon fan");
        CHECK(s.tris[4].n[2][2] == 1.0f && s.tris[4].n[0][0] == 0.0f, "vn normalised");
        CHECK(s.tris[10].v[2][0] == 0 && s.tris[10].v[2][1] == 0, "hexagon fan closes on 1");
        CHECK(s.tris[11].v[2][0] == 1 && s.tris[11].v[2][1] == 1, "relative refs: vertex 3");
    }
    a = &s.mats[0];
    b = &s.mats[1];
    CHECK(strcmp(a->name, "a") == 0 && a->kd[2] == 0.3f && a->ks[0] == 0 && a->ns == 1 &&
              a->bump == 0,
          "material a");
    CHECK(strcmp(b->name, "b") == 0 && b->kd[0] == 0.5f && b->ks[2] == 0.6f && b->ns == 25 &&
              b->ke[1] == 2 && b->bump == 0.05f && b->bump_freq == 7,
          "material b");
    CHECK(s.nmats < 3 || (s.mats[2].kd[1] == 0.5f && s.mats[2].ke[0] == 0), "default");
    CHECK(s.nspheres == 1 && s.spheres[0].r == 0.5f && s.spheres[0].c[2] == 3 &&
              s.spheres[0].mat == 0,
          "sphere");
    CHECK(s.cam.width == 16384 && s.cam.height == 1 && s.cam.fov_deg == 40, "camera");
    CHECK(s.env.kind == ENV_GAUSSIAN && s.env.dir[2] == -1 && s.env.dir[0] == 0 &&
              s.env.peak[1] == 2 && s.env.base[2] == 0.3f && s.env.sigma_deg == 30,
          "environment");
    scene_free(&s);
    CHECK(is_empty(&s), "scene_free leaves it empty");
    scene_free(&s); /* twice is harmless */
}

/* A big generated OBJ: growth must be geometric, not one realloc per line. */
TEST(test_big)
{
    char dir[64], scn[96], obj[96];
    int n = 300, i, j;
    FILE *f;
    scene s;
    clock_t t0;
    snprintf(dir, sizeof dir, "/tmp/t_loader.%ld", (long)getpid());
    snprintf(scn, sizeof scn, "%s/big.scene", dir);
    snprintf(obj, sizeof obj, "%s/big.obj", dir);
    CHECK(mkdir(dir, 0700) == 0, "mkdir %s", dir);
    if ((f = fopen(obj, "w"))) {
        for (j = 0; j <= n; j++)
            for (i = 0; i <= n; i++)
                fprintf(f, "v %d %d 0\n", i, j);
        for (j = 0; j < n; j++)
            for (i = 0; i < n; i++)
                fprintf(f, "f %d %d %d %d\n", j * (n + 1) + i + 1, j * (n + 1) + i + 2,
                        (j + 1) * (n + 1) + i + 2, (j + 1) * (n + 1) + i + 1);
        fclose(f);
    }
    if ((f = fopen(scn, "w"))) {
        fprintf(f, "obj %s\ncamera 0 0 -5 0 0 0 0 1 0 40\nresolution 8 8\n", obj);
        fclose(f);
    }
    t0 = clock();
    if (load(scn, &s) == 0) {
        printf("  %d triangles in %.3f s\n", s.ntris, (double)(clock() - t0) / CLOCKS_PER_SEC);
        CHECK(s.ntris == 2 * n * n, "%d triangles", s.ntris);
        CHECK(s.nmats == 1 && strcmp(s.mats[0].name, "default") == 0, "default material");
        CHECK(s.tris[s.ntris - 1].v[1][0] == n && s.tris[s.ntris - 1].v[1][1] == n, "last");
        scene_free(&s);
    }
    remove(obj);
    remove(scn);
    rmdir(dir);
}

/* ------------------------------------------------------------ shipped scenes */

static int count_emitters(const scene *s, int *which)
{
    int i, n = 0;
    for (i = 0; i < s->nmats; i++)
        if (s->mats[i].ke[0] > 0 || s->mats[i].ke[1] > 0 || s->mats[i].ke[2] > 0) {
            n++;
            *which = i;
        }
    return n;
}

TEST(test_cornell)
{
    scene s;
    int i, light = -1, nlight = 0;
    const material *m;
    if (load("demo/scenes/cornell.scene", &s) < 0)
        return;
    /* 16 surfaces: 15 quads of 2 triangles, the left wall as 2 */
    CHECK(s.ntris == 32, "%d triangles", s.ntris);
    CHECK(s.nspheres == 0 && s.nmats == 4, "%d spheres, %d materials", s.nspheres, s.nmats);
    CHECK(count_emitters(&s, &light) == 1, "emitters");
    m = &s.mats[light];
    CHECK(strcmp(m->name, "light") == 0 && m->ke[0] == 17 && m->ke[1] == 12 && m->ke[2] == 4 &&
              m->kd[0] == 0 && m->kd[1] == 0 && m->kd[2] == 0,
          "light material");
    i = mat_named(&s, "white");
    CHECK(i >= 0 && s.mats[i].kd[0] == 0.725f && s.mats[i].kd[1] == 0.71f &&
              s.mats[i].kd[2] == 0.68f,
          "white");
    i = mat_named(&s, "red");
    CHECK(i >= 0 && s.mats[i].kd[0] == 0.63f && s.mats[i].kd[1] == 0.065f &&
              s.mats[i].kd[2] == 0.05f,
          "red");
    i = mat_named(&s, "green");
    CHECK(i >= 0 && s.mats[i].kd[0] == 0.14f && s.mats[i].kd[1] == 0.45f &&
              s.mats[i].kd[2] == 0.091f,
          "green");
    for (i = 0; i < s.ntris; i++) {
        float n[3];
        tri_normal(&s.tris[i], n);
        if (s.tris[i].mat == light) {
            nlight++;
            CHECK(n[1] < -0.999f && s.tris[i].v[0][1] == 548.7f, "light faces down");
        }
        CHECK(!s.tris[i].has_n, "no vertex normals");
    }
    CHECK(nlight == 2, "%d light triangles", nlight);
    CHECK(s.cam.eye[0] == 278 && s.cam.eye[1] == 273 && s.cam.eye[2] == -800 &&
              s.cam.look[2] == 0 && s.cam.up[1] == 1 && near(s.cam.fov_deg, 39.3077, 1e-4),
          "camera");
    CHECK(s.cam.width == 512 && s.cam.height == 512 && s.env.kind == ENV_NONE, "res/env");
    scene_free(&s);
}

TEST(test_fig5)
{
    scene s;
    int i, light = -1;
    const material *m;
    if (load("demo/scenes/fig5.scene", &s) < 0)
        return;
    CHECK(s.nspheres == 4 && s.ntris == 2, "%d spheres, %d triangles", s.nspheres, s.ntris);
    CHECK(count_emitters(&s, &light) == 1 && s.mats[light].ke[1] == 8, "one light, Ke 8");
    for (i = 0; i < s.ntris; i++) {
        float n[3];
        tri_normal(&s.tris[i], n);
        CHECK(s.tris[i].mat == light && n[1] < -0.999f && s.tris[i].v[0][1] == 5, "light");
    }
    if (s.nspheres == 4) {
        CHECK(s.spheres[0].r == 1000 && s.spheres[0].c[1] + s.spheres[0].r == 0, "table");
        for (i = 1; i < 4; i++)
            CHECK(s.spheres[i].r == 1 && s.spheres[i].c[1] == 1 &&
                      s.spheres[i].c[0] == -2.5f + 2.5f * (i - 1),
                  "sphere %d", i);
        m = &s.mats[s.spheres[2].mat];
        CHECK(m->kd[0] == 0.4f && m->ks[0] == 0.4f && m->ns == 60, "glossy");
        m = &s.mats[s.spheres[3].mat];
        CHECK(m->kd[0] == 0.6f && m->bump == 0.08f && m->bump_freq == 12, "bumpy");
        CHECK(s.mats[s.spheres[1].mat].kd[0] == 0.6f, "diffuse");
    }
    CHECK(s.cam.width == 512 && s.cam.height == 384, "resolution");
    CHECK(s.env.kind == ENV_CONSTANT && s.env.base[0] == 0.05f, "environment");
    scene_free(&s);
}

TEST(test_fig15)
{
    static const float centre[3] = {1.8f, 2.0f, 0.5f}; /* of the box */
    scene s;
    int i, k;
    if (load("demo/scenes/fig15.scene", &s) < 0)
        return;
    CHECK(s.ntris == 2 + 12 && s.nspheres == 1, "%d triangles", s.ntris);
    CHECK(s.nspheres == 1 && s.spheres[0].r == 1 && s.spheres[0].c[0] == -1.5f &&
              s.spheres[0].c[1] == 2 && s.mats[s.spheres[0].mat].kd[0] == 0,
          "sphere");
    for (i = 0; i < s.ntris; i++) {
        const triangle *t = &s.tris[i];
        float n[3], d = 0;
        tri_normal(t, n);
        if (i < 2) {
            CHECK(n[1] > 0.999f && s.mats[t->mat].kd[0] == 0.8f, "ground faces up");
            continue;
        }
        for (k = 0; k < 3; k++)
            d += n[k] * (t->v[0][k] - centre[k]);
        CHECK(d > 0.79f && s.mats[t->mat].kd[0] == 0, "box tri %d: outward 0.8 from centre", i);
        for (k = 0; k < 3; k++)
            CHECK(t->v[k][1] >= 1.2f - 1e-6f && t->v[k][1] <= 2.8f + 1e-6f, "box height");
    }
    CHECK(s.env.kind == ENV_GAUSSIAN && s.env.base[0] == 0.3f && s.env.peak[0] == 2.0f &&
              s.env.sigma_deg == 25,
          "environment");
    CHECK(near(s.env.dir[0] / s.env.dir[1], 0.3, 1e-6) &&
              near(s.env.dir[2] / s.env.dir[1], 0.2, 1e-6) &&
              near(hypot(hypot(s.env.dir[0], s.env.dir[1]), s.env.dir[2]), 1, 1e-6),
          "direction normalised");
    CHECK(s.cam.width == 512 && s.cam.height == 512, "resolution");
    scene_free(&s);
}

static float edge(const triangle *t, int a, int b)
{
    float d0 = t->v[b][0] - t->v[a][0], d1 = t->v[b][1] - t->v[a][1], d2 = t->v[b][2] - t->v[a][2];
    return sqrtf(d0 * d0 + d1 * d1 + d2 * d2);
}

TEST(test_sh)
{
    scene s;
    int i, k, seen[3] = {0, 0, 0};
    if (load("demo/scenes/sh.scene", &s) < 0)
        return;
    CHECK(s.ntris == 2 + 6 && s.nspheres == 1, "%d triangles", s.ntris);
    CHECK(s.nspheres == 1 && s.spheres[0].r == 1 && s.spheres[0].c[0] == 0 &&
              s.mats[s.spheres[0].mat].ks[0] == 0.3f && s.mats[s.spheres[0].mat].ns == 30,
          "object");
    for (i = 0; i < s.ntris; i++) {
        const triangle *t = &s.tris[i];
        const material *m = &s.mats[t->mat];
        float n[3], c[3], dist;
        int col;
        tri_normal(t, n);
        if (m->ke[0] + m->ke[1] + m->ke[2] == 0) {
            CHECK(t->v[0][1] == -1 && n[1] > 0.999f && m->kd[0] == 0.5f, "ground");
            continue;
        }
        col = m->ke[0] == 20 ? 0 : m->ke[1] == 20 ? 1 : 2;
        CHECK(m->ke[col] == 20 && m->ke[(col + 1) % 3] == 2 && m->ke[(col + 2) % 3] == 2, "colour");
        seen[col]++;
        /* a fan triangle's longest edge is the square's diagonal, its edge
         * 1-2 a side */
        for (k = 0; k < 3; k++)
            c[k] = edge(t, 0, 1) > edge(t, 0, 2) ? 0.5f * (t->v[0][k] + t->v[1][k])
                                                 : 0.5f * (t->v[0][k] + t->v[2][k]);
        dist = sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        CHECK(dist >= 1.5f && dist <= 2.5f, "emitter at %g", (double)dist);
        CHECK(near(edge(t, 1, 2), 0.4, 1e-3), "side %g", (double)edge(t, 1, 2));
        CHECK(-(n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / dist > 0.9999f, "faces the centre");
    }
    CHECK(seen[0] == 2 && seen[1] == 2 && seen[2] == 2, "two triangles per colour");
    CHECK(s.env.kind == ENV_NONE && s.cam.width == 512 && s.cam.height == 512, "env, res");
    scene_free(&s);
}

/* ------------------------------------------------------------ main */

/* Makes the project's root the current directory (the expected errors
 * name files relative to it): argv[1], else the current directory, else
 * the program's directory or one of its two parents. */
static int find_root(int argc, char **argv)
{
    static const char *const up[] = {"", "/..", "/../.."};
    struct stat st;
    char dir[4096], probe[4200], *slash;
    size_t i;
    if (argc > 1)
        return chdir(argv[1]);
    if (stat("tests/data/bad", &st) == 0)
        return 0;
    snprintf(dir, sizeof dir, "%s", argv[0]);
    if (!(slash = strrchr(dir, '/')))
        return -1;
    *slash = '\0';
    for (i = 0; i < sizeof up / sizeof up[0]; i++) {
        snprintf(probe, sizeof probe, "%s%s/tests/data/bad", dir[0] ? dir : "", up[i]);
        if (stat(probe, &st) == 0) {
            probe[strlen(probe) - strlen("/tests/data/bad")] = '\0';
            return chdir(probe[0] ? probe : "/");
        }
    }
    return -1;
}

int main(int argc, char **argv)
{
    static const test_case all[] = {TESTS(TEST_ROW)};
    if (find_root(argc, argv) < 0) {
        fprintf(stderr, "t_loader: run from the project's root or pass it: t_loader ROOT\n");
        return 2;
    }
    /* after ROOT come the names of the tests to run */
    if (argc > 1) {
        argc--;
        argv++;
    }
    return test_run(all, sizeof all / sizeof all[0], argc, argv);
}

/* obj FILE S TX TY TZ: each vertex is S v + T, exactly as float arithmetic
 * gives it; normals unchanged; the sun's direction normalised. */
TEST(test_placed)
{
    scene s;
    int k, c;
    if (load("tests/data/good/placed.scene", &s) < 0)
        return;
    CHECK(s.ntris == 2, "%d triangles", s.ntris);
    if (s.ntris == 2) {
        static const float t[3] = {1.0f, -2.0f, 0.5f};
        for (k = 0; k < 3; k++)
            for (c = 0; c < 3; c++)
                CHECK(s.tris[1].v[k][c] == 2.0f * s.tris[0].v[k][c] + t[c], "vertex %d.%d: %g", k,
                      c, (double)s.tris[1].v[k][c]);
        CHECK(s.tris[0].v[2][2] == -0.5f && s.tris[1].v[2][2] == -0.5f, "z of the third vertex");
        CHECK(s.tris[1].has_n && s.tris[1].n[0][2] == 1.0f, "normals kept");
    }
    CHECK(s.sun.on && near(s.sun.dir[1], 0.6, 1e-7) && near(s.sun.dir[2], 0.8, 1e-7) &&
              s.sun.dir[0] == 0.0f && s.sun.e[1] == 2.0f && s.sun.e[2] == 0.5f,
          "sun (%g %g %g)", (double)s.sun.dir[0], (double)s.sun.dir[1], (double)s.sun.dir[2]);
    scene_free(&s);
}

/* The real scenes as make real-scenes leaves them in build/scenes: every
 * face of both models (all triangles), the bunny standing on the atrium's
 * floor (y = 0.0933), a sun and no area light. */
TEST(test_real)
{
    static const char *const views[2] = {"build/scenes/sponza-atrium.scene",
                                         "build/scenes/sponza-arcade.scene"};
    int v, i, k;
    for (v = 0; v < 2; v++) {
        scene s;
        float lo = 1e30f;
        if (load(views[v], &s) < 0)
            return;
        CHECK(s.ntris == 66454 + 69451, "%s: %d triangles", views[v], s.ntris);
        for (i = 66454; i < s.ntris; i++)
            for (k = 0; k < 3; k++)
                lo = s.tris[i].v[k][1] < lo ? s.tris[i].v[k][1] : lo;
        CHECK(near(lo, 0.0933, 2e-4), "bunny's lowest point at y = %g", (double)lo);
        CHECK(s.sun.on && s.env.kind == ENV_NONE, "sun, black sky");
        for (i = 0; i < s.ntris; i++)
            if (s.mats[s.tris[i].mat].ke[0] > 0.0f)
                break;
        CHECK(i == s.ntris, "no emitter");
        CHECK(s.nmats == 1 && s.mats[0].kd[1] == 0.6f, "grey 0.6");
        scene_free(&s);
    }
}
