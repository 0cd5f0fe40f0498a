/*
 * cachefile.c -- the demo's cache files: snapshots written and merged
 * through stdio, and the scene fingerprint they carry.
 */
#define _POSIX_C_SOURCE 200809L
#include "cachefile.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

/* Crash-safe: the snapshot goes to PATH.tmp.PID, is flushed to the disk
 * (fsync), and is renamed over PATH, which rename() replaces atomically: a
 * writer killed at any point leaves the old file or the new one, never a
 * torn one (at worst a stale .tmp file beside it). */
int cache_save(irc_cache *c, uint64_t fp, const char *path, char *err, size_t n)
{
    size_t len = strlen(path) + 32, written = 0;
    char *tmp = malloc(len);
    FILE *f = NULL;
    int st = -1, e = 0;
    if (tmp) {
        snprintf(tmp, len, "%s.tmp.%ld", path, (long)getpid());
        f = fopen(tmp, "wb");
    }
    if (!f) {
        snprintf(err, n, "%s: %s", path, tmp ? strerror(errno) : "out of memory");
        free(tmp);
        return -1;
    }
    st = irc_snapshot_write(c, fp, NULL, 0, to_file, f, &written);
    if (st >= 0 && (fflush(f) != 0 || fsync(fileno(f)) != 0))
        st = -1, e = errno;
    if (fclose(f) != 0 && st >= 0)
        st = -1, e = errno;
    if (st >= 0 && rename(tmp, path) != 0)
        st = -1, e = errno;
    if (st < 0) {
        remove(tmp);
        snprintf(err, n, "%s: %s", path,
                 st != -1 ? irc_strerror(st) : e ? strerror(e) : "write failed");
    }
    free(tmp);
    return st < 0 ? -1 : 0;
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
