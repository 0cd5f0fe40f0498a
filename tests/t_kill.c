/* t_kill.c -- processes killed (SIGKILL) inside calls on a cache they
 * share with others (irc_join): at a record computation, holding the read
 * lock, holding the write lock in the middle of a write, and at random
 * points of fills and passes.  Every time, a survivor fills the cache
 * within 10 s, every record it then holds equals a fresh computation at
 * its query and is found by a lookup there, and the index passes the
 * checks irc_attach makes. */
#define IRC_EXPERIMENTAL /* irc_join (irrcache.h) */
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include "irrcache.h"
#include "block/cache.h" /* internals on purpose: a writer stopped mid-write */
#include "scenes.h"
#include "share.h"
#include "test.h"
#include "block/torn.h"
#include "index/verify.h"
#include "store/lock.h"

/* A block in a file mapped shared (the file itself unlinked at once),
 * then a page for the tests' own flags; *mapped: the bytes to unmap. */
static void *map_block(irc_config *cfg, uint32_t records, size_t *mapped)
{
    char path[] = "/tmp/irc_kill_XXXXXX";
    size_t bytes = 0;
    void *map = MAP_FAILED;
    int fd = mkstemp(path);
    if (fd < 0)
        return NULL;
    unlink(path);
    if (irc_footprint(cfg, records, &bytes) == IRC_OK) {
        *mapped = (bytes + 4095) / 4096 * 4096 + 4096;
        if (ftruncate(fd, (off_t)*mapped) == 0)
            map = mmap(NULL, *mapped, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    }
    close(fd);
    cfg->buffer = map == MAP_FAILED ? NULL : map;
    cfg->buffer_size = bytes;
    return cfg->buffer;
}

/* Waits up to 10 s for pid; kills it after that.  1 if it exited with 0. */
static int finished(pid_t pid)
{
    int status = -1, i;
    for (i = 0; i < 10000; i++) {
        if (waitpid(pid, &status, WNOHANG) == pid)
            return WIFEXITED(status) && WEXITSTATUS(status) == 0;
        share_nap();
    }
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return 0;
}

/* The survivor, in a child of its own (a hang is a failure, not the end
 * of the suite): ends a pass the victim left open, fills the lattice on
 * the creator's handle, and checks every record and the index.  1 if it
 * finished in time with nothing wrong. */
static int survivor_checks(irc_cache *c, uint32_t min_records)
{
    irc_stats st;
    int bad, end = irc_pass_end(c, NULL);
    bad = end != IRC_OK && end != IRC_ERR_STATE;
    bad += share_fill_half(c, 0) + share_fill_half(c, 1) + share_verify_all(c);
    bad += !irc__block_sane(c);
    bad += irc_cache_stats(c, &st) != IRC_OK || st.records < min_records;
    return bad;
}

static int survives(irc_cache *c, uint32_t min_records)
{
    pid_t pid = fork();
    if (pid == 0) {
        const int bad = survivor_checks(c, min_records);
        _exit(bad > 99 ? 99 : bad);
    }
    return pid > 0 && finished(pid);
}

static irc_config share_config(tscene *s)
{
    irc_config cfg = scene_config(s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    cfg.max_radius = 1.0f;
    cfg.threads = 1;
    return cfg;
}

/* A joined process killed inside a record computation keeps a scratch
 * slot; with one slot, every other process's next miss would wait for it
 * forever.  The port's owner check hands the slot over.  The victim kills
 * itself from its trace callback at several points of its first records. */
typedef struct suicidal {
    tscene s;
    unsigned long calls, die_at;
} suicidal;

static int suicidal_trace(const irc_trace_args *a)
{
    irc_trace_args b = *a;
    suicidal *k = (suicidal *)a->context;
    if (++k->calls == k->die_at)
        kill(getpid(), SIGKILL);
    b.context = &k->s;
    return scene_trace(&b);
}

TEST(test_share_killed)
{
    static const unsigned long die_at[6] = {1, 128, 256, 257, 400, 700};
    suicidal host;
    irc_config cfg;
    irc_cache *c;
    size_t mapped = 0;
    int t;
    scene_sphere_plane(&host.s);
    host.calls = host.die_at = 0;
    cfg = share_config(&host.s);
    cfg.trace = suicidal_trace;
    cfg.context = &host;
    CHECK(map_block(&cfg, 4096, &mapped) != NULL, "mapped block");
    if (!cfg.buffer)
        return;
    for (t = 0; t < 6; t++) {
        pid_t victim;
        int status = -1;
        if (irc_init(&cfg, 4096, &c) != IRC_OK) {
            CHECK(0, "init");
            break;
        }
        victim = fork();
        if (victim == 0) {
            static double view[IRC_VIEW_BYTES / sizeof(double)];
            irc_cache *v;
            host.die_at = die_at[t];
            if (irc_join(&cfg, view, sizeof view, &v) != IRC_OK)
                _exit(100);
            share_fill_half(v, 1);
            _exit(101); /* it should have died */
        }
        waitpid(victim, &status, 0);
        CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL, "trial %d: the victim %s", t,
              WIFEXITED(status) ? "exited" : "did not die by SIGKILL");
        CHECK(survives(c, 100), "trial %d (victim killed at ray %lu): the survivor hung or found "
                                "bad records", t, die_at[t]);
        irc_fini(c);
    }
    munmap(cfg.buffer, mapped);
}

/* Holding a lock, the victim stops where an insert would be, by hand:
 *   0: the read lock (a lookup's), nothing written;
 *   1: the write lock, nothing written yet;
 *   2: the write lock, record 3 half overwritten with another's position,
 *      as an eviction that packs into slot 3 leaves it (irc__mark names
 *      the slot first);
 *   3: as 2, recovered by irc_attach of the block at rest instead.
 * With a pthread rwlock every survivor of 0-2 hung.  After 2 and 3 the
 * torn record is gone and every other is whole. */
static void stop_in_lock(irc_cache *c, int how)
{
    if (how == 0) {
        c->port->read_lock(irc__lock(c));
    } else {
        irc__write_lock(c);
        if (how >= 2) {
            irc__mark(c, 3, IRC__NIL);
            irc__rec_at(c, 3)->p[0] += 0.5f;
            irc__rec_at(c, 3)->e[0] *= 0.5f;
        }
    }
    kill(getpid(), SIGKILL);
}

/* The posix port asks the system for its process id once and keeps it:
 * a child of fork() must not go on counting itself in under its parent's
 * id, or its death holding the read lock would go unseen (a survivor that
 * thought the count its own would wait on it forever).  The parent asks
 * first, so the id is kept when it forks; the child and a grandchild must
 * each see their own. */
TEST(test_port_owner_after_fork)
{
    int status = -1;
    pid_t pid;
    CHECK(irc_port_posix.owner() == (uint64_t)getpid(), "the parent's owner token");
    pid = fork();
    if (pid == 0) {
        pid_t grand;
        int bad = irc_port_posix.owner() != (uint64_t)getpid();
        grand = fork();
        if (grand == 0)
            _exit(irc_port_posix.owner() != (uint64_t)getpid());
        bad += grand < 0 || waitpid(grand, &status, 0) != grand || !WIFEXITED(status) ||
               WEXITSTATUS(status) != 0;
        _exit(bad);
    }
    CHECK(pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) &&
              WEXITSTATUS(status) == 0,
          "a forked child or grandchild took its parent's owner token");
    CHECK(irc_port_posix.owner() == (uint64_t)getpid(), "the parent's token after the fork");
}

TEST(test_share_killed_in_lock)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_stats before, after;
    size_t mapped = 0;
    int how, k;
    scene_sphere_plane(&s);
    cfg = share_config(&s);
    CHECK(map_block(&cfg, 4096, &mapped) != NULL, "mapped block");
    if (!cfg.buffer)
        return;
    for (how = 0; how < 4; how++) {
        int status = -1;
        pid_t pid;
        CHECK(irc_init(&cfg, 4096, &c) == IRC_OK, "init");
        for (k = 0; k < 30; k++) {
            const float p[3] = {0.2f * (float)k - 3.0f, 0.0f, 0.0f}, n[3] = {0, 0, 1};
            float rgb[3], w;
            irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
        }
        CHECK(irc_cache_stats(c, &before) == IRC_OK && before.records > 5, "records");
        pid = fork();
        if (pid == 0)
            stop_in_lock(c, how);
        waitpid(pid, &status, 0);
        CHECK(WIFSIGNALED(status), "the victim died");
        if (how == 3) {
            CHECK(irc_attach(&cfg, &c) == IRC_OK && irc_cache_stats(c, &after) == IRC_OK &&
                      after.records == before.records - 1 && share_verify_all(c) == 0,
                  "attach of a block left mid-write: %u records of %u, or one not whole",
                  (unsigned)after.records, (unsigned)before.records);
        } else {
            CHECK(survives(c, 100), "%d: the survivor hung or found bad records", how);
        }
        irc_fini(c);
    }
    munmap(cfg.buffer, mapped);
}

/* The victim of test_share_zombie: dies holding the read lock (0), the
 * write lock (1) or, joined with one slot, its scratch slot (2). */
static void zombie_victim(irc_cache *c, irc_config cfg, suicidal *host, int how)
{
    static double view[IRC_VIEW_BYTES / sizeof(double)];
    irc_cache *v;
    if (how < 2)
        stop_in_lock(c, how);
    host->calls = 0;
    host->die_at = 1;
    cfg.trace = suicidal_trace;
    cfg.context = host;
    if (irc_join(&cfg, view, sizeof view, &v) == IRC_OK)
        share_fill_half(v, 1);
    _exit(100); /* it should have died */
}

/* A dead victim not yet reaped (a zombie) still answers kill(pid, 0): the
 * waiter must see it gone all the same.  The victim dies in the lock or
 * in its slot, and is left unreaped (waitid with WNOWAIT) while its
 * parent (as_parent: the process that alone could reap it, asked by
 * waitid) or a sibling (asked by /proc on Linux) goes on with the cache.
 * Without the check every one of these hung. */
static int zombie_trial(irc_config cfg, suicidal *host, int how, int as_parent)
{
    irc_cache *c;
    siginfo_t si;
    int k, ok, status = -1;
    pid_t pid, victim;
    if (irc_init(&cfg, 4096, &c) != IRC_OK)
        return 0;
    for (k = 0; k < 30; k++) {
        const float p[3] = {0.2f * (float)k - 3.0f, 0.0f, 0.0f}, n[3] = {0, 0, 1};
        float rgb[3], w;
        irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
    }
    if (as_parent) {
        pid = fork();
        if (pid == 0) {
            victim = fork();
            if (victim == 0)
                zombie_victim(c, cfg, host, how);
            if (victim < 0 || waitid(P_PID, (id_t)victim, &si, WEXITED | WNOWAIT) != 0)
                _exit(98);
            _exit(survivor_checks(c, 100) ? 1 : 0);
        }
        ok = pid > 0 && finished(pid);
    } else {
        victim = fork();
        if (victim == 0)
            zombie_victim(c, cfg, host, how);
        ok = victim > 0 && waitid(P_PID, (id_t)victim, &si, WEXITED | WNOWAIT) == 0 &&
             survives(c, 100);
        if (victim > 0)
            waitpid(victim, &status, 0);
    }
    irc_fini(c);
    return ok;
}

TEST(test_share_zombie)
{
    static const char *what[3] = {"the read lock", "the write lock", "its scratch slot"};
    suicidal host;
    irc_config cfg;
    size_t mapped = 0;
    int how, role;
    scene_sphere_plane(&host.s);
    host.calls = host.die_at = 0;
    cfg = share_config(&host.s);
    CHECK(map_block(&cfg, 4096, &mapped) != NULL, "mapped block");
    if (!cfg.buffer)
        return;
    for (how = 0; how < 3; how++)
        for (role = 1; role >= 0; role--)
            CHECK(zombie_trial(cfg, &host, how, role),
                  "a victim dead in %s, not yet reaped: its %s hung or found bad records",
                  what[how], role ? "parent" : "sibling");
    munmap(cfg.buffer, mapped);
}

/* A port that kills its process at its die_at-th call (any call: loads of
 * a lookup, a slot's claim, the write lock's taking, a slot's marking
 * inside it...), after the call for the locks, so that the victim dies
 * holding them.  Same name as irc_port_posix: it joins that block. */
static unsigned long port_calls, port_die_at;
static int port_held;   /* 1: the read lock, 2: the write lock */
static int port_count = -1; /* count only calls made holding this (-1: all) */
static int *port_died;  /* shared with the parent: port_held at death */

static void tick(void)
{
    if ((port_count < 0 || port_held == port_count) && ++port_calls == port_die_at) {
        if (port_died)
            *port_died = port_held;
        kill(getpid(), SIGKILL);
    }
}
static int k_read_lock(void *l)
{
    int st = irc_port_posix.read_lock(l);
    port_held = st == 0;
    tick();
    return st;
}
static void k_read_unlock(void *l) { tick(); port_held = 0; irc_port_posix.read_unlock(l); }
static int k_write_lock(void *l)
{
    int st = irc_port_posix.write_lock(l);
    port_held = st >= 0 ? 2 : 0;
    tick();
    return st;
}
static void k_write_unlock(void *l) { tick(); port_held = 0; irc_port_posix.write_unlock(l); }
static uint64_t k_load(const uint64_t *o) { tick(); return irc_port_posix.load(o); }
static void k_store(uint64_t *o, uint64_t v) { tick(); irc_port_posix.store(o, v); }
static uint64_t k_add(uint64_t *o, uint64_t v) { tick(); return irc_port_posix.fetch_add(o, v); }
static uint64_t k_or(uint64_t *o, uint64_t v) { tick(); return irc_port_posix.fetch_or(o, v); }
static int k_cas(uint64_t *o, uint64_t e, uint64_t d)
{
    int st = irc_port_posix.cas(o, e, d);
    tick();
    return st;
}

static irc_port killing_port(void)
{
    irc_port p = irc_port_posix;
    p.read_lock = k_read_lock;
    p.read_unlock = k_read_unlock;
    p.write_lock = k_write_lock;
    p.write_unlock = k_write_unlock;
    p.load = k_load;
    p.store = k_store;
    p.fetch_add = k_add;
    p.fetch_or = k_or;
    p.cas = k_cas;
    return p;
}

/* The victim: a fill of half the lattice, in two passes on odd trials
 * (each ending with its records joining the index and a compaction, all
 * under the write lock), with clamping (which writes neighbours' radii)
 * and CLOCK eviction in a pool too small for the lattice. */
static unsigned char *merge_snap; /* mode 2's snapshot: half 1 computed */
static size_t merge_bytes;
static int *in_merge; /* shared with the parent: 1 while the victim merges */

/* mode 0: fills the lattice; 1: in two passes; 2: merges a snapshot of
 * half 1 into it. */
static void victim_fill(irc_cache *v, int mode)
{
    int round;
    if (mode == 2) {
        if (in_merge)
            *in_merge = 1;
        irc_merge(v, 7, merge_snap, merge_bytes);
        if (in_merge)
            *in_merge = 0;
        return;
    }
    for (round = 0; round < 2; round++) {
        if (mode)
            irc_pass_begin(v);
        share_fill_half(v, round);
        if (mode)
            irc_pass_end(v, NULL);
    }
}

/* merge_snap: half 1 computed in a cache of the trials' config. */
static int make_merge_snap(irc_config cfg)
{
    irc_cache *c;
    size_t bytes = 0;
    int ok = 0;
    if (irc_footprint(&cfg, 300, &bytes) != IRC_OK || !(cfg.buffer = malloc(bytes)))
        return 0;
    cfg.buffer_size = bytes;
    if (irc_init(&cfg, 300, &c) == IRC_OK) {
        ok = share_fill_half(c, 1) == 0 && irc_snapshot_size(c, &merge_bytes) == IRC_OK &&
             (merge_snap = malloc(merge_bytes)) != NULL &&
             irc_snapshot_write(c, 7, merge_snap, merge_bytes, NULL, NULL, NULL) == IRC_OK;
        irc_fini(c);
    }
    free(cfg.buffer);
    return ok;
}

/* Port calls of one whole victim fill made holding `held` (0 none, 1 the
 * read lock, 2 the write lock): the range die_at is drawn from. */
static unsigned long calls_of_fill(irc_config cfg, int mode, int held)
{
    irc_port kp = killing_port();
    irc_cache *c;
    size_t bytes = 0;
    cfg.port = &kp;
    port_calls = port_die_at = 0;
    port_count = held;
    if (irc_footprint(&cfg, 300, &bytes) != IRC_OK || !(cfg.buffer = malloc(bytes)))
        return 0;
    cfg.buffer_size = bytes;
    if (irc_init(&cfg, 300, &c) == IRC_OK) {
        victim_fill(c, mode);
        irc_fini(c);
    }
    free(cfg.buffer);
    port_count = -1;
    return port_calls;
}

static const char *const fill_modes[3] = {"no pass", "passes", "a merge"};

TEST(test_share_killed_random)
{
    /* IRC_TEST_KILLS=N: N trials (a long run; TESTING.md) */
    const char *env = getenv("IRC_TEST_KILLS");
    const int trials = env && atoi(env) >= 3 ? atoi(env) : irc_t_quick ? 18 : 72;
    tscene s;
    irc_config cfg;
    irc_cache *c;
    size_t mapped = 0;
    unsigned long total[3][3];
    unsigned long long seed = 12345;
    int t, h, m, died = 0, held[3] = {0, 0, 0}, *where, few = 0, by_mode[3] = {0, 0, 0};
    int merging = 0, zombies = 0, killed;
    scene_sphere_plane(&s);
    cfg = share_config(&s);
    cfg.evict = IRC_EVICT_CLOCK;
    cfg.clamp_neighbours = IRC_ON;
    CHECK(make_merge_snap(cfg), "the merge's snapshot");
    /* Each trial dies at a random call among those made in one state (no
     * lock, the read lock, the write lock, in turn), so that every state
     * is hit however few of a fill's calls it makes.  Lookups inside a
     * pass take no lock: a pass's trials die outside it or in the write
     * lock.  A third of the victims merge a snapshot (the merge holds the
     * write lock while it rebuilds the index and renumbers, and makes
     * every port call in it) and die in it. */
    for (h = 0; h < 3; h++)
        for (m = 0; m < 3; m++) {
            total[m][h] = calls_of_fill(cfg, m, h);
            few |= total[m][h] < 100 && !(m == 1 && h == 1) && !(m == 2 && h != 2);
        }
    CHECK(!few, "port calls of a fill: %lu %lu %lu, in passes %lu %lu %lu, merging %lu %lu %lu",
          total[0][0], total[0][1], total[0][2], total[1][0], total[1][1], total[1][2],
          total[2][0], total[2][1], total[2][2]);
    CHECK(map_block(&cfg, 300, &mapped) != NULL, "mapped block");
    if (!cfg.buffer || few || !merge_snap)
        return;
    where = (int *)(void *)((unsigned char *)cfg.buffer + mapped - 4096);
    in_merge = where + 1;
    for (t = 0; t < trials; t++) {
        pid_t victim;
        int status = -1;
        unsigned long at;
        const int mode = t % 3, round = t / 3;
        /* a merge makes every port call in the write lock */
        const int state = mode == 2 ? 2 : mode == 1 && round % 3 == 1 ? 0 : round % 3;
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        at = 1 + (unsigned long)(seed >> 33) % total[mode][state];
        if (irc_init(&cfg, 300, &c) != IRC_OK) {
            CHECK(0, "init");
            break;
        }
        victim = fork();
        if (victim == 0) {
            static double view[IRC_VIEW_BYTES / sizeof(double)];
            irc_port kp = killing_port();
            irc_config vc = cfg;
            irc_cache *v;
            vc.port = &kp;
            port_calls = 0;
            port_die_at = at;
            port_count = state;
            port_died = where;
            if (irc_join(&vc, view, sizeof view, &v) != IRC_OK)
                _exit(100);
            victim_fill(v, mode);
            _exit(101);
        }
        *where = -1;
        *in_merge = 0;
        if (round & 1) {
            /* left unreaped (a zombie) while the survivor runs */
            siginfo_t si;
            memset(&si, 0, sizeof si);
            killed = waitid(P_PID, (id_t)victim, &si, WEXITED | WNOWAIT) == 0 &&
                     si.si_code == CLD_KILLED && si.si_status == SIGKILL;
            zombies += killed;
        } else {
            waitpid(victim, &status, 0);
            killed = WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
        }
        if (killed && *where >= 0) {
            died++;
            by_mode[mode]++;
            merging += *in_merge;
            held[*where]++;
        }
        CHECK(survives(c, 150), "trial %d (%s, killed at port call %lu of %lu holding %d): the "
                                "survivor hung or found bad records", t, fill_modes[mode], at,
              total[mode][state], state);
        if (round & 1)
            waitpid(victim, &status, 0);
        irc_fini(c);
    }
    /* a join's calls come before the fill's: a late die_at may miss */
    CHECK(died >= trials * 3 / 4 && held[0] >= 1 && held[2] >= 1 && held[1] >= 1 &&
              by_mode[2] >= trials / 4 && merging >= trials / 4,
          "%d of %d victims died (%d of the merging ones inside irc_merge), %d holding no lock, "
          "%d the read lock, %d the write lock", died, trials, merging, held[0], held[1],
          held[2]);
    printf("  %d victims of %d died (%d filling, %d in passes, %d merging, %d of them inside "
           "irc_merge; %d left unreaped while the survivor ran): %d holding no lock, %d the "
           "read lock, %d the write lock\n", died, trials, by_mode[0], by_mode[1], by_mode[2],
           merging, zombies, held[0], held[1], held[2]);
    in_merge = NULL;
    munmap(cfg.buffer, mapped);
    free(merge_snap);
    merge_snap = NULL;
}
