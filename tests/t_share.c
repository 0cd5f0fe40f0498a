/* t_share.c -- one cache shared live by two processes: a file mapped by
 * each at its own address, the creator's handle and the other's view
 * (irc_join), both filling at once; then every record is checked against a
 * fresh computation at its query, from both processes. */
#define IRC_EXPERIMENTAL /* irc_join (irrcache.h) */
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "irrcache.h"
#include "scenes.h"
#include "share.h"
#include "test.h"

/* A host context whose callback counts its own calls: each process must
 * reach its own host, never the other's. */
typedef struct counting {
    tscene s;
    unsigned long calls;
} counting;

static int counting_trace(const irc_trace_args *a)
{
    irc_trace_args b = *a;
    counting *k = (counting *)a->context;
    k->calls++;
    b.context = &k->s;
    return scene_trace(&b);
}

void share_nap(void)
{
    struct timespec t = {0, 1000000};
    nanosleep(&t, NULL);
}

int share_fill_half(irc_cache *c, int half)
{
    const float up[3] = {0, 0, 1};
    int i, bad = 0;
    for (i = 0; i < SHARE_SIDE * SHARE_SIDE; i++) {
        int ix = i % SHARE_SIDE;
        float p[3] = {(float)(ix - SHARE_SIDE / 2) * 0.2f, (float)(i / SHARE_SIDE - SHARE_SIDE / 2) * 0.2f, 0.0f},
              rgb[3], w;
        if ((half == 0 && ix > SHARE_SIDE / 2) || (half == 1 && ix < SHARE_SIDE / 2))
            continue;
        bad += irc_cache_lookup_or_compute(c, p, up, rgb, &w, NULL) < 0;
    }
    return bad;
}

/* Every stored record equals a fresh record computed at its query (its
 * position, normal +z): position, radius and irradiance exactly, the
 * normal and the gradients to their packed precision; and a lookup there
 * finds it.  Returns failures. */
int share_verify_all(irc_cache *c)
{
    const float up[3] = {0, 0, 1};
    irc_stats st;
    uint32_t id;
    int bad = 0, k;
    if (irc_cache_stats(c, &st) != IRC_OK || st.records == 0)
        return 1;
    for (id = 0; id < st.records; id++) {
        irc_record r, f;
        float rgb[3], w = 0.0f;
        if (irc_cache_record(c, id, &r) != IRC_OK ||
            irc_record_compute(c, r.p, up, &f, NULL) != IRC_OK) {
            bad++;
            continue;
        }
        bad += r.radius != f.radius || memcmp(r.p, f.p, sizeof r.p) != 0 ||
               memcmp(r.e, f.e, sizeof r.e) != 0;
        for (k = 0; k < 3; k++) {
            /* Gradients are packed in the tangent frame of the packed
             * normal, to 2^-14 of the channel's largest component. */
            const float *g = f.grad_t[k], *h = r.grad_t[k];
            double norm = sqrt((double)g[0] * g[0] + (double)g[1] * g[1] + (double)g[2] * g[2]);
            int q;
            bad += fabs(r.n[k] - f.n[k]) > 1e-4;
            for (q = 0; q < 3; q++)
                bad += fabs(h[q] - g[q]) > 1e-3 * norm + 1e-9;
        }
        bad += irc_cache_lookup(c, r.p, r.n, rgb, &w) != IRC_OK || !(w > 1.0f);
    }
    return bad;
}

TEST(test_share_processes)
{
    char path[] = "/tmp/irc_share_XXXXXX";
    counting host;
    irc_config cfg;
    irc_cache *c;
    size_t bytes = 0;
    int fd = mkstemp(path), status = -1, *flags;
    void *map;
    pid_t pid;
    scene_sphere_plane(&host.s);
    host.calls = 0;
    cfg = scene_config(&host.s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    cfg.trace = counting_trace;
    cfg.context = &host;
    cfg.max_radius = 1.0f;
    cfg.threads = 4;
    CHECK(fd >= 0 && irc_footprint(&cfg, 4096, &bytes) == IRC_OK &&
              ftruncate(fd, (off_t)((bytes + 4095) / 4096 * 4096 + 4096)) == 0,
          "temporary file");
    /* The block, then a page of flags the two processes signal with. */
    map = mmap(NULL, (bytes + 4095) / 4096 * 4096 + 4096, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    CHECK(map != MAP_FAILED, "mmap");
    if (fd < 0 || map == MAP_FAILED)
        return;
    flags = (int *)(void *)((unsigned char *)map + (bytes + 4095) / 4096 * 4096);
    cfg.buffer = map;
    cfg.buffer_size = bytes;
    CHECK(irc_init(&cfg, 4096, &c) == IRC_OK, "init");
    flags[0] = flags[1] = 0;
    pid = fork();
    if (pid == 0) {
        /* The other process: its own mapping of the file (another
         * address), its own host, a view of the block. */
        static double view[IRC_VIEW_BYTES / sizeof(double)];
        counting mine;
        irc_config mc = cfg;
        irc_cache *v;
        unsigned long before = host.calls;
        int bad = 0;
        void *m2 = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
        scene_sphere_plane(&mine.s);
        mine.calls = 0;
        mc.context = &mine;
        mc.buffer = m2;
        bad += m2 == MAP_FAILED || m2 == map;
        bad += irc_join(&mc, view, 64, &v) != IRC_ERR_NOMEM;
        if (bad || irc_join(&mc, view, sizeof view, &v) != IRC_OK)
            _exit(100);
        bad += share_fill_half(v, 1);
        __atomic_store_n(&flags[0], 1, __ATOMIC_RELEASE);
        while (!__atomic_load_n(&flags[1], __ATOMIC_ACQUIRE))
            share_nap();
        bad += share_verify_all(v);
        bad += mine.calls == 0 || host.calls != before; /* its own host only */
        bad += irc_fini(v) != IRC_OK;
        _exit(bad > 99 ? 99 : bad);
    }
    CHECK(pid > 0, "fork");
    if (pid > 0) {
        irc_stats st;
        int bad = share_fill_half(c, 0), gone = 0;
        while (!gone && !__atomic_load_n(&flags[0], __ATOMIC_ACQUIRE)) {
            gone = waitpid(pid, &status, WNOHANG) == pid;
            share_nap();
        }
        CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records > 100 &&
                  st.records == st.computes && st.records == st.inserts,
              "records %u computes %u inserts %u", (unsigned)st.records, (unsigned)st.computes,
              (unsigned)st.inserts);
        bad += share_verify_all(c);
        CHECK(bad == 0, "the creator found %d bad records or failed lookups", bad);
        __atomic_store_n(&flags[1], 1, __ATOMIC_RELEASE);
        if (!gone)
            waitpid(pid, &status, 0);
        CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0,
              "the joined process: status %d (100: could not join)",
              WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    }
    irc_fini(c);
    munmap(map, (bytes + 4095) / 4096 * 4096 + 4096);
    close(fd);
    unlink(path);
}

/* A view cannot be made from a block at another offset from a 64-byte
 * boundary, nor with another port; neither writes to the block. */
TEST(test_join_refused)
{
    tscene s;
    irc_config cfg, other;
    irc_cache *c, *v;
    static double view[IRC_VIEW_BYTES / sizeof(double)];
    unsigned char *copy;
    c = NULL;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, 0, 4, 16);
    c = block_cache(&cfg, 64, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    copy = malloc(cfg.buffer_size + 64);
    other = cfg;
    other.port = &irc_port_none;
    CHECK(irc_join(&other, view, sizeof view, &v) == IRC_ERR_CONFIG, "another port");
    CHECK(copy != NULL, "malloc");
    if (copy) {
        size_t shift = 8;
        while (((uintptr_t)(copy + shift) & 63u) == ((uintptr_t)cfg.buffer & 63u))
            shift += 8;
        memcpy(copy + shift, cfg.buffer, cfg.buffer_size);
        other = cfg;
        other.buffer = copy + shift;
        CHECK(irc_join(&other, view, sizeof view, &v) == IRC_ERR_CONFIG, "another offset");
        CHECK(memcmp(copy + shift, cfg.buffer, cfg.buffer_size) == 0, "the block was written");
        free(copy);
    }
    CHECK(irc_join(&cfg, NULL, sizeof view, &v) == IRC_ERR_NULL, "NULL view");
    /* irrcache.h: IRC_ERR_CONFIG for no cache of this build, IRC_ERR_NOMEM
     * for a buffer_size short of the block, IRC_ERR_NOMEM for a short view */
    other = cfg;
    other.buffer_size = 64;
    CHECK(irc_join(&other, view, sizeof view, &v) == IRC_ERR_NOMEM, "a short buffer_size");
    CHECK(irc_join(&cfg, view, IRC_VIEW_BYTES - 1u, &v) == IRC_ERR_NOMEM, "a short view");
    CHECK(irc_join(&cfg, (char *)view + 4, sizeof view - 8u, &v) == IRC_ERR_NOMEM,
          "a view not aligned for a double");
    {
        unsigned char *junk = malloc(cfg.buffer_size);
        if (junk) {
            memset(junk, 0x5a, cfg.buffer_size);
            junk[0] = 8; /* the pad byte a block starts with */
            other = cfg;
            other.buffer = junk;
            CHECK(irc_join(&other, view, sizeof view, &v) == IRC_ERR_CONFIG, "no cache joined");
            free(junk);
        }
    }
    CHECK(irc_join(&cfg, view, sizeof view, &v) == IRC_OK && irc_fini(v) == IRC_OK &&
              irc_cache_clear(c) == IRC_OK,
          "a view's fini leaves the creator's lock");
    block_free(&cfg);
}
