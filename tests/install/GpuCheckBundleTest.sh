#!/usr/bin/env bash
# The GPU check bundle (scripts/gpu-check.sh, docs/testing.md "GPU check") made from this build
# and run the way it runs on a GPU machine that has only a driver and a Vulkan loader: unpacked
# from its archive into an empty folder, started with a bare environment, in --quick mode on
# lavapipe. Where a private mount namespace is allowed (root), every library the bundle carries
# is also hidden at its system path (an empty file bound over it), so a run that still works
# used the bundle's copies only.
#   GpuCheckBundleTest.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(realpath "$1")
src=$(realpath "$2")
tmp=$(mktemp -d /tmp/fovea-gpucheck.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

bash "$src/scripts/gpu-check.sh" bundle "$tmp/make/fovea-gpu-check" --build "$build" ||
  fail "gpu-check.sh bundle failed"
archive="$tmp/make/fovea-gpu-check.tar.gz"
[[ -f $archive ]] || fail "no archive"
size=$(stat -c %s "$archive")
(( size < 60 * 1048576 )) || fail "the archive has $(( size / 1048576 )) MB, over 60 MB"
# Refuses to overwrite a bundle without --overwrite.
if bash "$src/scripts/gpu-check.sh" bundle "$tmp/make/fovea-gpu-check" --build "$build" 2> "$tmp/again.err"; then
  fail "bundle overwrote an existing folder without --overwrite"
fi
grep -q "not empty" "$tmp/again.err" || fail "no reason given: $(cat "$tmp/again.err")"

# Unpacked on a clean path, away from the build and source trees.
mkdir -p "$tmp/target"
tar -C "$tmp/target" -xzf "$archive"
bundle="$tmp/target/fovea-gpu-check"
# Every library of the bundle resolves into the bundle (glibc and the Vulkan loader excepted).
while read -r name path; do
  case "$name" in libvulkan.so.*|libc.so.*|libm.so.*|ld-linux*|libdl.so.*|libpthread.so.*|librt.so.*) continue ;; esac
  [[ $path == "$bundle/lib/"* ]] || fail "$name resolves to $path, not into the bundle"
done < <(LD_LIBRARY_PATH="$bundle/lib" ldd "$bundle/bin/fovea" | awk '/=>/ { print $1, $3 }')

check="env -i PATH=/usr/bin:/bin HOME=$tmp/home $bundle/gpu-check.sh run $tmp/results --quick --budget 400"
if unshare -m true 2> /dev/null; then
  # Not the libraries of the tools the script itself runs (bash, python3, coreutils, tar, ...):
  # those are the target's own, and hiding them would break the tools, not test the bundle.
  # (Looked up on the PATH the run gets below, so python3 is the system's, not a shim's.)
  tools=$(env -i PATH=/usr/bin:/bin bash -c 'for t in bash env timeout date awk sed grep tar ls \
            du wc cat mkdir rm python3; do command -v "$t"; done' |
          while read -r t; do ldd "$t" 2> /dev/null; done | awk '/=>/ { print $1 }' | sort -u)
  hide=""
  for lib in "$bundle"/lib/*.so*; do
    name=$(basename "$lib")
    grep -qxF "$name" <<< "$tools" && continue
    for dir in /usr/lib/x86_64-linux-gnu /lib/x86_64-linux-gnu /usr/lib; do
      [[ -e $dir/$name ]] && hide+="mount --bind /dev/null '$dir/$name'; "
    done
  done
  # The source tree's shaders and graphs too: the bundle brings its own.
  mkdir -p "$tmp/empty"
  hide+="mount --bind '$tmp/empty' '$src/shaders'; mount --bind '$tmp/empty' '$src/graphs'; "
  unshare -m bash -c "set -e; $hide $check" || fail "gpu-check.sh run failed with the system's copies hidden"
  echo "ran with $(grep -o 'mount --bind /dev/null' <<< "$hide" | wc -l) system libraries and the source tree's shaders/graphs hidden"
else
  echo "NOTE: no private mount namespace (unshare -m): the system libraries stay visible"
  $check || fail "gpu-check.sh run failed"
fi
[[ -s $tmp/results/summary.md ]] || fail "no summary.md"
grep -q "^default: " "$tmp/results/devices.txt" || fail "devices.txt lacks the default device"
runs=$(wc -l < "$tmp/results/runs.tsv")
(( runs >= 20 )) || fail "only $runs runs in runs.tsv"
! grep -v $'\tok\t' "$tmp/results/runs.tsv" || fail "runs not ok (above)"
# The smoke runs had the bundled validation layer (a missing layer is only a warning in fovea).
! grep -l "validation requested but" "$tmp"/results/runs/smoke_*.log || fail "validation layer missing"
grep -q "peres_nh3ld_fhd" "$tmp/results/summary.md" || fail "summary.md lacks the timing rows"
echo "archive $(( size / 1048576 )) MB, unpacked $(du -sm "$bundle" | cut -f1) MB; $runs runs ok"
echo "PASS"
