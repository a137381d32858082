#!/usr/bin/env bash
# ctest's script.gpu_check (see CMakeLists.txt here): pack, then `run --quick` with the source tree
# hidden where the machine allows it.
#   gpu_check_test.sh SOURCE BUILD DIR
set -euo pipefail
root=$1 build=$2 dir=$3
rm -rf "$dir"
"$root/scripts/gpu-check" pack "$dir/pack" --build "$build"
mkdir -p "$dir/out"

# Whether this machine lets an unprivileged mount namespace mount a tmpfs and bind a folder.
can_hide() {
  local probe ok=0
  probe=$(mktemp -d)
  mkdir "$probe/from" "$probe/to"
  # shellcheck disable=SC2016  # expanded inside the namespace
  unshare -rm bash -c 'mount --bind "$1/from" "$1/to" && mount -t tmpfs none "$1/from"' bash "$probe" \
    >/dev/null 2>&1 || ok=1
  rmdir "$probe/from" "$probe/to" "$probe"
  return "$ok"
}

if can_hide; then
  echo "gpu_check_test: running the pack with $root and ../shared hidden (a private mount namespace)"
  # Inside the namespace: the pack and the output folder are bound to a folder outside the source
  # tree first, then empty file systems are mounted over the source tree and ../shared.
  stage=$(mktemp -d)
  mkdir "$stage/pack" "$stage/out"
  status=0
  # shellcheck disable=SC2016  # the script is expanded inside the namespace
  unshare -rm bash -euo pipefail -c '
    root=$1 dir=$2 stage=$3
    mount --bind "$dir/pack" "$stage/pack"
    mount --bind "$dir/out" "$stage/out"
    shared=$(readlink -f "$root/../shared" 2>/dev/null || true)
    mount -t tmpfs none "$root"
    if [ -n "$shared" ] && [ -d "$shared" ]; then mount -t tmpfs none "$shared"; fi
    test -z "$(ls -A "$root")"
    "$stage/pack/gpu-check" run --quick --out "$stage/out"
  ' bash "$root" "$dir" "$stage" || status=$?
  rmdir "$stage/pack" "$stage/out" "$stage"  # empty here: the binds lived in the namespace only
  [ "$status" = 0 ]
else
  echo "gpu_check_test: this machine allows no private mount namespace; the run can see the source tree"
  "$dir/pack/gpu-check" run --quick --out "$dir/out"
fi
for f in summary.txt biker.png gpu-check.tar.gz; do test -s "$dir/out/$f"; done
