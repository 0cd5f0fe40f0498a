/* user_config.h -- a user configuration header (-DIRC_USER_CONFIG) as a
 * port would write one: it replaces two macros of src/util.h and leaves
 * the others at their defaults.  make test builds the library with it and
 * checks that the replacements, and only they, took effect. */
#ifndef IRC_TEST_USER_CONFIG_H
#define IRC_TEST_USER_CONFIG_H
double irc_user_sqrt(double x);
void irc_user_assert(int ok);
#define IRC_SQRT(x) irc_user_sqrt(x)
#define IRC_ASSERT(x) irc_user_assert((x) != 0)
#endif
