/*
 * port/posix/irc_port.c -- POSIX processes and threads: a reader/writer
 * lock in the cache's block that survives a holder killed inside it, and
 * the GCC/Clang __atomic builtins on the block's 64-bit words.
 */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "irrcache.h"

#if !defined(__GNUC__) && !defined(__clang__)
#error "port/posix needs GCC or Clang __atomic builtins; use port/c11 with another compiler"
#endif

/*
 * The lock: a reader/writer lock that outlives its holders.  A pthread
 * rwlock cannot: a process killed while it holds one (even for reading,
 * inside a lookup) leaves it taken, and every process sharing the block
 * hangs.  This one is built from words in the block:
 *   - writer: the process id of the writer, 0 if none;
 *   - readers: a table of words, each 0 or (process id << 32 | count).
 *     Any process may hold several: a thread starts its search at an entry
 *     of its own (its stack's address, hashed), so that threads on other
 *     cores count themselves in on other lines.
 * A reader counts itself in, then looks at writer (both sequentially
 * consistent, so of a reader and a writer arriving together at least one
 * sees the other) and backs out if a writer came.  A writer claims writer,
 * then waits for the counts to drain.  A waiter that has waited a while
 * asks the system whether the process it waits for still runs: a dead
 * reader's count is dropped (readers change nothing), a dead writer's
 * claim is taken over and write_lock returns 1 so that the library
 * repairs what the writer left half done; read_lock returns 1 without the
 * lock, for the library to take the write lock and repair.
 * A waiting writer keeps new readers out, so writers do not starve.
 * Process ids are of one pid namespace; a reused id looks alive; an
 * exited one not yet reaped does not (posix_exited).
 */
#define POSIX_READERS 63u
#define POSIX_CHECK_EVERY 64u /* waits between liveness checks */
#define POSIX_LINE 8u         /* words a cache line */

/* Every word on a cache line of its own: a reader's count changes twice a
 * lookup, and threads whose entries shared a line would trade it between
 * their cores on every lookup (64 bytes: x86 and most ARM cores). */
typedef struct posix_lock {
    uint64_t writer[POSIX_LINE];
    uint64_t readers[POSIX_READERS][POSIX_LINE];
} posix_lock;

/* An owner is a process id; kill(pid, 0) tells whether it still runs
 * (EPERM: it does, as another user's).  The id is asked of the system
 * once per process: a lookup takes and gives back a read count under it,
 * and getpid is a system call (glibc caches nothing), two a lookup.  A
 * child made by fork() forgets it (pthread_atfork's child handler runs
 * before fork returns there); if the handler cannot be registered the
 * id is asked every time.  A child made by a raw clone system call, which
 * runs no handler, would keep its parent's id: use fork or posix_spawn. */
static pid_t posix_pid;         /* 0: not known in this process */
static int posix_pid_kept = -1; /* 1: the handler is registered, 0: it failed */
static pthread_once_t posix_pid_once = PTHREAD_ONCE_INIT;
static void posix_pid_forget(void) { __atomic_store_n(&posix_pid, 0, __ATOMIC_RELAXED); }
static void posix_pid_watch(void)
{
    __atomic_store_n(&posix_pid_kept, pthread_atfork(NULL, NULL, posix_pid_forget) == 0,
                     __ATOMIC_RELEASE);
}
static uint64_t posix_owner(void)
{
    pid_t p = __atomic_load_n(&posix_pid, __ATOMIC_RELAXED);
    if (p)
        return (uint64_t)p;
    pthread_once(&posix_pid_once, posix_pid_watch);
    p = getpid();
    if (__atomic_load_n(&posix_pid_kept, __ATOMIC_ACQUIRE) == 1)
        __atomic_store_n(&posix_pid, p, __ATOMIC_RELAXED);
    return (uint64_t)p;
}

/* Whether a process that kill() still finds has exited and waits to be
 * reaped (a zombie), which only its parent can do: a parent that waits
 * inside the library for a lock or slot its dead child held would wait
 * forever.  Its own child it asks waitid without reaping it (WNOWAIT,
 * POSIX); any other process, on Linux, by the state letter of
 * /proc/<pid>/stat, which follows the last ')' (the command name may hold
 * one).  Asked only by a waiter every POSIX_CHECK_EVERY waits, never on a
 * lookup's way. */
static int posix_exited(pid_t pid)
{
    siginfo_t si;
    memset(&si, 0, sizeof si);
    if (waitid(P_PID, (id_t)pid, &si, WEXITED | WNOHANG | WNOWAIT) == 0 && si.si_pid == pid)
        return 1;
#ifdef __linux__
    {
        char path[32] = "/proc/", digits[12], buf[256];
        const char *at = NULL;
        unsigned long v = (unsigned long)pid;
        size_t nd = 0, len = 6, i;
        ssize_t got;
        int fd;
        do {
            digits[nd++] = (char)('0' + v % 10);
            v /= 10;
        } while (v && nd < sizeof digits);
        while (nd)
            path[len++] = digits[--nd];
        memcpy(path + len, "/stat", 6);
        if ((fd = open(path, O_RDONLY | O_CLOEXEC)) < 0)
            return 0;
        got = read(fd, buf, sizeof buf - 1);
        close(fd);
        for (i = 0; got > 0 && i < (size_t)got; i++)
            if (buf[i] == ')')
                at = buf + i;
        return at && at + 2 < buf + got && at[1] == ' ' && (at[2] == 'Z' || at[2] == 'X');
    }
#else
    return 0;
#endif
}

/* Alive: kill() finds it (EPERM: another user's) and it has not exited. */
static int posix_owner_alive(uint64_t tok)
{
    if (kill((pid_t)tok, 0) != 0 && errno == ESRCH)
        return 0;
    return !posix_exited((pid_t)tok);
}

static uint64_t posix_get(const uint64_t *w) { return __atomic_load_n(w, __ATOMIC_SEQ_CST); }
static int posix_swap(uint64_t *w, uint64_t e, uint64_t d)
{
    return __atomic_compare_exchange_n(w, &e, d, 0, __ATOMIC_SEQ_CST, __ATOMIC_SEQ_CST);
}

/* The calling thread's first entry: its process and the 1 MiB granule of
 * its stack (threads' stacks lie megabytes apart; one thread's calls stay
 * in one granule or two, and lock and unlock find the entry either way). */
static unsigned posix_home_entry(uint64_t me)
{
    unsigned char here;
    uint64_t a = (uint64_t)(uintptr_t)&here >> 20;
    return (unsigned)((me * 2654435761u + a * 0x9e3779b97f4a7c15ull) >> 40) % POSIX_READERS;
}

static int posix_lock_init(void *l)
{
    memset(l, 0, sizeof(posix_lock));
    return 0;
}
static void posix_lock_destroy(void *l) { (void)l; }

/* One more count on the first entry from the thread's own that is this
 * process's or free, or (when the table is full) on one of a process that
 * is gone.  0 if none. */
static int posix_count_in(posix_lock *k, uint64_t me)
{
    unsigned i, at, pass, home = posix_home_entry(me);
    for (pass = 0; pass < 2; pass++)
        for (i = 0; i < POSIX_READERS; i++) {
            uint64_t *e = k->readers[(home + i) % POSIX_READERS];
            uint64_t v = posix_get(e);
            at = 0;
            if (pass == 0 && v >> 32 == me)
                at = posix_swap(e, v, v + 1);
            else if (pass == 0 && v == 0)
                at = posix_swap(e, 0, me << 32 | 1u);
            else if (pass == 1 && v >> 32 != me && !posix_owner_alive(v >> 32))
                at = posix_swap(e, v, me << 32 | 1u);
            if (at)
                return 1;
        }
    return 0;
}

static void posix_count_out(posix_lock *k, uint64_t me)
{
    const unsigned home = posix_home_entry(me);
    for (;;) {
        unsigned i;
        for (i = 0; i < POSIX_READERS; i++) {
            uint64_t *e = k->readers[(home + i) % POSIX_READERS];
            uint64_t v = posix_get(e);
            if (v >> 32 == me && (v & 0xffffffffu) &&
                posix_swap(e, v, (v & 0xffffffffu) == 1u ? 0 : v - 1))
                return;
        }
    }
}

static int posix_read_lock(void *l)
{
    posix_lock *k = (posix_lock *)l;
    uint64_t me = posix_owner(), w;
    unsigned waits = 0;
    for (;;) {
        if ((w = posix_get(k->writer)) == 0) {
            if (posix_count_in(k, me)) {
                if (posix_get(k->writer) == 0)
                    return 0;
                posix_count_out(k, me);
            }
        } else if (++waits % POSIX_CHECK_EVERY == 0 && w != me && !posix_owner_alive(w)) {
            return 1;
        }
        sched_yield();
    }
}
static void posix_read_unlock(void *l) { posix_count_out((posix_lock *)l, posix_owner()); }

/* Waits for entry e's readers to leave, or drops them if their process is
 * gone. */
static void posix_drain(uint64_t *e, uint64_t me)
{
    unsigned waits = 0;
    uint64_t v;
    while ((v = posix_get(e)) != 0) {
        if (++waits % POSIX_CHECK_EVERY == 0 && v >> 32 != me && !posix_owner_alive(v >> 32))
            posix_swap(e, v, 0);
        else
            sched_yield();
    }
}

static int posix_write_lock(void *l)
{
    posix_lock *k = (posix_lock *)l;
    uint64_t me = posix_owner(), w;
    unsigned waits = 0, i;
    int took_over = 0;
    for (;;) {
        if ((w = posix_get(k->writer)) == 0) {
            if (posix_swap(k->writer, 0, me))
                break;
        } else if (++waits % POSIX_CHECK_EVERY == 0 && w != me && !posix_owner_alive(w) &&
                   posix_swap(k->writer, w, me)) {
            took_over = 1;
            break;
        }
        sched_yield();
    }
    for (i = 0; i < POSIX_READERS; i++)
        posix_drain(k->readers[i], me);
    return took_over;
}
static void posix_write_unlock(void *l)
{
    __atomic_store_n(((posix_lock *)l)->writer, 0, __ATOMIC_SEQ_CST);
}

static void posix_yield(void) { sched_yield(); }

/* A thread's token: the address of a thread-local byte, distinct among the
 * live threads of a process (never written: no state is kept in it). */
static __thread char posix_me;
static uint64_t posix_thread(void) { return (uint64_t)(uintptr_t)&posix_me; }

static uint64_t posix_load(const uint64_t *o) { return __atomic_load_n(o, __ATOMIC_ACQUIRE); }
static void posix_store(uint64_t *o, uint64_t v) { __atomic_store_n(o, v, __ATOMIC_RELEASE); }
static uint64_t posix_add(uint64_t *o, uint64_t v) { return __atomic_fetch_add(o, v, __ATOMIC_RELAXED); }
static uint64_t posix_or(uint64_t *o, uint64_t v) { return __atomic_fetch_or(o, v, __ATOMIC_RELAXED); }
static int posix_cas(uint64_t *o, uint64_t e, uint64_t d)
{
    return __atomic_compare_exchange_n(o, &e, d, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE);
}

const irc_port irc_port_posix = {
    "posix", sizeof(posix_lock), posix_lock_init, posix_lock_destroy,
    posix_read_lock, posix_read_unlock, posix_write_lock, posix_write_unlock, posix_yield,
    posix_load, posix_store, posix_add, posix_or, posix_cas, posix_owner, posix_owner_alive,
    posix_thread};
