/*
 * store.c -- records in and out of the pool: insert (into a free slot, or
 * CLOCK's victim, or in an open fill pass a reserved slot past the frozen
 * records), neighbour clamping, a record read back by id, and clearing.
 * Anything that changes records or the index holds the write lock
 * (lock.c); a slot being written is named in the block (torn.c) so that a
 * writer's death leaves nothing half written.  Counters are updated only
 * once a call has succeeded, so a call that fails leaves the block as it
 * was.
 */
#include "../block/cache.h"
#include "../block/check.h"
#include "../block/torn.h"
#include "../index/index.h"
#include "lock.h"
#include "stats.h"
#include "store.h"

/* Second-chance CLOCK: the hand clears the bit of every used record it
 * passes and stops at the first unused one.  Two turns at most. */
static uint32_t irc__clock_victim(irc_cache *c)
{
    uint64_t *used = irc__used(c);
    for (;;) {
        uint32_t id = irc__st(c)->hand;
        uint64_t *w = &used[id >> 6], bit = 1ull << (id & 63u);
        irc__st(c)->hand = id + 1 == c->capacity ? 0 : id + 1;
        if (!(c->port->load(w) & bit))
            return id;
        c->port->store(w, c->port->load(w) & ~bit);
    }
}

/* Neighbour clamping (Krivanek et al. 2006): records j within the new
 * record's radius R give R = min(R, R_j + |x - x_j|), then records whose
 * radius holds x get R_j = min(R_j, R + |x - x_j|), so that radii change
 * no faster than distance (only such pairs can break that).  Done
 * under the write lock, after the insert can no longer fail; a shrunk
 * R_j keeps every index bound an upper bound, and removal finds records
 * whose home moved deeper (index.c). */
typedef struct irc__near {
    irc_cache *c;
    irc__rec *r;
    int back;
} irc__near;

static void irc__clamp_visit(void *ud, uint32_t id)
{
    irc__near *k = (irc__near *)ud;
    irc__rec *j = irc__rec_at(k->c, id);
    float dx = j->p[0] - k->r->p[0], dy = j->p[1] - k->r->p[1],
           dz = j->p[2] - k->r->p[2], d = IRC_SQRTF(dx * dx + dy * dy + dz * dz);
    if (!k->back && d < k->r->r && j->r + d < k->r->r)
        k->r->r = (float)(j->r + d);
    else if (k->back && d < j->r && k->r->r + d < j->r) {
        j->r = (float)(k->r->r + d);
        irc__index_tighten(k->c, id);
    }
}

static void irc__clamp_neighbours(irc_cache *c, irc__rec *r)
{
    irc__near k;
    k.c = c;
    k.r = r;
    k.back = 0;
    irc__index_range(c, r->p, r->r, irc__clamp_visit, &k);
    k.back = 1;
    irc__index_range(c, r->p, -1.0f, irc__clamp_visit, &k);
    if (r->r < c->cfg.min_radius)
        r->r = c->cfg.min_radius;
}

void irc__commit_locked(irc_cache *c, uint32_t id)
{
    if (c->cfg.clamp_neighbours)
        irc__clamp_neighbours(c, irc__rec_at(c, id));
    irc__index_insert(c, id);
    irc__index_tidy(c);
    irc__count(c, IRC__C_INSERTS, 1);
}

/* A checked record packed straight into its slot: no packed copy of the
 * largest kind on the stack. */
static void irc__pack_at(irc_cache *c, const void *rec, const float un[3], uint32_t id)
{
    IRC_MEMSET(irc__rec_at(c, id), 0, c->rec_size);
    c->kind->pack(c, rec, un, irc__rec_at(c, id));
}

/* In an open pass a record waits, unindexed, in a slot of its own past the
 * frozen records until irc_pass_end; the slot is reserved atomically, so
 * no lock is taken and lookups, which see only indexed records, are not
 * disturbed.  A pass never evicts (that would change what its lookups
 * see): without a free slot the record is not stored. */
static int irc__store_in_pass(irc_cache *c, const void *rec, const float un[3])
{
    const uint64_t room = (uint64_t)(c->capacity - irc__st(c)->pass_base);
    uint64_t k = c->port->load(&irc__st(c)->pending);
    /* Reserved only when there is room: a refused record leaves the
     * block as it was. */
    for (;;) {
        if (k >= room)
            return IRC_ERR_FULL;
        if (c->port->cas(&irc__st(c)->pending, k, k + 1))
            break;
        k = c->port->load(&irc__st(c)->pending);
    }
    irc__pack_at(c, rec, un, irc__st(c)->pass_base + (uint32_t)k);
    c->port->fetch_add(&irc__st(c)->packed, 1);
    return IRC_OK;
}

/* Stores a checked record (un: its unit normal) in a free slot, or in
 * CLOCK's victim. */
static int irc__store(irc_cache *c, const void *rec, const float un[3])
{
    uint32_t id;
    if (irc__st(c)->pass_open)
        return irc__store_in_pass(c, rec, un);
    if (irc__write_lock(c) < 0)
        return IRC_ERR_PORT;
    if (irc__st(c)->count < c->capacity) {
        id = irc__st(c)->count++;
    } else if (c->o_used) {
        id = irc__clock_victim(c);
        irc__index_remove(c, id);
        irc__count(c, IRC__C_EVICTIONS, 1);
    } else {
        irc__write_unlock(c);
        return IRC_ERR_FULL;
    }
    irc__mark(c, id, IRC__NIL);
    irc__pack_at(c, rec, un, id);
    irc__unmark(c);
    irc__commit_locked(c, id);
    irc__write_unlock(c);
    return IRC_OK;
}

int irc__store_refresh(irc_cache *c, uint32_t id, const void *rec)
{
    float un[3];
    int st;
    if ((st = c->kind->check(c, rec, un)) < 0)
        return st;
    if (irc__write_lock(c) < 0)
        return IRC_ERR_PORT;
    irc__mark(c, id, IRC__NIL);
    irc__pack_at(c, rec, un, id);
    irc__unmark(c);
    irc__write_unlock(c);
    return IRC_OK;
}

int irc__insert_checked(irc_cache *c, const void *rec)
{
    float un[3];
    int st;
    if ((st = c->kind->check(c, rec, un)) < 0)
        return st;
    return irc__store(c, rec, un);
}

int irc__insert(irc_cache *c, const irc__kind *want, const void *rec)
{
    int st = irc__enter(c, want);
    if (st < 0)
        return st;
    return rec ? irc__insert_checked(c, rec) : IRC_ERR_NULL;
}

int irc__record_get(irc_cache *c, const irc__kind *want, uint32_t id, void *out)
{
    int st = irc__enter(c, want);
    if (st < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    if (id >= c->capacity)
        return IRC_ERR_RANGE;
    if (irc__read_lock(c) < 0)
        return IRC_ERR_PORT;
    st = id < irc__st(c)->count ? IRC_OK : IRC_MISS;
    if (st == IRC_OK)
        c->kind->unpack(c, irc__rec_at(c, id), out);
    irc__read_unlock(c);
    return st;
}
