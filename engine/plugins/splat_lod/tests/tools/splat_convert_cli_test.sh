#!/usr/bin/env bash
# splat_convert as a user runs it: PLY → .glb → .gltf → .glb gives the same bytes, .glb → PLY reads back;
# bad input and a bad output name fail with exit code 1, a message naming the problem, and leave an
# existing output as it was.
#   splat_convert_cli_test.sh SPLAT_CONVERT SPLAT_SYNTH OUTPUT_DIR
set -uo pipefail
convert=$1
synth=$2
dir=$3
rm -rf "$dir"
mkdir -p "$dir"
# shellcheck source=cli_test_lib.sh
source "$(dirname "$0")/cli_test_lib.sh"

"$synth" --out "$dir/garden.ply" --seed 3 --detail 0.02 >/dev/null || { echo "FAIL: splat_synth"; exit 1; }
"$convert" --input "$dir/garden.ply" --output "$dir/a.glb" > "$dir/1.log" 2>&1 || fail "ply to glb: $(cat "$dir/1.log")"
"$convert" --input "$dir/a.glb" --output "$dir/a.gltf" > "$dir/2.log" 2>&1 || fail "glb to gltf: $(cat "$dir/2.log")"
"$convert" --input "$dir/a.gltf" --output "$dir/b.glb" > "$dir/3.log" 2>&1 || fail "gltf to glb: $(cat "$dir/3.log")"
cmp -s "$dir/a.glb" "$dir/b.glb" || fail "PLY -> .glb -> .gltf -> .glb changed the bytes"
"$convert" --input "$dir/b.glb" --output "$dir/c.ply" > "$dir/4.log" 2>&1 || fail "glb to ply: $(cat "$dir/4.log")"
grep -q "wrote .*c.ply (" "$dir/4.log" || fail "glb to ply printed: $(cat "$dir/4.log")"
[ "$(head -c 4 "$dir/a.glb")" = "glTF" ] || fail "a.glb is not binary glTF"
echo "ok   conversions: $(cat "$dir/1.log")"

echo "previous output" > "$dir/keep.glb"
cp "$dir/keep.glb" "$dir/keep.orig"
head -c 3000 "$dir/garden.ply" > "$dir/truncated.ply"
for case in "truncated.ply:truncated.ply:keep.glb" "missing.ply:missing.ply:keep.glb" "garden.ply:must end in:out.spz"; do
  IFS=: read -r input text output <<< "$case"
  "$convert" --input "$dir/$input" --output "$dir/$output" > "$dir/bad.log" 2>&1
  code=$?
  if [ "$code" -ne 1 ] || ! grep -q -- "$text" "$dir/bad.log"; then
    fail "$input -> $output: exit code $code, message: $(cat "$dir/bad.log")"
  else
    echo "ok   $input -> $output: $(tail -n 1 "$dir/bad.log")"
  fi
done
cmp -s "$dir/keep.glb" "$dir/keep.orig" || fail "a failed conversion changed the existing output"
exit $((failures > 0))
