#!/usr/bin/env bash
# splat_world --from as a user runs it: a capture imported whole, and in two shards run at once (one of
# them twice at once) then merged, gives the same world.json and the same bytes in every file of its
# generation folder; a merge with a shard missing, --count-only with --from and a missing --cameras file
# fail with exit code 1 and a message naming the problem.
#   splat_world_import_cli_test.sh SPLAT_WORLD SPLAT_SYNTH OUTPUT_DIR
set -uo pipefail
world=$1
synth=$2
dir=$3
rm -rf "$dir"
mkdir -p "$dir"
# shellcheck source=cli_test_lib.sh
source "$(dirname "$0")/cli_test_lib.sh"
fast=(--max-chunk-gaussians 2048 --bake-width 64 --bake-height 64 --refine-iterations 0 --threads 1)

"$synth" --out "$dir/garden.ply" --seed 3 --detail 0.02 >/dev/null || { echo "FAIL: splat_synth"; exit 1; }
"$world" --from "$dir/garden.ply" --out "$dir/whole" "${fast[@]}" > "$dir/whole.log" 2>&1 ||
  fail "whole import: $(tail -n 3 "$dir/whole.log")"
grep -q "^frame: up (0.0000, 1.0000, 0.0000)" "$dir/whole.log" || fail "the garden's up: $(grep '^frame' "$dir/whole.log")"

"$world" --from "$dir/garden.ply" --out "$dir/sharded" "${fast[@]}" --shard 1/2 > "$dir/s1.log" 2>&1 ||
  fail "shard 1/2: $(tail -n 3 "$dir/s1.log")"
expect_failure merge_with_a_shard_missing "missing shards 2/2" \
  "$world" --from "$dir/garden.ply" --out "$dir/sharded" "${fast[@]}" --merge
[ -e "$dir/sharded/world.json" ] && fail "the failed merge wrote world.json"

# Shard 2/2 twice at once (a requeued task whose first run still runs), beside shard 1/2 run again.
"$world" --from "$dir/garden.ply" --out "$dir/sharded" "${fast[@]}" --shard 2/2 > "$dir/s2.log" 2>&1 &
"$world" --from "$dir/garden.ply" --out "$dir/sharded" "${fast[@]}" --shard 2/2 --force > "$dir/s2b.log" 2>&1 &
"$world" --from "$dir/garden.ply" --out "$dir/sharded" "${fast[@]}" --shard 1/2 --force > "$dir/s1b.log" 2>&1 &
wait %1 || fail "shard 2/2: $(tail -n 3 "$dir/s2.log")"
wait %2 || fail "shard 2/2 at the same time: $(tail -n 3 "$dir/s2b.log")"
wait %3 || fail "shard 1/2 again: $(tail -n 3 "$dir/s1b.log")"
grep -q "^shard 2/2: .*shard-2-of-2.json" "$dir/s2.log" || fail "shard 2/2 printed: $(tail -n 2 "$dir/s2.log")"
"$world" --from "$dir/garden.ply" --out "$dir/sharded" "${fast[@]}" --merge > "$dir/merge.log" 2>&1 ||
  fail "merge: $(tail -n 3 "$dir/merge.log")"
cmp -s "$dir/whole/world.json" "$dir/sharded/world.json" || fail "world.json differs between whole and sharded"
diff -r "$dir/whole/gen-1" "$dir/sharded/gen-1" > "$dir/diff.log" 2>&1 || fail "files differ: $(head -n 3 "$dir/diff.log")"
ls -d "$dir"/sharded/staging-* > /dev/null 2>&1 && fail "the staging folder outlived the merge"
echo "ok   sharded import merged to the whole import's bytes: $(grep '^merged world' "$dir/merge.log")"

expect_failure count_only_with_from "--count-only is for generated worlds" \
  "$world" --from "$dir/garden.ply" --out "$dir/other" "${fast[@]}" --count-only
expect_failure missing_cameras "missing.json" \
  "$world" --from "$dir/garden.ply" --out "$dir/other" "${fast[@]}" --cameras "$dir/missing.json"
exit $((failures > 0))
