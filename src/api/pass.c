/*
 * pass.c -- fill passes: records made while a pass is open wait outside
 * the index, so every lookup of the pass sees the same frozen cache, and
 * join it at the end in the canonical order of merges.  The records a
 * pass adds then depend only on the cache it began with and the queries
 * made, not on how many threads made them or in what order.
 *
 * The end of a pass costs what its records cost: they are inserted into
 * the live index one by one in that order, so the index after a pass is a
 * function of the passes before it and their records' sets, never of the
 * threads.  Rebuilding the index every pass instead cost passes x records
 * (a host's 1,024 passes at 640 x 480 spent 54-81% of its render there).
 * The records are renumbered in the index's order (compact.c: lookups
 * unchanged, faster) only when the cache has grown by a quarter since they
 * last were, so over a fill each record moves about five times in all.
 * A pass as large as the cache it joins is indexed again whole, in the
 * scattered order of merges: that costs at most twice the pass's own.
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

/* The pass's records [base, base + n), sorted and unique, joined one at a
 * time: each is counted in, then clamped (when on) by those before it and
 * indexed, as a free fill's insert does. */
static void irc__pass_join(irc_cache *c, uint32_t base, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        irc__st(c)->count = base + i + 1;
        irc__commit_locked(c, base + i);
    }
}

int irc_pass_end(irc_cache *c, uint32_t *added)
{
    uint64_t pend;
    uint32_t n, kept, room, base;
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (irc__write_lock(c) < 0)
        return IRC_ERR_PORT;
    if (!irc__st(c)->pass_open) {
        irc__write_unlock(c);
        return IRC_ERR_STATE;
    }
    base = irc__st(c)->pass_base;
    pend = c->port->load(&irc__st(c)->pending);
    room = c->capacity - base;
    n = pend < (uint64_t)room ? (uint32_t)pend : room;
    /* Fewer whole than reserved: a process died while it packed one, and
     * which is torn cannot be told; the pass's records are dropped (their
     * queries compute them again). */
    if (c->port->load(&irc__st(c)->packed) != n)
        n = 0;
    /* Slot order is the order threads happened to finish in; the
     * canonical order is not.  Two queries that made the same record made
     * it once as far as the cache is concerned. */
    irc__sort(c, base, n);
    kept = irc__unique(c, base, n);
    irc__zero_slots(c, base + kept, n - kept);
    irc__pass_join(c, base, kept);
    /* A pass at least as large as the cache it joins (a fill's first
     * passes, a bulk insert) arrived in space order, which spends the
     * node pool on the first part of the scene (compact.c): it is indexed
     * again in a scattered order, at a cost of at most twice its own. */
    if (kept && kept >= base) {
        irc__index_clear(c);
        irc__index_rebuild(c);
    }
    if (4u * (uint64_t)irc__st(c)->count > 5u * (uint64_t)irc__st(c)->compacted)
        irc__index_compact(c);
    irc__st(c)->pass_open = 0;
    c->port->store(&irc__st(c)->pending, 0);
    c->port->store(&irc__st(c)->packed, 0);
    irc__write_unlock(c);
    if (added)
        *added = kept;
    return IRC_OK;
}
