#!/bin/sh
# farm-demo.sh [TILES] -- what `make farm-demo` runs: the Cornell box
# rendered by a Slurm job array of TILES tile jobs (default 4), each saving
# its records, then one job that merges them and renders the frame with no
# new records; beside it one single-process render to compare with.
# Starts a single-node Slurm of its own (farm/slurm-local.sh, as root) when
# no cluster answers; on a real cluster run it where sbatch works and the
# build directory is on a shared file system.
set -e
tiles=${1:-4}
root=$(cd "$(dirname "$0")/.." && pwd)
out=$root/build/farm
demo=$root/build/irc_demo
scene=$root/demo/scenes/cornell.scene
# Without neighbour clamping: a clamped record shrinks after the lookups
# it served, so the merged cache would miss a few pixels the tiles had
# covered (3 of 65,536 here) and the final job's check of 0 misses, that
# the tiles' records cover the frame, would not hold.  Without per-pixel
# detail for the same reason: a detail point is answered from its own
# hemisphere and leaves no record, so the final job's lookups there miss.
args="--size 256x256 --strata 16x64 --indirect --light-samples 1 --quiet --no-clamp --detail-pixels -1"
rm -rf "$out/jobs" && mkdir -p "$out/jobs"
own=0
if ! sinfo -h >/dev/null 2>&1; then
    sh "$root/farm/slurm-local.sh" start "$out/slurm"
    own=1
    export SLURM_CONF=$out/slurm/slurm.conf
    trap 'sh "$root/farm/slurm-local.sh" stop "$out/slurm"' EXIT
fi

echo "single process, 1 thread:"
t0=$(date +%s.%N)
"$demo" "$scene" $args --threads 1 --out "$out/jobs/single" | sed -n '2,3p'
t1=$(date +%s.%N)

env="ALL,DEMO=$demo,SCENE=$scene,TILES=$tiles,OUT=$out/jobs,ARGS=$args"
array=$(sbatch --parsable --array=0-$((tiles - 1)) --output="$out/jobs/slurm-%A_%a.out" \
    --export="$env" "$root/farm/tile.sbatch")
final=$(sbatch --parsable --dependency=afterok:"$array" --output="$out/jobs/slurm-%j.out" \
    --export="$env,COMPARE=--compare $out/jobs/single.exr" "$root/farm/final.sbatch")
echo "submitted: job array $array ($tiles tiles), final job $final (after the array)"
# sbatch --wait polls slowly; squeue every 0.2 s.
while squeue -h -j "$array,$final" 2>/dev/null | grep -q .; do sleep 0.2; done
t2=$(date +%s.%N)

fail=0
for i in $(seq 0 $((tiles - 1))); do
    log=$out/jobs/tile-$i.log
    if [ -f "$log" ]; then
        printf 'tile %d: %s; %s\n' "$i" "$(grep -o 'records [0-9]*' "$log" | head -1)" \
            "$(grep -o 'wall [0-9.]* s' "$log")"
    else
        echo "tile $i: no log (see $out/jobs/slurm-${array}_$i.out)"
        fail=1
    fi
done
if [ -f "$out/jobs/final.log" ]; then
    printf 'final: %s; %s; %s\n' "$(grep -o 'merged [0-9]* cache files*: [0-9]* records' "$out/jobs/final.log")" \
        "$(grep -o 'wall [0-9.]* s' "$out/jobs/final.log")" \
        "$(grep -o '[0-9]* misses computed and dropped' "$out/jobs/final.log")"
    grep -q ' 0 misses computed and dropped' "$out/jobs/final.log" || fail=1
    grep 'against' "$out/jobs/final.log" | sed 's/^ *against [^:]*:/final against the single-process render:/'
else
    echo "final: no log (see $out/jobs/slurm-$final.out)"
    fail=1
fi
if [ $own = 1 ] && [ -f "$out/slurm/jobcomp.txt" ]; then
    bad=$(grep -c 'JobState=\(FAILED\|CANCELLED\|TIMEOUT\|NODE_FAIL\)' "$out/slurm/jobcomp.txt" || true)
    [ "$bad" = 0 ] || { echo "$bad job(s) failed (see $out/slurm/jobcomp.txt)"; fail=1; }
fi
awk -v a="$t0" -v b="$t1" -v c="$t2" -v k="$tiles" 'BEGIN {
    printf "wall: single process %.1f s; farm (%d tile jobs on this machine, then the final job) %.1f s\n", b - a, k, c - b }'
exit $fail
