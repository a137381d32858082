#!/usr/bin/env bash
# The windowed path end to end, in a virtual X server: engine_view opens a GLFW window, renders
# a scene offscreen, blits it, draws the ImGui overlay and writes screenshots, which are checked:
#   1. the window with the overlay is not a uniform image;
#   2. without the overlay the window equals the offscreen frame read back by
#      RenderTarget::read_color() (the blit is complete and upright);
#   3. the overlay changes a clear share of the pixels (it is drawn);
#   4. with --stereo the window holds the two eyes side by side as they were read back (each eye's
#      blit into its half is complete and upright).
# A missing xvfb-run is a failure, not a skip: scripts/setup installs xvfb and xauth.
set -euo pipefail

if [ $# -ne 4 ]; then
  echo "usage: $0 ENGINE_VIEW PNG_STATS SCENE.json OUT_DIR" >&2
  exit 2
fi
view=$1 stats=$2 scene=$3 out=$4

for tool in xvfb-run xauth; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "window test: '$tool' not found; install the Debian packages xvfb and xauth (scripts/setup does)" >&2
    exit 1
  fi
done

mkdir -p "$out"
rm -f "$out"/with_ui.png "$out"/no_ui.png "$out"/offscreen.png "$out"/stereo.png "$out"/stereo_offscreen.png

run_view() {
  xvfb-run -a -s "-screen 0 1280x720x24" \
    "$view" --scene "$scene" --width 960 --height 540 --frames 5 "$@"
}

run_view --screenshot "$out/with_ui.png"
run_view --no-ui --screenshot "$out/no_ui.png" --offscreen "$out/offscreen.png"

"$stats" stats "$out/with_ui.png" --min-stddev 10
"$stats" diff "$out/no_ui.png" "$out/offscreen.png" --max-fraction 0.001
"$stats" diff "$out/with_ui.png" "$out/no_ui.png" --min-fraction 0.02
run_view --no-ui --stereo --ipd 0.2 --screenshot "$out/stereo.png" --offscreen "$out/stereo_offscreen.png"
"$stats" stats "$out/stereo.png" --min-stddev 10
"$stats" diff "$out/stereo.png" "$out/stereo_offscreen.png" --max-fraction 0.001
echo "window test: passed; screenshots in $out"
