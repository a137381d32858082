#!/usr/bin/env bash
# splat_bake on bad input: each case must fail with exit code 1 and a message naming the problem,
# and an existing output file must come through every failure byte for byte.
#   splat_bake_cli_test.sh SPLAT_BAKE SPLAT_SYNTH OUTPUT_DIR
set -uo pipefail
bake=$1
synth=$2
dir=$3
rm -rf "$dir"
mkdir -p "$dir"
# shellcheck source=cli_test_lib.sh
source "$(dirname "$0")/cli_test_lib.sh"

"$synth" --out "$dir/garden.ply" --seed 3 --detail 0.02 >/dev/null || { echo "FAIL: splat_synth"; exit 1; }
echo "previous output" > "$dir/keep.ply"
cp "$dir/keep.ply" "$dir/keep.orig"

expect_failure missing_input "missing.ply" "$bake" --input "$dir/missing.ply" --output "$dir/keep.ply"
expect_failure missing_cameras "no_cameras.json" "$bake" --input "$dir/garden.ply" --output "$dir/keep.ply" --cameras "$dir/no_cameras.json"
echo '[{"eye": [0, 0, 50], "target": [0, 0, 100]}]' > "$dir/away.json"
expect_failure cameras_see_nothing "sees any" "$bake" --input "$dir/garden.ply" --output "$dir/keep.ply" --cameras "$dir/away.json"
{
  printf 'ply\nformat binary_little_endian 1.0\nelement vertex 0\n'
  for p in x y z f_dc_0 f_dc_1 f_dc_2 opacity scale_0 scale_1 scale_2 rot_0 rot_1 rot_2 rot_3; do
    printf 'property float %s\n' "$p"
  done
  printf 'end_header\n'
} > "$dir/empty.ply"
expect_failure empty_scene "no Gaussians" "$bake" --input "$dir/empty.ply" --output "$dir/keep.ply"
head -c 4000 "$dir/garden.ply" > "$dir/truncated.ply"
expect_failure truncated_input "truncated.ply" "$bake" --input "$dir/truncated.ply" --output "$dir/keep.ply"
expect_failure output_folder_missing "does not exist" "$bake" --input "$dir/garden.ply" --output "$dir/nowhere/out.ply"
expect_failure output_is_folder "is a folder" "$bake" --input "$dir/garden.ply" --output "$dir"
expect_failure output_is_input "replace the input" "$bake" --input "$dir/garden.ply" --output "$dir/garden.ply"
expect_failure impossible_threshold "S_T" "$bake" --input "$dir/garden.ply" --output "$dir/keep.ply" --size-threshold -1

if ! cmp -s "$dir/keep.ply" "$dir/keep.orig"; then
  echo "FAIL: a failed bake changed the existing output"; failures=$((failures + 1))
fi
if ls "$dir" | grep -q "tmp-"; then
  echo "FAIL: a failed bake left a temporary file"; failures=$((failures + 1))
fi

# And a bake that works (tiny, no refinement) replaces the output with a LOD asset.
if "$bake" --input "$dir/garden.ply" --output "$dir/keep.ply" --refine-iterations 0 > "$dir/ok.log" 2>&1 &&
   head -c 2000 "$dir/keep.ply" | grep -q "property uchar lod_level"; then
  echo "ok   working bake: $(tail -n 1 "$dir/ok.log")"
else
  echo "FAIL: the working bake"; cat "$dir/ok.log"; failures=$((failures + 1))
fi

# A .glb output: a failed bake leaves the previous one, a working bake writes glTF with the LOD attributes.
echo "previous glb" > "$dir/keep.glb"
cp "$dir/keep.glb" "$dir/keep_glb.orig"
expect_failure glb_truncated_input "truncated.ply" "$bake" --input "$dir/truncated.ply" --output "$dir/keep.glb"
cmp -s "$dir/keep.glb" "$dir/keep_glb.orig" || { echo "FAIL: a failed bake changed the .glb"; failures=$((failures + 1)); }
if "$bake" --input "$dir/garden.ply" --output "$dir/keep.glb" --refine-iterations 0 > "$dir/ok_glb.log" 2>&1 &&
   [ "$(head -c 4 "$dir/keep.glb")" = "glTF" ] && grep -q "_SPLAT_LOD_LEVEL" "$dir/keep.glb"; then
  echo "ok   working bake to .glb: $(tail -n 1 "$dir/ok_glb.log")"
else
  echo "FAIL: the working bake to .glb"; cat "$dir/ok_glb.log"; failures=$((failures + 1))
fi
exit $((failures > 0))
