/*
 * cachefile.c -- the demo's cache files: snapshots written and merged
 * through stdio, and the scene fingerprint they carry.
 */
#include "cachefile.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* FNV-1a, 64 bits, over the scene file's bytes: a snapshot made for
 * another scene file (or another version of it) is refused by the
 * library with IRC_ERR_FINGERPRINT.  The mesh the file names is not
 * hashed: edit it and rename it. */
int scene_fingerprint(const char *path, uint64_t *fp)
{
    FILE *f = fopen(path, "rb");
    uint64_t h = 0xcbf29ce484222325ull;
    int ch;
    if (!f)
        return -1;
    while ((ch = getc(f)) != EOF)
        h = (h ^ (uint64_t)(unsigned char)ch) * 0x100000001b3ull;
    fclose(f);
    *fp = h;
    return 0;
}

static int to_file(void *context, const void *bytes, size_t count)
{
    return fwrite(bytes, 1, count, (FILE *)context) == count ? 0 : -1;
}

int cache_save(irc_cache *c, uint64_t fp, const char *path, char *err, size_t n)
{
    FILE *f = fopen(path, "wb");
    size_t written = 0;
    int st;
    if (!f) {
        snprintf(err, n, "%s: %s", path, strerror(errno));
        return -1;
    }
    st = irc_snapshot_write(c, fp, NULL, 0, to_file, f, &written);
    if (fclose(f) != 0 && st >= 0)
        st = -1;
    if (st < 0) {
        snprintf(err, n, "%s: %s", path, st == -1 ? "write failed" : irc_strerror(st));
        return -1;
    }
    return 0;
}

int cache_merge(irc_cache *c, uint64_t fp, const char *path, char *err, size_t n)
{
    FILE *f = fopen(path, "rb");
    unsigned char *buf = NULL;
    long size;
    int st = -1;
    if (!f) {
        snprintf(err, n, "%s: %s", path, strerror(errno));
        return -1;
    }
    if (fseek(f, 0, SEEK_END) == 0 && (size = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (buf = malloc((size_t)size + 1)) && fread(buf, 1, (size_t)size, f) == (size_t)size) {
        st = irc_merge(c, fp, buf, (size_t)size);
        if (st < 0)
            snprintf(err, n, "%s: %s", path, irc_strerror(st));
    } else {
        snprintf(err, n, "%s: cannot read", path);
    }
    free(buf);
    fclose(f);
    return st < 0 ? -1 : 0;
}
