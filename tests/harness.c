/* harness.c -- runs the tests named on the command line (by prefix), or
 * all of them, each with its wall time, and ends with "N passed, N
 * failed".  A test that evaluated no CHECK fails: it proved nothing. */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "test.h"

int irc_t_fails;
long irc_t_checks;
int irc_t_quick;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int test_run(const test_case *all, size_t n, int argc, char **argv)
{
    int passed = 0, failed = 0;
    double start = now_s();
    size_t i;
    const char *q = getenv("IRC_TEST_QUICK");
    irc_t_quick = q ? atoi(q) : 0; /* 1: sanitizer builds; 2: make check */
    for (i = 0; i < n; i++) {
        int run = argc < 2, a, before;
        long checks;
        double t0;
        for (a = 1; a < argc; a++)
            if (strncmp(all[i].name, argv[a], strlen(argv[a])) == 0)
                run = 1;
        if (!run)
            continue;
        printf("%s\n", all[i].name);
        fflush(stdout);
        before = irc_t_fails;
        checks = irc_t_checks;
        t0 = now_s();
        all[i].fn();
        if (irc_t_checks == checks) {
            irc_t_fails++;
            printf("  no CHECK was made\n");
        }
        if (irc_t_fails == before) {
            passed++;
            printf("ok   %s (%.2f s)\n", all[i].name, now_s() - t0);
        } else {
            failed++;
            printf("FAIL %s (%.2f s)\n", all[i].name, now_s() - t0);
        }
        fflush(stdout);
    }
    printf("%.1f s in all\n", now_s() - start);
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
