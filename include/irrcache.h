/*
 * irrcache.h -- an embeddable irradiance cache.  This header is the manual.
 *
 * The host casts rays through a callback; the library samples hemispheres
 * through it, builds records carrying translational and rotational
 * gradients, keeps them in one memory block the host hands over at init,
 * and answers Ward-Heckbert weighted, gradient-extrapolated lookups.  A
 * cache may hold spherical-harmonic records of incident radiance instead
 * ("SH records" below).  Each record kind has its own typed calls
 * (irc_cache_* / irc_record_*, irc_sh_*: docs/DESIGN.md, "Record kinds");
 * a call of the other kind returns IRC_ERR_UNSUPPORTED.
 *
 *   - The library NEVER allocates: every structure (records, index, sampling
 *     scratch, the lock) lives in the block given to irc_init(), which the
 *     caller owns.  No global mutable state: any number of caches coexist.
 *   - The block holds offsets, not pointers: copied byte for byte to another
 *     address, or mapped by another process, it is a working cache again
 *     after irc_attach() (same build of the library, same ABI).
 *   - Thread safety: with a locking port (this build's default is POSIX
 *     threads), every call may run concurrently from any threads on one
 *     cache, except irc_init, irc_attach, irc_cache_clear,
 *     irc_snapshot_read, irc_merge, irc_pass_begin, irc_pass_end,
 *     irc_progress and irc_fini, which must not run concurrently with
 *     anything else on that cache.  Lookups take the
 *     port's read lock; inserts (and the insert of lookup_or_compute) its
 *     write lock; the trace callback runs with no lock held.  With
 *     irc_port_none, one thread at a time.
 *   - Stability: while the major version is 0, a minor release may change
 *     the block's layout (irc_attach refuses an older block), the config
 *     (IRC_CONFIG_VERSION refuses an older one) and a call's arguments;
 *     CHANGES.md, "Upgrading", lists each change.  The calls behind
 *     IRC_EXPERIMENTAL (at the end) may change in any release.
 *   - Determinism: for a callback that answers a ray the same way, a record
 *     is a pure function of (p, n, config, seed, the _px call's ng and
 *     footprint),
 *     bit for bit on any thread; which records a multi-threaded fill stores
 *     depends on timing, unless it fills in passes ("Fill passes").
 *   - Errors: every call returns an int: IRC_OK (0), a positive informational
 *     status (IRC_MISS, IRC_NOT_STORED: the pool is full), or a negative
 *     irc_status code, after which the block is byte for byte as it was but
 *     for the port's lock object.  A negative code from the trace callback
 *     is passed through unchanged: keep host codes below IRC_ERR_LAST.
 *
 * Quick start (examples/minimal.c is a complete host): irc_config cfg =
 * IRC_CONFIG_INIT, then trace and context (the fields left 0: the measured
 * defaults), irc_footprint, irc_init in a block of that size,
 * irc_cache_lookup_or_compute_px at each camera ray's hit with both
 * normals and the pixel's footprint there, irc_fini.
 *
 * Vectors are float[3] in the host's world space and units (nothing depends
 * on the scene's scale).  Irradiance E is the integral of L cos over the
 * hemisphere (E = pi L under a uniform sky of radiance L), per channel.
 */
#ifndef IRRCACHE_H
#define IRRCACHE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The one place the version is defined (the Makefile reads it).  Another
 * major, or another minor while the major is 0, is another ABI, config and
 * cost (CHANGES.md, "Upgrading from 0.3"), so a host written for 0.4
 * refuses any other at build time:
 *     #if IRC_VERSION_MAJOR != 0 || IRC_VERSION_MINOR != 5
 *     #error "written for irrcache 0.4: see its CHANGES.md"
 *     #endif
 * and at run time irc_version_number() / 100 == IRC_VERSION_NUMBER / 100. */
#define IRC_VERSION_MAJOR 0
#define IRC_VERSION_MINOR 5
#define IRC_VERSION_PATCH 0
#define IRC_VERSION_NUMBER \
    (IRC_VERSION_MAJOR * 10000 + IRC_VERSION_MINOR * 100 + IRC_VERSION_PATCH)
#define IRC__STR_(x) #x
#define IRC__STR(x) IRC__STR_(x)
#define IRC_VERSION_STRING \
    IRC__STR(IRC_VERSION_MAJOR) "." IRC__STR(IRC_VERSION_MINOR) "." IRC__STR(IRC_VERSION_PATCH)

/* Every declaration of this header, and nothing else of the library, is
 * visible from the shared library (built with -fvisibility=hidden).  Define
 * IRC_API yourself to decorate it otherwise (e.g. __declspec(dllexport)). */
#ifndef IRC_API
#if defined(__GNUC__) || defined(__clang__)
#define IRC_API __attribute__((visibility("default")))
#else
#define IRC_API
#endif
#endif

/* ------------------------------------------------------------------------ */
/* Status codes.  Values are stable; new codes are only ever appended.      */

typedef enum irc_status {
    IRC_OK = 0,
    IRC_MISS = 1,             /* lookup: no record within a R (where a
                                 lookup_or_compute computes); a record read:
                                 the slot is empty (not an error) */
    IRC_NOT_STORED = 2,       /* lookup_or_compute: the value was computed and
                                 returned, not stored (pool full, no eviction) */
    IRC_DETAIL = 3,           /* the _px call: answered by the point's own
                                 estimate (cfg.irr.detail_pixels), stored
                                 nowhere (*weight 0 as for a computed
                                 record, though none was made); a host
                                 that comes back to the same pixel may
                                 keep the value (irc_stats.details) */
    IRC_ERR_NULL = -1,        /* a required pointer, or cfg.trace, is NULL */
    IRC_ERR_CONFIG = -2,      /* a config field out of its range; a handle not
                                 of a live cache (never made, finished, not
                                 re-attached); a block irc_attach cannot take
                                 (another ABI or layout version) */
    IRC_ERR_NONFINITE = -3,   /* a NaN or infinite coordinate or value; a
                                 record or lookup whose values overflow float
                                 (radiances near FLT_MAX) */
    IRC_ERR_NORMAL = -4,      /* a normal is zero (or not finite) */
    IRC_ERR_NOMEM = -5,       /* the block is smaller than irc_footprint() asks */
    IRC_ERR_FULL = -6,        /* insert: the record pool is full, eviction is off */
    IRC_ERR_CALLBACK = -7,    /* the trace callback returned a positive value or
                                 reported nonsense: negative, zero or NaN distance,
                                 non-finite or negative radiance, zero normal,
                                 unknown ray status */
    IRC_ERR_NOSAMPLES = -8,   /* fewer than half of the hemisphere's rays were
                                 usable (the host reported them as failed) */
    IRC_ERR_BUSY = -9,        /* every scratch slot in use, and the cache does
                                 not wait (cfg.no_wait, a port without yield) */
    IRC_ERR_UNSUPPORTED = -10,/* a call the cache's kind or features do not
                                 serve (an irradiance call on an SH cache, an
                                 SH call on another, occlusion without
                                 VISIBILITY), or a config or block asking for
                                 what the build left out (an IRC_NO_* switch:
                                 docs/PORTING.md; without SH every SH call,
                                 irc_sh_irradiance and irc_sh_glossy too) */
    IRC_ERR_PORT = -11,       /* the port failed to initialise or take its lock */
    IRC_ERR_RANGE = -12,      /* a value out of its range: a record id past
                                 the capacity, a radius <= 0, negative
                                 irradiance, SH bands or channels not the
                                 cache's, a lobe exponent out of [0, 1e4] */
    IRC_ERR_TRUNCATED = -13,  /* a snapshot shorter than its header says */
    IRC_ERR_CORRUPT = -14,    /* a snapshot whose magic, checksums, length or
                                 values are wrong; irc_attach, irc_join: a
                                 block no cache could have made */
    IRC_ERR_VERSION = -15,    /* a snapshot of another format version; a
                                 config whose version is not
                                 IRC_CONFIG_VERSION (use IRC_CONFIG_INIT) */
    IRC_ERR_MISMATCH = -16,   /* a snapshot of another kind, features, record
                                 size, SH bands, channels or accuracy */
    IRC_ERR_FINGERPRINT = -17,/* a snapshot for another scene (fingerprint) */
    IRC_ERR_STATE = -18,      /* a pass begun in a pass or ended outside one;
                                 clear, snapshot read or merge in a pass */
    IRC_ERR_NESTED = -19,     /* a call that would compute a record in the
                                 cache whose callback is running on this
                                 thread ("Several bounces" below) */
    IRC_ERR_LAST = -19        /* the most negative code the library returns */
} irc_status;

/* A one-line English description of any status code (never NULL); any thread. */
IRC_API const char *irc_strerror(int status);

/* The library's version as IRC_VERSION_NUMBER and _STRING were when it was
 * built, to check the header against the library loaded (while the major is
 * 0: irc_version_number() / 100 == IRC_VERSION_NUMBER / 100).  Any thread. */
IRC_API unsigned irc_version_number(void);
IRC_API const char *irc_version_string(void);

/* ------------------------------------------------------------------------ */
/* Host callback: the library asks the host to cast rays.                   */

typedef struct irc_ray {
    float org[3];   /* the record's position p, exactly: offset it yourself
                       (args->n is the record's normal) */
    float dir[3];   /* unit direction in the hemisphere around the record's n
                       (any direction for a free-point SH record) */
} irc_ray;

/* Per-ray outcome, written by the host into irc_hit.status. */
enum irc_ray_status {
    IRC_RAY_HIT = 0,      /* dist, normal, radiance are valid */
    IRC_RAY_ESCAPED = 1,  /* nothing hit: radiance is the environment's along
                             dir; dist and normal are ignored */
    IRC_RAY_FAILED = 2    /* the host could not trace this ray; the library
                             leaves its stratum out (see IRC_ERR_NOSAMPLES) */
};

typedef struct irc_hit {
    float dist;        /* hit distance along dir, > 0 and finite */
    float normal[3];   /* geometric normal at the hit, any nonzero length,
                          either orientation */
    float radiance[3]; /* RGB radiance leaving the hit toward org, >= 0 */
    int status;        /* an irc_ray_status; the library sets it to -1 before
                          the call, so a hit the host leaves untouched is
                          IRC_ERR_CALLBACK */
} irc_hit;

typedef struct irc_trace_args {
    void *context;          /* cfg.context, unchanged */
    void *host;             /* the per-call pointer the host passed to the
                               call that is computing (NULL if it passed
                               none): its thread's sampler, ray packet, ... */
    float p[3];             /* the record's position (= every ray's org); for
                               confirming rays, the query's */
    float n[3];             /* the record's unit normal; 0, 0, 0 for a
                               free-point SH record; for confirming rays,
                               the query's */
    const irc_ray *rays;    /* count rays to cast (read only) */
    irc_hit *hits;          /* count results to write, same order */
    uint32_t count;         /* 1 <= count <= cfg.max_batch */
    uint32_t visibility_only; /* nonzero: only status and dist are read
                                 (the nearest hit's distance); normal and
                                 radiance need not be written, nor the
                                 hits shaded: an irc_visibility */
} irc_trace_args;

/* What rays with irc_trace_args.visibility_only set are for. */
enum irc_visibility {
    IRC_VISIBILITY_CONFIRM = 1, /* confirming rays (check_visibility): from
                                   the query toward a record each (maybe a
                                   little below n) */
    IRC_VISIBILITY_PROBE = 2    /* the _px call's detail probes
                                   (cfg.irr.detail_pixels) from the query */
};

/*
 * Cast args->count rays and fill args->hits.  The callback may touch only
 * args->hits[0 .. count-1] and its own state, and may call into other
 * caches (below); for rays with visibility_only set it calls no cache.
 * It runs on the thread that called into the library, with no lock of the
 * cache held, possibly on several threads at once.  Return 0 on success or
 * a negative code of the host's own to abort the record (the library
 * returns it unchanged and keeps nothing of the record).
 *
 * Shading normals: give the _px call the geometric normal too (ng), and
 * the rays that would leave below the surface never reach the callback.
 * The calls without ng (lookup_or_compute, record_compute, irc_progress's
 * refinements) cast every ray of n's hemisphere: a host that passes a
 * shading normal there answers those below its geometric surface
 * IRC_RAY_FAILED itself (the geometric normal reaching the callback
 * through args->host: demo/bounce.c), or passes the geometric normal as n.
 *
 * Several bounces take one cache per level: level k's callback shades its
 * hits with level k+1's lookup, passing args->host on (examples/levels.c;
 * docs/DESIGN.md, "Threads and memory"); fill deeper levels outside
 * passes.  Levels cannot deadlock.  A call that would compute a record in
 * a cache whose callback runs on this thread, directly or through a cycle
 * of caches, returns IRC_ERR_NESTED (ports with thread, or none).  Across
 * threads a cycle can deadlock: give each cache of a cycle as many slots
 * (cfg.threads) as host threads call into it, or set no_wait.
 */
typedef int (*irc_trace_fn)(const irc_trace_args *args);

/* ------------------------------------------------------------------------ */
/* Port: locks and atomics.  Implementations live in port/, not in the core. */

/*
 * The library's only contact with threads.  The lock object lives in the
 * cache's block at a 64-byte boundary, lock_size bytes (0: no lock object).
 * It is a reader/writer lock: any number of readers or one writer.
 *   - lock_init: make a fresh lock in that memory; 0, or negative on
 *     failure (irc_init and irc_attach then return IRC_ERR_PORT).
 *   - lock_destroy: release what lock_init took (irc_fini).
 *   - read_lock / write_lock: block until the lock is held shared /
 *     exclusive; 0, or negative if it cannot be taken (the call returns
 *     IRC_ERR_PORT and has changed nothing).  Or 1 when the write lock's
 *     holder died holding it: write_lock then holds the lock and the
 *     library repairs the block first; read_lock returns 1 without the
 *     lock, and the library takes the write lock to repair.  A port that
 *     cannot tell never returns 1.  The library never takes a lock it
 *     already holds and never upgrades one.
 *   - read_unlock / write_unlock: release a lock this thread holds.
 *   - yield: let other threads run while this one waits for a scratch slot
 *     (NULL: the port cannot wait).
 *   - owner / owner_alive (both or neither; NULL: none): a scratch slot
 *     records the token of the process that claimed it, and a call that
 *     finds every slot taken takes over a slot whose process is gone.
 *     irc_port_posix has them, and its lock counts out a dead reader and
 *     takes over from a dead writer; irc_port_c11 recovers nothing until
 *     irc_attach (docs/DESIGN.md, "Reliability: how").
 * The atomics act on naturally aligned 64-bit words inside the block.
 */
typedef struct irc_port {
    const char *name;
    size_t lock_size;                     /* bytes of one lock object, <= 4096 */
    int (*lock_init)(void *lock);
    void (*lock_destroy)(void *lock);
    int (*read_lock)(void *lock);
    void (*read_unlock)(void *lock);
    int (*write_lock)(void *lock);
    void (*write_unlock)(void *lock);
    void (*yield)(void);
    uint64_t (*load)(const uint64_t *obj);                 /* acquire */
    void (*store)(uint64_t *obj, uint64_t v);              /* release */
    uint64_t (*fetch_add)(uint64_t *obj, uint64_t v);      /* relaxed */
    uint64_t (*fetch_or)(uint64_t *obj, uint64_t v);       /* relaxed */
    int (*cas)(uint64_t *obj, uint64_t expected, uint64_t desired); /* acq_rel;
                                                         1 if swapped */
    uint64_t (*owner)(void);              /* optional: a nonzero token of the
                                             calling process (its id) */
    int (*owner_alive)(uint64_t token);   /* optional: 0 if the process
                                             whose owner() gave token is
                                             gone, else 1 */
    uint64_t (*thread)(void);             /* optional: a nonzero token of
                                             the calling thread, unique among
                                             live ones (for IRC_ERR_NESTED) */
} irc_port;

/* The ports, all defined in every build.  A build compiles the one chosen
 * by `make PORT=posix|c11|none` (default posix) and irc_port_none; the
 * others are ports that cannot make a lock: irc_init and irc_join with
 * one return IRC_ERR_PORT. */
IRC_API extern const irc_port irc_port_posix;  /* a lock that outlives its holders + GCC/Clang atomics */
IRC_API extern const irc_port irc_port_c11;    /* C11 <stdatomic.h>, spinning rwlock */
IRC_API extern const irc_port irc_port_none;   /* single-threaded: no locks at all */
IRC_API extern const irc_port *const irc_port_default; /* the chosen one: what
                                                          cfg.port = NULL means */

/* ------------------------------------------------------------------------ */
/* Configuration.  Start from IRC_CONFIG_INIT; zero in any other field    */
/* means its default.                                                        */

/* Gradient terms a record carries.  A cache pays in memory and time only for
 * the terms it enables: 32 bytes per record bare, +16 per gradient. */
enum irc_feature {
    IRC_FEATURE_TRANSLATION = 1u << 0, /* translational gradient (Krivanek et
                                          al. 2005 stratified form) */
    IRC_FEATURE_ROTATION = 1u << 1,    /* rotational gradient (Ward-Heckbert 1992) */
    /* TRANSLATION's gradient from exact visibility gradients at silhouettes
     * (first-order paper, Sec. 6-7; implies TRANSLATION): 14 extra rays a
     * silhouette crossing of the strata grid, ~300 scratch bytes a stratum. */
    IRC_FEATURE_VISIBILITY = 1u << 2,
    IRC_FEATURE_SH = 1u << 3,          /* SH records ("SH records" below);
                                          not with the three flags above */
    /* SH records with the coefficients' translational gradients, from the
     * same rays (SH-gradient paper, Eq. 6-12): implies SH. */
    IRC_FEATURE_SH_GRADIENT = 1u << 4,
    /* The occlusion-aware Hessian of E from the rays already cast
     * (Schwarzhaupt et al. 2012) and the ellipse it implies (docs/DESIGN.md,
     * "Error control"): no extra rays, 24 scratch bytes a stratum, 8 a record. */
    IRC_FEATURE_HESSIAN = 1u << 5,
    IRC_FEATURE_NONE = 1u << 6         /* no gradients: Ward's split-sphere
                                          radius; only alone (features = 0
                                          is TRANSLATION | ROTATION) */
};

/* Settings that are on or off: 0 is the setting's default, which its
 * field names; IRC_ON and IRC_OFF say which the host wants. */
enum irc_switch { IRC_DEFAULT = 0, IRC_ON = 1, IRC_OFF = 2 };

/* What insert does when the record pool is full. */
enum irc_evict {
    IRC_EVICT_NONE = 0,  /* refuse the insert: IRC_ERR_FULL (lookups go on) */
    IRC_EVICT_CLOCK = 1  /* second-chance CLOCK, 1 bit a record: a hand sweeps
                            the slots and replaces the first record no lookup
                            used since it last passed */
};

typedef struct irc_config {
    /* IRC_CONFIG_VERSION, which IRC_CONFIG_INIT sets.  Every call that takes
     * a config refuses another value (IRC_ERR_VERSION): a config zeroed or
     * initialised by position for another version of this struct, or one
     * compiled against another version of this header. */
    uint32_t version;
    irc_trace_fn trace;      /* required */
    void *context;           /* handed to trace unchanged */
    uint32_t max_batch;      /* rays per trace call, 1..4096 (default 1;
                                past M N: M N); more serve packet tracers,
                                at 56 bytes per ray and thread */
    uint32_t features;       /* IRC_FEATURE_* bits (default 0: TRANSLATION |
                                ROTATION) */
    float accuracy;          /* Ward's a: a record counts at p when
                                |p-p_i|/R_i + sqrt(1-n.n_i) < a; (0, 10]
                                (default 0.2) */
    float min_radius;        /* R_i >= min_radius; finite, in
                                [0, IRC_RADIUS_CAP) (default 0) */
    /* R_i <= max_radius, in (min_radius, IRC_RADIUS_CAP] (default 0: the
     * cap); also the radius of a record whose rays all escaped (by default
     * the smallest float: set it for open scenes, or use the _px call). */
    float max_radius;
    /* M rows in theta, 1..1024, and N columns in phi, 1..4096; M * N <=
     * IRC_MAX_STRATA.  Default: they follow a, so that one knob sets a
     * record's cost: M = 8 from a = 0.375, 16 from 0.25, 32 from 0.125, 64
     * below 0.125 and 128 below 0.0625 (and at any smaller a), and N = 4 M
     * (SH records: 16 x 64).  Why: bench/notes.md, "One knob". */
    uint32_t strata_theta;
    uint32_t strata_phi;
    /* Scratch slots: record computations at once, 1..64 (default 1), each
     * bytes_scratch / threads bytes.  A compute that finds every slot taken
     * waits for one (see no_wait); any number of host threads may share it. */
    uint32_t threads;
    uint32_t no_wait;        /* 1: a compute that finds every slot taken
                                returns IRC_ERR_BUSY at once (default 0:
                                wait through the port's yield) */
    uint32_t evict;          /* an irc_evict (default IRC_EVICT_NONE) */
    /* An irc_switch: neighbour clamping (Krivanek et al. 2006) at every
     * insert, R <= R_j + |x - x_j| both ways.  On for irradiance records, off
     * for SH records (why: bench/notes.md, "On real geometry"). */
    uint32_t clamp_neighbours;
    /* An irc_switch: confirming rays (V-Ray's "check sample visibility"):
     * the lookup_or_compute calls cast a ray toward each record they would
     * use (up to 32) and leave out those hit before 0.9 of the way.  On for
     * irradiance records, off for SH (why: bench/notes.md, "Confirming rays
     * on curved surfaces"); IRC_NO_SIGHT builds refuse it. */
    uint32_t check_visibility;
    /* Fields of one record kind: a kind's own, zero for its defaults,
     * and all zero in a config of the other kind (else IRC_ERR_CONFIG). */
    struct irc_config_irr {  /* irradiance records */
        /* After the M x N rays, this many more, one a stratum, into the
         * strata whose four neighbours' samples spread most (Radiance's
         * -as), which take the mean of their two samples.  0..M N
         * (default 0); not with VISIBILITY. */
        uint32_t supersamples;
        /* An irc_switch: records keep a leak guard (irc_record.leak_guard,
         * 8 bytes) against light through thin walls.  Off by default (why:
         * bench/notes.md, "On real geometry"). */
        uint32_t leak_guard;
        /* Bounds in pixels on the reach a R of a _px call's record
         * (pbrt-v2's pixel spacings).  Finite (past IRC_RADIUS_CAP: as
         * IRC_RADIUS_CAP, as for every pixel count here); 0: the
         * defaults, none and 15 (why: bench/notes.md, "The corpus");
         * negative: unbounded;
         * max_pixels >= min_pixels (a default one is at least min_pixels). */
        float min_pixels;
        float max_pixels;
        /* A _px record whose R spans fewer than full_pixels pixels is
         * sampled on M/2 x N/2 strata, below full_pixels / 2 on M/4 x N/4
         * (docs/DESIGN.md, "Records that cost what they serve").  Not with
         * VISIBILITY, HESSIAN or supersamples (IRC_ERR_CONFIG).  Finite; 0
         * or negative: off. */
        float full_pixels;
        /* The _px call first casts up to 8 probe rays; a point with a hit
         * within detail_pixels x footprint gets its own M x N estimate (E
         * alone, stored nowhere, weight 0, a lookup but not a hit; not so
         * when no slot is free with no_wait, or in the cache's own
         * callback).  Finite; 0: 0.5; negative: off (why: bench/notes.md,
         * "Detail computed per pixel"). */
        float detail_pixels;
        /* Lookups average the records within blend x the reach a R that
         * decides a miss (V-Ray's "interpolation samples"): a point is
         * computed only where no record lies within a R, but answered
         * from every record within blend a R, weighted (1 - t^2)^2 at t =
         * e / (blend a), e Ward's distance, so each record's noise is
         * shared by more pixels.  1: Ward's weight 1/e within a R (0.3's
         * lookups).  Finite, 1..4; 0: 2 (why: bench/notes.md, "Noise and
         * bias"). */
        float blend;
    } irr;
    struct irc_config_sh {   /* SH records (IRC_FEATURE_SH) */
        uint32_t bands;      /* L: bands 0..L-1, L*L coefficients per
                                channel; 1..IRC_SH_MAX_BANDS (default 3) */
        uint32_t channels;   /* 3 (RGB, default) or 1 (radiance[0] only) */
        float power;         /* free points: b of the weight
                                (R_j/|p - p_j|)^b; (0, 16] (default 2) */
    } sh;
    uint64_t seed;           /* mixed into the random numbers of every record
                                and every detail estimate (IRC_DETAIL):
                                another seed, other records and other
                                detail pixels; 0 is one seed among others */
    const irc_port *port;    /* locks and atomics (default irc_port_default) */
    void *buffer;            /* the caller's block, any alignment; the library
                                uses [buffer, buffer + buffer_size) only */
    size_t buffer_size;      /* bytes, >= what irc_footprint() returned */
} irc_config;

/* The config's version (0.5) and size: what IRC_CONFIG_INIT sets. */
#define IRC_CONFIG_VERSION ((uint32_t)(0x1C050000u | (uint32_t)sizeof(irc_config)))

/*
 * The config every host starts from: irc_config cfg = IRC_CONFIG_INIT; then
 * set fields by name (cfg.trace = ...; C99: {.version = IRC_CONFIG_VERSION,
 * .trace = ...}).  Every other field zero: its default.
 */
#ifdef __cplusplus
#define IRC_CONFIG_INIT                                                          \
    {IRC_CONFIG_VERSION, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f, 0, 0, 0, 0, 0, 0, 0,      \
     {0, 0, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f}, {0, 0, 0.0f}, 0, 0, 0, 0}
#else
#define IRC_CONFIG_INIT {.version = IRC_CONFIG_VERSION}
#endif

#define IRC_MAX_STRATA 4194304u /* 1024 x 4096 */
#define IRC_MAX_BATCH 4096u
#define IRC_MAX_THREADS 64u
#define IRC_MAX_RECORDS 0x3fffffffu
/* Radii are clamped to 2^100 (about 1.27e30; all rays escaped), a power of
 * two that compares equal to a stored radius in any float evaluation. */
#define IRC_RADIUS_CAP 1267650600228229401496703205376.0f
/* An ellipse's major radius is at most this multiple of its minor one
 * (HESSIAN records; hand-built records are clamped to it when stored). */
#define IRC_ANISOTROPY 4.0f
#define IRC_SH_MAX_BANDS 5u
#define IRC_SH_MAX_COEFFS 25u /* IRC_SH_MAX_BANDS squared */

/*
 * Compile-time bounds on irc_footprint(), for static blocks: never less
 * than it asks for the same numbers (make test checks a grid of configs).
 * features: IRC_FEATURE_* bits; records: max_records; s: strata M * N
 * (default 4096, SH 1024); t: cfg.threads; b: cfg.max_batch; SH: bands L,
 * channels ch.  In size_t: on a 32-bit target a bound over 4 GiB wraps.
 */
#define IRC_FOOTPRINT_BOUND(features, records, s, t, b)                          \
    (8192u + (size_t)(s) * 40u +                                                 \
     (size_t)(t) * (448u + sizeof(irc_record) +                                  \
                    (size_t)(s) * (((features) & IRC_FEATURE_VISIBILITY) ? 456u : \
                                          ((features) & IRC_FEATURE_HESSIAN) ? 88u : 56u) + \
                    (size_t)(b) * 56u) + \
     (size_t)(records) * (((features) & IRC_FEATURE_HESSIAN) ? 230u : 222u) +   \
     ((size_t)(records) / 8u + 16u) * 128u)
#define IRC_SH_FOOTPRINT_BOUND(records, bands, ch, s, t, b)                      \
    (8192u + (size_t)(s) * 40u +                                                 \
     (size_t)(t) * (192u + sizeof(irc_sh) + (size_t)(s) * 112u + (size_t)(b) * 56u) + \
     (size_t)(records) * (177u + 16u * (size_t)(bands) * (bands) * (ch) + 4u + 1u) + \
     ((size_t)(records) / 8u + 16u) * 128u)

/* ------------------------------------------------------------------------ */
/* Size, init, attach, fini.                                                 */

typedef struct irc_cache irc_cache; /* lives inside cfg.buffer; opaque */

/*
 * Bytes of block a cache of max_records (1..IRC_MAX_RECORDS) records needs
 * with this config (buffer and buffer_size ignored).  Thread safe.  Returns
 * IRC_OK and writes *bytes, IRC_ERR_CONFIG when that would not fit a
 * size_t, or a negative error code.  Sizing: a lookup-or-compute makes at
 * most one record, so a frame of one lookup a pixel needs max_records =
 * pixels at most, at every setting (what views make: bench/notes.md,
 * "The corpus"); a host that looks up at several points a pixel (one a
 * sample) can make up to one a lookup, so size it by the distinct points
 * or evict.  A full pool computes every later miss again
 * (IRC_NOT_STORED, a positive status, counted in irc_stats.not_stored):
 * keep that counter 0, or IRC_EVICT_CLOCK.
 */
IRC_API int irc_footprint(const irc_config *cfg, uint32_t max_records, size_t *bytes);

/*
 * Build an empty cache in cfg->buffer.  The config is copied; the cache
 * handle points into the block.  Returns IRC_OK and writes *cache, or a
 * negative error code (IRC_ERR_NOMEM when the block is too small).  Every
 * error but IRC_ERR_PORT leaves the block untouched; IRC_ERR_PORT (the
 * port's lock_init failed, or the port is one this build did not compile)
 * comes after the block was laid out, which then holds no cache.
 */
IRC_API int irc_init(const irc_config *cfg, uint32_t max_records, irc_cache **cache);

/*
 * Re-attach a block that holds a cache made by irc_init (and filled) at
 * another address: a copy, a file read back, another process's mapping.
 * cfg->buffer and cfg->buffer_size name the block (its first buffer_size
 * bytes, as copied); cfg->trace, cfg->context and cfg->port are taken anew,
 * the other fields are the block's own.  At another address modulo 64 the
 * contents move to the new 64-byte boundary.  The lock is made afresh: no
 * other thread or process may use the cache during the call.  Same build,
 * same ABI (pointer and size_t widths, byte order); else use snapshots.
 * Nothing in the block is trusted: it is checked in linear time, and one
 * whose writer died in the write lock is repaired first (docs/DESIGN.md,
 * "Reliability: how").  Returns IRC_OK and writes *cache; IRC_ERR_CONFIG
 * (no cache, or another ABI or layout version), IRC_ERR_CORRUPT (a check
 * failed), IRC_ERR_NOMEM (buffer_size short), or a negative code.
 */
IRC_API int irc_attach(const irc_config *cfg, irc_cache **cache);

/* Release the port's lock; the block is the caller's again.  Returns
 * IRC_OK, or a negative error code. */
IRC_API int irc_fini(irc_cache *cache);

/*
 * The cache's config as resolved: every field left at 0 replaced by what
 * the defaults chose (accuracy, strata, max_batch, threads, max_radius,
 * the kind's fields: pixel bounds, detail_pixels, full_pixels, blend or
 * bands, channels, power; "none" as -1), features as implied (0: TRANSLATION
 * | ROTATION, VISIBILITY with TRANSLATION, bare records IRC_FEATURE_NONE),
 * every irc_switch IRC_ON or IRC_OFF, port the one in use, and trace,
 * context, buffer, buffer_size as this process gave them.  Given to
 * irc_footprint or irc_init, it makes the same cache.  Any thread.
 * Returns IRC_OK, IRC_ERR_NULL, or IRC_ERR_CONFIG (not a live cache).
 */
IRC_API int irc_cache_config(irc_cache *cache, irc_config *out);

/* ------------------------------------------------------------------------ */
/* Irradiance records.                                                       */

/* A record as the host sees it, stored packed: position, radius and
 * irradiance exactly; the normal to about 5e-5 rad; each gradient channel
 * to 2^-14 of its largest component.  Read back (irc_cache_record):
 * mean_dist NaN, rays and rays_used 0, features the cache's, the gradients
 * it does not carry zero. */
typedef struct irc_record {
    float p[3];          /* position */
    float n[3];          /* unit normal */
    float e[3];          /* RGB irradiance (see the units above) */
    /* R_i, the reach along axis: the harmonic mean hit distance, at most
     * E/|grad E| a channel (TRANSLATION), or the Hessian's (docs/DESIGN.md,
     * "Error control"); clamped to [min_pixels, max_pixels] footprint / a
     * (the _px call) and [min_radius, max_radius]; with no hit, max_pixels
     * footprint / a, else max_radius, else the smallest float. */
    float radius;
    float minor_radius;  /* the reach across axis, in (0, radius]; 0 in a
                            host's record means radius (a disk).  Only
                            HESSIAN caches store ellipses */
    float axis[3];       /* unit tangent direction of radius when
                            minor_radius < radius, else zero (a host's is
                            projected on the tangent plane) */
    float mean_dist;     /* that harmonic mean before the other bounds */
    /* grad_t[c] = dE_c/dp per unit of length along the surface (zero
     * unless TRANSLATION), scaled down where |grad_t[c]| radius > e[c]. */
    float grad_t[3][3];
    float grad_r[3][3];  /* grad_r[c]: E_c(n') ~ e[c] + (n x n').grad_r[c],
                            per radian of normal rotation (zero unless
                            ROTATION) */
    float hessian[3][6]; /* hessian[c]: d2E_c/dp2, world space, packed xx xy
                            xz yy yz zz, meaningful along the surface (zero
                            unless HESSIAN; not stored: zero read back) */
    /* The nearest grazing hit in each of 16 sectors about n, 4 bits each,
     * so that a lookup from behind a wall does not use the record
     * (docs/DESIGN.md, "Leak guard"); 0 in a host's record: no guard.
     * Stored when cfg.irr.leak_guard is IRC_ON. */
    uint64_t leak_guard;
    uint32_t features;   /* which gradients are valid */
    uint32_t rays;       /* rays cast, and how many were usable: */
    uint32_t rays_used;
} irc_record;

/* Sample the hemisphere around (p, n) (n any length > 0; args->host = host)
 * and build a record; nothing is stored.  Waits for a free scratch slot.
 * Returns IRC_OK, or a negative code (the host's own if trace gave one). */
IRC_API int irc_record_compute(irc_cache *cache, const float p[3], const float n[3],
                               irc_record *out, void *host);

/* Store a record (a copy, packed): rec->radius > 0, rec->e >= 0 (else
 * IRC_ERR_RANGE), every field it stores finite (p, n, e, the radii, axis,
 * the gradients; else IRC_ERR_NONFINITE, IRC_ERR_NORMAL for n; mean_dist,
 * hessian and the counts are not read).  Returns IRC_OK, IRC_ERR_FULL (pool
 * full, eviction off), or a negative error code. */
IRC_API int irc_cache_insert(irc_cache *cache, const irc_record *rec);

/*
 * Interpolate irradiance at (p, n).  Record i counts when its Ward
 * distance e_i = |p - p_i|/R_i + sqrt(1 - n.n_i) is below blend x a
 * (cfg.irr.blend, default 2; an ellipse's |p - p_i|/R_i is docs/DESIGN.md's,
 * "Error control"), it is not in front of p ((p - p_i).(n + n_i)/2 >= -0.05
 * R_i) and its leak guard does not reject p; records facing away (n.n_i <=
 * 0) never count.  Each is extrapolated, E_i + (p - p_i).grad_t + (n_i x
 * n).grad_r, clamped at 0 a channel, and averaged with weights (1 -
 * t^2)^2, t = e_i / (blend a) (blend 1: Ward-Heckbert's 1/e_i, capped at
 * 1e6).  rgb gets the average and *weight (optional) the summed weight.
 * Returns IRC_OK when some record lies within a R (e_i < a); IRC_MISS when
 * none does, which is where irc_cache_lookup_or_compute computes a record
 * (rgb and *weight then hold the average over those within blend a R, 0
 * and 0 when there are none); IRC_ERR_NONFINITE when the extrapolation
 * overflows float, or a negative error code.
 */
IRC_API int irc_cache_lookup(irc_cache *cache, const float p[3], const float n[3],
                             float rgb[3], float *weight);

/*
 * Lookup; on a miss, compute a record at (p, n) (the callback gets host),
 * insert it, and return its irradiance with *weight = 0.  With
 * cfg.check_visibility the lookup first confirms its records (a callback
 * failure there returns as a record's would, nothing changed).  A miss that
 * waited for a slot looks up again first.  Returns IRC_OK, IRC_NOT_STORED
 * (value valid, pool full, eviction off), or a negative error code
 * (IRC_ERR_NESTED inside this cache's own callback: see irc_trace_fn).
 */
IRC_API int irc_cache_lookup_or_compute(irc_cache *cache, const float p[3],
                                        const float n[3], float rgb[3], float *weight,
                                        void *host);

/*
 * irc_cache_lookup_or_compute with a screen-space bound and both normals:
 * the recommended call at camera-ray hits.  n: the shading normal (smooth
 * or interpolated; any length > 0).  ng: the geometric normal of the
 * surface hit (either side, any length > 0), or NULL when n is it.  The
 * hemisphere is gathered around n, and its rays that leave below the
 * geometric surface fail without reaching the callback (left out of the
 * estimate, as IRC_RAY_FAILED is: they would find the surface itself at
 * distance 0, making tiny records: bench/notes.md, "Rays under the
 * surface"); where n lies more than 60 degrees from ng, the point gathers
 * and looks up around ng instead.  footprint: the width of one pixel at
 * p, the square root of the area it covers on the surface (pbrt's
 * sqrt(|dp/dx x dp/dy|) from ray differentials; irc_pixel_footprint for a
 * pinhole camera); 0 is the plain call.  A record computed here gets a reach a R
 * in [cfg.irr.min_pixels, cfg.irr.max_pixels] x footprint (by default none
 * to 15 pixels) before [min_radius, max_radius], and points near finer
 * geometry get their own estimate first (cfg.irr.detail_pixels): that
 * answer returns IRC_DETAIL (weight 0), which a host that calls again for
 * the same pixel (more samples a pixel: docs/DESIGN.md, "Many samples a
 * pixel") may keep instead; its weight is 0 as a computed record's,
 * though nothing was stored: the status tells them apart.  Otherwise
 * returns as irc_cache_lookup_or_compute; IRC_ERR_NORMAL for an ng zero or
 * not finite, IRC_ERR_NONFINITE (nothing done) for a footprint not
 * finite, else IRC_ERR_RANGE for a negative one.
 */
IRC_API int irc_cache_lookup_or_compute_px(irc_cache *cache, const float p[3],
                                           const float n[3], const float ng[3],
                                           float footprint, float rgb[3], float *weight,
                                           void *host);

/*
 * The footprint the _px call wants, for a pinhole camera: the width of one
 * pixel on the surface at p (normal n, either side) seen from eye, along
 * forward (any length), a pixel pixel_angle wide at distance 1 (2
 * tan(fov_y / 2) / height): pixel_angle |p - eye| (d.f)^(3/2) /
 * sqrt(max(|d.n|, 0.05)), d and f unit (forward, n and p - eye of any
 * finite length).  Returns IRC_OK, IRC_ERR_NULL, IRC_ERR_NONFINITE (an
 * input not finite, or a footprint past FLT_MAX), IRC_ERR_NORMAL (n zero
 * or not finite), or
 * IRC_ERR_RANGE (pixel_angle <= 0, forward zero, p at eye or behind it);
 * *footprint is written only on IRC_OK.  Thread safe; needs no cache.
 * A point seen through flat mirrors: pass the unfolded path, eye = p - L d
 * (L the path's length from the eye, d the last segment's unit direction)
 * and forward = the camera's forward reflected by the same mirrors, or d
 * itself (then up to 1/(d0.f)^(3/2) wider off the image's axis, d0 the
 * camera ray); through curved mirrors or refraction the cone changes: use
 * a ray differential's sqrt(|dp/dx x dp/dy|) instead.
 */
IRC_API int irc_pixel_footprint(const float eye[3], const float forward[3], float pixel_angle,
                                const float p[3], const float n[3], float *footprint);

/* Read the record in slot id.  Returns IRC_OK, IRC_MISS (an empty slot),
 * IRC_ERR_RANGE (id >= capacity), or a negative error code. */
IRC_API int irc_cache_record(irc_cache *cache, uint32_t id, irc_record *out);

/* Remove every record (irc_stats' counters are kept); not concurrent with
 * other calls.  Returns IRC_OK, or a negative error code. */
IRC_API int irc_cache_clear(irc_cache *cache);

/* ------------------------------------------------------------------------ */
/* Snapshots: a cache's records as portable bytes (docs/FORMAT.md defines   */
/* the format), to save a cache and load it in another process.             */

/* The format version this build writes and the only one it reads (bytes
 * 4-5 of a snapshot); another gets IRC_ERR_VERSION. */
#define IRC_SNAPSHOT_VERSION 1u

/* A writer for streamed snapshots: takes count bytes; returns 0, or nonzero
 * to stop (a negative value is passed through, a positive one becomes
 * IRC_ERR_CALLBACK).  Called with the cache's read lock held: it must not
 * call the cache's writers. */
typedef int (*irc_write_fn)(void *context, const void *bytes, size_t count);

/* The bytes irc_snapshot_write would write now (48 + records x record
 * bytes + 4).  Returns IRC_OK, IRC_ERR_NOMEM when that exceeds size_t, or
 * a negative error code. */
IRC_API int irc_snapshot_size(irc_cache *cache, size_t *bytes);

/*
 * Writes every stored record, with a header carrying the host's 64-bit
 * scene fingerprint, into buffer (write NULL; size at least
 * irc_snapshot_size, else IRC_ERR_NOMEM and nothing written) or through
 * write(context, ...) in pieces.  *written (optional) gets the bytes
 * produced; the cache is unchanged.  Returns IRC_OK or a negative code.
 */
IRC_API int irc_snapshot_write(irc_cache *cache, uint64_t fingerprint, void *buffer,
                               size_t size, irc_write_fn write, void *context,
                               size_t *written);

/*
 * Replaces the cache's records with a snapshot's, after checking everything:
 * IRC_ERR_TRUNCATED, IRC_ERR_CORRUPT, IRC_ERR_VERSION, IRC_ERR_FINGERPRINT
 * (not the fingerprint given), IRC_ERR_MISMATCH (another kind, features,
 * record size, SH bands or channels, or accuracy), IRC_ERR_FULL (more
 * records than the cache holds); on any of them the cache is as it was.
 * Records of other strata load: a record holds what lookups read, whatever
 * rays made it.  Lookups then answer as the written cache did, bit for bit
 * (at the same blend).  Not concurrent with other calls.  Returns IRC_OK
 * or a negative error code.
 */
IRC_API int irc_snapshot_read(irc_cache *cache, uint64_t fingerprint, const void *data,
                              size_t size);

/*
 * Adds a snapshot's records to the cache's, checked as irc_snapshot_read
 * checks (IRC_ERR_FULL when both, duplicates counted, exceed the capacity;
 * the cache unchanged on any error).  The records are put in one canonical
 * order (docs/DESIGN.md, "Snapshots and merges"), records equal in every
 * byte kept once, and renumbered as at irc_pass_end: merges into an empty
 * cache in any order give byte-identical snapshots, and merging one twice
 * adds nothing.  No neighbour clamping.  Not concurrent with other calls.
 * Returns IRC_OK or a negative error code.
 */
IRC_API int irc_merge(irc_cache *cache, uint64_t fingerprint, const void *data, size_t size);

/* ------------------------------------------------------------------------ */
/* Fill passes: the same records whatever the threads and their timing.    */

/*
 * Opens a fill pass.  Until irc_pass_end, every lookup (any call, any
 * thread, no lock taken) sees the cache as it was here: records computed
 * by misses and inserted wait in free slots, not indexed (a miss still
 * returns its record's value, weight 0), so the pass's answers and records
 * depend only on the cache it began with and the set of queries.  A pass
 * never evicts: once the free slots are taken, its further records are not
 * stored (IRC_NOT_STORED; IRC_ERR_FULL from insert) and which were kept
 * depends on timing.  Two misses within a record's reach both compute:
 * shade sparse pixels first, in several passes (docs/DESIGN.md, "Fill
 * passes": pixels P apart in P^2 passes, P up to 32).  A pass's end costs
 * in proportion to its own records, so many passes cost little (what they
 * cost measured: docs/DESIGN.md, "Fill passes").  Not concurrent with
 * other calls.  Returns IRC_OK,
 * IRC_ERR_STATE when a pass is open, or a negative code.
 */
IRC_API int irc_pass_begin(irc_cache *cache);

/*
 * Closes the open pass: its records, in merge's canonical order with exact
 * duplicates kept once, are inserted into the index (and clamped, when
 * on), at a cost in proportion to the pass's records, not the cache's.
 * When the cache has grown by a quarter since they last were, every
 * record is then renumbered in the order lookups visit the index (answers
 * bit for bit as before, faster; ids change); else earlier records keep
 * their ids and the pass's follow them.  *added (optional) gets how many
 * were added.  Not concurrent with other calls: every thread of the pass
 * must be done.  Returns IRC_OK, IRC_ERR_STATE when no pass is open, or a
 * negative code.  In a pass, irc_cache_clear, irc_snapshot_read and
 * irc_merge return IRC_ERR_STATE and change nothing.
 */
IRC_API int irc_pass_end(irc_cache *cache, uint32_t *added);

/* ------------------------------------------------------------------------ */
/* SH records (IRC_FEATURE_SH).                                              */
/*
 * An SH cache stores, per record and channel, the real spherical-harmonic
 * coefficients c_i = integral of y_i(w) L(w) dw of the incident radiance,
 * bands 0..L-1 (index l*l + l + m, Condon-Shortley phase), and with
 * IRC_FEATURE_SH_GRADIENT their translational gradients (c_i(p + d) ~ c_i
 * + grad c_i . d).  Surface records (n given) sample the hemisphere around
 * n and serve lookups with n, weighted as irc_cache_lookup's; free-point
 * records (n NULL) sample the whole sphere and serve lookups with n NULL,
 * weighted (R_j/|p - p_j|)^b, b = cfg.sh.power (docs/DESIGN.md, "SH
 * records", has the weights, radii and bytes a record).
 */
typedef struct irc_sh {
    float p[3];            /* position (a lookup: the query's) */
    float n[3];            /* unit normal; 0, 0, 0 for a free point */
    float radius;          /* R_j (a lookup: 0) */
    float e[3];            /* irradiance about n from the samples themselves,
                              not band limited (0 for a free point; a
                              lookup: the records' weighted mean) */
    uint32_t bands;        /* L */
    uint32_t channels;     /* 1 or 3 */
    float c[3][IRC_SH_MAX_COEFFS];       /* c[ch][i], i < L*L, ch < channels */
    /* d c[ch][i] / dp, all three components (a surface record's along n
     * includes what crosses its horizon); zero without
     * IRC_FEATURE_SH_GRADIENT; a lookup: the weighted mean. */
    float grad[3][IRC_SH_MAX_COEFFS][3];
    uint32_t features;     /* cfg.features */
    uint32_t rays;         /* rays cast, and how many were usable */
    uint32_t rays_used;
} irc_sh;

/*
 * Sample around p through the trace callback (args->host = host; args->n
 * 0, 0, 0 for a free point) and build an SH record: the hemisphere around
 * n, or with n NULL the whole sphere.  Nothing is stored.  Returns IRC_OK,
 * or a negative error code (IRC_ERR_NOSAMPLES when fewer than half the rays
 * were usable, the host's own if trace returned one).
 */
IRC_API int irc_sh_compute(irc_cache *cache, const float p[3], const float n[3],
                           irc_sh *out, void *host);

/* Store an SH record (a copy).  rec->bands and rec->channels must match the
 * cache's config, rec->radius > 0 and rec->e >= 0 (else IRC_ERR_RANGE),
 * every used field finite.  Returns IRC_OK, IRC_ERR_FULL, or a negative
 * error code. */
IRC_API int irc_sh_insert(irc_cache *cache, const irc_sh *rec);

/*
 * Interpolated coefficients at p (Eq. 15): every accepted record
 * extrapolated to p with its gradient, averaged with the weights above; n
 * NULL looks up free-point records, n given surface records.  out->c gets
 * the average and *weight (optional) the summed weight.  Returns IRC_OK,
 * IRC_MISS (out->c = 0, weight = 0), IRC_ERR_NONFINITE when an
 * extrapolation overflows float, or a negative error code.
 */
IRC_API int irc_sh_lookup(irc_cache *cache, const float p[3], const float n[3],
                  irc_sh *out, float *weight);

/* Lookup; on a miss, compute, insert and return the new record (*weight
 * 0).  Returns IRC_OK, IRC_NOT_STORED (pool full), or a negative code. */
IRC_API int irc_sh_lookup_or_compute(irc_cache *cache, const float p[3],
                                     const float n[3], irc_sh *out, float *weight,
                                     void *host);

/* Read the SH record in slot id: all exactly but n (to about 5e-5 rad);
 * bands, channels and features the cache's; rays and rays_used 0.  Returns
 * IRC_OK, IRC_MISS (empty slot), IRC_ERR_RANGE, or a negative code. */
IRC_API int irc_sh_record(irc_cache *cache, uint32_t id, irc_sh *out);

/*
 * Irradiance about the unit-ish normal n from sh's coefficients: the
 * clamped-cosine convolution (Ramamoorthi-Hanrahan 2001), sum over l, m of
 * A_l c_lm y_lm(n), A_0..4 = pi, 2 pi/3, pi/4, 0, -pi/24; exact for
 * radiance of band < L.  rgb gets sh->channels values (one is copied to
 * all three).  Returns IRC_OK, IRC_ERR_NULL, IRC_ERR_NORMAL, or
 * IRC_ERR_RANGE (bands or channels out of range).
 */
IRC_API int irc_sh_irradiance(const irc_sh *sh, const float n[3], float rgb[3]);

/*
 * A Phong-like lobe: integral of L(w) max(0, w.r)^s dw about the unit-ish
 * axis r, sum A_l(s) c_lm y_lm(r), A_l(s) = 2 pi integral_0^1 z^s P_l(z) dz
 * (times (s + 2)/(2 pi) for normalised Phong); L bands resolve s up to
 * about L^2.  Returns as irc_sh_irradiance (IRC_ERR_RANGE: s not in [0, 1e4]).
 */
IRC_API int irc_sh_glossy(const irc_sh *sh, const float r[3], float s, float rgb[3]);

/* ------------------------------------------------------------------------ */
/* Counters and sizes.                                                       */

typedef struct irc_stats {
    uint64_t records;        /* live records */
    uint64_t capacity;       /* max_records */
    uint64_t inserts;        /* records stored */
    uint64_t evictions;      /* records replaced by CLOCK */
    uint64_t lookups;        /* lookup calls (including lookup_or_compute) */
    uint64_t hits;           /* lookups answered from records */
    uint64_t computes;       /* records computed */
    uint64_t not_stored;     /* computed by lookup_or_compute but not stored:
                                the pool was full (IRC_NOT_STORED) */
    uint64_t waits;          /* computes that waited for a scratch slot */
    uint64_t details;        /* _px calls answered per pixel (IRC_DETAIL) */
    uint64_t rays;           /* rays cast through the callback: records',
                                occlusion's, confirming rays and per-pixel
                                detail's (probes and estimates) */
    uint64_t index_nodes;    /* index nodes in use */
    uint64_t index_nodes_max;
    uint64_t index_refs;     /* index references in use: a record is listed
                                in every node its reach's box overlaps at
                                its level, 1 to 8 */
    uint64_t index_refs_max; /* when they run short records are listed in
                                fewer, larger nodes: lookups slow down */
    size_t record_bytes;     /* bytes per stored record (feature dependent) */
    size_t bytes_records;    /* block bytes for records */
    size_t bytes_index;      /* block bytes for the index */
    size_t bytes_scratch;    /* block bytes for sampling scratch */
    size_t bytes_total;      /* all block bytes the cache uses */
} irc_stats;

/* Thread safe (a concurrent call may be half counted).  Returns IRC_OK, or
 * a negative error code. */
IRC_API int irc_cache_stats(irc_cache *cache, irc_stats *out);

#ifdef __cplusplus
}
#endif
#endif /* IRRCACHE_H */

/* ------------------------------------------------------------------------ */
/* Experimental calls ("Stability" above): declared where the host defines  */
/* IRC_EXPERIMENTAL before it includes this header, even after an include   */
/* without it (the block has a guard of its own).                           */

#if defined(IRC_EXPERIMENTAL) && !defined(IRC_EXPERIMENTAL_DEFINED)
#define IRC_EXPERIMENTAL_DEFINED

#ifdef __cplusplus
extern "C" {
#endif

/* Net visibility, for hosts that cache occlusion rather than irradiance. */
typedef struct irc_occlusion {
    float visible;   /* the fraction of the hemisphere's solid angle whose rays
                        escape (first-order paper, Eq. 47, over 2 pi); every
                        hit blocks */
    float grad[3];   /* its gradient along the surface (Eq. 48), per unit of
                        length */
    uint32_t rays;   /* rays cast */
} irc_occlusion;

/* The net visibility about (p, n) and its exact gradient from the
 * silhouettes; needs IRC_FEATURE_VISIBILITY (else IRC_ERR_UNSUPPORTED).
 * Nothing is stored.  Returns IRC_OK, or a negative error code. */
IRC_API int irc_occlusion_compute(irc_cache *cache, const float p[3], const float n[3],
                                  irc_occlusion *out, void *host);

/* Interpolated irradiance's first derivatives at a point, per channel c. */
typedef struct irc_gradient {
    float dp[3][3];  /* dE_c/dp: E_c changes by dp[c] . dx as p moves by dx
                        (per unit of length; along the surface) */
    float dn[3][3];  /* dE_c/dn: E_c changes by dn[c] . dm as the unit normal
                        turns by a small dm (perpendicular to n; per radian) */
} irc_gradient;

/*
 * irc_cache_lookup, and the gradient of what it interpolates: each
 * record's extrapolation differentiated (dp = grad_t, dn = grad_r x n_i; 0
 * for a clamped channel or a gradient the cache lacks), averaged with the
 * same weights, whose own derivatives are left out (docs/DESIGN.md, "What
 * a record is").  rgb and grad not NULL (IRC_ERR_NULL); an SH cache:
 * IRC_ERR_UNSUPPORTED.  Otherwise as irc_cache_lookup (grad on IRC_MISS
 * that of its average, zero with no record within blend a R),
 * IRC_ERR_NONFINITE also for a gradient that overflows float.
 */
IRC_API int irc_cache_lookup_gradient(irc_cache *cache, const float p[3], const float n[3],
                                      float rgb[3], irc_gradient *grad, float *weight);

/*
 * The ids (slot numbers) of the records a lookup at (p, n) would use, in no
 * order: up to cap in ids, how many there are in *count (maybe > cap).
 * Either kind (n NULL in an SH cache: free points); for debugging.  An id
 * is a record's until irc_pass_end, irc_merge, irc_cache_clear or its
 * eviction.  Returns IRC_OK, or a negative error code.
 */
IRC_API int irc_cache_neighbours(irc_cache *cache, const float p[3], const float n[3],
                                 uint32_t *ids, uint32_t cap, uint32_t *count);

/*
 * Share a block live between processes of one machine (docs/DESIGN.md,
 * "Sharing a cache between processes"): one makes the cache in memory
 * every process maps; each other joins it, building its view in view
 * (view_size >= IRC_VIEW_BYTES, aligned for a double, kept until irc_fini
 * of the view), which holds its own cfg->trace, cfg->context and
 * cfg->port; the rest is the block's, shared.  cfg->buffer is this
 * process's mapping, at the creator's offset from a 64-byte boundary (any
 * mmap is); the port must be the creator's.  irc_fini of a view releases
 * the view; the creator's, after every view's, destroys the lock.  The
 * block is checked as irc_attach checks it and never written.  Returns
 * IRC_OK and writes *cache; IRC_ERR_CONFIG (no cache of this build, another
 * offset or port), IRC_ERR_CORRUPT (a check failed), IRC_ERR_NOMEM
 * (view_size short of IRC_VIEW_BYTES, view not aligned for a double, or
 * buffer_size short), or a negative code.
 */
#define IRC_VIEW_BYTES 1024u
IRC_API int irc_join(const irc_config *cfg, void *view, size_t view_size, irc_cache **cache);

/* The band-limited radiance arriving from the unit-ish direction w, sum
 * over l, m of c_lm y_lm(w): what a host integrates its own BRDF against
 * (e.g. over samples of a lobe whose product with the cosine is not
 * zonal).  Returns as irc_sh_irradiance. */
IRC_API int irc_sh_radiance(const irc_sh *sh, const float w[3], float rgb[3]);

#ifdef __cplusplus
}
#endif
/* Progressive renderers: many samples a pixel, the image shown as it       */
/* converges (docs/DESIGN.md, "Progressive hosts"; bench/progressive.c).   */

/*
 * Tells the cache how many samples a pixel the host has taken, between
 * iterations (only a new power of two does anything).  From the first
 * call on the cache is progressive: a record holds M N s / 1024 rays at
 * s samples a pixel, at least M N / 16 (M N / 4 for a >= 0.375), M x N
 * the knob's strata; at each power of two every record gets new,
 * independent rays as many as it has, its E and gradients their mean,
 * its position and radius kept (docs/DESIGN.md, "Progressive hosts").
 * Records computed later get the level's rays at once, and a _px record
 * reaches a pixel at least (a R >= footprint, within max_pixels and
 * max_radius).  The refinement casts 2x the rays the records hold through
 * cfg.trace from the calling thread (args->host = host), the same
 * whatever threads made the records.  Not concurrent with any other call;
 * not inside a pass (IRC_ERR_STATE); samples may fall back only in an
 * empty cache, else IRC_ERR_RANGE.  Records a snapshot or merge brings in
 * count as holding the level's rays.  A record keeps no geometric normal:
 * its new rays are all cast (a host whose shading normals differ from its
 * geometric ones fails those below in its callback, or passes ng as n).
 * Returns IRC_OK, IRC_ERR_UNSUPPORTED
 * (SH, VISIBILITY, HESSIAN or supersamples), or a negative code; the
 * callback's stops the refinement: the records before it are refined,
 * the rest keep their rays, and the cache is at the new level.
 */
IRC_API int irc_progress(irc_cache *cache, uint32_t samples, void *host);

/* A pixel's answers, kept by the host for its later samples: one
 * irc_pixel a pixel, zeroed before the first call.  Two answers, for a
 * pixel on an edge.  Its fields are the library's. */
typedef struct irc_pixel_answer {
    float p[3], n[3];    /* the point the answer was made for */
    float e[3];          /* the answer */
    float weight;        /* its weight (0: computed there, or a detail) */
    float footprint;
    int32_t status;      /* what the call that made it returned */
    uint32_t epoch;      /* the cache's level + 1 then; 0: nothing kept */
    uint32_t level;      /* a detail estimate's: its rays are T0 2^level */
} irc_pixel_answer;
typedef struct irc_pixel {
    irc_pixel_answer kept[2];
    uint32_t older;      /* which of them the next new answer replaces */
    uint32_t unused;
} irc_pixel;

/*
 * The _px call for a sample of a pixel whose answers the host keeps in
 * *pixel.  A point within 2 footprints of a kept answer's point, with a
 * normal within about 18 degrees of its normal, gets that answer (rgb,
 * *weight, the same status) with no lookup and no probe until the cache's
 * level changes (irc_progress); then it is looked up again without probes
 * and answered by any record within blend a R, or, for a kept detail
 * estimate (IRC_DETAIL), given more rays: up to T0 2^(level - top), about
 * one a sample (top 2 for the default grids below a = 0.375, 1 above); a
 * new detail estimate has T0 (M N / 16 or / 4).  Any other point is
 * answered by irc_cache_lookup_or_compute_px, kept in place of the answer
 * used less recently.  Calls for one irc_pixel must not run concurrently;
 * zero it again after irc_cache_clear, irc_snapshot_read or irc_merge, and
 * use it with one cache only.  ng as the _px call's; a kept detail
 * estimate's new rays take the sample's ng.  Returns as the _px call,
 * IRC_ERR_NULL for a NULL pixel; *pixel changes only on success.
 */
IRC_API int irc_cache_lookup_pixel(irc_cache *cache, irc_pixel *pixel, const float p[3],
                                   const float n[3], const float ng[3], float footprint,
                                   float rgb[3], float *weight, void *host);

#endif /* IRC_EXPERIMENTAL */
