/*
 * shrec.h -- the SH record's estimator: the basis (sh.c) and the
 * samples projected onto it with their gradients (shgrad.c).
 */
#ifndef IRC_SHREC_H
#define IRC_SHREC_H

#include "cache.h"
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
