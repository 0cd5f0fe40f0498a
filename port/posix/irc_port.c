/*
 * port/posix/irc_port.c -- POSIX threads: a pthread rwlock in the cache's
 * block, and the GCC/Clang __atomic builtins on the block's 64-bit words.
 */
#include <errno.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include "irrcache.h"

#if !defined(__GNUC__) && !defined(__clang__)
#error "port/posix needs GCC or Clang __atomic builtins; use port/c11 with another compiler"
#endif

/* Process-shared, so that processes mapping one block (irc_join) share the
 * lock; within one process it costs nothing more. */
static int posix_lock_init(void *l)
{
    pthread_rwlockattr_t a;
    int st;
    if (pthread_rwlockattr_init(&a) != 0)
        return -1;
    st = pthread_rwlockattr_setpshared(&a, PTHREAD_PROCESS_SHARED) == 0 &&
                 pthread_rwlock_init((pthread_rwlock_t *)l, &a) == 0
             ? 0
             : -1;
    pthread_rwlockattr_destroy(&a);
    return st;
}
static void posix_lock_destroy(void *l) { pthread_rwlock_destroy((pthread_rwlock_t *)l); }
static int posix_read_lock(void *l) { return pthread_rwlock_rdlock((pthread_rwlock_t *)l) == 0 ? 0 : -1; }
static int posix_write_lock(void *l) { return pthread_rwlock_wrlock((pthread_rwlock_t *)l) == 0 ? 0 : -1; }
static void posix_yield(void) { sched_yield(); }
static void posix_unlock(void *l) { pthread_rwlock_unlock((pthread_rwlock_t *)l); }

static uint64_t posix_load(const uint64_t *o) { return __atomic_load_n(o, __ATOMIC_ACQUIRE); }
static void posix_store(uint64_t *o, uint64_t v) { __atomic_store_n(o, v, __ATOMIC_RELEASE); }
static uint64_t posix_add(uint64_t *o, uint64_t v) { return __atomic_fetch_add(o, v, __ATOMIC_RELAXED); }
static uint64_t posix_or(uint64_t *o, uint64_t v) { return __atomic_fetch_or(o, v, __ATOMIC_RELAXED); }
static int posix_cas(uint64_t *o, uint64_t e, uint64_t d)
{
    return __atomic_compare_exchange_n(o, &e, d, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE);
}

/* A scratch slot's owner: the process id; kill(pid, 0) tells whether it
 * still runs (EPERM: it does, as another user's). */
static uint64_t posix_owner(void) { return (uint64_t)getpid(); }
static int posix_owner_alive(uint64_t tok)
{
    return kill((pid_t)tok, 0) == 0 || errno != ESRCH;
}

const irc_port irc_port_posix = {
    "posix", sizeof(pthread_rwlock_t), posix_lock_init, posix_lock_destroy,
    posix_read_lock, posix_unlock, posix_write_lock, posix_unlock, posix_yield,
    posix_load, posix_store, posix_add, posix_or, posix_cas, posix_owner, posix_owner_alive};
