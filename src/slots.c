/*
 * Scratch slots: one per record computation in flight (cfg.threads), each
 * owned through a word in its head (cache.h irc__slot_owner) that holds
 * the claiming process's port token, so that a slot whose process died
 * can be taken over (irc_port owner / owner_alive).
 */
#include "cache.h"

/* The claiming process's token: the port's (its process id), or 1 for
 * a port that cannot tell processes apart.  Never 0, which marks a free
 * slot. */
static uint64_t irc__token(const irc_cache *c)
{
    uint64_t tok = c->port->owner ? c->port->owner() : 1u;
    return tok ? tok : 1u;
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
 * not to wait, or a port that cannot, reports IRC_ERR_BUSY. */
#define IRC__RECOVER_AFTER 256u
int irc__slot_claim(irc_cache *c, uint32_t *t, int *waited)
{
    const uint64_t me = irc__token(c);
    uint32_t spins = 0, i;
    for (;;) {
        for (i = 0; i < c->cfg.threads; i++) {
            uint64_t *own = irc__slot_owner(c, i);
            if (c->port->load(own) == 0 && c->port->cas(own, 0, me)) {
                *t = i;
                return IRC_OK;
            }
        }
        if ((c->cfg.no_wait || ++spins % IRC__RECOVER_AFTER == 0) &&
            irc__slot_recover(c, me, t))
            return IRC_OK;
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
    do
        tok = c->port->load(own);
    while (!c->port->cas(own, tok, 0));
}

