#!/bin/sh
# docs.sh -- the documents list what they promise to: every status code
# in README.md's "Status codes", every public call in "The API on one
# screen", every source file of the library in docs/DESIGN.md's "Source
# layout".  Prints what is missing; fails if anything is.
cd "$(dirname "$0")/.."
section() { # FILE HEADING: the lines from HEADING to the next heading of its level or above
    awk -v h="$2" '
        BEGIN { match(h, /^#+/); lvl = RLENGTH }
        index($0, h) == 1 { on = 1; next }
        on && match($0, /^#+ /) && RLENGTH - 1 <= lvl { exit }
        on { print }' "$1"
}
missing=0
status=$(section README.md "### Status codes")
for s in $(sed -n '/^typedef enum irc_status/,/} irc_status;/p' include/irrcache.h |
           grep -o 'IRC_[A-Z_]* *=' | tr -d ' ='); do
    case $status in *"$s"*) ;; *) echo "README.md, Status codes: $s missing"; missing=1 ;; esac
done
api=$(section README.md "## The API on one screen")
for f in $(grep -o 'IRC_API [^(]*(' include/irrcache.h | grep -o 'irc_[a-z0-9_]*' | sort -u); do
    case $api in *"$f"*) ;; *) echo "README.md, The API on one screen: $f missing"; missing=1 ;; esac
done
layout=$(section docs/DESIGN.md "## Source layout")
for f in src/*.c src/*.h src/*/*.c src/*/*.h port/*/*.c port/*.c; do
    name=${f#src/} # a library file by its path in src/: api/life.c
    name=${name#port/} # a port by its folder: posix/irc_port.c
    case $layout in *"$name"*) ;; *) echo "docs/DESIGN.md, Source layout: $f missing"; missing=1 ;; esac
done
[ $missing = 0 ] && echo "docs: every status, call and source file listed"
exit $missing
