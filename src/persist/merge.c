/*
 * merge.c -- a snapshot's records added to a cache so that the result does
 * not depend on the order of merges: after every merge the records sit in
 * one canonical order with exact duplicates removed, and the index is
 * rebuilt from that order.
 */
#include "../block/cache.h"
#include "../block/check.h"
#include "../block/torn.h"
#include "../bytes.h"
#include "../index/index.h"
#include "../store/lock.h"
#include "snapshot.h"

/* The canonical order: field by field in the format's order, each field
 * compared as an unsigned integer of its width, so every machine sorts
 * alike whatever its byte order.  Returns <0, 0, >0. */
int irc__order(const irc_cache *c, const unsigned char *a, const unsigned char *b)
{
    uint32_t at = 0;
    while (at < c->rec_size) {
        unsigned w = irc__field_width(c, at);
        uint64_t x = irc__native_get(a + at, w), y = irc__native_get(b + at, w);
        if (x != y)
            return x < y ? -1 : 1;
        at += w;
    }
    return 0;
}

static unsigned char *irc__bytes(const irc_cache *c, uint32_t id)
{
    return (unsigned char *)irc__rec_at(c, id);
}

/* Heap positions are relative to first. */
static void irc__sift(irc_cache *c, uint32_t first, uint32_t root, uint32_t n)
{
    for (;;) {
        uint32_t child = 2 * root + 1;
        if (child >= n)
            return;
        if (child + 1 < n &&
            irc__order(c, irc__bytes(c, first + child), irc__bytes(c, first + child + 1)) < 0)
            child++;
        if (irc__order(c, irc__bytes(c, first + root), irc__bytes(c, first + child)) >= 0)
            return;
        irc__rec_swap(c, first + root, first + child);
        root = child;
    }
}

/* Heap sort in the record pool itself: no memory beyond 64 bytes. */
void irc__sort(irc_cache *c, uint32_t first, uint32_t n)
{
    uint32_t i;
    for (i = n / 2; i-- > 0;)
        irc__sift(c, first, i, n);
    for (i = n; i-- > 1;) {
        irc__rec_swap(c, first, first + i);
        irc__sift(c, first, 0, i);
    }
}

/* Sorted slots [first, first + n) with runs of equal records kept once,
 * moved down.  Returns the records kept; the caller zeroes the slots
 * freed (irc__zero_slots) once they are no longer counted in. */
void irc__zero_slots(irc_cache *c, uint32_t first, uint32_t n)
{
    IRC_MEMSET(irc__bytes(c, first), 0, (size_t)n * c->rec_size);
}

uint32_t irc__unique(irc_cache *c, uint32_t first, uint32_t n)
{
    uint32_t i, kept;
    for (i = kept = 0; i < n; i++)
        if (kept == 0 ||
            irc__order(c, irc__bytes(c, first + kept - 1), irc__bytes(c, first + i)) != 0) {
            if (kept != i) {
                irc__mark(c, first + kept, IRC__NIL);
                IRC_MEMCPY(irc__bytes(c, first + kept), irc__bytes(c, first + i), c->rec_size);
                irc__unmark(c);
            }
            kept++;
        }
    return kept;
}

int irc_merge(irc_cache *c, uint64_t fingerprint, const void *data, size_t size)
{
    const unsigned char *d = (const unsigned char *)data;
    uint32_t count = 0, i, n, kept;
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (!data)
        return IRC_ERR_NULL;
    if ((st = irc__write_lock_idle(c)) < 0)
        return st;
    st = irc__snap_check(c, fingerprint, d, size, c->capacity - irc__st(c)->count, &count);
    if (st < 0) {
        irc__write_unlock(c);
        return st;
    }
    n = irc__st(c)->count + count;
    for (i = 0; i < count; i++)
        irc__convert(c, d + IRC__SNAP_HEAD + (size_t)i * c->rec_size,
                     irc__bytes(c, irc__st(c)->count + i), 0);
    /* Counted in before the sort moves them among the others: the repair
     * after a death (lock.c) keeps the records counted and drops the rest. */
    irc__st(c)->count = n;
    irc__sort(c, 0, n);
    kept = irc__unique(c, 0, n);
    irc__st(c)->count = kept;
    irc__zero_slots(c, kept, n - kept);
    /* The index and CLOCK start over from the canonical order. */
    irc__forget_locked(c);
    irc__index_rebuild(c);
    irc__index_compact(c);
    irc__write_unlock(c);
    return IRC_OK;
}
