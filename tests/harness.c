/* harness.c -- runs the tests named on the command line (by prefix), or
 * all of them, and ends with "N passed, N failed". */
#include <stdlib.h>
#include <string.h>

#include "test.h"

int irc_t_fails;
int irc_t_quick;

int test_run(const test_case *all, size_t n, int argc, char **argv)
{
    int passed = 0, failed = 0;
    size_t i;
    const char *q = getenv("IRC_TEST_QUICK");
    irc_t_quick = q && *q && *q != '0';
    for (i = 0; i < n; i++) {
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
