#!/bin/sh
# examples/need-embree.sh -- installs what `make embree-example` needs on a
# fresh Debian machine: Embree 3's headers and library (libembree-dev).
# Installs when root with apt; otherwise says what to install and fails.
set -u
[ -e /usr/include/embree3/rtcore.h ] && exit 0
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing: libembree-dev"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends libembree-dev >/dev/null ||
        { echo "could not install: libembree-dev"; exit 1; }
else
    echo "needs: libembree-dev (sudo apt-get install libembree-dev)"
    exit 1
fi
