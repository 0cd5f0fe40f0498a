/*
 * lock.c -- the port's locks as the library takes them: the write lock
 * taken so that a writer killed inside it (a process sharing the block,
 * irc_join) leaves nothing the next writer cannot make whole, and the
 * read lock, which lets that repair run first.
 *
 * Writers keep two promises.  Every slot below count holds a whole
 * record, except the slots the block's torn word names while their bytes
 * are written (an insert's slot, the two records a swap exchanges, a
 * merge's copy); and the writing word is set while the lock is held.  The
 * index is not trusted after a death: a list or a node may be half
 * linked.  So the repair drops the named slots and any record that is not
 * sane, and builds the index anew from the records.  It runs when the port
 * reports a lock taken over from a dead holder (irrcache.h, irc_port) and
 * in irc_attach when a block at rest was left mid-write.  What the dead
 * writer had in progress is lost: the record it stored, or the records of
 * a pass it was ending that were not yet counted in; an open pass goes on
 * from the records that are.
 */
#include "../block/cache.h"
#include "../block/torn.h"
#include "../index/index.h"
#include "../index/verify.h"
#include "lock.h"

void irc__repair_locked(irc_cache *c)
{
    irc__state *h = irc__st(c);
    uint64_t t = c->port->load(&h->torn);
    uint32_t id, k;
    /* A torn slot's radius 0 fails every later check, so the slot stays
     * dropped if this repair dies too. */
    for (k = 0; k < 2; k++) {
        uint32_t s = (uint32_t)(t >> (32u * k));
        if (s && s - 1u < h->count)
            irc__rec_at(c, s - 1u)->r = 0.0f;
    }
    irc__unmark(c);
    /* From the top: every slot above id is whole, so the last fills a
     * hole. */
    for (id = h->count; id-- > 0;)
        if (!irc__rec_sane(c, id)) {
            uint32_t last = h->count - 1u;
            if (id != last) {
                irc__mark(c, id, IRC__NIL);
                IRC_MEMCPY(irc__rec_at(c, id), irc__rec_at(c, last), c->rec_size);
                irc__unmark(c);
            }
            h->count = last;
        }
    irc__forget_locked(c);
    irc__index_rebuild(c);
    irc__index_compact(c);
    if (h->pass_open) {
        h->pass_base = h->count;
        c->port->store(&h->pending, 0);
        c->port->store(&h->packed, 0);
    }
}

int irc__write_lock(irc_cache *c)
{
    int st = c->port->write_lock(irc__lock(c));
    if (st < 0)
        return IRC_ERR_PORT;
    if (st > 0 || c->port->load(&irc__st(c)->writing))
        irc__repair_locked(c);
    irc__set(c, &irc__st(c)->writing, 1);
    return IRC_OK;
}

void irc__write_unlock(irc_cache *c)
{
    c->port->store(&irc__st(c)->writing, 0);
    c->port->write_unlock(irc__lock(c));
}

/* A port that finds the writer dead hands the read lock back untaken: the
 * write lock's repair runs first. */
int irc__read_lock(irc_cache *c)
{
    for (;;) {
        int st = c->port->read_lock(irc__lock(c));
        if (st == 0)
            return IRC_OK;
        if (st < 0 || (st = irc__write_lock(c)) < 0)
            return IRC_ERR_PORT;
        irc__write_unlock(c);
    }
}

void irc__read_unlock(irc_cache *c) { c->port->read_unlock(irc__lock(c)); }

/* A call a fill pass forbids (clear, snapshot read, merge) takes the write
 * lock only when no pass is open. */
int irc__write_lock_idle(irc_cache *c)
{
    if (irc__write_lock(c) < 0)
        return IRC_ERR_PORT;
    if (!irc__st(c)->pass_open)
        return IRC_OK;
    irc__write_unlock(c);
    return IRC_ERR_STATE;
}
