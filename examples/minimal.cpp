// minimal.cpp -- minimal.c's host from C++: the header is plain C inside
// extern "C", the trace callback a captureless lambda, the block a vector.
// Prints the same lines (E along a line next to a black ball, and the
// closed form).
#include <cmath>
#include <cstdio>
#include <vector>

#include "irrcache.h"

int main()
{
    if (irc_version_number() / 100 != IRC_VERSION_NUMBER / 100) {
        std::fprintf(stderr, "irrcache %s loaded, %s expected\n", irc_version_string(),
                     IRC_VERSION_STRING);
        return 1;
    }
    irc_config cfg = IRC_CONFIG_INIT;
    // A black unit ball centred at (0, 0, 2) under a sky of radiance 1.
    cfg.trace = [](const irc_trace_args *a) -> int {
        for (uint32_t i = 0; i < a->count; i++) {
            const float *o = a->rays[i].org, *d = a->rays[i].dir;
            irc_hit &h = a->hits[i];
            const float oc[3] = {o[0], o[1], o[2] - 2.0f};
            const float b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
            const float c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - 1.0f;
            const float disc = b * b - c, t = -b - std::sqrt(disc > 0.0f ? disc : 0.0f);
            const bool hit = disc > 0.0f && t > 0.0f;
            h.status = hit ? IRC_RAY_HIT : IRC_RAY_ESCAPED;
            h.dist = hit ? t : 0.0f;
            for (int k = 0; k < 3; k++) {
                h.normal[k] = hit ? oc[k] + t * d[k] : 0.0f;
                h.radiance[k] = hit ? 0.0f : 1.0f;
            }
        }
        return 0;
    };
    cfg.max_batch = 64;
    cfg.max_radius = 4.0f;
    size_t bytes = 0;
    int st = irc_footprint(&cfg, 1000, &bytes);
    if (st < 0)
        return std::fprintf(stderr, "%s\n", irc_strerror(st)), 1;
    std::vector<unsigned char> block(bytes);
    cfg.buffer = block.data();
    cfg.buffer_size = block.size();
    irc_cache *cache = 0;
    if ((st = irc_init(&cfg, 1000, &cache)) < 0)
        return std::fprintf(stderr, "%s\n", irc_strerror(st)), 1;
    for (int i = 0; i <= 8; i++) {
        const float p[3] = {0.25f * i, 0.0f, 0.0f}, n[3] = {0.0f, 0.0f, 1.0f};
        float rgb[3], w;
        const double d2 = p[0] * p[0] + 4.0, exact = 3.14159265 * (1.0 - 2.0 / (d2 * std::sqrt(d2)));
        if ((st = irc_cache_lookup_or_compute(cache, p, n, rgb, &w, 0)) < 0)
            return std::fprintf(stderr, "%s\n", irc_strerror(st)), 1;
        std::printf("x = %.2f  E = %.4f  exact %.4f  %s\n", p[0], rgb[0], exact,
                    w > 0.0f ? "(interpolated)" : "(new record)");
    }
    irc_fini(cache);
    return 0;
}
