#!/usr/bin/env bash
# fovea installed (docs/install.md): `cmake --install` into a temporary prefix, then the installed
# executable runs a shipped graph and a reference with the shaders and graphs of the prefix, also
# when the source tree's shaders/ and graphs/ are out of reach (hidden by an empty bind mount in a
# private mount namespace, where that is allowed); a missing shader folder is exit 1 naming the
# folders looked in.
#   InstallTest.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(realpath "$1")
src=$(realpath "$2")
tmp=$(mktemp -d /tmp/fovea-install.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

cmake --install "$build" --prefix "$tmp/prefix" --strip > "$tmp/install.log" ||
  { cat "$tmp/install.log"; fail "cmake --install failed"; }
fovea="$tmp/prefix/bin/fovea"
share="$tmp/prefix/share/fovea"
for f in "$fovea" "$share/shaders/common" "$share/graphs/demo.json" "$share/graphs/reference.json"; do
  [[ -e $f ]] || fail "not installed: $f"
done
echo "installed: bin/fovea $(stat -c %s "$fovea") bytes (stripped), share/fovea $(du -sk "$share" | cut -f1) KiB"

# From an unrelated working directory, with the shipped graph of the prefix.
cd "$tmp"
"$fovea" run "$share/graphs/demo.json" --size 32x32 --frames 1 --out "$tmp/run" --quiet ||
  fail "the installed fovea could not run demo.json"
grep -q "\"shader_dir\": \"$share/shaders\"" "$tmp/run/report.json" ||
  fail "the installed fovea compiled from another shader folder: $(grep shader_dir "$tmp/run/report.json")"
"$fovea" reference --spp 1 --size 16x16 --out "$tmp/ref" --quiet || fail "reference failed"
grep -q "\"graph\": \"$share/graphs/reference.json\"" "$tmp/ref/report.json" ||
  fail "fovea reference did not use the installed reference graph"

# FOVEA_SHADER_DIR overrides; a wrong one is exit 1 naming it (never a silent fallback).
set +e
FOVEA_SHADER_DIR="$tmp/nowhere" "$fovea" run "$share/graphs/demo.json" --size 16x16 --frames 1 \
  --out "$tmp/bad" --quiet 2> "$tmp/bad.err"
code=$?
set -e
[[ $code == 1 ]] || fail "FOVEA_SHADER_DIR=nowhere: exit $code, expected 1"
grep -q "$tmp/nowhere" "$tmp/bad.err" || fail "the error does not name the folder: $(cat "$tmp/bad.err")"

# The source tree out of reach: only possible with a private mount namespace (root).
if unshare -m true 2> /dev/null; then
  mkdir -p "$tmp/empty"
  unshare -m bash -c "
    set -e
    mount --bind '$tmp/empty' '$src/shaders'
    mount --bind '$tmp/empty' '$src/graphs'
    FOVEA_SHADER_CACHE= '$fovea' run '$share/graphs/demo.json' --size 32x32 --frames 1 \
      --out '$tmp/hidden' --quiet
    # Both shader folders gone: exit 1 naming where it looked.
    mv '$share/shaders' '$share/shaders.away'
    set +e
    FOVEA_SHADER_CACHE= '$fovea' run '$share/graphs/demo.json' --size 16x16 --frames 1 \
      --out '$tmp/none' --quiet 2> '$tmp/none.err'
    echo \$? > '$tmp/none.code'
    mv '$share/shaders.away' '$share/shaders'
  " || fail "the installed fovea failed with the source tree out of reach"
  [[ $(cat "$tmp/none.code") == 1 ]] || fail "no shader folder: exit $(cat "$tmp/none.code"), expected 1"
  grep -q "no shader folder: looked in '$share/shaders'" "$tmp/none.err" ||
    fail "the error does not name the folders: $(cat "$tmp/none.err")"
  echo "ran with the source tree's shaders/ and graphs/ hidden"
else
  echo "NOTE: no private mount namespace here (unshare -m); the source-tree-hidden case is skipped"
fi
# An application against the installed package (find_package(fovea)), with a pass of its own,
# and that pass as a plugin of the installed executable (docs/plugins.md).
if [[ ${FOVEA_INSTALL_TEST_EXAMPLE:-1} == 1 ]]; then
  for f in "$tmp/prefix/lib/cmake/fovea/foveaConfig.cmake" "$tmp/prefix/include/fovea/core/graph/Pass.h" \
           "$tmp/prefix/lib/libfovea_core.a"; do
    [[ -e $f ]] || fail "not installed: $f"
  done
  cmake -S "$src/examples/custom_pass" -B "$tmp/example" -G Ninja \
    -DCMAKE_PREFIX_PATH="$tmp/prefix" > "$tmp/example.log" 2>&1 ||
    { cat "$tmp/example.log"; fail "examples/custom_pass does not configure against the install"; }
  if grep -qF -e "-I$src " -e "-isystem $src " "$tmp/example/build.ninja"; then
    fail "the example's build reads headers from the source tree, not the install"
  fi
  cmake --build "$tmp/example" >> "$tmp/example.log" 2>&1 ||
    { tail -40 "$tmp/example.log"; fail "examples/custom_pass does not build against the install"; }
  "$tmp/example/custom_pass" || fail "examples/custom_pass failed"
  # The same pass as a plugin of the installed (stripped) fovea: its symbols are still exported.
  "$fovea" run "$src/examples/custom_pass/invert.json" --plugin "$tmp/example/fovea_invert.so" \
    --out "$tmp/plugin" --quiet || fail "the installed fovea could not run the example's plugin"
  grep -q "\"plugin\": \"$tmp/example/fovea_invert.so\"" "$tmp/plugin/report.json" ||
    fail "report.json does not name the plugin: $(grep -c plugin "$tmp/plugin/report.json")"
  echo "ran examples/custom_pass/invert.json with the plugin built against the install"
fi
echo "PASS"
