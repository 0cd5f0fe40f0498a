/*
 * pass.c -- fill passes: records made while a pass is open wait outside
 * the index, so every lookup of the pass sees the same frozen cache, and
 * join it at the end in the canonical order of merges.  The records a
 * pass adds then depend only on the cache it began with and the queries
 * made, not on how many threads made them or in what order.  The end of a
 * pass also renumbers every record in the index's order (compact.c).
 */
#include "../block/cache.h"
#include "../block/check.h"
#include "../index/index.h"
#include "../persist/snapshot.h"
#include "../store/lock.h"
#include "../store/stats.h"
#include "../store/store.h"

int irc_pass_begin(irc_cache *c)
{
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (irc__write_lock(c) < 0)
        return IRC_ERR_PORT;
    if (irc__st(c)->pass_open) {
        st = IRC_ERR_STATE;
    } else {
        irc__st(c)->pass_base = irc__st(c)->count;
        c->port->store(&irc__st(c)->pending, 0);
        c->port->store(&irc__st(c)->packed, 0);
        irc__st(c)->pass_open = 1;
    }
    irc__write_unlock(c);
    return st;
}

int irc_pass_end(irc_cache *c, uint32_t *added)
{
    uint64_t pend;
    uint32_t n, kept, i, room;
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (irc__write_lock(c) < 0)
        return IRC_ERR_PORT;
    if (!irc__st(c)->pass_open) {
        irc__write_unlock(c);
        return IRC_ERR_STATE;
    }
    pend = c->port->load(&irc__st(c)->pending);
    room = c->capacity - irc__st(c)->pass_base;
    n = pend < (uint64_t)room ? (uint32_t)pend : room;
    /* Fewer whole than reserved: a process died while it packed one, and
     * which is torn cannot be told; the pass's records are dropped (their
     * queries compute them again). */
    if (c->port->load(&irc__st(c)->packed) != n)
        n = 0;
    /* Slot order is the order threads happened to finish in; the
     * canonical order is not.  Two queries that made the same record made
     * it once as far as the cache is concerned. */
    irc__sort(c, irc__st(c)->pass_base, n);
    kept = irc__unique(c, irc__st(c)->pass_base, n);
    irc__zero_slots(c, irc__st(c)->pass_base + kept, n - kept);
    /* Committed in canonical order (each one clamped by those before,
     * found through the index), indexed in a scattered one (compact.c):
     * without clamping only the scattered order indexes them. */
    for (i = 0; i < kept && c->cfg.clamp_neighbours; i++) {
        irc__st(c)->count = irc__st(c)->pass_base + i + 1;
        irc__commit_locked(c, irc__st(c)->pass_base + i);
    }
    if (!c->cfg.clamp_neighbours) {
        irc__st(c)->count = irc__st(c)->pass_base + kept;
        irc__count(c, IRC__C_INSERTS, kept);
    }
    if (kept) {
        irc__index_clear(c);
        irc__index_rebuild(c);
    }
    irc__index_compact(c);
    irc__st(c)->pass_open = 0;
    c->port->store(&irc__st(c)->pending, 0);
    c->port->store(&irc__st(c)->packed, 0);
    irc__write_unlock(c);
    if (added)
        *added = kept;
    return IRC_OK;
}
