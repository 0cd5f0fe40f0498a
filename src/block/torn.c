/*
 * torn.c -- writes a death may interrupt, named in the block: the block's
 * torn word holds the one or two slots whose bytes are being written (an
 * insert's slot, the two records a swap exchanges, a merge's copy), so
 * that the repair after a writer's death (lock.c) drops exactly those.
 */
#include "cache.h"
#include "torn.h"

void irc__set(irc_cache *c, uint64_t *w, uint64_t v)
{
    /* acq_rel: what follows is not written before the word is */
    uint64_t old = c->port->load(w);
    while (!c->port->cas(w, old, v))
        old = c->port->load(w);
}

void irc__mark(irc_cache *c, uint32_t a, uint32_t b)
{
    irc__set(c, &irc__st(c)->torn, (uint64_t)(uint32_t)(a + 1u) | (uint64_t)(uint32_t)(b + 1u) << 32);
}

void irc__unmark(irc_cache *c) { c->port->store(&irc__st(c)->torn, 0); }

void irc__rec_swap(irc_cache *c, uint32_t i, uint32_t j)
{
    unsigned char *a = (unsigned char *)irc__rec_at(c, i), *b = (unsigned char *)irc__rec_at(c, j);
    unsigned char tmp[64]; /* no record of the largest kind on the stack */
    uint32_t at, n;
    irc__mark(c, i, j);
    for (at = 0; at < c->rec_size; at += n) {
        n = c->rec_size - at < 64u ? c->rec_size - at : 64u;
        IRC_MEMCPY(tmp, a + at, n);
        IRC_MEMCPY(a + at, b + at, n);
        IRC_MEMCPY(b + at, tmp, n);
    }
    irc__unmark(c);
}

