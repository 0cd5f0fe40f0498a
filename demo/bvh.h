/*
 * bvh.h -- a binned-SAH bounding volume hierarchy over a scene's triangles
 * and analytic spheres, for nearest-hit and shadow queries.
 */
#ifndef DEMO_BVH_H
#define DEMO_BVH_H

#include "scene.h"

typedef struct bvh_node {
    float lo[3], hi[3];
    int first;  /* leaf: first index into prims; inner: left child */
    int count;  /* leaf: number of prims (> 0); inner: 0 (right = left + 1) */
} bvh_node;

typedef struct bvh_hit bvh_hit;

/* Another tracer behind bvh_intersect and bvh_occluded for the scene's
 * triangles (the bench's Embree backend, demo/embree_rays.c); spheres stay
 * this BVH's.  intersect NULL: this BVH alone.  release frees ctx (at
 * bvh_free). */
typedef struct bvh_rays {
    int (*intersect)(void *ctx, const float o[3], const float d[3], float tmin, float tmax,
                     bvh_hit *h);
    int (*occluded)(void *ctx, const float o[3], const float d[3], float tmin, float tmax);
    void (*release)(void *ctx);
    void *ctx;
} bvh_rays;

typedef struct bvh {
    const scene *s;
    bvh_rays rays;
    bvh_node *nodes;
    int nnodes;
    int *prims;  /* >= 0: triangle index; < 0: sphere -(i + 1) */
    int nprims;
} bvh;

struct bvh_hit {
    float t;
    int prim;    /* as in bvh.prims */
    float u, v;  /* triangle barycentrics (of v[1], v[2]) */
};

int bvh_build(bvh *b, const scene *s); /* 0, or -1 out of memory */
void bvh_free(bvh *b);
/* Hands the scene's triangles to Embree (demo/embree_rays.c, built into
 * the bench when Embree is installed): 0, or -1 with err set. */
int bvh_embree(bvh *b, char *err, size_t n);

/* Nearest hit with t in (tmin, tmax).  Returns 1 and fills h, else 0. */
int bvh_intersect(const bvh *b, const float o[3], const float d[3], float tmin,
                  float tmax, bvh_hit *h);
/* Any hit with t in (tmin, tmax). */
int bvh_occluded(const bvh *b, const float o[3], const float d[3], float tmin, float tmax);

/* The hit of ray (o, d) with the surface primitive prim lies on: a
 * triangle's plane (barycentrics unbounded, so vertex normals extrapolate)
 * or a sphere.  For differentials: the same surface a little aside. */
int hit_surface_of(const scene *s, int prim, const float o[3], const float d[3], bvh_hit *h);

/* The same queries by a loop over every primitive (for tests). */
int brute_intersect(const scene *s, const float o[3], const float d[3], float tmin,
                    float tmax, bvh_hit *h);

#endif
