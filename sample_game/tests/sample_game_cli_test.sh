#!/usr/bin/env bash
# sample_game and sample_game_harness on bad input: each case must fail with exit code 1 and a
# message naming the problem, before any window or GL context is made (so this runs without a GPU or
# display).
#   sample_game_cli_test.sh SAMPLE_GAME SAMPLE_GAME_HARNESS OUTPUT_DIR
set -uo pipefail
game=$1
harness=$2
dir=$3
rm -rf "$dir"
mkdir -p "$dir"
failures=0

expect_failure() {  # expect_failure NAME EXPECTED_TEXT PROGRAM ARGS...
  local name=$1 text=$2 program=$3
  shift 3
  local log="$dir/$name.log"
  "$program" "$@" >"$log" 2>&1
  local code=$?
  if [ "$code" -ne 1 ]; then
    echo "FAIL $name: exit code $code, expected 1"; cat "$log"; failures=$((failures + 1)); return
  fi
  if ! grep -q -- "$text" "$log"; then
    echo "FAIL $name: message lacks \"$text\":"; cat "$log"; failures=$((failures + 1)); return
  fi
  echo "ok   $name: $(tail -n 1 "$log")"
}

expect_failure missing_world "$dir/nowhere/world.json: not found" "$harness" --profile --world "$dir/nowhere" --out "$dir/out"
expect_failure missing_world_window "splat_world --out" "$game" --world "$dir/nowhere"
expect_failure too_few_frames "--frames must be at least 10" "$harness" --profile --world "$dir/nowhere" --frames 5
expect_failure rel_min_above_rel_max "lod_settings.rel_min" "$harness" --profile --world "$dir/nowhere" --lod-rel-min 3
expect_failure upload_below_a_page "upload_budget_bytes_per_frame" "$harness" --profile --world "$dir/nowhere" --upload-budget-mib 0.01 --sh-degree 3 --gpu-storage full
expect_failure fade_frames_out_of_range "--fade-frames" "$harness" --profile --world "$dir/nowhere" --fade-frames 2000
expect_failure unknown_upscaler "upscaler" "$harness" --profile --upscaler sharpest
expect_failure unknown_option "--teleport" "$harness" --profile --teleport
expect_failure no_run_named "give one of --profile" "$harness" --world "$dir/nowhere"
expect_failure two_runs_named "give one of --profile" "$harness" --profile --soak --world "$dir/nowhere"
expect_failure profile_in_the_game "--profile" "$game" --profile --world "$dir/nowhere"
expect_failure screenshot_without_frames "need --frames" "$game" --world "$dir/nowhere" --screenshot "$dir/shot.png"

for program in "$game" "$harness"; do
  if ! "$program" --help > "$dir/help.log" 2>&1 || ! grep -q -- "--memory-budget-mib" "$dir/help.log"; then
    echo "FAIL help: $program --help did not list the options"; failures=$((failures + 1))
  fi
done
if [ -e "$dir/out" ]; then
  echo "FAIL: a failed run created its output folder"; failures=$((failures + 1))
fi

if [ "$failures" -ne 0 ]; then
  echo "sample_game cli test: $failures failures"
  exit 1
fi
echo "sample_game cli test: passed"
