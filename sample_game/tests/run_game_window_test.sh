#!/usr/bin/env bash
# The game's window end to end, in a virtual X server: sample_game opens a GLFW window on a tiny
# generated world, streams it along the walkthrough for a few frames (synchronously, so the
# frames are repeatable), draws the overlay with the "Splat LOD", "Streaming" and "Walkthrough"
# panels and writes screenshots, which are checked:
#   1. the window with the overlay is not a uniform image;
#   2. without the overlay the window equals the offscreen frame (the blit is complete and upright);
#   3. the overlay changes a clear share of the pixels (it is drawn);
#   4. with --stereo the window holds the two eyes side by side as they were read back.
# A missing xvfb-run is a failure, not a skip: scripts/setup installs xvfb and xauth.
#   run_game_window_test.sh SAMPLE_GAME SPLAT_WORLD PNG_STATS OUT_DIR
set -euo pipefail

if [ $# -ne 4 ]; then
  echo "usage: $0 SAMPLE_GAME SPLAT_WORLD PNG_STATS OUT_DIR" >&2
  exit 2
fi
game=$1 world_tool=$2 stats=$3 out=$4

for tool in xvfb-run xauth; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "game window test: '$tool' not found; install the Debian packages xvfb and xauth (scripts/setup does)" >&2
    exit 1
  fi
done

mkdir -p "$out"
rm -f "$out"/with_ui.png "$out"/no_ui.png "$out"/offscreen.png "$out"/stereo.png "$out"/stereo_offscreen.png
# 3 x 3 chunks of 32 m at a tenth of the density: about a second to make, reused when it matches.
"$world_tool" --out "$out/world" --size 96 --chunk 32 --density 0.1 --refine-iterations 3 \
  --bake-width 128 --bake-height 128 --threads 2 > "$out/world.log" 2>&1 || { cat "$out/world.log"; exit 1; }

run_game() {
  xvfb-run -a -s "-screen 0 1280x720x24" \
    "$game" --world "$out/world" --width 640 --height 360 --frames 6 --sync-streaming "$@"
}

run_game --screenshot "$out/with_ui.png"
run_game --no-ui --screenshot "$out/no_ui.png" --offscreen "$out/offscreen.png"

"$stats" stats "$out/with_ui.png" --min-stddev 10
"$stats" stats "$out/no_ui.png" --min-stddev 5
"$stats" diff "$out/no_ui.png" "$out/offscreen.png" --max-fraction 0.001
"$stats" diff "$out/with_ui.png" "$out/no_ui.png" --min-fraction 0.02
run_game --no-ui --stereo --screenshot "$out/stereo.png" --offscreen "$out/stereo_offscreen.png"
"$stats" stats "$out/stereo.png" --min-stddev 5
"$stats" diff "$out/stereo.png" "$out/stereo_offscreen.png" --max-fraction 0.001
echo "game window test: passed; screenshots in $out"
