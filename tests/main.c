/* main.c -- runs the tests named on the command line (prefixes), or all. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"

int irc_t_fails;
int irc_t_quick;

#define TESTS(X)                                                     \
    X(test_uniform_sky) X(test_sphere_over_plane) X(test_flat_blocker)                    \
    X(test_rotational_gradient_sky) X(test_radius_rules)             \
    X(test_pack_roundtrip) X(test_weighted_mean) X(test_behind_relative)  \
    X(test_extrapolation) X(test_lookup_or_compute) X(test_full_no_evict) \
    X(test_evict_clock) X(test_index_exact) X(test_index_scales)          \
    X(test_config_checks) X(test_footprints) X(test_init_block)         \
    X(test_bad_input_unchanged) X(test_callback_failures) X(test_ports) \
    X(test_threads_stress) X(test_threads_determinism)

#define DECL(name) void name(void);
TESTS(DECL)

static const struct { const char *name; void (*fn)(void); } all[] = {
#define ROW(name) {#name, name},
    TESTS(ROW)
};

int main(int argc, char **argv)
{
    int passed = 0, failed = 0;
    size_t i;
    const char *q = getenv("IRC_TEST_QUICK");
    irc_t_quick = q && *q && *q != '0';
    for (i = 0; i < sizeof all / sizeof all[0]; i++) {
        int run = argc < 2, a, before;
        for (a = 1; a < argc; a++)
            if (strncmp(all[i].name, argv[a], strlen(argv[a])) == 0)
                run = 1;
        if (!run)
            continue;
        printf("%s\n", all[i].name);
        fflush(stdout);
        before = irc_t_fails;
        all[i].fn();
        if (irc_t_fails == before) {
            passed++;
            printf("ok   %s\n", all[i].name);
        } else {
            failed++;
            printf("FAIL %s\n", all[i].name);
        }
        fflush(stdout);
    }
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
