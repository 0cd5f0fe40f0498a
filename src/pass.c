/*
 * pass.c -- fill passes: records made while a pass is open wait outside
 * the index, so every lookup of the pass sees the same frozen cache, and
 * join it at the end in the canonical order of merges.  The records a
 * pass adds then depend only on the cache it began with and the queries
 * made, not on how many threads made them or in what order.  The end of a
 * pass also renumbers every record in the index's order (compact.c).
 */
#include "cache.h"

int irc_pass_begin(irc_cache *c)
{
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (c->port->write_lock(irc__lock(c)) < 0)
        return IRC_ERR_PORT;
    if (c->home->pass_open) {
        st = IRC_ERR_STATE;
    } else {
        c->home->pass_open = 1;
        c->home->pass_base = c->home->count;
        c->port->store(&c->home->pending, 0);
    }
    c->port->write_unlock(irc__lock(c));
    return st;
}

int irc_pass_end(irc_cache *c, uint32_t *added)
{
    uint64_t pend;
    uint32_t n, kept, i, room;
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (c->port->write_lock(irc__lock(c)) < 0)
        return IRC_ERR_PORT;
    if (!c->home->pass_open) {
        c->port->write_unlock(irc__lock(c));
        return IRC_ERR_STATE;
    }
    pend = c->port->load(&c->home->pending);
    room = c->capacity - c->home->pass_base;
    n = pend < (uint64_t)room ? (uint32_t)pend : room;
    /* Slot order is the order threads happened to finish in; the
     * canonical order is not.  Two queries that made the same record made
     * it once as far as the cache is concerned. */
    irc__sort(c, c->home->pass_base, n);
    kept = irc__unique(c, c->home->pass_base, n);
    for (i = 0; i < kept; i++) {
        c->home->count = c->home->pass_base + i + 1;
        irc__commit_locked(c, c->home->pass_base + i);
    }
    irc__index_compact(c);
    c->home->pass_open = 0;
    c->port->store(&c->home->pending, 0);
    c->port->write_unlock(irc__lock(c));
    if (added)
        *added = kept;
    return IRC_OK;
}
