/*
 * shade.h -- what the tracer knows about light and surfaces: the shading
 * frame at a hit (with the procedural bump map), the environment, area
 * lights sampled explicitly, and the Lambert + normalised Phong BRDF.
 */
#ifndef DEMO_SHADE_H
#define DEMO_SHADE_H

#include <stdint.h>

#include "bvh.h"

typedef struct lights {
    int *tri;        /* emissive triangles */
    double *cdf;     /* by power (area x luminance of Ke) */
    int count;
    double total;    /* summed power */
} lights;

typedef struct surface {
    float p[3];      /* hit point */
    float ng[3];     /* geometric normal, facing the incoming ray */
    float ns[3];     /* shading normal (interpolated, bumped), same side */
    float nsm[3];    /* the same before the bump map: irradiance is sampled
                        around it, so hemisphere rays do not dive under bumps */
    const material *m;
    int front;       /* the ray hit the front face (emitters emit there only) */
} surface;

int lights_build(lights *l, const scene *s); /* 0, or -1 out of memory */
void lights_free(lights *l);

/* Surface at the hit of ray (o, d). */
void surface_at(const scene *s, const float o[3], const float d[3], const bvh_hit *h,
                surface *out);

void env_radiance(const environment *e, const float d[3], float out[3]);

/* Radiance emitted at a surface toward -d (front faces of emitters only). */
void emitted(const surface *sf, float out[3]);

/* Radiance leaving sf toward -d from direct lighting by the area lights,
 * with `samples` light samples, and by the scene's sun (one shadow ray);
 * key seeds the random numbers.  *rays counts the shadow rays cast. */
void direct_light(const bvh *b, const lights *l, const surface *sf, const float d[3],
                  int samples, uint64_t key, float out[3], uint64_t *rays);

/* A light sample that reached a surface: the point on the light, the
 * light's normal, its emission and the density it was picked with (per
 * unit area).  Kept, it shades the same surface moved a little, with its
 * visibility frozen (the image gradients of imgrad.c). */
typedef struct light_sample {
    float y[3], nl[3];
    const float *ke;
    float pdf;
} light_sample;

/* direct_light in two halves: samples k0 .. k1 - 1 of `samples`, those
 * that face sf and are unoccluded written to out (returns how many); and
 * their radiance toward -d from sf, added to out. */
int direct_samples(const bvh *b, const lights *l, const surface *sf, int k0, int k1,
                   int samples, uint64_t key, light_sample *out, uint64_t *rays);
void direct_eval(const light_sample *ls, int n, int samples, const surface *sf, const float d[3],
                 float out[3]);

/* a . b */
float dot3(const float a[3], const float b[3]);

/* The normal a hit's E is gathered around: the smooth shading normal, or
 * the geometric one where the two are more than 60 degrees apart (a
 * quarter of the shading normal's hemisphere would be below the surface).
 * The directions below the geometric surface are left out either way
 * (bounce.h, cast). */
const float *gather_normal(const surface *sf);

/* How far rays leaving p start from it: relative to p's magnitude, the
 * scale of float rounding in p, not to the scene's size (a huge floor must
 * not push rays off small objects). */
float ray_offset(const float p[3]);

/* The cosine-distributed direction around unit n for (u1, u2) in [0,1)^2:
 * sin^2 theta = u1, phi = 2 pi u2, in a frame built from n alone (Duff et
 * al.'s branchless basis), so every caller sampling around n agrees. */
void cosine_dir(const float n[3], double u1, double u2, float out[3]);

/* A hash-based uniform number in [0,1) for (key, index). */
double rnd(uint64_t key, uint32_t i);
uint64_t hash64(uint64_t x);

#endif
