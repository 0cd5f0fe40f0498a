/*
 * scenes.h -- reference hosts for tests and benchmarks: analytic ray casters
 * whose irradiance has a closed form, and callbacks that inject failures.
 */
#ifndef IRC_SCENES_H
#define IRC_SCENES_H

#include "irrcache.h"

#define TPI 3.14159265358979323846

typedef struct tscene {
    /* Sky radiance L(w) = sky_a + sky_b * w.z per channel. */
    float sky_a[3], sky_b[3];
    /* Optional sky lobe, + lobe_l * max(0, w.lobe_dir)^lobe_k (a soft sun):
     * a sky that no few SH bands hold exactly. */
    float lobe_l[3];
    double lobe_dir[3], lobe_k;
    /* Optional black sphere (reflects nothing). */
    int has_sphere;
    double centre[3], radius;
    /* Optional emitting sphere's radiance (instead of black). */
    float sphere_l[3];
    /* Optional black disk facing down, parallel to z = 0 (a flat blocker:
     * the hit distance at its edge is exact, unlike a sphere's). */
    int has_disk;
    double disk_c[3], disk_r;
    /* Optional black axis-aligned box (a polygonal blocker). */
    int has_box;
    double box_lo[3], box_hi[3];
    /* Optional ground plane z = plane_z facing +z with constant radiance. */
    int has_plane;
    double plane_z;
    float plane_l[3];
    /* Failure injection: every fail_every-th ray (if > 0) gets fail_kind. */
    unsigned fail_every, fail_kind, calls;
    int return_code; /* returned by the callback when nonzero */
} tscene;

enum {
    FAIL_NONE, FAIL_RAY, FAIL_NEG_DIST, FAIL_NAN_DIST, FAIL_ZERO_DIST,
    FAIL_INF_RADIANCE, FAIL_NAN_RADIANCE, FAIL_NEG_RADIANCE, FAIL_ZERO_NORMAL,
    FAIL_BAD_STATUS, FAIL_UNTOUCHED, FAIL_INF_DIST, FAIL_NAN_NORMAL
};

void scene_init(tscene *s);
/* The sky's radiance along the unit direction d, channel c. */
double scene_sky(const tscene *s, const double d[3], int c);
/* The tests' two oracle scenes, under a uniform sky of radiance 1: a black
 * sphere of radius 1 centred at (0, 0, 2) (sphere_plane_e), and a black box
 * [-0.5, 1.1] x [-0.3, 0.7] x [1.0, 1.8] (box_plane_e). */
void scene_sphere_plane(tscene *s);
void scene_box_plane(tscene *s);
/* Uniform sky L = 1 over z = 0 and a black disk of radius 0.8 at height 1
 * centred over the origin (disk_plane_e). */
void scene_disk_plane(tscene *s);
int scene_trace(const irc_trace_args *a);

/* E at a point on the plane z = 0 (normal +z) under a uniform sky L with a
 * black sphere entirely above the horizon: pi L (1 - r^2 cos(theta)/d^2). */
double sphere_plane_e(const tscene *s, const double p[3]);
void sphere_plane_grad(const tscene *s, const double p[3], double g[3]);

/* The same under a black disk of radius R at height h, lateral offset a:
 * pi L (1 - F), F = 1/2 [1 - (h^2 + a^2 - R^2) / sqrt((h^2 + a^2 + R^2)^2 -
 * 4 a^2 R^2)] (point to parallel offset disk). */
double disk_plane_e(const tscene *s, const double p[3]);

/* The same under a black axis-aligned box entirely above the horizon:
 * E = pi L (1 - F), F the sum of Lambert's polygon form factors of the box
 * faces that face the point (a convex blocker's faces facing the point tile
 * its silhouette). */
double box_plane_e(const tscene *s, const double p[3]);

/* A config for scene s with the given features and strata (0 = default). */
irc_config scene_config(tscene *s, uint32_t features, uint32_t m, uint32_t n);
/* The same for an SH cache of the given bands. */
irc_config sh_config(tscene *s, uint32_t features, uint32_t m, uint32_t n, uint32_t bands);
/* A record by hand: at the origin, normal +z, irradiance e in every
 * channel, radius rad, the rest zero. */
void disk_record(irc_record *r, float e, float rad);

/* Allocates a block for cfg with `guard` canary bytes after it; returns the
 * cache or NULL.  block_free() checks the canary. */
irc_cache *block_cache(irc_config *cfg, uint32_t records, size_t guard);
int block_guard_ok(const irc_config *cfg, size_t guard);
void block_free(irc_config *cfg);
/* 1 when the block equals copy byte for byte, the lock object excepted. */
int block_same(const irc_config *cfg, const unsigned char *copy, const irc_cache *c);

double xrand(unsigned long long *state); /* uniform [0,1) */

#endif
