/*
 * snapshot.h -- the snapshot format's parts (snapshot.c) that merges
 * share, and the canonical order of records (merge.c).
 */
#ifndef IRC_SNAPSHOT_H
#define IRC_SNAPSHOT_H

#include "../base/kind.h"
/* merge.c: the canonical order of packed records, and a heap sort of
 * slots [first, first + n) by it */
int irc__order(const irc_cache *c, const unsigned char *a, const unsigned char *b);
void irc__sort(irc_cache *c, uint32_t first, uint32_t n);
uint32_t irc__unique(irc_cache *c, uint32_t first, uint32_t n);
void irc__zero_slots(irc_cache *c, uint32_t first, uint32_t n);

/* snapshot.c: the format's parts merge.c shares */
#define IRC__SNAP_HEAD 48u /* header bytes, its own CRC included */
#define IRC__SNAP_TAIL 4u  /* the CRC of everything before it */
int irc__snap_check(const irc_cache *c, uint64_t fingerprint, const unsigned char *d,
                    size_t size, uint32_t room, uint32_t *count);
void irc__convert(const irc_cache *c, const unsigned char *src, unsigned char *dst, int to_le);
unsigned irc__field_width(const irc_cache *c, uint32_t at);

#endif
