/*
 * fig15.c -- the first-order paper's Fig. 15 experiment on the fig15 scene:
 * the ground plane's irradiance in a head-on view (W x W pixels over the
 * square [-4, 4]^2 of the plane y = 0), sampled by records on a 20 x 20
 * grid (1% of the pixels) and reconstructed over every pixel three ways:
 *   linear:     bilinear interpolation of E between the four grid records;
 *   Krivanek:   bilinear blend of the four records' first-order
 *               extrapolations E_i + g_i.(p - p_i), g from Krivanek's
 *               stratified gradient;
 *   visibility: the same with g from visibility gradients.
 * Each against a brute-force reference (REF rays per pixel).  Prints the
 * relative RMSE (sqrt(sum (a-b)^2 / sum b^2)) and the largest error over
 * the reference's largest value, and writes PNGs to build/fig15-out/.
 *   fig15 [SCENE [W [REF [M N]]]]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "image.h"
#include "render.h"

#define GRID 20
#define HALF 4.0f

static void pixel_point(int w, double x, double y, float p[3])
{
    p[0] = (float)(-HALF + 2.0 * HALF * (x + 0.5) / w);
    p[1] = 1e-4f; /* just above the plane */
    p[2] = (float)(-HALF + 2.0 * HALF * (y + 0.5) / w);
}

/* Grid records with one feature set; 0 or a negative status. */
static int grid(const scene *s, uint32_t features, uint32_t m, uint32_t n, int w,
                irc_record rec[GRID][GRID])
{
    render_opts o;
    renderer r;
    char err[256];
    int i, j, st = 0;
    memset(&o, 0, sizeof o);
    o.mode = MODE_CACHE;
    o.features = features;
    o.accuracy = 0.2f;
    o.strata_m = m;
    o.strata_n = n;
    o.max_records = 16;
    o.threads = 1;
    o.seed = 7;
    if (renderer_init(&r, s, &o, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    for (j = 0; j < GRID && st >= 0; j++)
        for (i = 0; i < GRID && st >= 0; i++) {
            float p[3], up[3] = {0, 1, 0};
            pixel_point(w, i * (w - 1.0) / (GRID - 1), j * (w - 1.0) / (GRID - 1), p);
            st = render_record(&r, p, up, &rec[j][i]);
        }
    renderer_free(&r);
    return st;
}

/* Bilinear blend over the grid cell holding pixel (x, y); grad: use the
 * records' translational gradients. */
static float reconstruct(irc_record rec[GRID][GRID], int w, int x, int y, int grad)
{
    double gx = x * (GRID - 1.0) / (w - 1.0), gy = y * (GRID - 1.0) / (w - 1.0), sum = 0.0;
    int i0 = (int)gx < GRID - 1 ? (int)gx : GRID - 2, j0 = (int)gy < GRID - 1 ? (int)gy : GRID - 2;
    double fx = gx - i0, fy = gy - j0;
    float p[3];
    int a, b;
    pixel_point(w, x, y, p);
    for (b = 0; b < 2; b++)
        for (a = 0; a < 2; a++) {
            const irc_record *r = &rec[j0 + b][i0 + a];
            double wgt = (a ? fx : 1.0 - fx) * (b ? fy : 1.0 - fy), v = r->e[0];
            int k;
            if (grad)
                for (k = 0; k < 3; k++)
                    v += r->grad_t[0][k] * (p[k] - r->p[k]);
            sum += wgt * v;
        }
    return (float)sum;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "demo/scenes/fig15.scene";
    int w = argc > 2 ? atoi(argv[2]) : 200, ref_rays = argc > 3 ? atoi(argv[3]) : 4096;
    uint32_t m = argc > 5 ? (uint32_t)atoi(argv[4]) : 32, n = argc > 5 ? (uint32_t)atoi(argv[5]) : 128;
    static irc_record rec[3][GRID][GRID];
    static const char *names[3] = {"linear", "Krivanek gradients", "visibility gradients"};
    static const uint32_t feats[3] = {IRC_FEATURE_NONE, IRC_FEATURE_TRANSLATION, IRC_FEATURE_VISIBILITY};
    scene s;
    renderer rr;
    render_opts o;
    render_stats st;
    char err[512];
    float *pts, *ref, *img;
    double rmse[3];
    int k, x, y;
    if (scene_load(path, &s, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    pts = malloc(sizeof(float) * 6 * (size_t)w * w);
    ref = malloc(sizeof(float) * 3 * (size_t)w * w);
    img = malloc(sizeof(float) * 3 * (size_t)w * w);
    for (y = 0; y < w; y++)
        for (x = 0; x < w; x++) {
            float *q = &pts[6 * ((size_t)y * w + x)];
            pixel_point(w, x, y, q);
            q[3] = q[5] = 0.0f;
            q[4] = 1.0f;
        }
    memset(&o, 0, sizeof o);
    o.mode = MODE_REFERENCE;
    o.ref_rays = ref_rays;
    o.threads = 1;
    o.seed = 11;
    if (renderer_init(&rr, &s, &o, err, sizeof err) < 0 ||
        render_points(&rr, pts, w * w, ref, &st) < 0) {
        fprintf(stderr, "reference failed\n");
        return 1;
    }
    renderer_free(&rr);
    printf("fig15: %dx%d pixels of the ground plane, %d x %d records (%.2f%% of pixels), "
           "%ux%u strata; reference %d rays/pixel (%.1f s)\n",
           w, w, GRID, GRID, 100.0 * GRID * GRID / ((double)w * w), m, n, ref_rays, st.wall);
    mkdir("build", 0777);
    mkdir("build/fig15-out", 0777);
    png_write("build/fig15-out/reference.png", w, w, ref, 1.0f, err, sizeof err);
    for (k = 0; k < 3; k++) {
        double se = 0, sr = 0, big = 0, rmax = 0;
        char file[128];
        unsigned long long rays = 0;
        if (grid(&s, feats[k], m, n, w, rec[k]) < 0) {
            fprintf(stderr, "records failed\n");
            return 1;
        }
        for (y = 0; y < GRID; y++)
            for (x = 0; x < GRID; x++)
                rays += rec[k][y][x].rays;
        for (y = 0; y < w; y++)
            for (x = 0; x < w; x++) {
                size_t at = (size_t)y * w + x;
                float v = reconstruct(rec[k], w, x, y, k > 0), r0 = ref[3 * at];
                double d = v - r0;
                img[3 * at] = img[3 * at + 1] = img[3 * at + 2] = v;
                se += d * d;
                sr += (double)r0 * r0;
                if (fabs(d) > big) big = fabs(d);
                if (r0 > rmax) rmax = r0;
            }
        rmse[k] = sqrt(se / sr);
        printf("  %-22s relative RMSE %.4f  largest error %5.2f%% of the reference's largest"
               "  (%llu rays for the records)\n", names[k], rmse[k], 100.0 * big / rmax, rays);
        snprintf(file, sizeof file, "build/fig15-out/%s.png", k == 0 ? "linear" : k == 1 ? "krivanek" : "visibility");
        png_write(file, w, w, img, 1.0f, err, sizeof err);
    }
    printf("  visibility gradients cut linear interpolation's RMSE %.1fx and Krivanek's %.1fx\n",
           rmse[0] / rmse[2], rmse[1] / rmse[2]);
    free(pts);
    free(ref);
    free(img);
    scene_free(&s);
    return 0;
}
