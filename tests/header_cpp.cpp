// Compile-only: the public header from C++ (no C++ runtime is linked).
#include "irrcache.h"

static int trace(const irc_trace_args *a)
{
    return a->count ? 0 : -1;
}

int header_cpp_use(void);
int header_cpp_use(void)
{
    irc_config cfg = IRC_CONFIG_INIT;
    size_t bytes = 0;
    cfg.trace = trace;
    cfg.features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
    return irc_footprint(&cfg, 16, &bytes) == IRC_OK && bytes > 0 ? 0 : 1;
}
