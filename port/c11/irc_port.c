/*
 * port/c11/irc_port.c -- C11 <stdatomic.h> and <threads.h>.  C11 threads
 * have no reader-writer lock, so this port builds one from one atomic word:
 * -1 while a writer holds it, else the number of readers.  Waiters yield.
 * Writers are rare (an insert per record computed), so spinning is cheap.
 */
#include <stdatomic.h>
#include <threads.h>

#include "irrcache.h"

typedef struct c11_lock {
    atomic_int state;
} c11_lock;

/* The library's counters are plain uint64_t words; this port needs their
 * atomic twins to be the same object size, lock free. */
typedef char c11_same_size[sizeof(_Atomic uint64_t) == sizeof(uint64_t) ? 1 : -1];

static int c11_lock_init(void *l)
{
    atomic_init(&((c11_lock *)l)->state, 0);
    return 0;
}
static void c11_lock_destroy(void *l) { (void)l; }

static int c11_read_lock(void *l)
{
    atomic_int *s = &((c11_lock *)l)->state;
    for (;;) {
        int v = atomic_load_explicit(s, memory_order_relaxed);
        if (v >= 0 && atomic_compare_exchange_weak_explicit(
                          s, &v, v + 1, memory_order_acquire, memory_order_relaxed))
            return 0;
        thrd_yield();
    }
}
static void c11_read_unlock(void *l)
{
    atomic_fetch_sub_explicit(&((c11_lock *)l)->state, 1, memory_order_release);
}
static int c11_write_lock(void *l)
{
    atomic_int *s = &((c11_lock *)l)->state;
    for (;;) {
        int v = 0;
        if (atomic_compare_exchange_weak_explicit(s, &v, -1, memory_order_acquire,
                                                  memory_order_relaxed))
            return 0;
        thrd_yield();
    }
}
static void c11_write_unlock(void *l)
{
    atomic_store_explicit(&((c11_lock *)l)->state, 0, memory_order_release);
}

static void c11_yield(void) { thrd_yield(); }

#define C11_A(o) ((_Atomic uint64_t *)(o))
static uint64_t c11_load(const uint64_t *o)
{
    return atomic_load_explicit(C11_A((uint64_t *)o), memory_order_acquire);
}
static void c11_store(uint64_t *o, uint64_t v)
{
    atomic_store_explicit(C11_A(o), v, memory_order_release);
}
static uint64_t c11_add(uint64_t *o, uint64_t v)
{
    return atomic_fetch_add_explicit(C11_A(o), v, memory_order_relaxed);
}
static uint64_t c11_or(uint64_t *o, uint64_t v)
{
    return atomic_fetch_or_explicit(C11_A(o), v, memory_order_relaxed);
}
static int c11_cas(uint64_t *o, uint64_t e, uint64_t d)
{
    return atomic_compare_exchange_strong_explicit(C11_A(o), &e, d, memory_order_acq_rel,
                                                   memory_order_acquire);
}

/* A thread's token: the address of a thread-local byte, distinct among the
 * live threads of a process (never written). */
static _Thread_local char c11_me;
static uint64_t c11_thread(void) { return (uint64_t)(uintptr_t)&c11_me; }

const irc_port irc_port_c11 = {
    "c11", sizeof(c11_lock), c11_lock_init, c11_lock_destroy,
    c11_read_lock, c11_read_unlock, c11_write_lock, c11_write_unlock, c11_yield,
    c11_load, c11_store, c11_add, c11_or, c11_cas, NULL, NULL, c11_thread};
