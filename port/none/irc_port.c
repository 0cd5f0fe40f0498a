/*
 * port/none/irc_port.c -- single-threaded builds: no locks, plain loads and
 * stores.  A cache using it must be touched by one thread at a time.
 */
#include "irrcache.h"

static int none_lock_init(void *l) { (void)l; return 0; }
static void none_lock(void *l) { (void)l; }
static int none_take(void *l) { (void)l; return 0; }
static uint64_t none_load(const uint64_t *o) { return *o; }
static void none_store(uint64_t *o, uint64_t v) { *o = v; }
static uint64_t none_add(uint64_t *o, uint64_t v) { uint64_t old = *o; *o = old + v; return old; }
static uint64_t none_or(uint64_t *o, uint64_t v) { uint64_t old = *o; *o = old | v; return old; }
static int none_cas(uint64_t *o, uint64_t e, uint64_t d)
{
    if (*o != e)
        return 0;
    *o = d;
    return 1;
}

const irc_port irc_port_none = {
    "none", 0, none_lock_init, none_lock, none_take, none_lock, none_take,
    none_lock, NULL, none_load, none_store, none_add, none_or, none_cas, NULL, NULL, NULL};
