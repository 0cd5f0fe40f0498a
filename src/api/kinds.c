/*
 * kinds.c -- the record kinds a build has: the one list, and how a config
 * or a block picks one.  A kind is one file (its table, kind.h) and one
 * line here; IRC_KIND_EXTRA adds a kind built outside src/ (a program
 * compiles this file again with it, as the tests do with tests/kind_occ.c).
 */
#include "../base/kind.h"

extern const irc__kind irc__kind_irr, irc__kind_sh;
#ifdef IRC_KIND_EXTRA
extern const irc__kind IRC_KIND_EXTRA;
#endif

/* The first takes a config that names no kind's features. */
static const irc__kind *const irc__kinds[] = {
    &irc__kind_irr, &irc__kind_sh,
#ifdef IRC_KIND_EXTRA
    &IRC_KIND_EXTRA,
#endif
};
#define IRC__N_KINDS (sizeof irc__kinds / sizeof irc__kinds[0])

const irc__kind *irc__kind_of(uint32_t features)
{
    uint32_t i;
    for (i = 1; i < IRC__N_KINDS; i++)
        if (features & irc__kinds[i]->features)
            return irc__kinds[i];
    return irc__kinds[0];
}

const irc__kind *irc__kind_by_id(uint32_t id)
{
    uint32_t i;
    for (i = 0; i < IRC__N_KINDS; i++)
        if (irc__kinds[i]->id == id)
            return irc__kinds[i];
    return NULL;
}

int irc__kind_features(uint32_t features)
{
    uint32_t i, known = 0, kinds = 0;
    for (i = 0; i < IRC__N_KINDS; i++) {
        known |= irc__kinds[i]->features;
        kinds += (features & irc__kinds[i]->features) != 0;
    }
    if ((features & ~known) || kinds > 1)
        return IRC_ERR_CONFIG;
    /* A kind this build leaves out keeps a table of its features alone
     * (absent.c), so that its configs are named as unsupported, not as
     * wrong. */
    return features & irc__kind_of(features)->unbuilt ? IRC_ERR_UNSUPPORTED : IRC_OK;
}

int irc__kind_fields_alone(const irc__kind *k, const irc_config *cfg)
{
    const unsigned char *b = (const unsigned char *)cfg;
    uint32_t i, j;
    for (i = 0; i < IRC__N_KINDS; i++)
        if (irc__kinds[i] != k)
            for (j = 0; j < irc__kinds[i]->cfg_bytes; j++)
                if (b[irc__kinds[i]->cfg_at + j])
                    return IRC_ERR_CONFIG;
    return IRC_OK;
}
