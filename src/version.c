/*
 * version.c -- the version the library was built as (irrcache.h).
 */
#include "irrcache.h"

unsigned irc_version_number(void)
{
    return IRC_VERSION_NUMBER;
}

const char *irc_version_string(void)
{
    return IRC_VERSION_STRING;
}
