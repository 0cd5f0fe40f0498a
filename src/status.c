/*
 * status.c -- the one-line description of every status code.
 */
#include "irrcache.h"

const char *irc_strerror(int status)
{
    switch (status) {
    case IRC_OK: return "ok";
    case IRC_MISS: return "no record close enough (or an empty slot)";
    case IRC_NOT_STORED: return "computed, but the pool is full: not stored";
    case IRC_DETAIL: return "answered by the point's own estimate: stored nowhere";
    case IRC_ERR_NULL: return "a required pointer is NULL";
    case IRC_ERR_CONFIG: return "a config field is out of range, or not a live cache";
    case IRC_ERR_NONFINITE: return "a coordinate or value is NaN or infinite";
    case IRC_ERR_NORMAL: return "a normal is zero or not finite";
    case IRC_ERR_NOMEM: return "the block is smaller than irc_footprint() asks";
    case IRC_ERR_FULL: return "the record pool is full and eviction is off";
    case IRC_ERR_CALLBACK: return "the trace callback reported an invalid result";
    case IRC_ERR_NOSAMPLES: return "too few usable rays for a record";
    case IRC_ERR_BUSY: return "every scratch slot is in use and the cache does not wait";
    case IRC_ERR_UNSUPPORTED: return "a call this cache's kind or features do not serve";
    case IRC_ERR_PORT: return "the port could not initialise or take its lock";
    case IRC_ERR_RANGE: return "a value or index is out of its range";
    case IRC_ERR_TRUNCATED: return "the snapshot is shorter than its header says";
    case IRC_ERR_CORRUPT: return "the snapshot is corrupt (magic, checksum, length or values)";
    case IRC_ERR_VERSION: return "another version: a snapshot of another format, or a config not from IRC_CONFIG_INIT";
    case IRC_ERR_MISMATCH: return "the snapshot's kind or config differs from the cache's";
    case IRC_ERR_FINGERPRINT: return "the snapshot was made for another scene";
    case IRC_ERR_STATE: return "a fill pass is open, or none is, where the call needs otherwise";
    case IRC_ERR_NESTED: return "a trace callback called into the cache computing its record";
    default: return status < 0 ? "error from the trace callback" : "unknown status";
    }
}
