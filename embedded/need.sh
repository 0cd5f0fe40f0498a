#!/bin/sh
# embedded/need.sh -- installs what `make cross` and `make embedded-test`
# need on a fresh Debian machine (as tests/run.sh does for its tools):
# the Arm bare-metal compiler, newlib, and QEMU's Arm system emulator.
# Installs when root with apt; otherwise says what to install and fails.
set -u
need=""
command -v arm-none-eabi-gcc >/dev/null 2>&1 || need="$need gcc-arm-none-eabi binutils-arm-none-eabi"
[ -d /usr/lib/arm-none-eabi/newlib ] || [ -e /usr/lib/arm-none-eabi/lib/libc.a ] ||
    need="$need libnewlib-arm-none-eabi"
command -v qemu-system-arm >/dev/null 2>&1 || need="$need qemu-system-arm"
[ -n "$need" ] || exit 0
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing:$need"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $need >/dev/null ||
        { echo "could not install:$need"; exit 1; }
else
    echo "needs:$need (sudo apt-get install$need)"
    exit 1
fi
