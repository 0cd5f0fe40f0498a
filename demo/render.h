/*
 * render.h -- the demo's integrator.  Each pixel shows the radiance at the
 * camera ray's first hit: emission + direct light from the area lights
 * (explicit sampling, Lambert + Phong) + one bounce of indirect diffuse
 * light, kd/pi x E, where E (irradiance from the environment and from the
 * direct-lit surfaces seen from the hit) comes from the cache or from
 * brute-force hemisphere sampling; with lobe_rays, glossy surfaces also
 * reflect one bounce of indirect light through their lobe (glossy.h).
 */
#ifndef DEMO_RENDER_H
#define DEMO_RENDER_H

#include <stdint.h>

#include "irrcache.h"
#include "shade.h"

enum { MODE_CACHE, MODE_REFERENCE };
/* With bounces > 1, where a record's (or the reference's) gather rays get
 * the light of the bounces beyond their hits (bounce.c). */
enum { GATHER_CACHE, GATHER_PATH };
#define MAX_BOUNCES 8
enum { SHOW_FULL, SHOW_INDIRECT };

typedef struct render_opts {
    int mode;
    int ref_rays;         /* reference: hemisphere rays per shading point */
    uint32_t features;    /* cache: IRC_FEATURE_* (with IRC_FEATURE_SH, E is
                             the SH record's clamped-cosine irradiance) */
    uint32_t sh_bands;    /* cache with SH: L (0: the library's default) */
    float accuracy;       /* cache: a */
    uint32_t strata_m, strata_n;
    uint32_t supersamples; /* cache: irc_config.irr.supersamples */
    float full_pixels;     /* cache: irc_config.irr.full_pixels */
    float detail_pixels;   /* cache: irc_config.irr.detail_pixels */
    float blend;           /* cache: irc_config.irr.blend */
    int final_sweep;       /* cache with passes: after the fill, every
                              pixel again with a plain lookup, so that it
                              blends every record near it (a pixel whose
                              _px call answered IRC_DETAIL keeps it) */
    uint32_t max_records;
    float min_radius, max_radius; /* max < 0: 0.1 x the diagonal of what
                                     the camera sees; 0: the library's */
    int leak_guard;       /* cache: irc_config.irr.leak_guard (an irc_switch) */
    float min_pixels, max_pixels; /* cache: irc_config.irr's screen-space bounds
                                     on records made for camera rays */
    int clamp_neighbours; /* cache: irc_config.clamp_neighbours (an irc_switch) */
    int no_footprint;     /* cache: records ignore the pixel's footprint
                             (the plain lookup-or-compute call) */
    int check_visibility; /* cache: irc_config.check_visibility (an
                             irc_switch) */
    int threads;
    int show;             /* SHOW_FULL or SHOW_INDIRECT (kd/pi E only) */
    int light_samples;    /* at the camera ray's hit */
    int secondary_samples;/* at secondary hits (0: 1): the noise of every
                             record's and reference ray's radiance */
    int lobe_rays;        /* > 0: glossy surfaces also reflect indirect light
                             (glossy.h): from the SH record in an SH cache
                             while the exponent is at most sh_lobe_max,
                             else from this many samples of the lobe;
                             0: none (direct light's lobe only) */
    float sh_lobe_max;    /* the largest Phong exponent SH records shade
                             (0: 0.4 L^2, the measured crossover) */
    uint64_t seed;
    int progress;         /* draw a progress bar on stderr after a second */
    int stride;           /* > 1: shade only pixels whose x and y are
                             multiples of it (the rest stay 0), as for a
                             reference on a lattice */
    int stride_offset;    /* ... plus this (0 <= offset < stride) */
    int tiles, tile;      /* tiles > 1: render only rows [tile H / tiles,
                             (tile + 1) H / tiles) (a farm job's share) */
    int frozen;           /* cache: add no records; a miss computes one,
                             uses its value and drops it (counted) */
    int bounces;          /* bounces of indirect light, 1 .. MAX_BOUNCES
                             (0: 1) */
    int gather;           /* GATHER_CACHE: a cache at every level, each
                             filled freely; GATHER_PATH: the cache at the
                             first level only, paths beyond (the reference
                             always takes paths) */
    float level_scale;    /* GATHER_CACHE: level k's accuracy is a x
                             level_scale^(k-1) (0: 1) */
    int level_strata;     /* ... its strata M x N / level_strata^(k-1)
                             (0: 1) */
    float level_min_radius; /* ... its radii at least this x the maximum
                               (0.1 x the visible diagonal; 0: none) */
    int level_check_visibility; /* ... 1: its lookups confirm records with
                                   rays (cfg.check_visibility), 0: not */
    int free_fill;        /* cache: threads insert records as they make
                             them, so the records (and the image) depend on
                             thread timing; 0: deterministic passes, pixels
                             P apart in P^2 passes coarse to fine, each an
                             irc_pass_begin/irc_pass_end (render.c) */
} render_opts;

typedef struct render_stats {
    double wall;          /* seconds */
    double cpu;           /* the process's CPU seconds over every thread
                             (render_image): what the bench compares */
    double trace_s;       /* thread-seconds in the host's ray casting + shading
                             of secondary hits (inside the trace callback and
                             for the reference's rays) */
    double cache_s;       /* thread-seconds in cache calls, callback excluded
                             (pass ends included) */
    double lookup_s;      /* of which: camera hits' calls that sampled no
                             hemisphere (lookups, with their probes) */
    double gather_s;      /* ... calls that did: the library's part of
                             sampling records and detail estimates, and
                             inserting them */
    double pass_s;        /* ... irc_pass_end and irc_pass_begin */
    uint64_t rays;        /* every ray cast: camera, hemisphere, shadow */
    uint64_t dropped;     /* frozen: misses whose record was not kept */
    uint64_t records;
    uint64_t lookups, hits;
    uint64_t evictions, not_stored; /* the first cache's (irc_stats) */
    uint64_t details;     /* its per-pixel estimates (irc_stats.details) */
    size_t cache_bytes;   /* the cache's block */
    size_t record_bytes;  /* bytes of one stored record */
    uint64_t level_records[MAX_BOUNCES]; /* records of levels 2, 3, ... */
} render_stats;

struct renderer;
typedef struct level_ctx {  /* a level's cfg.context */
    const struct renderer *r;
    int level;              /* 1: the camera's hits */
} level_ctx;

typedef struct renderer {
    const scene *s;
    bvh b;
    lights l;
    render_opts o;
    irc_cache *cache;     /* MODE_CACHE */
    void *block;
    irc_cache *deeper[MAX_BOUNCES];  /* levels 2 .. bounces (GATHER_CACHE) */
    void *deeper_block[MAX_BOUNCES];
    level_ctx ctx[MAX_BOUNCES];
    irc_config cfg;        /* the first level cache's configuration */
    unsigned char *detail_map; /* optional, w x h: 1 where render_image's
                                  pixel was answered per pixel (IRC_DETAIL) */
} renderer;

/* irc_demo's defaults: the cache with the library's defaults (every cache
 * field 0), 200,000 records, 16 light samples, seed 1, one thread,
 * deterministic fill passes; the rest 0. */
void render_opts_defaults(render_opts *o);

int renderer_init(renderer *r, const scene *s, const render_opts *o, char *err, size_t n);
void renderer_free(renderer *r);

/* Renders the camera's image into rgb (w x h x 3). */
int render_image(renderer *r, float *rgb, render_stats *st);

/* Seconds on a monotonic clock: what every render and experiment times
 * with. */
double render_clock(void);
/* The process's CPU seconds, every thread's summed. */
double render_cpu_clock(void);

/* Irradiance E at n points (p, n: 6 floats a point) into rgb (3 a point). */
int render_points(renderer *r, const float *pn, int n, float *rgb, render_stats *st);

/* A record at (p, n) through the renderer's cache config and host (for
 * experiments that place records themselves).  MODE_CACHE only. */
int render_record(renderer *r, const float p[3], const float n[3], irc_record *out);

/* Whether the segment from p to q crosses geometry (each end lifted off
 * its surface by ray_offset; ends closer than that are in sight). */
int render_hidden(const renderer *r, const float p[3], const float q[3]);

/* False colour of the cache's records over the camera's image: each pixel
 * coloured by the record of largest weight there (hue from its id, so
 * neighbouring records differ), black where none counts; record centres
 * seen by the camera as white dots. */
int render_records(renderer *r, float *rgb);


#endif
