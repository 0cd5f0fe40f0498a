/* t_adaptive.c -- the demo's adaptive image sampling: the Delaunay
 * triangulation against its defining property, the reconstruction against
 * functions it must reproduce, and where the quad-tree puts its samples. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sampling.h"
#include "scenes.h"
#include "test.h"

/* Checks a triangulation of the n points of xy: every triangle
 * counter-clockwise and not flat, their areas summing to the rectangle's
 * (so they tile it), and no point strictly inside any circumcircle (the
 * Delaunay property, tested against every point). */
static void check_delaunay(const long long *xy, int n, long long w, long long h, const char *what)
{
    int *tri = NULL, nt = 0, k, i, bad_area = 0, bad_circle = 0;
    long long area2 = 0;
    CHECK(delaunay(xy, n, &tri, &nt) == 0, "%s: triangulation failed", what);
    for (k = 0; k < nt; k++) {
        const long long *a = xy + 2 * tri[3 * k], *b = xy + 2 * tri[3 * k + 1],
                        *c = xy + 2 * tri[3 * k + 2];
        const long long o = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        bad_area += o <= 0;
        area2 += o;
        for (i = 0; i < n; i++) {
            const long long *d = xy + 2 * i;
            const double adx = (double)(a[0] - d[0]), ady = (double)(a[1] - d[1]),
                         bdx = (double)(b[0] - d[0]), bdy = (double)(b[1] - d[1]),
                         cdx = (double)(c[0] - d[0]), cdy = (double)(c[1] - d[1]);
            const double det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                               (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                               (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
            bad_circle += det > 0.5; /* exact here: small integers */
        }
    }
    for (i = 0, k = 0; i < n; i++) /* points on the rectangle's border */
        k += xy[2 * i] == 0 || xy[2 * i] == w || xy[2 * i + 1] == 0 || xy[2 * i + 1] == h;
    printf("  %s: %d points (%d on the border), %d triangles\n", what, n, k, nt);
    CHECK(nt == 2 * n - 2 - k, "%s: %d triangles for %d points, %d on the border", what, nt, n, k);
    CHECK(bad_area == 0, "%s: %d triangles flat or clockwise", what, bad_area);
    CHECK(area2 == 2 * w * h, "%s: areas sum to %lld, not %lld", what, area2 / 2, w * h);
    CHECK(bad_circle == 0, "%s: %d points inside a circumcircle", what, bad_circle);
    free(tri);
}

/* Random distinct points inside a 300 x 200 rectangle; then a full grid
 * (every four neighbours co-circular), the degenerate case quad-trees make. */
TEST(test_delaunay_property)
{
    enum { N = 600 };
    static long long xy[2 * N];
    static unsigned char used[301 * 201];
    unsigned long long st = 3;
    int n = 4, x, y;
    const long long corner[8] = {0, 0, 300, 0, 300, 200, 0, 200};
    memcpy(xy, corner, sizeof corner);
    memset(used, 0, sizeof used);
    used[0] = used[300] = used[200 * 301] = used[200 * 301 + 300] = 1;
    while (n < N) {
        x = (int)(xrand(&st) * 301);
        y = (int)(xrand(&st) * 201);
        if (x > 300 || y > 200 || used[y * 301 + x])
            continue;
        used[y * 301 + x] = 1;
        xy[2 * n] = x;
        xy[2 * n + 1] = y;
        n++;
    }
    check_delaunay(xy, n, 300, 200, "random");
    n = 4;
    for (y = 0; y <= 20; y++)
        for (x = 0; x <= 24; x++)
            if (!((x == 0 || x == 24) && (y == 0 || y == 20))) {
                xy[2 * n] = x;
                xy[2 * n + 1] = y;
                n++;
            }
    xy[2] = 24; xy[4] = 24; xy[5] = 20; xy[7] = 20;
    check_delaunay(xy, n, 24, 20, "grid");
}

/* The sampler's evaluator for the tests: an affine image, importance a
 * step (the right third 30 times the rest), one object boundary at
 * x = bx (none when bx < 0). */
typedef struct tctx {
    float bx;
    int calls;
} tctx;

static float affine(float x, float y, int k)
{
    return 0.25f + 0.01f * x - 0.02f * y + 0.1f * (float)k;
}

static int teval(void *ctx, ad_sample *s)
{
    tctx *t = (tctx *)ctx;
    int k;
    t->calls++;
    for (k = 0; k < 3; k++)
        s->rgb[k] = affine(s->x, s->y, k);
    s->importance = s->x > 2.0f * 96.0f / 3.0f ? 30.0f : 1.0f;
    s->object = t->bx >= 0.0f && s->x > t->bx;
    return 0;
}

/* No two samples at one place (the triangulation needs that) and, at
 * pixels, every one at a pixel centre.  Returns how many are wrong. */
static int misplaced(const ad_sample *s, int n, int at_pixels)
{
    int i, j, bad = 0;
    for (i = 0; i < n; i++) {
        if (at_pixels && (s[i].x - 0.5f != floorf(s[i].x) || s[i].y - 0.5f != floorf(s[i].y)))
            bad++;
        for (j = 0; j < i; j++)
            bad += s[i].x == s[j].x && s[i].y == s[j].y;
    }
    return bad;
}

/* The reconstruction reproduces an affine image at every pixel (linear
 * interpolation is exact there), whatever the sample positions: at the
 * squares' centres and at pixel centres. */
static void affine_case(int mode)
{
    const ad_opts o = {96, 64, 8, 0.2, 1.0f, mode};
    tctx t = {-1.0f, 0};
    ad_sample *s = NULL;
    float *img = malloc(sizeof *img * 3 * 96 * 64), worst = 0.0f;
    int n = 0, x, y, k;
    CHECK(adaptive_sample(&o, teval, &t, &s, &n) == 0, "sampling");
    CHECK(misplaced(s, n, mode) == 0, "%d samples misplaced (at_pixels %d)", misplaced(s, n, mode), mode);
    CHECK(adaptive_reconstruct(s, n, 96, 64, 0.5f, img) == 0, "reconstruction");
    for (y = 0; y < 64; y++)
        for (x = 0; x < 96; x++)
            for (k = 0; k < 3; k++) {
                const float e = fabsf(img[3 * (y * 96 + x) + k] - affine((float)x + 0.5f, (float)y + 0.5f, k));
                if (e > worst)
                    worst = e;
            }
    printf("  at_pixels %d: %d samples; largest error against the affine image %.2e\n", mode, n, worst);
    CHECK(worst < 1e-5f, "an affine image is not reproduced: %g", worst);
    free(s);
    free(img);
}

TEST(test_adaptive_reconstruct_affine)
{
    affine_case(0); /* at the squares' centres */
    affine_case(1); /* at pixel centres */
}

/* Samples follow importance: the budget is kept (to the 3 a split may
 * pass it by), every sample was evaluated once, and the right third,
 * 30 times as important, holds far more than a third of them. */
static void density_case(int mode)
{
    const ad_opts o = {96, 64, 8, 0.15, 1.0f, mode};
    tctx t = {-1.0f, 0};
    ad_sample *s = NULL;
    int n = 0, i, right = 0;
    CHECK(adaptive_sample(&o, teval, &t, &s, &n) == 0, "sampling");
    for (i = 0; i < n; i++)
        right += s[i].x > 64.0f;
    printf("  %d samples (budget %d), %d in the right third\n", n, (int)(0.15 * 96 * 64), right);
    CHECK(n <= (int)(0.15 * 96 * 64) + 3 && n >= (int)(0.15 * 96 * 64), "count %d", n);
    CHECK(t.calls == n, "%d evaluations for %d samples", t.calls, n);
    CHECK(right > n / 2, "only %d of %d samples where importance is 30x", right, n);
    CHECK(misplaced(s, n, mode) == 0, "misplaced samples");
    free(s);
}

TEST(test_adaptive_density)
{
    density_case(0); /* at the squares' centres */
    density_case(1); /* at pixel centres */
}

/* An object boundary at x = 37.3 is refined to the smallest squares
 * first: with importance the same everywhere, samples within a pixel of
 * it are far denser than elsewhere. */
static void boundary_case(int mode)
{
    const ad_opts o = {96, 64, 8, 0.1, 1.0f, mode};
    tctx t = {37.3f, 0};
    ad_sample *s = NULL;
    int n = 0, i, near = 0;
    CHECK(adaptive_sample(&o, teval, &t, &s, &n) == 0, "sampling");
    for (i = 0; i < n; i++)
        near += fabsf(s[i].x - 37.3f) < 1.5f;
    printf("  %d samples, %d within 1.5 pixels of the boundary (3/96 of the width)\n", n, near);
    CHECK(near * 96 > n * 3 * 4, "boundary not refined: %d of %d", near, n);
    free(s);
}

TEST(test_adaptive_boundary)
{
    boundary_case(0); /* at the squares' centres */
    boundary_case(1); /* at pixel centres */
}

/* Evaluators for boundaries on a block line (y = 32: between pixel rows
 * 31 and 32) and for a region edge inside one object (x = 53.7, where
 * the luminance steps by 1); importance 0 everywhere. */
static int eval_row_boundary(void *ctx, ad_sample *s)
{
    (void)ctx;
    s->rgb[0] = s->rgb[1] = s->rgb[2] = s->y > 32.0f ? 1.0f : 0.0f;
    s->object = s->y > 32.0f;
    return 0;
}

static int eval_region(void *ctx, ad_sample *s)
{
    const int *on = (const int *)ctx;
    s->rgb[0] = s->rgb[1] = s->rgb[2] = s->x > 53.7f ? 1.0f : 0.0f;
    s->region = *on && s->x > 53.7f;
    return 0;
}

/* An object boundary on a block line is refined from both sides to the
 * pixel: every column has samples in pixel rows 31 and 32.  (Squares
 * compare with their same-size neighbours both ways; found from the
 * side split second only, row 31 or 32 kept 8-pixel gaps.) */
TEST(test_adaptive_boundary_both_sides)
{
    const ad_opts o = {96, 64, 8, 0.3, 1.0f, 1};
    ad_sample *s = NULL;
    int n = 0, i, x, missing = 0;
    unsigned char row[2][96];
    memset(row, 0, sizeof row);
    CHECK(adaptive_sample(&o, eval_row_boundary, NULL, &s, &n) == 0, "sampling");
    for (i = 0; i < n; i++)
        if (s[i].y == 31.5f || s[i].y == 32.5f)
            row[s[i].y == 32.5f][(int)s[i].x] = 1;
    for (x = 0; x < 96; x++)
        missing += !row[0][x] + !row[1][x];
    printf("  %d samples; %d of 192 pixels beside the boundary not sampled\n", n, missing);
    CHECK(missing == 0, "%d pixels beside the boundary not sampled", missing);
    free(s);
}

/* A region edge (a shadow's, inside one object) with no importance
 * elsewhere: with regions the samples crowd within 1.5 pixels of it (its
 * jump is the only importance); with them off the same image spreads
 * its samples (no importance anywhere: the heap's order). */
TEST(test_adaptive_region)
{
    const ad_opts o = {96, 64, 8, 0.1, 1.0f, 1};
    int on, near[2] = {0, 0}, n = 0;
    for (on = 0; on < 2; on++) {
        ad_sample *s = NULL;
        int i;
        CHECK(adaptive_sample(&o, eval_region, &on, &s, &n) == 0, "sampling");
        for (i = 0; i < n; i++)
            near[on] += fabsf(s[i].x - 53.7f) < 1.5f;
        free(s);
    }
    printf("  %d samples; within 1.5 pixels of the region edge: %d with regions, %d without\n",
           n, near[1], near[0]);
    CHECK(near[1] * 96 > n * 3 * 4, "edge not refined: %d of %d", near[1], n);
    CHECK(near[1] > 2 * near[0], "regions change nothing: %d vs %d", near[1], near[0]);
}

#define TESTS(X) X(test_delaunay_property) X(test_adaptive_reconstruct_affine) \
    X(test_adaptive_density) X(test_adaptive_boundary) X(test_adaptive_boundary_both_sides) \
    X(test_adaptive_region)
TESTS(TEST_DECL)

int main(int argc, char **argv)
{
    static const test_case all[] = {TESTS(TEST_ROW)};
    return test_run(all, sizeof all / sizeof all[0], argc, argv);
}
