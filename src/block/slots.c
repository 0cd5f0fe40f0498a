/*
 * Scratch slots: one per record computation in flight (cfg.threads), each
 * owned through a word in its head (form.h irc__slot_owner) that holds
 * the claiming process's port token, so that a slot whose process died
 * can be taken over (irc_port owner / owner_alive), and the second the
 * claiming thread's (irc_port thread), so that a call nested in its own
 * cache's callback is told so instead of waiting for its own slot.
 */
#include "form.h"
#include "slots.h"

/* The claiming process's token: the port's (its process id), or 1 for
 * a port that cannot tell processes apart.  Never 0, which marks a free
 * slot. */
static uint64_t irc__token(const irc_cache *c)
{
    uint64_t tok = c->port->owner ? c->port->owner() : 1u;
    return tok ? tok : 1u;
}

/* The calling thread's token, or 0 when the port cannot tell threads
 * apart; a port that cannot yield runs one thread, token 1. */
static uint64_t irc__thread(const irc_cache *c)
{
    if (c->port->thread) {
        uint64_t th = c->port->thread();
        return th ? th : 1u;
    }
    return c->port->yield ? 0u : 1u;
}

/* Whether this thread already holds a slot: it is inside a callback of
 * this cache.  Only this thread writes its token into a slot's head, and
 * it clears it before releasing, so a match is never stale. */
static int irc__nested(const irc_cache *c, uint64_t me, uint64_t th)
{
    uint32_t i;
    if (!th)
        return 0;
    for (i = 0; i < c->cfg.threads; i++) {
        uint64_t *own = irc__slot_owner(c, i);
        if (c->port->load(own) == me && c->port->load(own + 1) == th)
            return 1;
    }
    return 0;
}

/* A slot whose owner process is gone (it died inside a computation) is
 * taken over: its working area is zeroed as a release would. */
static int irc__slot_recover(irc_cache *c, uint64_t me, uint32_t *t)
{
    uint32_t i;
    if (!c->port->owner_alive)
        return 0;
    for (i = 0; i < c->cfg.threads; i++) {
        uint64_t *own = irc__slot_owner(c, i), tok = c->port->load(own);
        if (tok && !c->port->owner_alive(tok) && c->port->cas(own, tok, me)) {
            IRC_MEMSET(irc__slot(c, i), 0, c->slot_bytes - IRC__ALIGN);
            *t = i;
            return 1;
        }
    }
    return 0;
}

/* Claims a free scratch slot (index in *t): its owner word 0 -> this
 * process's token.  When all are taken it waits through the port's yield,
 * so a miss always gets its value, and every IRC__RECOVER_AFTER waits (at
 * once with no_wait) looks for a slot whose owner died; only a cache told
 * not to wait, or a port that cannot, reports IRC_ERR_BUSY.  A thread that
 * holds a slot already gets IRC_ERR_NESTED: it could wait for itself. */
#define IRC__RECOVER_AFTER 256u
int irc__slot_claim(irc_cache *c, uint32_t *t, int *waited)
{
    const uint64_t me = irc__token(c), th = irc__thread(c);
    uint32_t spins = 0, i;
    if (irc__nested(c, me, th))
        return IRC_ERR_NESTED;
    for (;;) {
        for (i = 0; i < c->cfg.threads; i++) {
            uint64_t *own = irc__slot_owner(c, i);
            if (c->port->load(own) == 0 && c->port->cas(own, 0, me)) {
                c->port->store(own + 1, th);
                *t = i;
                return IRC_OK;
            }
        }
        if ((c->cfg.no_wait || ++spins % IRC__RECOVER_AFTER == 0) &&
            irc__slot_recover(c, me, t)) {
            c->port->store(irc__slot_owner(c, *t) + 1, th);
            return IRC_OK;
        }
        if (c->cfg.no_wait || !c->port->yield)
            return IRC_ERR_BUSY;
        *waited = 1;
        c->port->yield();
    }
}

/* Zeroes the slot, so that a failed call leaves the block as it was and no
 * samples outlive it, and frees it through the acq_rel CAS, so that its
 * next owner sees this thread's writes as done. */
void irc__slot_release(irc_cache *c, uint32_t t)
{
    uint64_t *own = irc__slot_owner(c, t), tok;
    IRC_MEMSET(irc__slot(c, t), 0, c->slot_bytes - IRC__ALIGN);
    c->port->store(own + 1, 0);
    do
        tok = c->port->load(own);
    while (!c->port->cas(own, tok, 0));
}

