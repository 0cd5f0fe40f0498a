/* test.h -- a minimal harness: CHECK records a failure and goes on. */
#ifndef IRC_TEST_H
#define IRC_TEST_H

#include <stdio.h>

extern int irc_t_fails;
extern long irc_t_checks; /* CHECKs evaluated: a test that made none fails */
extern int irc_t_quick; /* IRC_TEST_QUICK: 1 sanitizer builds scale down, 2 make check */

#define CHECK(cond, ...)                                                    \
    do {                                                                    \
        irc_t_checks++;                                                     \
        if (!(cond)) {                                                      \
            irc_t_fails++;                                                  \
            printf("  %s:%d: CHECK(%s) failed: ", __FILE__, __LINE__, #cond); \
            printf(__VA_ARGS__);                                            \
            printf("\n");                                                   \
        }                                                                   \
    } while (0)

#define TEST(name) void name(void)

typedef struct test_case {
    const char *name;
    void (*fn)(void);
} test_case;

/* Declares every test of a list X(name) and builds its table. */
#define TEST_DECL(name) void name(void);
#define TEST_ROW(name) {#name, name},

int test_run(const test_case *all, size_t n, int argc, char **argv);

/* The library's SH basis (and its gradient, g may be NULL) and tangent
 * frame, which work in float, called from double (t_sh.c). */
void sh_eval_d(int bands, const double s[3], double *y, double (*g)[3]);
void frame_d(const double n[3], double t1[3], double t2[3]);

#endif
