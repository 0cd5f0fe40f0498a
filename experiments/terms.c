/*
 * terms.c -- the first-order paper's Fig. 5 and 6 on its scene: what each
 * term of the image gradient does (experiments/imgrad.c).  SV, the lighting's
 * spatial variation (the point moves, normal and view held), and CDV, the
 * curvature-weighted directional variation (the normal turns with
 * curvature and bumps), per pixel as |lum(d/dx)|, |lum(d/dy)| combined;
 * their ratio CDV/SV on a log scale (Fig. 5e); and that ratio as the area
 * light rises away from the table (Fig. 6): the paper's reading is that
 * SV falls faster than CDV with distance (L_x ~ L_theta / d), so distant
 * light is curvature-dominated.  Writes PNGs with a colour bar under each
 * to build/terms-out/ and prints the median log10(CDV/SV) on each sphere
 * per light height.  Direct light only (the terms are its).
 *   terms SCENE [W H]
 * Colour scales: SV and CDV map log10 of the magnitude over [-4, 0]
 * (radiance per pixel) from black through orange to white; the ratio maps
 * log10(CDV/SV) over [-2, 2] from blue (SV dominates) through white to red
 * (CDV dominates).  The bar under an image runs over the same range, left
 * to right.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "image.h"
#include "imgrad.h"

#define BAR 12 /* colour bar rows under each image */

/* The radiance png_write shows as v in [0, 1) (it maps x to 1 - exp(-x)
 * at exposure 1, then to sRGB): the inverse, so colours come out as set. */
static float shown(float v)
{
    return -logf(1.0f - (v > 0.999f ? 0.999f : v < 0.0f ? 0.0f : v));
}

/* t in [0, 1]: black, orange, white. */
static void heat(float t, float c[3])
{
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    c[0] = shown(fminf(1.0f, 2.0f * t));
    c[1] = shown(t < 0.5f ? 0.6f * 2.0f * t : 0.6f + 0.4f * (2.0f * t - 1.0f));
    c[2] = shown(t < 0.5f ? 0.0f : 2.0f * t - 1.0f);
}

/* t in [0, 1]: blue, white, red. */
static void diverge(float t, float c[3])
{
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    c[0] = shown(t < 0.5f ? 2.0f * t : 1.0f);
    c[1] = shown(t < 0.5f ? 2.0f * t : 2.0f - 2.0f * t);
    c[2] = shown(t < 0.5f ? 1.0f : 2.0f - 2.0f * t);
}

/* Writes values v (NaN: no surface, shown grey) mapped from [lo, hi] with
 * a colour bar of the same map underneath. */
static void write_map(const char *path, const float *v, int w, int h, float lo, float hi,
                      void (*map)(float, float[3]))
{
    float *img = malloc(sizeof *img * 3 * (size_t)w * (size_t)(h + BAR));
    char err[256];
    int x, y;
    if (!img)
        return;
    for (y = 0; y < h + BAR; y++)
        for (x = 0; x < w; x++) {
            float *c = &img[3 * ((size_t)y * w + x)];
            if (y >= h)
                map((float)x / (float)(w - 1), c);
            else if (v[y * w + x] != v[y * w + x])
                c[0] = c[1] = c[2] = shown(0.25f);
            else
                map((v[y * w + x] - lo) / (hi - lo), c);
        }
    if (png_write(path, w, h + BAR, img, 1.0f, err, sizeof err) < 0)
        fprintf(stderr, "terms: %s\n", err);
    free(img);
}

static float mag(float (*g)[3])
{
    const float x = lum3(g[0]), y = lum3(g[1]);
    return sqrtf(x * x + y * y);
}

static int cmp_float(const void *a, const void *b)
{
    const float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Raises every emissive triangle by dy. */
static void raise_lights(scene *s, float dy)
{
    int i, k;
    for (i = 0; i < s->ntris; i++) {
        const float *ke = s->mats[s->tris[i].mat].ke;
        if (ke[0] + ke[1] + ke[2] > 0.0f)
            for (k = 0; k < 3; k++)
                s->tris[i].v[k][1] += dy;
    }
}

/* One light height: the three maps, and the median log ratio per sphere
 * material.  Returns 0 or -1. */
static int height(scene *s, float dy, int write)
{
    static const char *const spheres[3] = {"diffuse", "glossy", "bumpy"};
    const int w = s->cam.width, h = s->cam.height;
    render_opts o;
    renderer r;
    cam_frame cf;
    char err[256], path[256];
    float *sv = malloc(sizeof *sv * 3 * (size_t)w * (size_t)h), *cdv = sv + w * h,
          *ratio = cdv + w * h, *med = malloc(sizeof *med * (size_t)w * (size_t)h);
    int x, y, k, st = 0;
    if (!sv || !med)
        return -1;
    raise_lights(s, dy);
    render_opts_defaults(&o);
    o.mode = MODE_REFERENCE; /* E is not needed: the terms are direct light's */
    o.ref_rays = 1;
    if (renderer_init(&r, s, &o, err, sizeof err) < 0) {
        fprintf(stderr, "terms: %s\n", err);
        raise_lights(s, -dy);
        return -1;
    }
    camera_frame(&s->cam, &cf);
    for (y = 0; y < h && st == 0; y++)
        for (x = 0; x < w && st == 0; x++) {
            img_point ip;
            const int i = y * w + x;
            st = image_point(&r, &cf, (float)x + 0.5f, (float)y + 0.5f, IMG_GRADIENT_PARTS, 0, &ip);
            if (ip.object < 0 || (mag(ip.sv) == 0.0f && mag(ip.cdv) == 0.0f)) {
                sv[i] = cdv[i] = ratio[i] = NAN;
                continue;
            }
            sv[i] = log10f(mag(ip.sv) + 1e-12f);
            cdv[i] = log10f(mag(ip.cdv) + 1e-12f);
            ratio[i] = cdv[i] - sv[i];
        }
    printf("light raised %5.1f:", dy);
    for (k = 0; k < 3; k++) {
        int n = 0;
        for (y = 0; y < h; y++)
            for (x = 0; x < w; x++) {
                float d[3];
                bvh_hit bh;
                camera_ray(&cf, &s->cam, x, y, d);
                if (ratio[y * w + x] == ratio[y * w + x] &&
                    bvh_intersect(&r.b, cf.eye, d, 0.0f, 1e30f, &bh) && bh.prim < 0 &&
                    strcmp(s->mats[s->spheres[-bh.prim - 1].mat].name, spheres[k]) == 0)
                    med[n++] = ratio[y * w + x];
            }
        qsort(med, (size_t)n, sizeof *med, cmp_float);
        printf("  %s %+.2f", spheres[k], n ? med[n / 2] : 0.0f);
    }
    printf("  (median log10 CDV/SV)\n");
    if (write) {
        write_map("build/terms-out/sv.png", sv, w, h, -4.0f, 0.0f, heat);
        write_map("build/terms-out/cdv.png", cdv, w, h, -4.0f, 0.0f, heat);
    }
    snprintf(path, sizeof path, "build/terms-out/ratio-up%02.0f.png", dy);
    write_map(path, ratio, w, h, -2.0f, 2.0f, diverge);
    renderer_free(&r);
    raise_lights(s, -dy);
    free(sv);
    free(med);
    return st;
}

int main(int argc, char **argv)
{
    static const float ups[4] = {0.0f, 5.0f, 15.0f, 35.0f};
    scene s;
    char err[1024];
    int i, rc = 0;
    if (argc < 2) {
        fprintf(stderr, "usage: terms SCENE [W H]\n");
        return 2;
    }
    if (scene_load(argv[1], &s, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    if (argc >= 4) {
        s.cam.width = atoi(argv[2]);
        s.cam.height = atoi(argv[3]);
    }
    mkdir("build", 0777);
    mkdir("build/terms-out", 0777);
    for (i = 0; i < 4 && rc == 0; i++)
        rc = height(&s, ups[i], i == 0) < 0;
    scene_free(&s);
    return rc;
}
