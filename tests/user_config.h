/* user_config.h -- a user configuration header (-DIRC_USER_CONFIG) as a
 * port would write one: it replaces two macros of src/util.h and leaves
 * the others at their defaults.  make test builds the library with it and
 * checks that the replacements, and only they, took effect. */
#ifndef IRC_TEST_USER_CONFIG_H
#define IRC_TEST_USER_CONFIG_H
float irc_user_sqrtf(float x);
void irc_user_assert(int ok);
#define IRC_SQRTF(x) irc_user_sqrtf(x)
#define IRC_ASSERT(x) irc_user_assert((x) != 0)
#endif
