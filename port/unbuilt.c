/*
 * port/unbuilt.c -- the ports this build did not compile, so that every
 * port irrcache.h declares is defined in every build: a build compiles the
 * port `make PORT=` chose and irc_port_none, and defines the others here
 * as ports that cannot make a lock.  A cache configured with one fails
 * irc_init and irc_join with IRC_ERR_PORT, and irc_attach refuses a block
 * whose lock another port made (its name differs).  The Makefile passes
 * IRC_BUILT_POSIX or IRC_BUILT_C11 for the port it compiled.
 */
#include "irrcache.h"

#if !defined(IRC_BUILT_POSIX) || !defined(IRC_BUILT_C11)
static int unbuilt_lock_init(void *l) { (void)l; return -1; }
static void unbuilt_lock(void *l) { (void)l; }
static int unbuilt_take(void *l) { (void)l; return -1; }
static uint64_t unbuilt_load(const uint64_t *o) { return *o; }
static void unbuilt_store(uint64_t *o, uint64_t v) { *o = v; }
static uint64_t unbuilt_add(uint64_t *o, uint64_t v) { uint64_t old = *o; *o = old + v; return old; }
static uint64_t unbuilt_or(uint64_t *o, uint64_t v) { uint64_t old = *o; *o = old | v; return old; }
static int unbuilt_cas(uint64_t *o, uint64_t e, uint64_t d)
{
    if (*o != e)
        return 0;
    *o = d;
    return 1;
}
#define IRC__UNBUILT_PORT(name)                                                   \
    {name, 0, unbuilt_lock_init, unbuilt_lock, unbuilt_take, unbuilt_lock,        \
     unbuilt_take, unbuilt_lock, NULL, unbuilt_load, unbuilt_store, unbuilt_add, \
     unbuilt_or, unbuilt_cas, NULL, NULL, NULL}
#endif

#ifndef IRC_BUILT_POSIX
const irc_port irc_port_posix = IRC__UNBUILT_PORT("posix, unbuilt");
#endif
#ifndef IRC_BUILT_C11
const irc_port irc_port_c11 = IRC__UNBUILT_PORT("c11, unbuilt");
#endif
