/*
 * cachefile.h -- the demo's cache files (snapshots on disk).
 */
#ifndef DEMO_CACHEFILE_H
#define DEMO_CACHEFILE_H

#include <stddef.h>
#include <stdint.h>

#include "irrcache.h"

/* The 64-bit fingerprint of a scene file (FNV-1a of its bytes). */
int scene_fingerprint(const char *path, uint64_t *fp);
/* The cache's snapshot into path; 0, or -1 with a message in err. */
int cache_save(irc_cache *c, uint64_t fp, const char *path, char *err, size_t n);
/* A snapshot file merged into the cache (irc_merge); 0, or -1 and err. */
int cache_merge(irc_cache *c, uint64_t fp, const char *path, char *err, size_t n);

#endif
