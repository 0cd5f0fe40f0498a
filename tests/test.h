/* test.h -- a minimal harness: CHECK records a failure and goes on. */
#ifndef IRC_TEST_H
#define IRC_TEST_H

#include <stdio.h>

extern int irc_t_fails;
extern int irc_t_quick; /* IRC_TEST_QUICK=1: sanitizer builds scale down */

#define CHECK(cond, ...)                                                    \
    do {                                                                    \
        if (!(cond)) {                                                      \
            irc_t_fails++;                                                  \
            printf("  %s:%d: CHECK(%s) failed: ", __FILE__, __LINE__, #cond); \
            printf(__VA_ARGS__);                                            \
            printf("\n");                                                   \
        }                                                                   \
    } while (0)

#define TEST(name) void name(void)

#endif
