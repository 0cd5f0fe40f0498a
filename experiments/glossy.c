/*
 * glossy.c -- glossy indirect light from SH records against sampling the
 * lobe (SH records where they matter).  For one glossy material of
 * a scene, its diffuse part set to 0 so that its pixels show only the
 * glossy bounce (--indirect image: kd/pi E elsewhere), and its Phong
 * exponent s set in turn to each value below, renders:
 *   reference  lobe sampling with 4096 rays a pixel;
 *   SH, L      an SH cache of L bands (3, 4, 5), every lobe from the
 *              record (irc_sh_glossy about the mirror direction);
 *   lobe, K    an irradiance cache for E and K lobe rays a pixel, K = 1,
 *              4, 16, 64;
 * and prints the relative RMSE on the material's pixels against the
 * reference and each render's time, one thread: warm (the least of two
 * renders after a first that made the records, so the glossy bounce and
 * lookups alone) and, for SH L = 5, cold; and the L = 5 SH render's error
 * over the lobe renders' error at its warm time (interpolated log-log).
 * With --table, markdown rows for make bench's glossy table.
 *   glossy SCENE MATERIAL [W H] [--exponents S,S,...] [--table FILE]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "camera.h"
#include "render.h"

static int secondary = 16; /* light samples at secondary hits, every render */

/* Renders s with o into img; *cold gets that first render's time (its
 * records made), and the return value is the least time of `runs` more
 * renders on the same cache (warm: every record there, the glossy bounce
 * and lookups alone), or the first's when runs is 0; < 0 on failure. */
static double render(const scene *s, const render_opts *in, float *img, int runs, double *cold)
{
    render_opts o = *in;
    renderer r;
    render_stats st;
    char err[256];
    double best = HUGE_VAL, t0 = 0.0, t;
    int k;
    o.secondary_samples = secondary;
    if (renderer_init(&r, s, &o, err, sizeof err) < 0) {
        fprintf(stderr, "glossy: %s\n", err);
        return -1.0;
    }
    for (k = 0; k <= runs; k++) {
        t0 = render_clock();
        if (render_image(&r, img, &st) < 0) {
            renderer_free(&r);
            return -1.0;
        }
        t = render_clock() - t0;
        if (k == 0)
            *cold = t;
        if ((k > 0 || runs == 0) && t < best)
            best = t;
    }
    renderer_free(&r);
    return best;
}

/* Relative RMSE of a against b over the pixels of mask. */
static double masked_rmse(const float *a, const float *b, const unsigned char *mask, int n)
{
    double num = 0.0, den = 0.0;
    int i, k;
    for (i = 0; i < n; i++)
        for (k = 0; k < 3 && mask[i]; k++) {
            num += ((double)a[3 * i + k] - b[3 * i + k]) * ((double)a[3 * i + k] - b[3 * i + k]);
            den += (double)b[3 * i + k] * b[3 * i + k];
        }
    return den > 0.0 ? sqrt(num / den) : 0.0;
}

/* The pixels whose centre sees material mat. */
static int mask_of(const scene *s, int mat, unsigned char *mask)
{
    renderer r;
    render_opts o;
    cam_frame cf;
    char err[256];
    int x, y, count = 0;
    render_opts_defaults(&o);
    o.mode = MODE_REFERENCE;
    o.ref_rays = 1;
    if (renderer_init(&r, s, &o, err, sizeof err) < 0)
        return -1;
    camera_frame(&s->cam, &cf);
    for (y = 0; y < s->cam.height; y++)
        for (x = 0; x < s->cam.width; x++) {
            float d[3];
            bvh_hit bh;
            const int i = y * s->cam.width + x;
            camera_ray(&cf, &s->cam, x, y, d);
            mask[i] = bvh_intersect(&r.b, cf.eye, d, 0.0f, 1e30f, &bh) &&
                      (bh.prim >= 0 ? s->tris[bh.prim].mat : s->spheres[-bh.prim - 1].mat) == mat;
            count += mask[i];
        }
    renderer_free(&r);
    return count;
}

/* The lobe renders' error at time t: log-log between the two renders
 * either side (errors of a sampled lobe fall as a power of the rays);
 * -1 when t is outside their times. */
static double lobe_error_at(const double *t, const double *e, int n, double at)
{
    int k;
    for (k = 0; k + 1 < n; k++)
        if (t[k] <= at && at <= t[k + 1]) {
            double f = log(at / t[k]) / log(t[k + 1] / t[k]);
            return exp(log(e[k]) + f * (log(e[k + 1]) - log(e[k])));
        }
    return -1.0;
}

/* One line of the table at exponent expo (already set in s): the
 * reference, the SH renders of 3, 4 and 5 bands, the lobe renders of 1, 4,
 * 16, 64 rays (times warm, cold in brackets for the last two), and the
 * 5-band SH error over the lobe error at its warm time; a markdown row to
 * md when given. */
static int row(const scene *s, const char *name, float expo, const unsigned char *mask, int n,
               float *ref, float *img, FILE *md)
{
    static const int rays[4] = {1, 4, 16, 64};
    double t_sh[6], c_sh[6], rm[6], t_lobe[4], c_lobe[4], r_lobe[4], cold, eq;
    render_opts o;
    int L, k;
    render_opts_defaults(&o);
    o.show = SHOW_INDIRECT;
    o.mode = MODE_REFERENCE;
    o.ref_rays = 64;
    o.lobe_rays = 4096;
    if (render(s, &o, ref, 0, &cold) < 0)
        return 1;
    for (L = 3; L <= 5; L++) {
        render_opts_defaults(&o);
        o.show = SHOW_INDIRECT;
        o.features = IRC_FEATURE_SH;
        o.sh_bands = (uint32_t)L;
        o.lobe_rays = 1;
        o.sh_lobe_max = 1e4f;
        if ((t_sh[L] = render(s, &o, img, 2, &c_sh[L])) < 0)
            return 1;
        rm[L] = masked_rmse(img, ref, mask, n);
    }
    render_opts_defaults(&o);
    o.show = SHOW_INDIRECT;
    printf("s %3.0f: SH L=3 %.4f (%.3f s), L=4 %.4f (%.3f s), L=5 %.4f (%.3f s, cold %.2f s); lobe",
           expo, rm[3], t_sh[3], rm[4], t_sh[4], rm[5], t_sh[5], c_sh[5]);
    for (k = 0; k < 4; k++) {
        o.lobe_rays = rays[k];
        if ((t_lobe[k] = render(s, &o, img, 2, &c_lobe[k])) < 0)
            return 1;
        r_lobe[k] = masked_rmse(img, ref, mask, n);
        printf(" %d %.4f (%.3f s)%s", rays[k], r_lobe[k], t_lobe[k], k < 3 ? "," : "");
    }
    eq = lobe_error_at(t_lobe, r_lobe, 4, t_sh[5]);
    if (eq > 0.0)
        printf(": at equal warm time SH L=5 / lobe %.2f\n", rm[5] / eq);
    else
        printf(": SH L=5 / lobe 1 ray %.2f (SH %s)\n", rm[5] / r_lobe[0],
               t_sh[5] < t_lobe[0] ? "faster than one ray" : "slower than 64 rays");
    if (md) {
        fprintf(md, "| %s | %.0f | %.4f (%.0f ms; cold %.2f s) | %.4f (%.0f ms) | %.4f (%.0f ms) | "
                    "%.4f (%.0f ms) | ", name, expo, rm[5], 1e3 * t_sh[5], c_sh[5], r_lobe[0],
                1e3 * t_lobe[0], r_lobe[2], 1e3 * t_lobe[2], r_lobe[3], 1e3 * t_lobe[3]);
        if (eq > 0.0)
            fprintf(md, "%.2f |\n", rm[5] / eq);
        else
            fprintf(md, "%s %.2f |\n", t_sh[5] < t_lobe[0] ? "faster than 1 ray:" : "slower than 64:",
                    rm[5] / (t_sh[5] < t_lobe[0] ? r_lobe[0] : r_lobe[3]));
    }
    fflush(stdout);
    return 0;
}

int main(int argc, char **argv)
{
    float exps[16] = {2, 5, 10, 20, 40, 80};
    int nexp = 6;
    scene s;
    char err[1024];
    float *ref, *img;
    unsigned char *mask;
    FILE *md = NULL;
    int mat = -1, i, e, n, pixels, rc = 0;
    while (argc > 4 && argv[argc - 2][0] == '-' && argv[argc - 2][1] == '-') {
        if (!strcmp(argv[argc - 2], "--exponents")) {
            char *p = argv[argc - 1];
            for (nexp = 0; nexp < 16 && *p; nexp++) {
                exps[nexp] = strtof(p, &p);
                p += *p == ',';
            }
        } else if (!strcmp(argv[argc - 2], "--table")) {
            if (!(md = fopen(argv[argc - 1], "a"))) {
                fprintf(stderr, "glossy: cannot append to %s\n", argv[argc - 1]);
                return 1;
            }
        } else
            break;
        argc -= 2;
    }
    if (argc < 3) {
        fprintf(stderr, "usage: glossy SCENE MATERIAL [W H] [--exponents S,S,...] [--table FILE]\n");
        return 2;
    }
    if (scene_load(argv[1], &s, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    if (argc >= 5) {
        s.cam.width = atoi(argv[3]);
        s.cam.height = atoi(argv[4]);
    }
    for (i = 0; i < s.nmats; i++)
        if (strcmp(s.mats[i].name, argv[2]) == 0)
            mat = i;
    n = s.cam.width * s.cam.height;
    ref = malloc(sizeof *ref * 3 * (size_t)n);
    img = malloc(sizeof *img * 3 * (size_t)n);
    mask = malloc((size_t)n);
    if (mat < 0 || !ref || !img || !mask || (pixels = mask_of(&s, mat, mask)) <= 0) {
        fprintf(stderr, "glossy: no material %s in view\n", argv[2]);
        return 1;
    }
    s.mats[mat].kd[0] = s.mats[mat].kd[1] = s.mats[mat].kd[2] = 0.0f;
    if (!(s.mats[mat].ks[0] + s.mats[mat].ks[1] + s.mats[mat].ks[2] > 0.0f))
        s.mats[mat].ks[0] = s.mats[mat].ks[1] = s.mats[mat].ks[2] = 0.5f;
    printf("%s, material %s (%d pixels), %dx%d, one thread; relative RMSE of its glossy "
           "bounce against 4096 lobe rays, and render times\n", argv[1], argv[2], pixels,
           s.cam.width, s.cam.height);
    for (e = 0; e < nexp && rc == 0; e++) {
        s.mats[mat].ns = exps[e];
        rc = row(&s, argv[1], exps[e], mask, n, ref, img, md);
    }
    if (md)
        fclose(md);
    free(ref);
    free(img);
    free(mask);
    scene_free(&s);
    return rc;
}
