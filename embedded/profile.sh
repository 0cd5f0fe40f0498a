#!/bin/sh
# embedded/profile.sh PART -- where the instructions of one part of
# embedded/host.c go on the Cortex-M4F: 1 the irradiance records (one
# 16 x 64 record, trans + rot, and the sphere's 32 x 128), 2 the lookups
# among 1,000 records, 3 the SH record.  The library is built as make
# cross builds it, with -g; QEMU runs the host one instruction a block
# (-singlestep) and logs every block it executes (-d exec), and each
# address is counted and named by arm-none-eabi-addr2line (inlined code
# under the inlined function's name); LOOKUPS=N sets part 2's lookups
# (1,000; 0 counts the inserts alone).  Prints the instructions of the
# whole run by function, and the share in libgcc's software double.
set -eu
cd "$(dirname "$0")/.."
PART=${1:-1}
CROSS=${CROSS:-arm-none-eabi-}
B=build-prof
M4="-mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard -mthumb"
sh embedded/need.sh
command -v python3 >/dev/null || { echo "profile.sh needs python3"; exit 1; }
rm -rf $B
make -s CC=${CROSS}gcc AR=${CROSS}ar PORT=none BUILD=$B \
    OPT="$M4 -Os -g -ffunction-sections -fdata-sections" $B/libirrcache.a
${CROSS}gcc -std=c99 $M4 -Os -g -ffunction-sections -fdata-sections -DHOST_PART=$PART -DHOST_LOOKUPS=${LOOKUPS:-1000} \
    -Iinclude -Iembedded embedded/host.c embedded/board.c $B/libirrcache.a \
    --specs=rdimon.specs -nostartfiles -T embedded/mps2.ld -Wl,--gc-sections -lm -o $B/host.elf
# Each executed block is one line "Trace N: host [flags/pc/...] name".
qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native -singlestep -d exec,nochain \
    -D $B/exec.log -kernel $B/host.elf > $B/out.txt
awk '/^Trace/ { split($4, a, "/"); n[a[2]]++ } END { for (p in n) print p, n[p] }' \
    $B/exec.log > $B/pcs.txt
rm -f $B/exec.log
python3 - "$B" <<'PY'
import collections, subprocess, sys
b = sys.argv[1]
rows = [l.split() for l in open(b + '/pcs.txt')]
names = subprocess.run(['arm-none-eabi-addr2line', '-f', '-e', b + '/host.elf'] +
                       ['0x' + r[0] for r in rows], capture_output=True, text=True).stdout.split('\n')
by = collections.Counter()
for i, r in enumerate(rows):
    by[names[2 * i]] += int(r[1])
total = sum(by.values())
soft = sum(v for k, v in by.items()
           if k.startswith('__aeabi_d') or k.endswith('df3') or k.endswith('df2') or
           k in ('__extendsfdf2', '__truncdfsf2', '__fixdfsi', '__fixunsdfsi', '__floatsidf',
                 '__floatunsidf', 'floor', 'ldexp', 'frexp'))
print('instructions, whole run: %d; in software double: %d (%.1f%%)' % (total, soft, 100.0 * soft / total))
for k, v in by.most_common(25):
    print('%10d %5.1f%%  %s' % (v, 100.0 * v / total, k))
PY
