/*
 * inspect.c -- the calls that read a cache's state or empty it: its
 * config as resolved (irc_cache_config), its counters and sizes
 * (irc_cache_stats), the records a lookup would use (irc_cache_neighbours),
 * and clearing (irc_cache_clear).
 */
#include "../block/check.h"
#include "../index/index.h"
#include "../store/lock.h"
#include "../store/lookup.h"
#include "../store/stats.h"

int irc_cache_config(irc_cache *c, irc_config *out)
{
    irc_config r;
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    r = c->cfg;
    r.clamp_neighbours = r.clamp_neighbours ? IRC_ON : IRC_OFF;
    r.check_visibility = r.check_visibility ? IRC_ON : IRC_OFF;
    if (c->kind->publish)
        c->kind->publish(&r);
    *out = r;
    return IRC_OK;
}

int irc_cache_stats(irc_cache *c, irc_stats *out)
{
    return irc__stats(c, out);
}

int irc_cache_neighbours(irc_cache *c, const float p[3], const float n[3], uint32_t *ids,
                         uint32_t cap, uint32_t *count)
{
    return irc__neighbours(c, p, n, ids, cap, count);
}

int irc_cache_clear(irc_cache *c)
{
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if ((st = irc__write_lock_idle(c)) < 0)
        return st;
    irc__clear_locked(c);
    irc__write_unlock(c);
    return IRC_OK;
}
