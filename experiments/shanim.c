/*
 * shanim.c -- the SH-gradient paper's setting as an animation (experiments/README.md:
 * "A moving object"): the `sh` scene's object travels a loop among the three
 * coloured emitters, and every frame it is shaded from SH records at free
 * points computed for that frame (Eq. 14-16, SH-gradient paper):
 *
 *   1     one record at the centre, no gradient
 *   1+g   one record at the centre + its gradient (Eq. 14)
 *   8     eight records (corners of a cube about the centre), no gradients,
 *         weighted by Eq. 16 as the library makes it scale-free:
 *         (R_j/|p - p_j|)^b, R_j the record's harmonic mean distance
 *   8+g   the eight with gradients (Eq. 15)
 *
 * against a record at every pixel's point (the reference, whose own noise
 * is measured with a second seed).  Prints each frame's relative RMSE and
 * time per method and the paper's two claims frame by frame; writes
 * OUT/frame-NN.png (reference, 1, 1+g, 8, 8+g side by side) and
 * OUT/contact.png (every frame, one row each).
 *
 *   shanim [--frames F] [--size W] [--strata M N] [--corner K] [--power B]
 *          [--out DIR] [SCENE]
 *     defaults: 16 frames, 64 x 64, 32 x 128 strata a hemisphere, corners
 *     at K = 0.5 of the radius, b = 2 (the library's), build/sh-animation,
 *     demo/scenes/sh.scene
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "image.h"
#include "render.h"
#include "shobj.h"

#define PI 3.14159265358979323846
#define METHODS 4
#define PANELS (METHODS + 1)

typedef struct anim_opts {
    int frames, w;
    uint32_t m, n;
    float corner, power;
    const char *out, *scene;
} anim_opts;

/* The loop: a circle of radius 0.45 at y = 0.1 (the object's radius is 1;
 * it passes within 0.2 of the green emitter and never touches the ground). */
static void centre_at(int f, int frames, float c[3])
{
    double t = 2.0 * PI * f / frames;
    c[0] = (float)(0.45 * cos(t));
    c[1] = 0.1f;
    c[2] = (float)(0.45 * sin(t));
}

/* Panel `k` of a strip of PANELS images w wide, object pixels only. */
static void paste(float *strip, int w, int k, const float *rgb, const int *pix, int np)
{
    int i, ch;
    for (i = 0; i < np; i++) {
        int x = pix[i] % w, y = pix[i] / w;
        for (ch = 0; ch < 3; ch++)
            strip[3 * ((size_t)y * PANELS * w + (size_t)k * w + x) + ch] = rgb[3 * i + ch];
    }
}

typedef struct frame_result {
    double err[METHODS], sec[METHODS], noise, ref_sec;
} frame_result;

/* One frame: the reference, its second seed, the four methods; the strip
 * of panels goes to `strip` (PANELS w x w images side by side). */
static int frame(const anim_opts *o, sh_env *e, const material *mat, const sphere *obj,
                 const camera *cam, float *strip, frame_result *r)
{
    static const uint32_t feat[METHODS] = {IRC_FEATURE_SH, IRC_FEATURE_SH_GRADIENT,
                                           IRC_FEATURE_SH, IRC_FEATURE_SH_GRADIENT};
    size_t px = (size_t)o->w * o->w;
    float *pts = malloc(sizeof(float) * 9 * px), *ref = malloc(sizeof(float) * 3 * px);
    float *img = malloc(sizeof(float) * 3 * px);
    int *pix = malloc(sizeof(int) * px);
    float at[8][3];
    int np, i, k, st = -1;
    double t0;
    for (i = 0; i < 8; i++)
        for (k = 0; k < 3; k++)
            at[i][k] = obj->c[k] + o->corner * obj->r * (i >> k & 1 ? 1.0f : -1.0f);
    if (!pts || !ref || !img || !pix)
        goto done;
    np = sh_object_pixels(cam, obj, o->w, pts, pix);
    e->seed = 2;
    if (sh_truth(e, mat, pts, np, o->m, o->n, img) < 0)
        goto done;
    e->seed = 1;
    t0 = render_clock();
    if (sh_truth(e, mat, pts, np, o->m, o->n, ref) < 0)
        goto done;
    r->ref_sec = render_clock() - t0;
    r->noise = sh_rel_rmse(img, ref, np);
    paste(strip, o->w, 0, ref, pix, np);
    e->seed = 3;
    for (i = 0; i < METHODS; i++) {
        /* 1 and 1+g: the centre alone; 8 and 8+g: the corners */
        t0 = render_clock();
        if (sh_method(e, mat, pts, np, i < 2 ? (const float(*)[3])obj->c : (const float(*)[3])at,
                      i < 2 ? 1 : 8, feat[i], o->m, o->n, img) < 0)
            goto done;
        r->sec[i] = render_clock() - t0;
        r->err[i] = sh_rel_rmse(img, ref, np);
        paste(strip, o->w, i + 1, img, pix, np);
    }
    st = 0;
done:
    free(pts);
    free(ref);
    free(img);
    free(pix);
    return st;
}

static int write_png(const char *dir, const char *name, int w, int h, const float *rgb,
                     float exposure)
{
    char path[1024], err[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (png_write(path, w, h, rgb, exposure, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    return 0;
}

/* Mean of the reference panel's lit pixels: the exposure's scale. */
static float exposure_of(const float *strip, int w)
{
    double sum = 0.0;
    int x, y, cnt = 0;
    for (y = 0; y < w; y++)
        for (x = 0; x < w; x++) {
            const float *v = strip + 3 * ((size_t)y * PANELS * w + x);
            if (v[0] + v[1] + v[2] > 0.0f) {
                sum += (v[0] + v[1] + v[2]) / 3.0;
                cnt++;
            }
        }
    return cnt && sum > 0.0 ? (float)(cnt / sum) : 1.0f;
}

static void summary(const anim_opts *o, const frame_result *res)
{
    double worst1 = 0.0, worst8 = 0.0, sum[METHODS] = {0}, sec[METHODS] = {0}, ref = 0.0;
    int f, i, ok1 = 0, ok8 = 0;
    for (f = 0; f < o->frames; f++) {
        double a = res[f].err[1] / res[f].err[2], b = res[f].err[3] / res[f].err[2];
        ok1 += a <= 1.2;
        ok8 += b <= 0.5;
        worst1 = a > worst1 ? a : worst1;
        worst8 = b > worst8 ? b : worst8;
        for (i = 0; i < METHODS; i++) {
            sum[i] += res[f].err[i] / o->frames;
            sec[i] += res[f].sec[i] / o->frames;
        }
        ref += res[f].ref_sec / o->frames;
    }
    printf("mean     %6.4f %6.4f %6.4f %6.4f   ms a frame: %.1f %.1f %.1f %.1f, reference %.0f\n",
           sum[0], sum[1], sum[2], sum[3], 1e3 * sec[0], 1e3 * sec[1], 1e3 * sec[2], 1e3 * sec[3],
           1e3 * ref);
    printf("1+g within 1.2x of 8: %d of %d frames (worst ratio %.2f)\n", ok1, o->frames, worst1);
    printf("8+g at most half of 8: %d of %d frames (worst ratio %.2f)\n", ok8, o->frames, worst8);
}

static int run(const anim_opts *o, const scene *s)
{
    size_t stripsz = (size_t)PANELS * o->w * o->w * 3;
    float *strip = calloc(stripsz, sizeof(float)), *sheet;
    frame_result *res = calloc((size_t)o->frames, sizeof *res);
    float exposure = 1.0f;
    scene copy;
    sh_env e;
    int f;
    sheet = calloc(stripsz * (size_t)o->frames, sizeof(float));
    if (!strip || !sheet || !res || sh_env_init(&e, s, &copy, NULL) < 0)
        return -1;
    e.power = o->power;
    /* R_j as the library makes it (harmonic mean distance, clamped by the
     * gradient): Eq. 16's weights then favour records far from emitters. */
    e.min_radius = 0.01f;
    mkdir(o->out, 0777);
    printf("The sh scene's object on a loop among the emitters: %d frames, %dx%d, L = %d, "
           "%ux%u strata x 2 a record, corners at %.2f of the radius, b = %g\n",
           o->frames, o->w, o->w, SHOBJ_BANDS, o->m, o->n, o->corner,
           (double)o->power);
    printf("relative RMSE against a record per pixel (ref noise: that against another seed)\n");
    printf("frame  centre                 ref noise  1      1+g    8      8+g    "
           "(1+g)/8 (8+g)/8\n");
    for (f = 0; f < o->frames; f++) {
        sphere obj = s->spheres[0];
        char name[64];
        frame_result *r = &res[f];
        centre_at(f, o->frames, obj.c);
        memset(strip, 0, stripsz * sizeof(float));
        if (frame(o, &e, &s->mats[obj.mat], &obj, &s->cam, strip, r) < 0)
            return -1;
        if (f == 0)
            exposure = 0.5f * exposure_of(strip, o->w);
        snprintf(name, sizeof name, "frame-%02d.png", f);
        if (write_png(o->out, name, PANELS * o->w, o->w, strip, exposure) < 0)
            return -1;
        memcpy(sheet + stripsz * (size_t)f, strip, stripsz * sizeof(float));
        printf("%3d   (%5.2f %5.2f %5.2f)    %6.4f    %6.4f %6.4f %6.4f %6.4f  %5.2f  %5.2f\n", f,
               obj.c[0], obj.c[1], obj.c[2], r->noise, r->err[0], r->err[1], r->err[2],
               r->err[3], r->err[1] / r->err[2], r->err[3] / r->err[2]);
        fflush(stdout);
    }
    summary(o, res);
    if (write_png(o->out, "contact.png", PANELS * o->w, o->w * o->frames, sheet, exposure) < 0)
        return -1;
    printf("frames: %s/frame-NN.png (reference, 1, 1+g, 8, 8+g); contact sheet: %s/contact.png\n",
           o->out, o->out);
    sh_env_free(&e, &copy);
    free(strip);
    free(sheet);
    free(res);
    return 0;
}

static int parse(int argc, char **argv, anim_opts *o)
{
    int i;
    o->frames = 16;
    o->w = 64;
    o->m = 32;
    o->n = 128;
    o->corner = 0.5f;
    o->power = 2.0f;
    o->out = "build/sh-animation";
    o->scene = "demo/scenes/sh.scene";
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--frames") && i + 1 < argc)
            o->frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--size") && i + 1 < argc)
            o->w = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--strata") && i + 2 < argc) {
            o->m = (uint32_t)atoi(argv[++i]);
            o->n = (uint32_t)atoi(argv[++i]);
        } else if (!strcmp(argv[i], "--corner") && i + 1 < argc)
            o->corner = (float)atof(argv[++i]);
        else if (!strcmp(argv[i], "--power") && i + 1 < argc)
            o->power = (float)atof(argv[++i]);
        else if (!strcmp(argv[i], "--out") && i + 1 < argc)
            o->out = argv[++i];
        else if (argv[i][0] != '-')
            o->scene = argv[i];
        else
            return -1;
    }
    return o->frames >= 1 && o->w >= 8 && o->m >= 1 && o->n >= 1 && o->corner > 0.0f &&
                   o->power > 0.0f ? 0 : -1;
}

int main(int argc, char **argv)
{
    anim_opts o;
    scene s;
    char err[512];
    if (parse(argc, argv, &o) < 0) {
        fprintf(stderr, "usage: shanim [--frames F] [--size W] [--strata M N] [--corner K] "
                        "[--power B] [--out DIR] [SCENE]\n");
        return 2;
    }
    if (scene_load(o.scene, &s, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    if (s.nspheres < 1) {
        fprintf(stderr, "shanim: the scene's first sphere is the object\n");
        return 1;
    }
    if (run(&o, &s) < 0) {
        fprintf(stderr, "shanim: failed\n");
        return 1;
    }
    scene_free(&s);
    return 0;
}
