/*
 * irrcache.h -- an embeddable irradiance cache.  This header is the manual.
 *
 * irrcache caches irradiance for a host ray tracer.  The host casts rays
 * through a callback; the library samples hemispheres through it, builds
 * records carrying translational and rotational gradients, keeps them in one
 * memory block the host hands over at init, and answers Ward-Heckbert
 * weighted, gradient-extrapolated lookups.  A cache may hold spherical-
 * harmonic records of incident radiance instead (IRC_FEATURE_SH, "SH
 * records" below).
 *
 *   - The library NEVER allocates.  Every structure (records, index nodes,
 *     sampling scratch, the lock) lives in the block given to irc_init().
 *     There is no free function for memory: the caller owns the block.
 *   - No global mutable state.  Any number of caches may coexist.
 *   - The block holds offsets, not pointers: copied byte for byte to another
 *     address, or mapped by another process, it is a working cache again
 *     after irc_attach() (same build of the library, same ABI).
 *   - Thread safety: with a locking port (the default of this build is
 *     POSIX threads), every call below may run concurrently from any
 *     threads on one cache, except irc_init, irc_attach, irc_cache_clear,
 *     irc_snapshot_read, irc_merge and irc_fini, which must not run
 *     concurrently with anything else on that cache.  Lookups take the port's read lock; inserts (and the insert of
 *     lookup_or_compute) its write lock; the trace callback runs with no
 *     lock held.  With irc_port_none, one thread at a time.
 *   - Stability: while the major version is 0, a minor release may change
 *     the block's layout (irc_attach refuses an older block) but keeps the
 *     stable calls' contracts: footprint, init, attach, fini, compute,
 *     insert, lookup, lookup_or_compute(_px), record, clear, stats,
 *     snapshots and merges, passes, the SH calls but irc_sh_radiance,
 *     irc_strerror and the version calls, and
 *     the ports.  Five calls are experimental, research tools whose
 *     contract may change in any release: irc_occlusion_compute,
 *     irc_cache_lookup_gradient, irc_cache_neighbours, irc_join and
 *     irc_sh_radiance; each says so.
 *   - Determinism: a record is a pure function of (p, n, config, seed, and
 *     the _px call's footprint) for a deterministic trace callback, one
 *     that answers the same ray with the same hit.  Its random numbers come
 *     from a hash of the query, so the same query gives the same record,
 *     bit for bit, in any thread and at any time; a callback that samples
 *     lights or paths with numbers of its own makes records that differ by
 *     that noise.  Which records a multi-threaded fill stores still
 *     depends on timing (fill passes make it not: "Fill passes").
 *   - Errors: every call returns an int: IRC_OK (0), a positive informational
 *     status (IRC_MISS, IRC_NOT_STORED), or a negative irc_status code.  A
 *     call that returns a negative code has left the cache's block byte for
 *     byte as it was, but for the port's lock object (a call may take and
 *     release the lock before it fails, and a lock-unlock pair need not
 *     restore the lock's bytes).  A negative value returned
 *     by the host's trace callback is passed through unchanged, so keep host
 *     codes below IRC_ERR_LAST.  Positive statuses are not failures: a host
 *     that tests `st < 0` must still look at IRC_NOT_STORED (or at
 *     irc_stats.not_stored) to learn that its pool is full.
 *
 * Quick start (examples/minimal.c is a complete host):
 *
 *   irc_config cfg = {0};             (zero: the measured defaults)
 *   cfg.trace = my_trace; cfg.context = my_scene;
 *   size_t bytes; irc_footprint(&cfg, 100000, &bytes);
 *   cfg.buffer = my_block; cfg.buffer_size = bytes;
 *   irc_cache *c; irc_init(&cfg, 100000, &c);
 *   ... at a camera ray's hit, with the pixel's footprint there:
 *   irc_cache_lookup_or_compute_px(c, p, n, footprint, rgb, NULL, my_thread_state);
 *   irc_fini(c);
 *
 * All vectors are float[3] in the host's world space.  Units of length are
 * the host's; nothing in the library depends on the scene's scale.
 * Irradiance E is radiance times steradians (the integral of L cos over the
 * hemisphere: E = pi L under a uniform sky of radiance L), in the host's
 * radiance units per channel.
 *
 * Record kinds.  An irradiance cache (the default) and an SH cache
 * (IRC_FEATURE_SH) keep different records behind one store; each kind has
 * its own typed calls (irc_cache_* / irc_record_* for irradiance, irc_sh_*
 * for SH), thin wrappers over the same insert, lookup and eviction.  Typed
 * calls were kept over one call taking `void *` so that the compiler, not a
 * runtime check, catches an irc_sh passed where an irc_record belongs; a
 * call of the other kind returns IRC_ERR_UNSUPPORTED.
 */
#ifndef IRRCACHE_H
#define IRRCACHE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The one place the version is defined (the Makefile reads it from here
 * for the shared object's name, irrcache.pc and the CMake package).  A
 * different major version, or a different minor one while the major is 0,
 * is another ABI.  A host written for one minor version can refuse to
 * build against another, where meanings may have changed under unchanged
 * code (CHANGES.md, "Upgrading"):
 *     #if IRC_VERSION_MAJOR != 0 || IRC_VERSION_MINOR != 3
 *     #error "written for irrcache 0.3"
 *     #endif */
#define IRC_VERSION_MAJOR 0
#define IRC_VERSION_MINOR 3
#define IRC_VERSION_PATCH 0
#define IRC_VERSION_NUMBER \
    (IRC_VERSION_MAJOR * 10000 + IRC_VERSION_MINOR * 100 + IRC_VERSION_PATCH)
#define IRC__STR_(x) #x
#define IRC__STR(x) IRC__STR_(x)
#define IRC_VERSION_STRING \
    IRC__STR(IRC_VERSION_MAJOR) "." IRC__STR(IRC_VERSION_MINOR) "." IRC__STR(IRC_VERSION_PATCH)

/* Every declaration of this header, and nothing else of the library, is
 * visible from the shared library (the library builds with
 * -fvisibility=hidden).  Define IRC_API yourself to decorate it otherwise
 * (e.g. __declspec(dllexport)). */
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
    IRC_MISS = 1,             /* lookup: no record is close enough; a record
                                 read: the slot is empty (not an error) */
    IRC_NOT_STORED = 2,       /* lookup_or_compute: the value was computed and
                                 returned, but the pool is full and eviction
                                 is off, so it was not stored: every later
                                 miss nearby computes again (counted in
                                 irc_stats.not_stored) */
    IRC_ERR_NULL = -1,        /* a required pointer argument is NULL, or
                                 cfg.trace is */
    IRC_ERR_CONFIG = -2,      /* a config field is out of its documented range;
                                 also a handle that is not a live cache (never
                                 initialised, after irc_fini, or a block not
                                 re-attached), and a block irc_attach cannot
                                 take (another ABI or layout version) */
    IRC_ERR_NONFINITE = -3,   /* a NaN or infinite coordinate or value (also a
                                 record whose irradiance or gradients overflow
                                 float, from radiances near FLT_MAX, and a
                                 lookup whose extrapolation overflows) */
    IRC_ERR_NORMAL = -4,      /* a normal is zero (or not finite) */
    IRC_ERR_NOMEM = -5,       /* the block is smaller than irc_footprint() asks */
    IRC_ERR_FULL = -6,        /* insert: the record pool is full, eviction is off */
    IRC_ERR_CALLBACK = -7,    /* the trace callback returned a positive value or
                                 reported nonsense: negative, zero or NaN distance,
                                 non-finite or negative radiance, zero normal,
                                 unknown ray status */
    IRC_ERR_NOSAMPLES = -8,   /* fewer than half of the hemisphere's rays were
                                 usable (the host reported them as failed) */
    IRC_ERR_BUSY = -9,        /* every scratch slot was in use and the cache
                                 does not wait (cfg.no_wait, or a port that
                                 cannot yield) */
    IRC_ERR_UNSUPPORTED = -10,/* a call the cache's kind or features do not
                                 serve (an irradiance call on an SH cache, an
                                 SH call on an irradiance cache, occlusion
                                 without VISIBILITY), or a config or block
                                 asking for what the library was built
                                 without (IRC_NO_SH, IRC_NO_VISIBILITY,
                                 IRC_NO_HESSIAN, IRC_NO_SIGHT,
                                 IRC_NO_SUPERSAMPLE, IRC_NO_GUARD:
                                 docs/PORTING.md); then
                                 the SH calls, irc_sh_irradiance and
                                 irc_sh_glossy included, return it too */
    IRC_ERR_PORT = -11,       /* the port failed to initialise or take its
                                 lock */
    IRC_ERR_RANGE = -12,      /* a value out of its range: a record id past
                                 the capacity, a record with radius <= 0 or
                                 negative irradiance, SH bands or channels
                                 that do not match the cache, a lobe exponent
                                 out of [0, 1e4] */
    IRC_ERR_TRUNCATED = -13,  /* a snapshot shorter than its header says */
    IRC_ERR_CORRUPT = -14,    /* a snapshot whose magic, checksums, length or
                                 decoded values are wrong; irc_attach and
                                 irc_join: a block whose header, records or
                                 index no cache could have made */
    IRC_ERR_VERSION = -15,    /* a snapshot of another format version */
    IRC_ERR_MISMATCH = -16,   /* a snapshot of another record kind, feature
                                 set, record size, SH bands or channels,
                                 accuracy or strata than the cache's */
    IRC_ERR_FINGERPRINT = -17,/* a snapshot made for another scene (its
                                 fingerprint differs from the one given) */
    IRC_ERR_STATE = -18,      /* a call the cache's state forbids: a fill pass
                                 begun while one is open or ended when none
                                 is; clear, snapshot read or merge while a
                                 pass is open */
    IRC_ERR_NESTED = -19,     /* a trace callback called into the cache that
                                 is computing its record, and the call would
                                 compute one too (it would wait for its own
                                 slot): see "Several bounces" below */
    IRC_ERR_LAST = -19        /* the most negative code the library returns */
} irc_status;

/* A one-line English description of any status code (never NULL).  Thread
 * safe. */
IRC_API const char *irc_strerror(int status);

/* The version of the library the program runs with, as IRC_VERSION_NUMBER
 * and IRC_VERSION_STRING were when it was built: a host checks that the
 * header it compiled against matches the library it loaded, e.g.
 *     if (irc_version_number() / 100 != IRC_VERSION_NUMBER / 100) fail;
 * (major and minor, as long as the major is 0).  Any time, any thread; no
 * cache needed. */
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
    uint32_t visibility_only; /* 1: confirming rays (cfg.check_visibility),
                               each from the query toward a record (raised
                               toward the plane of n by as much of its dip
                               as the turn from n to the record's normal
                               explains, so that a record on the same
                               ball or column is not hidden by the bulge
                               of the surface between them); a ray may
                               still point a little below the plane of n.
                               Only status and dist are read: the host may
                               skip shading and leave normal and radiance
                               unset */
} irc_trace_args;

/*
 * Cast args->count rays and fill args->hits.  The callback may touch only
 * args->hits[0 .. count-1] and its own state, and may call into other
 * caches (below); a call into the same cache that would compute a record
 * must not be made (it returns IRC_ERR_NESTED where the port can tell,
 * below).  For confirming rays (visibility_only) it calls
 * no cache.  It runs on the thread that called into the library, with no
 * lock of the cache held, possibly on several threads at once.  Return 0 on
 * success or a negative code of the host's own to abort the record (the
 * library returns it unchanged and keeps nothing of the record).
 *
 * Several bounces (Radiance's -ab N) take one cache per level: the
 * callback of level k's cache shades each hit with level k+1's lookup
 * (radiance = emission + direct + albedo / pi * E_{k+1}), the last
 * level's with direct light only, passing args->host on.  Why not one
 * cache with records tagged by level: a level-k record holds N - k
 * bounces, so records of different levels must not answer each other's
 * lookups, and tagging would scan every level's records in each lookup;
 * separate caches keep each level's index, size (irc_footprint), config
 * and snapshots its own.  What paid for deeper levels on the Cornell box
 * (bench/README.md, "Several bounces"): the same accuracy, radii floored
 * at half of max_radius, half the strata a level, no confirming rays;
 * fill them freely (in a pass, their records would stay out of sight of
 * the pass's other lookups).  No deadlock: a thread holding a slot of
 * level k waits only for a slot of level k+1, whose holders wait only on
 * deeper levels, and the last waits on none, so some thread always runs,
 * with any number of host threads and slots (cfg.threads = 1 included).
 * A callback that calls back into its own cache, directly or through a
 * cycle of caches, would wait for its own slot or recurse without end:
 * the call returns IRC_ERR_NESTED instead when the port tells threads
 * apart (irc_port thread: posix and c11) or runs one thread (none).
 * Across threads a cycle can deadlock: two threads may each hold the
 * last slot of one cache and wait for the other's.  Give every cache of
 * a cycle as many slots (cfg.threads) as host threads call into it, or
 * set no_wait (IRC_ERR_BUSY instead of waiting).
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
 *     holder is a process that died holding it: write_lock then holds the
 *     lock, and the library repairs the block before it goes on (drops the
 *     record being written, rebuilds the index from the records); read_lock
 *     returns 1 without the lock, and the library takes the write lock to
 *     repair.  A port that cannot tell returns 0 or negative only.  The
 *     library never takes a lock it already holds and never upgrades one.
 *   - read_unlock / write_unlock: release a lock this thread holds; cannot
 *     fail.
 *   - yield: let other threads run while this one waits for a scratch slot;
 *     NULL if the port cannot wait (single-threaded).
 *   - owner / owner_alive (both or neither; NULL: none): a scratch slot
 *     records the token of the process that claimed it, and a call that
 *     finds every slot taken (at once with no_wait, else every 256 waits)
 *     takes over a slot whose process is gone: a process killed inside a
 *     record computation does not hang the others (irc_join).
 *     irc_port_posix has them (the process id, asked once per process;
 *     alive while kill(pid, 0) finds it and it has not exited: an exited
 *     child not yet reaped counts as gone, for its parent always, for
 *     others on Linux), and its lock asks them too: a process killed
 *     holding the read lock (in a lookup) is counted out, one killed
 *     holding the write lock (in an insert, a pass's end, a merge) is taken
 *     over with 1 as above.  Processes of one pid namespace; a reused
 *     process id looks alive.  irc_port_c11 has neither and recovers
 *     nothing: a process that dies inside its lock hangs the others, and
 *     one that dies computing keeps its slot (with every slot so kept,
 *     misses wait forever, or return IRC_ERR_BUSY with no_wait), until
 *     the block is attached anew (irc_attach makes a fresh lock, frees the
 *     slots and repairs).  Threads of one process are unaffected: a thread
 *     cannot die alone.  docs/DESIGN.md, "Reliability: how", tabulates
 *     what each port recovers.
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
    uint64_t (*thread)(void);             /* optional: a nonzero token of the
                                             calling thread, unique among
                                             its process's live threads;
                                             with it a call nested in its
                                             own cache's callback returns
                                             IRC_ERR_NESTED instead of
                                             waiting for itself */
} irc_port;

/* The ports.  A build compiles the one chosen by `make PORT=posix|c11|none`
 * (default posix) and irc_port_none; only those two are defined. */
IRC_API extern const irc_port irc_port_posix;  /* a lock that outlives its holders + GCC/Clang atomics */
IRC_API extern const irc_port irc_port_c11;    /* C11 <stdatomic.h>, spinning rwlock */
IRC_API extern const irc_port irc_port_none;   /* single-threaded: no locks at all */
IRC_API extern const irc_port *const irc_port_default; /* the chosen one: what
                                                          cfg.port = NULL means */

/* ------------------------------------------------------------------------ */
/* Configuration.  Zero in any field means its default.                    */

/* Gradient terms a record carries.  A cache pays in memory and time only for
 * the terms it enables: 32 bytes per record bare, +16 per gradient
 * (VISIBILITY changes how the translational gradient is made, not its
 * size). */
enum irc_feature {
    IRC_FEATURE_TRANSLATION = 1u << 0, /* translational gradient (Krivanek et
                                          al. 2005 stratified form) */
    IRC_FEATURE_ROTATION = 1u << 1,    /* rotational gradient (Ward-Heckbert 1992) */
    IRC_FEATURE_VISIBILITY = 1u << 2,  /* the translational gradient from exact
                                          visibility gradients at silhouettes
                                          (first-order paper, Sec. 6-7): implies
                                          TRANSLATION; costs extra rays (14 per
                                          silhouette crossing of the strata
                                          grid, + 1) and ~300 scratch bytes a
                                          stratum */
    IRC_FEATURE_SH = 1u << 3,          /* records hold spherical-harmonic
                                          coefficients of incident radiance
                                          instead of irradiance (see "SH
                                          records" below); excludes the three
                                          flags above */
    IRC_FEATURE_SH_GRADIENT = 1u << 4, /* SH records also carry the
                                          coefficients' translational
                                          gradients (SH-gradient paper, Eq.
                                          6-12), from the same rays: implies SH */
    IRC_FEATURE_HESSIAN = 1u << 5,     /* irradiance records: the
                                          occlusion-aware Hessian of E from
                                          the rays already cast (Schwarzhaupt
                                          et al. 2012), in irc_record.hessian,
                                          and the ellipse it implies: along
                                          each eigen-axis of the tangent
                                          Hessian (curvature k) the radius
                                          is sqrt(2 E/|k|), where first-order
                                          extrapolation errs by about a^2 E
                                          at the edge of reach; the major
                                          radius at most IRC_ANISOTROPY x the
                                          minor.  With TRANSLATION these
                                          radii replace E/|grad E| and the
                                          split sphere, bounded by the
                                          farthest hit; without it the split
                                          sphere still bounds them.  No extra
                                          rays, 24 scratch bytes a stratum,
                                          8 record bytes (the ellipse) */
    IRC_FEATURE_NONE = 1u << 6         /* no gradients: bare records with
                                          Ward's split-sphere radius; only
                                          alone (features = 0 means the
                                          default, TRANSLATION | ROTATION) */
};

/* Settings that are on or off: 0 is the setting's default, which its
 * field names; IRC_ON and IRC_OFF say which the host wants. */
enum irc_switch {
    IRC_DEFAULT = 0,
    IRC_ON = 1,
    IRC_OFF = 2
};

/* What insert does when the record pool is full. */
enum irc_evict {
    IRC_EVICT_NONE = 0,  /* refuse the insert: IRC_ERR_FULL (lookups go on) */
    IRC_EVICT_CLOCK = 1  /* second-chance CLOCK: a hand sweeps the records in
                            slot order; a record used by a lookup since the hand
                            last passed gets a second chance, the first unused
                            one is replaced.  Costs 1 bit per record. */
};

typedef struct irc_config {
    irc_trace_fn trace;      /* required */
    void *context;           /* handed to trace unchanged */
    uint32_t max_batch;      /* rays per trace call, 1..4096 (default 1, one
                                ray per call; larger values serve packet
                                tracers and cost 56 bytes per ray and thread) */
    uint32_t features;       /* IRC_FEATURE_* bits (default 0: TRANSLATION |
                                ROTATION; IRC_FEATURE_NONE for bare records) */
    float accuracy;          /* Ward's a: a record counts at p when
                                |p-p_i|/R_i + sqrt(1-n.n_i) < a; (0, 10]
                                (default 0.2) */
    float min_radius;        /* R_i >= min_radius; finite, in
                                [0, IRC_RADIUS_CAP) (default 0) */
    float max_radius;        /* R_i <= max_radius; finite, in
                                (min_radius, IRC_RADIUS_CAP] (default 0:
                                IRC_RADIUS_CAP, no limit).  Also the radius
                                of a record whose rays all escaped (with
                                the default, such a record has the
                                smallest radius and serves only its own
                                point, where a lookup answers from it;
                                set max_radius for open scenes, or use
                                the _px call) */
    uint32_t strata_theta;   /* M rows in theta, 1..1024 (default 32 for
                                irradiance records, 16 for SH records) */
    uint32_t strata_phi;     /* N columns in phi, 1..4096 (default 128,
                                SH 64); M * N <= IRC_MAX_STRATA.  A
                                record's noise reaches every pixel it
                                serves (bench/README.md, "The corpus") */
    uint32_t threads;        /* scratch slots: how many record computations
                                may run at once, 1..64 (default 1).  Each
                                costs irc_stats.bytes_scratch / threads.  A
                                compute that finds every slot taken waits
                                for one (see no_wait), so any number of host
                                threads may share a cache; give it as many
                                slots as host threads that compute at once
                                (your worker count) to never wait. */
    uint32_t no_wait;        /* 1: a compute that finds every slot taken
                                returns IRC_ERR_BUSY at once instead of
                                waiting (default 0: wait through the port's
                                yield) */
    uint32_t evict;          /* an irc_evict (default IRC_EVICT_NONE) */
    uint32_t clamp_neighbours; /* an irc_switch: neighbour clamping
                                (Krivanek et al. 2006) at every insert: the
                                new record's radius is at most R_j + |x -
                                x_j| over the records j within it, and
                                those are clamped back to R + |x - x_j|.
                                Default: on for irradiance records (why:
                                bench/README.md, "On real geometry"), off
                                for SH records */
    uint32_t check_visibility; /* an irc_switch: confirming rays (V-Ray's
                                "check sample visibility").  The
                                lookup_or_compute calls cast one ray from
                                the query toward each record they would
                                use (up to 32; the trace callback sees
                                visibility_only = 1) and leave out those
                                whose ray hits something before 0.9 of the
                                way: records outside a crevice, behind a
                                column or above a soffit stop lighting it;
                                when none is left the call computes a
                                record there.  Plain lookups do not check.
                                Default: on for irradiance records (why:
                                bench/README.md, "Confirming rays on
                                curved surfaces"), off for SH records; off
                                and refused in a build without them
                                (IRC_NO_SIGHT) */
    /* Fields of one record kind: a kind's own, zero for its defaults,
     * and all zero in a config of the other kind (else IRC_ERR_CONFIG). */
    struct irc_config_irr {  /* irradiance records */
        uint32_t supersamples; /* after the M x N rays, this many more, one a
                                stratum, into the strata around which the
                                radiance changes most (the spread of the
                                four neighbours' samples: Radiance's
                                ambient super-samples, -as); such a
                                stratum's radiance is then the mean of its
                                two samples and its distance the nearer,
                                and the gradients read those.  Unbiased: a
                                stratum's own sample never chooses it.
                                0..M N (default 0: none); not with
                                VISIBILITY (its silhouettes are the first
                                rays') */
        uint32_t leak_guard; /* an irc_switch: records keep a leak guard
                                (irc_record.leak_guard, 8 bytes) against
                                light through thin walls between spaces
                                lit differently.  Default off (why:
                                bench/README.md, "On real geometry") */
        float min_pixels;    /* screen-space bounds on a record's reach a R
                                (pbrt-v2's minimum and maximum pixel
                                spacing): a record computed by
                                irc_cache_lookup_or_compute_px with a
                                footprint f > 0 gets a R in [min_pixels f,
                                max_pixels f], then R in [min_radius,
                                max_radius]; one whose rays all escaped
                                gets max_pixels f.  Finite; 0 the default:
                                no lower bound and 15 (why none:
                                bench/README.md, "The corpus"), negative:
                                that side unbounded; max_pixels >=
                                min_pixels (a default max_pixels is at
                                least min_pixels) */
        float max_pixels;    /* see min_pixels */
        float full_pixels;   /* records whose rays follow the pixels they
                                serve: a record made by the _px call whose
                                radius R (within the pixel bounds) spans
                                fewer than full_pixels pixels (R /
                                footprint) is sampled on a coarser grid,
                                M/2 x N/2 below full_pixels, M/4 x N/4
                                below full_pixels / 2 (levels that keep
                                >= 64 strata, >= 2 rows, >= 8 columns).
                                The call samples the coarsest grid first
                                and refines it, keeping its rays.  Not
                                with VISIBILITY, HESSIAN or supersamples.
                                Finite; 0 the default, off, as is any
                                negative value (why: bench/README.md,
                                "Records that cost what they serve") */
        float detail_pixels; /* the _px call's per-pixel detail: up to 8
                                probe rays first; a point with a hit
                                within detail_pixels x footprint is
                                answered from its own M x N strata (E
                                alone), stored nowhere (a frozen cache
                                later misses there), weight 0, counted a
                                lookup but not a hit.  With every slot
                                taken (no_wait) or inside the cache's own
                                callback: answered as without detail.
                                Finite; 0: 0.5; negative: off (why:
                                bench/README.md, "Detail computed per
                                pixel") */
    } irr;
    struct irc_config_sh {   /* SH records (IRC_FEATURE_SH) */
        uint32_t bands;      /* L, bands 0..L-1, L*L coefficients per
                                channel; 1..IRC_SH_MAX_BANDS (default 3) */
        uint32_t channels;   /* 3 (RGB, default) or 1 (the hit's
                                radiance[0] only) */
        float power;         /* at free points: the exponent b of the
                                weight (R_j/|p - p_j|)^b; (0, 16]
                                (default 2) */
    } sh;
    uint64_t seed;           /* mixed into every record's random numbers */
    const irc_port *port;    /* locks and atomics (default irc_port_default) */
    void *buffer;            /* the caller's block, any alignment; the library
                                uses [buffer, buffer + buffer_size) only */
    size_t buffer_size;      /* bytes, >= what irc_footprint() returned */
} irc_config;

#define IRC_MAX_STRATA 4194304u /* 1024 x 4096 */
#define IRC_MAX_BATCH 4096u
#define IRC_MAX_THREADS 64u
#define IRC_MAX_RECORDS 0x3fffffffu
/* Radii are clamped to 2^100 (about 1.27e30; all rays escaped): a power of
 * two, so that it compares equal to a stored radius in any float
 * evaluation (x87's excess precision included). */
#define IRC_RADIUS_CAP 1267650600228229401496703205376.0f
/* An ellipse's major radius is at most this multiple of its minor one
 * (HESSIAN records; hand-built records are clamped to it when stored). */
#define IRC_ANISOTROPY 4.0f
#define IRC_SH_MAX_BANDS 5u
#define IRC_SH_MAX_COEFFS 25u /* IRC_SH_MAX_BANDS squared */

/*
 * Compile-time bounds on irc_footprint(), for static blocks: never less
 * than what irc_footprint() asks for the same numbers (make test checks a
 * grid of configs).  features: the irradiance cache's IRC_FEATURE_* bits;
 * records: max_records; s: strata M * N (4096 for an irradiance config's
 * default, 1024 for an SH config's); t: cfg.threads; b: cfg.max_batch;
 * for SH caches, bands L and channels ch.  The arithmetic is size_t's: on a
 * 32-bit target a bound above 4 GiB wraps (no static block is that large
 * there).  Each thread's slot also holds the record a lookup-or-compute
 * builds (sizeof(irc_record) or sizeof(irc_sh)).
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
 * Bytes of block a cache of max_records records needs with this config
 * (cfg->buffer and cfg->buffer_size are ignored).  1 <= max_records <=
 * IRC_MAX_RECORDS.  A config whose block would not fit a size_t is
 * IRC_ERR_CONFIG.  Thread safe.  Returns IRC_OK and writes *bytes, or a
 * negative error code on failure.
 *
 * Sizing max_records: a lookup-or-compute call stores at most one record,
 * so a frame that makes one such call a pixel never needs more records
 * than pixels (the hard bound): size max_records = pixels (what the
 * defaults make: bench/README.md, "The corpus").  When the pool fills,
 * inserts fail (IRC_ERR_FULL), lookup_or_compute returns IRC_NOT_STORED
 * and recomputes every later miss, irc_stats.not_stored counts those, and
 * inside a fill pass which records were kept depends on timing (a pass
 * never evicts): size the pool so that stays 0, or turn on
 * IRC_EVICT_CLOCK.
 */
IRC_API int irc_footprint(const irc_config *cfg, uint32_t max_records, size_t *bytes);

/*
 * Build an empty cache in cfg->buffer.  The config is copied; the cache
 * handle points into the block.  Returns IRC_OK and writes *cache, or a
 * negative error code on failure (IRC_ERR_NOMEM when the block is too small).
 */
IRC_API int irc_init(const irc_config *cfg, uint32_t max_records, irc_cache **cache);

/*
 * Re-attach a block that holds a cache made by irc_init (and filled) at
 * another address: a copy of it, a file read back, another process's
 * mapping.  cfg->buffer and cfg->buffer_size name the block (its first
 * buffer_size bytes, as copied); cfg->trace, cfg->context and cfg->port
 * are taken anew (the old process's pointers mean nothing here); every
 * other config field is the block's own and ignored here.  When the new
 * address differs from the old one modulo 64, the contents move within the
 * block to the new 64-byte boundary, so a block shared live between
 * processes should sit at addresses equal modulo 64 (pages are).  The lock
 * is initialised afresh: no other thread or process may use the cache
 * during the call.  The block must come from the same build of the library
 * on the same ABI (pointer and size_t widths, byte order): for anything
 * else use snapshots.  Nothing in the block is trusted: before any use,
 * the header must be one irc_init could have written for its stored
 * config and capacity, every record's values sane, every index link in
 * range and the index a tree whose lists hold each record at most once
 * (time linear in the block).  What no check can judge is made anew: the
 * strata's table and the scratch slots.  A block whose writer was killed
 * inside the write lock (a process sharing it, irc_join) is repaired
 * first, as the port's read_lock and write_lock returning 1 describe:
 * the record being written is dropped and the index rebuilt.  Returns
 * IRC_OK and writes
 * *cache; IRC_ERR_CONFIG when the block holds no cache or one of another
 * ABI or layout version; IRC_ERR_CORRUPT when it fails a check;
 * IRC_ERR_NOMEM when buffer_size is smaller than the cache; or a negative
 * error code (the block is then unchanged).
 */
IRC_API int irc_attach(const irc_config *cfg, irc_cache **cache);

/*
 * Experimental (see "Stability" above).
 * Share a block live between processes on one machine: one process makes
 * the cache (irc_init) in memory every process maps (a file or shm object
 * mapped MAP_SHARED); each other process joins it with irc_join, which
 * builds that process's view of it in view (view_size >= IRC_VIEW_BYTES,
 * aligned for a double; process-local memory the caller keeps until
 * irc_fini of the view).  The view holds this process's callback, context
 * and port (cfg->trace, cfg->context, cfg->port), so each process's misses
 * call its own host; records, index, counters, passes and the lock are the
 * block's, shared.  cfg->buffer is this process's mapping of the block,
 * which may sit at another address than the creator's but at the same
 * offset from a 64-byte boundary (mappings are page aligned, so any mmap
 * does); the port must be the creator's (the posix port's lock is
 * process-shared; port/none shares nothing safely).  irc_fini of a view
 * releases the view only; the creator's irc_fini, after every view's,
 * destroys the lock.  A process killed inside a record computation
 * gives its scratch slot back (irc_port owner); one killed while it holds
 * the write lock leaves the others waiting (irc_port).  The block is
 * checked as irc_attach checks it, its records and index under the read
 * lock.  Returns IRC_OK and writes *cache; IRC_ERR_CONFIG when the block
 * holds no cache of this build, sits at another offset, or the port
 * differs; IRC_ERR_CORRUPT when it fails a check; IRC_ERR_NOMEM when
 * view_size is too small or buffer_size smaller than the cache; or a
 * negative error code.  The block is never written.
 */
#define IRC_VIEW_BYTES 1024u
IRC_API int irc_join(const irc_config *cfg, void *view, size_t view_size, irc_cache **cache);

/*
 * Release what the port holds (the lock).  The block is the caller's again
 * afterwards.  Returns IRC_OK, or a negative error code on failure.
 */
IRC_API int irc_fini(irc_cache *cache);

/* ------------------------------------------------------------------------ */
/* Irradiance records.                                                       */

/* A record as the host sees it.  The cache stores a packed form: position,
 * radius and irradiance exactly; the normal to about 5e-5 rad; each
 * gradient channel to 2^-14 of its own largest component.  Read back
 * (irc_cache_record), a record has mean_dist NaN, rays and rays_used 0,
 * features = the cache's, and the gradients it does not carry zero. */
typedef struct irc_record {
    float p[3];          /* position */
    float n[3];          /* unit normal */
    float e[3];          /* RGB irradiance (see the units above) */
    float radius;        /* R_i, the record's reach along axis (the major
                            radius): the harmonic mean distance of the rays
                            that hit (escaped rays do not count: the
                            distance to what the record saw), at most
                            E/|grad E| per channel (with TRANSLATION and
                            without HESSIAN), the Hessian's radius along
                            axis (with HESSIAN, see there), then clamped to
                            [min_pixels, max_pixels] x the footprint / a
                            (irc_cache_lookup_or_compute_px) and to
                            [min_radius, max_radius]; when no ray hit,
                            max_pixels x the footprint / a, else
                            max_radius, else the smallest float */
    float minor_radius;  /* the reach across axis, in (0, radius]; 0 in a
                            record a host builds means radius (a disk).
                            Only caches with HESSIAN store ellipses;
                            others store the disk of radius */
    float axis[3];       /* unit tangent direction of radius when
                            minor_radius < radius (a host's axis need not
                            be unit length nor exactly tangent: it is
                            projected on the tangent plane); else zero */
    float mean_dist;     /* that harmonic mean before the other bounds */
    float grad_t[3][3];  /* grad_t[c] = dE_c/dp: irradiance per unit of the
                            host's length, along the surface (zero unless
                            TRANSLATION).  Stored scaled down where needed
                            so that |grad_t[c]| radius <= e[c]: a radius
                            lifted (min_radius, the host) keeps the
                            extrapolation within e (1 +- a) at the edge of
                            reach */
    float grad_r[3][3];  /* grad_r[c]: E_c(n') ~ e[c] + (n x n').grad_r[c],
                            irradiance per radian of normal rotation (zero
                            unless ROTATION) */
    float hessian[3][6]; /* hessian[c]: second derivatives of E_c in p,
                            world space, packed xx xy xz yy yz zz; only
                            moves along the surface are meaningful (zero
                            unless HESSIAN; not stored, zero when read
                            back) */
    uint64_t leak_guard; /* what the record saw near it, so that a lookup
                            from behind that geometry (a wall between two
                            rooms) does not use it: 16 sectors of 22.5
                            degrees counter-clockwise about n from t1 =
                            (1 - s n_x^2/(s + n_z), -s n_x n_y/(s + n_z),
                            -s n_x), s = +1 if n_z >= 0 else -1 (Duff et
                            al. 2017's frame of n), 4 bits each, sector k
                            in bits 4k..4k+3.  Nibble v: 0 = nothing seen
                            within reach; else the nearest hit at a
                            grazing angle (more than 45 degrees from n) in
                            the sector lies (15 - v)/15 of the reach away
                            (rounded down).  A lookup at t of the reach in
                            a direction between two sector centres is
                            rejected when t times the inverse distance,
                            interpolated linearly in angle between those
                            centres, exceeds 1 (a straight wall's inverse
                            distance is a cosine; v = 15 counts as 1/30).
                            Set by compute; a host's record may carry 0
                            (no guard).  Stored when cfg.irr.leak_guard is IRC_ON
                            (8 bytes) */
    uint32_t features;   /* which gradients are valid */
    uint32_t rays;       /* rays cast, and how many were usable: */
    uint32_t rays_used;
} irc_record;

/*
 * Sample the hemisphere around (p, n) through the trace callback and build a
 * record.  n need not be unit length.  host reaches the callback as
 * args->host.  Nothing is stored.  Waits for a scratch slot when all are in
 * use (see cfg.threads).  Returns IRC_OK, or a negative error code on
 * failure (the host's own code if trace returned one).
 */
IRC_API int irc_record_compute(irc_cache *cache, const float p[3], const float n[3],
                               irc_record *out, void *host);

/* Net visibility for hosts that cache occlusion rather than irradiance. */
typedef struct irc_occlusion {
    float visible;   /* the fraction of the hemisphere's solid angle whose rays
                        escape (first-order paper, Eq. 47, over 2 pi); every
                        hit blocks */
    float grad[3];   /* its gradient along the surface (Eq. 48), per unit of
                        length */
    uint32_t rays;   /* rays cast */
} irc_occlusion;

/*
 * Experimental (see "Stability" above).
 * Sample the hemisphere around (p, n) and return its net visibility and
 * that visibility's exact gradient from the silhouettes.  Needs
 * IRC_FEATURE_VISIBILITY in the config (IRC_ERR_UNSUPPORTED otherwise).
 * Nothing is stored; the rays count in irc_stats.rays.  Returns IRC_OK, or
 * a negative error code on failure.
 */
IRC_API int irc_occlusion_compute(irc_cache *cache, const float p[3], const float n[3],
                                  irc_occlusion *out, void *host);

/*
 * Store a record (a copy, packed).  rec->radius must be > 0 and rec->e >= 0
 * (IRC_ERR_RANGE) and every field finite.  Returns IRC_OK; IRC_ERR_FULL
 * when the pool is full and eviction is off (lookups keep working); or a
 * negative error code on failure.
 */
IRC_API int irc_cache_insert(irc_cache *cache, const irc_record *rec);

/*
 * Interpolate irradiance at (p, n): every record with Ward-Heckbert weight
 * w_i = 1 / (|p - p_i|/R_i + sqrt(1 - n.n_i)) > 1/a that is not in front of p
 * ((p - p_i).(n + n_i)/2 >= -0.05 R_i) and that its leak guard does not
 * reject (irc_record.leak_guard) is extrapolated with its gradients,
 * E_i + (p - p_i).grad_t + (n_i x n).grad_r, clamped at 0 per channel, and
 * averaged with weights w_i (w_i is capped at 1e6).  For an ellipse,
 * |p - p_i|/R_i reads sqrt(d_u^2 + |d - d_u u|^2/q^2)/R_i, d = p - p_i,
 * u the major axis, d_u = d.u, q = minor/major.  Records facing away
 * (n.n_i <= 0) never count.  rgb gets the average and *weight (optional) the
 * summed weight.  Returns IRC_OK, IRC_MISS (rgb = 0, weight = 0) when no
 * record counts, IRC_ERR_NONFINITE when the extrapolated value overflows
 * float (records near FLT_MAX), or a negative error code on failure.
 */
IRC_API int irc_cache_lookup(irc_cache *cache, const float p[3], const float n[3],
                             float rgb[3], float *weight);

/* Interpolated irradiance's first derivatives at a point, per channel c. */
typedef struct irc_gradient {
    float dp[3][3];  /* dE_c/dp: E_c changes by dp[c] . dx as p moves by dx
                        (per unit of length; along the surface) */
    float dn[3][3];  /* dE_c/dn: E_c changes by dn[c] . dm as the unit normal
                        turns by a small dm (perpendicular to n; per radian) */
} irc_gradient;

/*
 * Experimental (see "Stability" above).
 * irc_cache_lookup, and the gradient of what it interpolates: the same
 * records with the same weights, each record's extrapolation E_i + (p -
 * p_i).grad_t + (n_i x n).grad_r differentiated, dp = grad_t and dn =
 * grad_r x n_i (a channel clamped at 0 contributes zeros), averaged with
 * weights w_i.  The weights' own derivatives are left out: they change
 * where records enter and leave reach, so that part is a property of the
 * record set, not of the light (the first-order paper's image-space
 * gradient, Sec. 5, takes the light field's gradient the same way).  A
 * cache without translational (rotational) gradients answers dp (dn) = 0.
 * rgb and grad must not be NULL (IRC_ERR_NULL); an SH cache answers
 * IRC_ERR_UNSUPPORTED.  rgb, *weight, the status and the lookup counters
 * are irc_cache_lookup's; on IRC_MISS grad is zero too, and
 * IRC_ERR_NONFINITE also covers a gradient that overflows float.
 */
IRC_API int irc_cache_lookup_gradient(irc_cache *cache, const float p[3], const float n[3],
                                      float rgb[3], irc_gradient *grad, float *weight);

/*
 * Lookup; on a miss, compute a record at (p, n) (host reaches the callback),
 * insert it, and return its irradiance with *weight = 0 (a weight of 0 is
 * how the caller tells a fresh record from an interpolated value; the new
 * record's id is not reported: irc_cache_neighbours finds it).  With
 * cfg.check_visibility (the default for irradiance records) the lookup
 * first confirms its records with one ray each through the callback
 * (host reaches it, visibility_only = 1) and leaves out those out of
 * sight; a callback failure there returns as a record's would, with
 * nothing changed.  A miss that had to wait for a scratch slot looks up
 * again first, since another thread may have stored a record there
 * meanwhile.  Returns IRC_OK, IRC_NOT_STORED (value valid, pool full and
 * eviction off), or a negative error code on failure (IRC_ERR_NESTED from
 * inside this cache's own callback: see irc_trace_fn).
 */
IRC_API int irc_cache_lookup_or_compute(irc_cache *cache, const float p[3],
                                        const float n[3], float rgb[3], float *weight,
                                        void *host);

/*
 * irc_cache_lookup_or_compute with a screen-space bound: the recommended
 * call for a renderer's camera-ray hits.  footprint is the width, in the
 * host's length unit, of one pixel at p: the square root of the area a
 * pixel covers on the surface (pbrt's sqrt(|dp/dx x dp/dy|) from ray
 * differentials; for a pinhole camera about distance x pixel angle /
 * sqrt(|cos|) of the surface to the ray).  A record computed here gets a
 * reach a R in [cfg.irr.min_pixels, cfg.irr.max_pixels] x footprint (by default
 * none to 15 pixels) before the world bounds [min_radius, max_radius] (its
 * gradient is then limited to that radius, as always); so an open scene
 * needs no max_radius, and the records a frame makes are bounded by its
 * pixels.  footprint 0 is the plain call (no pixel bound).  Points near
 * finer geometry get their own estimate first (cfg.irr.detail_pixels).
 * A host that computes with irc_record_compute and inserts itself sets
 * the radius (and minor_radius) of the record the same way before
 * irc_cache_insert.
 * Returns as irc_cache_lookup_or_compute; IRC_ERR_RANGE (nothing done)
 * when footprint is negative, IRC_ERR_NONFINITE when it is not finite.
 */
IRC_API int irc_cache_lookup_or_compute_px(irc_cache *cache, const float p[3],
                                           const float n[3], float footprint, float rgb[3],
                                           float *weight, void *host);

/*
 * The footprint the _px call wants, for a pinhole camera: the width of one
 * pixel on the surface at p (normal n, either side) seen from eye.
 * forward: the camera's viewing axis (any length); pixel_angle: a pixel's
 * width on the image plane at distance 1 along it (2 tan(fov_y / 2) /
 * height in pixels).  footprint = pixel_angle |p - eye| (d.f)^(3/2) /
 * sqrt(max(|d.n|, 0.05)), d the unit direction from eye to p, f forward's:
 * the square root of the surface area the pixel covers, with its solid
 * angle shrinking off axis as (d.f)^3 and its stretch at grazing angles
 * held at 1/sqrt(0.05).  A host with ray differentials may pass its own
 * sqrt(|dp/dx x dp/dy|) instead.  Returns IRC_OK, IRC_ERR_NULL,
 * IRC_ERR_NONFINITE, IRC_ERR_NORMAL (n zero or not finite), or
 * IRC_ERR_RANGE (pixel_angle <= 0, forward zero, p at eye or behind it);
 * *footprint is written only on IRC_OK.  Thread safe; needs no cache.
 */
IRC_API int irc_pixel_footprint(const float eye[3], const float forward[3], float pixel_angle,
                                const float p[3], const float n[3], float *footprint);

/*
 * Experimental (see "Stability" above).
 * The ids (slot numbers) of the records a lookup at (p, n) would use, in no
 * particular order: up to cap of them in ids, and how many there are in
 * *count (which may exceed cap).  Either kind of cache (n NULL in an SH
 * cache: free points).  For debugging and visualisation.  An id stays a
 * record's until irc_pass_end, irc_merge or irc_cache_clear (which
 * renumber or remove records) or its eviction.  Returns IRC_OK,
 * or a negative error code on failure.
 */
IRC_API int irc_cache_neighbours(irc_cache *cache, const float p[3], const float n[3],
                                 uint32_t *ids, uint32_t cap, uint32_t *count);

/*
 * Read the record in slot id (0 <= id < capacity).  Returns IRC_OK,
 * IRC_MISS when the slot is empty, IRC_ERR_RANGE past the capacity, or a
 * negative error code on failure.
 */
IRC_API int irc_cache_record(irc_cache *cache, uint32_t id, irc_record *out);

/* Remove every record, of either kind (the counters in irc_stats are kept).
 * Not concurrent with other calls.  Returns IRC_OK, or a negative error
 * code on failure. */
IRC_API int irc_cache_clear(irc_cache *cache);



/* ------------------------------------------------------------------------ */
/* Snapshots: a cache's records as portable bytes (docs/FORMAT.md defines the */
/* format byte by byte), to save a cache and load it in another process.   */

/* The format version this build writes and the only one it reads (bytes
 * 4-5 of a snapshot); another gets IRC_ERR_VERSION. */
#define IRC_SNAPSHOT_VERSION 1u

/*
 * A writer for streamed snapshots: takes count bytes; returns 0, or a
 * nonzero value to stop (a negative one is passed through, a positive one
 * becomes IRC_ERR_CALLBACK).  Called with the cache's read lock held: it
 * must not call the cache's writers.
 */
typedef int (*irc_write_fn)(void *context, const void *bytes, size_t count);

/* The bytes irc_snapshot_write would write now (48 + records x record
 * bytes + 4).  Returns IRC_OK, IRC_ERR_NOMEM when that exceeds size_t, or
 * a negative error code. */
IRC_API int irc_snapshot_size(irc_cache *cache, size_t *bytes);

/*
 * Writes every stored record, with a header carrying the host's 64-bit
 * scene fingerprint, either into buffer (write NULL; size at least
 * irc_snapshot_size, else IRC_ERR_NOMEM and nothing written) or through
 * write(context, ...) in pieces (buffer ignored).  *written (optional)
 * gets the bytes produced.  The cache is not changed.  Returns IRC_OK or a
 * negative error code.
 */
IRC_API int irc_snapshot_write(irc_cache *cache, uint64_t fingerprint, void *buffer,
                               size_t size, irc_write_fn write, void *context,
                               size_t *written);

/*
 * Replaces the cache's records with a snapshot's.  Checks everything before
 * it touches the cache: IRC_ERR_TRUNCATED, IRC_ERR_CORRUPT (bad magic,
 * either checksum, trailing bytes, a record value no cache makes),
 * IRC_ERR_VERSION, IRC_ERR_FINGERPRINT (not the fingerprint given),
 * IRC_ERR_MISMATCH (kind, features, record size, SH bands or channels,
 * accuracy or strata differ from the cache's config), IRC_ERR_FULL (more
 * records than the cache holds); on any of them the cache is as it was.
 * Lookups then answer as the written cache did, bit for bit.  Like
 * irc_cache_clear, not concurrently with other calls on the cache.
 * Returns IRC_OK or a negative error code.
 */
IRC_API int irc_snapshot_read(irc_cache *cache, uint64_t fingerprint, const void *data,
                              size_t size);

/*
 * Adds a snapshot's records to the cache's, checked as irc_snapshot_read
 * checks (the same statuses, the cache unchanged on any of them;
 * IRC_ERR_FULL when the cache's records and the snapshot's together,
 * duplicates counted, exceed its capacity).  The result does not depend
 * on the order of merges: the records are put in one canonical order
 * (field by field in the format's order, each field as an unsigned
 * integer), records equal in every byte are kept once, the index is
 * rebuilt from that order, and the records are then renumbered in the
 * index's order (as at irc_pass_end); so merging a set of snapshots into an empty
 * cache in any order gives caches whose snapshots are byte-identical, and
 * merging one twice adds nothing.  Records from different snapshots that
 * differ in any bit are all kept (two tiles that computed a record at the
 * same point with the same config agree bit for bit: a record is a pure
 * function of its query).  Record ids change; neighbour clamping is not
 * applied.  Like irc_cache_clear, not concurrently with other calls.
 * Returns IRC_OK or a negative error code.
 */
IRC_API int irc_merge(irc_cache *cache, uint64_t fingerprint, const void *data, size_t size);

/* ------------------------------------------------------------------------ */
/* Fill passes: the same records whatever the threads and their timing.    */

/*
 * Opens a fill pass.  Until irc_pass_end, every lookup (of any call, on any
 * thread) sees the cache as it was here, frozen: records computed by
 * lookup_or_compute misses and records given to insert are kept aside in
 * free slots, not indexed, and the miss still returns the new record's
 * value (weight 0).  So a pass's answers and the records it adds depend
 * only on the cache it began with and on the set of queries made, never on
 * their order or on how many threads made them (a record is a pure
 * function of its query, the config and the host's callback).  A pass
 * never evicts: once the free slots are taken, further records of the pass
 * are not stored (IRC_NOT_STORED, IRC_ERR_FULL from insert, counted in
 * irc_stats.not_stored), and which ones were kept then depends on timing:
 * size the pool so that does not happen.  Within a pass, two misses close
 * together both compute a record where one might have served: a pass
 * should hold no two queries within a record's reach of each other.  The
 * rule the demo and the examples follow: pixels P apart in P^2 passes,
 * coarse to fine, P the power of two nearest the image width / 24 in [8,
 * 32] (8 up to 288 pixels, 16 up to 576, then 32), never from the thread
 * count (all pixels at strides 8, 4, 2, 1 in 4 passes made 1.5x the
 * records of a free fill, docs/DESIGN.md, "Fill passes").  Lookups in a pass take
 * no lock (nothing they read can change before irc_pass_end).  Not
 * concurrent with other calls on the cache.  Returns IRC_OK, IRC_ERR_STATE when a pass is
 * already open, or a negative error code.
 */
IRC_API int irc_pass_begin(irc_cache *cache);

/*
 * Closes the open pass: its records, sorted in merge's canonical order
 * (see irc_merge) with exact duplicates kept once, are inserted one by one
 * in that order (neighbour clamping, when on, applies in that order too)
 * and become visible; the index is then built anew in an order that
 * spreads its nodes over the scene (the same for the same records).  Then every record of the cache is renumbered in the
 * order lookups visit the index (depth first), which puts the records a
 * lookup reads side by side in memory: lookups answer bit for bit as
 * before, faster (bench/README.md, "Speed and memory"), but record ids change, and
 * the end of a pass costs a move of every record (a pass with no records,
 * begun and ended at once, does only that, for a cache filled without
 * passes).  *added (optional) gets how many.  Not concurrent
 * with other calls on the cache: every thread of the pass must be done.
 * Returns IRC_OK, IRC_ERR_STATE when no pass is open, or a negative error
 * code.  While a pass is open, irc_cache_clear, irc_snapshot_read and
 * irc_merge return IRC_ERR_STATE and change nothing.
 */
IRC_API int irc_pass_end(irc_cache *cache, uint32_t *added);
/* ------------------------------------------------------------------------ */
/* SH records (IRC_FEATURE_SH).                                              */
/*
 * An SH cache stores, per record, the real spherical-harmonic coefficients
 * c_i = integral of y_i(w) L(w) dw of the incident radiance, bands 0..L-1
 * (index l*l + l + m, Condon-Shortley phase), per channel, and with
 * IRC_FEATURE_SH_GRADIENT their translational gradients, so that
 * c_i(p + d) ~ c_i + grad c_i . d (SH-gradient paper, Eq. 14).  From the
 * coefficients, irc_sh_irradiance and irc_sh_glossy shade any normal.
 *
 * Two kinds of record:
 *   - surface records (n given): the hemisphere around n is sampled, the
 *     radiance below it counts as 0; lookups use the Ward-Heckbert weight of
 *     irc_cache_lookup and see surface records only;
 *   - free-point records (n NULL): the whole sphere is sampled (two
 *     hemispheres, twice the rays), as at an object's centre; lookups with
 *     n NULL see free-point records only, accept those with
 *     |p - p_j| < accuracy * R_j and weigh them (R_j/|p - p_j|)^b, b =
 *     cfg.sh.power (Eq. 16, made scale-free by R_j; capped at 1e6).
 * Strata are M x N of equal solid angle (cos theta uniform, not cosine
 * weighted): 2 pi/(M N) steradians each.  R_j is the harmonic mean hit
 * distance, clamped by |c_0|/|grad c_0| per channel (with gradients) and by
 * [min_radius, max_radius].
 *
 * Bytes per record: 32 + 4 L^2 channels, + 12 L^2 channels with gradients
 * (L = 3, RGB: 140, with gradients 464).  The irradiance calls
 * (irc_record_compute, irc_cache_insert, irc_cache_lookup,
 * irc_cache_lookup_gradient, irc_cache_lookup_or_compute, irc_cache_record,
 * irc_occlusion_compute) return
 * IRC_ERR_UNSUPPORTED on an SH cache, and the irc_sh_* calls on any other.
 */
typedef struct irc_sh {
    float p[3];            /* position (a lookup: the query's) */
    float n[3];            /* unit normal; 0, 0, 0 for a free point */
    float radius;          /* R_j (a lookup: 0) */
    float e[3];            /* irradiance about n integrated from the samples
                              themselves, not band limited (0 for a free
                              point; a lookup: the records' weighted mean) */
    uint32_t bands;        /* L */
    uint32_t channels;     /* 1 or 3 */
    float c[3][IRC_SH_MAX_COEFFS];       /* c[ch][i], i < L*L, ch < channels */
    float grad[3][IRC_SH_MAX_COEFFS][3]; /* d c[ch][i] / dp, all three
                                            components (a surface record's
                                            along n includes what crosses
                                            its horizon); zero without
                                            IRC_FEATURE_SH_GRADIENT; a
                                            lookup: the weighted mean */
    uint32_t features;     /* cfg.features */
    uint32_t rays;         /* rays cast, and how many were usable */
    uint32_t rays_used;
} irc_sh;

/*
 * Sample around p through the trace callback and build an SH record: the
 * hemisphere around n, or with n NULL the whole sphere.  Nothing is stored.
 * Returns IRC_OK, or a negative error code on failure (IRC_ERR_NOSAMPLES
 * when fewer than half the rays were usable, the host's own code if trace
 * returned one).  host reaches the callback as args->host (whose n is 0, 0, 0
 * for a free point).
 */
IRC_API int irc_sh_compute(irc_cache *cache, const float p[3], const float n[3],
                           irc_sh *out, void *host);

/*
 * Store an SH record (a copy).  rec->bands and rec->channels must match the
 * cache's config (IRC_ERR_RANGE), rec->radius > 0 and rec->e >= 0
 * (IRC_ERR_RANGE), every used field finite.  Returns IRC_OK, IRC_ERR_FULL,
 * or a negative error code.
 */
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

/* Lookup; on a miss, compute, insert and return the new record (*weight =
 * 0).  Returns IRC_OK, IRC_NOT_STORED (pool full, eviction off), or a
 * negative error code. */
IRC_API int irc_sh_lookup_or_compute(irc_cache *cache, const float p[3],
                                     const float n[3], irc_sh *out, float *weight,
                                     void *host);

/* Read the SH record in slot id.  Coefficients, gradients, position,
 * radius and e come back exactly; n to about 5e-5 rad (0, 0, 0 for a free
 * point); bands, channels and features are the cache's; rays and
 * rays_used are 0 (not stored).  Returns IRC_OK, IRC_MISS (empty slot),
 * IRC_ERR_RANGE, or a negative error code. */
IRC_API int irc_sh_record(irc_cache *cache, uint32_t id, irc_sh *out);

/*
 * Irradiance about the unit-ish normal n from sh's coefficients: the
 * clamped-cosine convolution (Ramamoorthi-Hanrahan 2001), sum over l, m of
 * A_l c_lm y_lm(n) with A_0 = pi, A_1 = 2 pi/3, A_2 = pi/4, A_3 = 0,
 * A_4 = -pi/24.  Exact for radiance of band < L; the band-limit error of
 * L = 3 is about 1% average for smooth skies (docs/DESIGN.md, "SH records").  rgb gets
 * sh->channels values (one channel is copied to all three).  Returns IRC_OK,
 * IRC_ERR_NULL, IRC_ERR_NORMAL, or IRC_ERR_RANGE (bands or channels out of
 * range).
 */
IRC_API int irc_sh_irradiance(const irc_sh *sh, const float n[3], float rgb[3]);

/*
 * A Phong-like lobe: integral of L(w) max(0, w.r)^s dw about the unit-ish
 * axis r (a mirror direction), as the zonal convolution sum A_l(s) c_lm
 * y_lm(r), A_l(s) = 2 pi integral_0^1 z^s P_l(z) dz.  s = 1 is the
 * irradiance; multiply by your BRDF's normalisation, e.g. (s + 2)/(2 pi)
 * for normalised Phong.  L bands resolve lobes up to s of about L^2; sharper
 * lobes come out blurred.  0 <= s <= 1e4.  Returns as irc_sh_irradiance
 * (IRC_ERR_RANGE also for s out of range).
 */
IRC_API int irc_sh_glossy(const irc_sh *sh, const float r[3], float s, float rgb[3]);

/*
 * Experimental (see "Stability" above).
 * The band-limited radiance arriving from the unit-ish direction w, sum
 * over l, m of c_lm y_lm(w): what a host integrates its own BRDF against
 * (e.g. over samples of a lobe whose product with the cosine is not
 * zonal).  Returns as irc_sh_irradiance.
 */
IRC_API int irc_sh_radiance(const irc_sh *sh, const float w[3], float rgb[3]);

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
    uint64_t rays;           /* rays cast through the callback: records',
                                occlusion's, confirming rays
                                (cfg.check_visibility) and per-pixel
                                detail (cfg.irr.detail_pixels: probes
                                and estimates) */
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

/* Counters and sizes.  Thread safe; the counters are read one by one, so a
 * concurrent call may be half counted.  Returns IRC_OK, or a negative
 * error code on failure. */
IRC_API int irc_cache_stats(irc_cache *cache, irc_stats *out);

#ifdef __cplusplus
}
#endif
#endif /* IRRCACHE_H */
