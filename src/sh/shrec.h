/*
 * shrec.h -- the SH record's estimator: the basis (sh.c) and the
 * samples projected onto it with their gradients (shgrad.c).
 */
#ifndef IRC_SHREC_H
#define IRC_SHREC_H

#include "../base/kind.h"

/* The SH record kind (kind_sh.c, or absent.c's table when the build
 * leaves it out): its number in a block, its record's parts in order. */
#define IRC__KIND_SH_ID 2u
extern const irc__kind irc__kind_sh;
enum { IRC__P_SH, IRC__P_SH_GRAD };
#define IRC__SH_MAX_BANDS 5
#define IRC__NC (IRC__SH_MAX_BANDS * IRC__SH_MAX_BANDS)
/* L * L coefficients and the channels of an SH cache's records. */
#define IRC__SH_N(c) ((c)->cfg.sh.bands * (c)->cfg.sh.bands)
#define IRC__SH_CH(c) ((c)->cfg.sh.channels)
/* sh.c */
void irc__sh_eval(int bands, const float s[3], float *y, float (*grad)[3]);

/* shgrad.c: an SH record's samples summed. */
typedef struct irc__shsum {
    float c[3][IRC__NC];
    float g[3][3 * IRC__NC]; /* d c_i / dp at [3 i + k] */
    float e[3];
    float inv_d;
    uint32_t used, total;
} irc__shsum;
int irc__sh_sample(irc__call *k, irc__shsum *a);

#endif
