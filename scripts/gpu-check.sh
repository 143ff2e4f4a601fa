#!/usr/bin/env bash
# The GPU check (docs/testing.md "GPU check"): fovea on a machine with a hardware GPU, in one
# short run.
#
#   scripts/gpu-check.sh bundle DIR [--build BUILD] [--overwrite]
#       Here: a self-contained folder (and DIR.tar.gz) holding the stripped executable, the
#       shared libraries a machine with only a GPU driver and a Vulkan loader lacks (glibc too,
#       as a fallback), the validation layer, the shaders, the graphs and this script.
#   DIR/gpu-check.sh run OUT [--quick] [--device D] [--budget SECONDS] [--overwrite]
#       There: lists the Vulkan devices, runs a smoke set of graphs with the validation layer
#       on, then the documents' pipelines at their sizes with GPU timestamps, and writes
#       everything into OUT (summary.md first). --budget (default 270 s) bounds the whole run;
#       what does not fit is reported as skipped. --quick: small sizes and few frames (lavapipe).
set -euo pipefail

die() { echo "gpu-check: error: $*" >&2; exit 2; }
note() { echo "gpu-check: $*"; }

# A folder we may fill: absent or empty, or --overwrite given (nothing is replaced silently).
claim_folder() {
  local dir=$1 overwrite=$2
  if [[ -e $dir && -n $(ls -A "$dir" 2> /dev/null) ]]; then
    [[ $overwrite == 1 ]] || die "$dir exists and is not empty (give --overwrite to replace it)"
    rm -rf "$dir"
  fi
  mkdir -p "$dir"
}

# The C library's own objects: the target has its own, and mixing two glibc versions in one
# process breaks. They are bundled apart (lib/glibc/) for the fallback loader only.
is_glibc() {
  case "$1" in
    ld-linux*|libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|libresolv.so.*|libutil.so.*) return 0 ;;
    *) return 1 ;;
  esac
}

# Copies the shared libraries ELF file $1 needs (ldd) into $2/lib (glibc into $2/lib/glibc),
# except the Vulkan loader, which must be the target's (it finds the target's driver).
copy_libraries() {
  local elf=$1 dir=$2 name path
  while read -r name path; do
    [[ -n $path && -f $path ]] || continue
    case "$name" in libvulkan.so.*|linux-vdso*) continue ;; esac
    if is_glibc "$name"; then
      cp -L -n "$path" "$dir/lib/glibc/$name"
    else
      [[ -e $dir/lib/$name ]] || { cp -L "$path" "$dir/lib/$name"; strip --strip-unneeded "$dir/lib/$name" 2> /dev/null || true; }
    fi
  done < <(ldd "$elf" | awk '/=>/ { print $1, $3 } /ld-linux/ && !/=>/ { n=$1; sub(".*/", "", n); print n, $1 }')
}

bundle() {
  local dir="" build=build overwrite=0
  while [[ $# -gt 0 ]]; do
    case "$1" in
      --build) build=${2:?--build needs a folder}; shift 2 ;;
      --overwrite) overwrite=1; shift ;;
      -*) die "bundle: unknown option $1" ;;
      *) [[ -z $dir ]] || die "bundle: one folder only"; dir=$1; shift ;;
    esac
  done
  [[ -n $dir ]] || die "usage: gpu-check.sh bundle DIR [--build BUILD] [--overwrite]"
  local src; src=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  [[ -x $build/fovea ]] || die "$build/fovea not found (build first: make build, or give --build)"
  command -v ldd > /dev/null || die "ldd not found"
  claim_folder "$dir" "$overwrite"
  dir=$(cd "$dir" && pwd)
  mkdir -p "$dir/bin" "$dir/lib/glibc" "$dir/layers" "$dir/share/fovea"
  cp "$build/fovea" "$dir/bin/fovea"
  strip --strip-unneeded "$dir/bin/fovea"  # keeps .dynsym: plugins still resolve against it
  cp -r "$src/shaders" "$src/graphs" "$dir/share/fovea/"
  copy_libraries "$dir/bin/fovea" "$dir"
  # The validation layer with a manifest that points at the bundled copy.
  local layer="" manifest=""
  for d in /usr/lib/x86_64-linux-gnu /usr/lib64 /usr/lib; do
    [[ -f $d/libVkLayer_khronos_validation.so ]] && { layer=$d/libVkLayer_khronos_validation.so; break; }
  done
  for d in /usr/share/vulkan/explicit_layer.d /etc/vulkan/explicit_layer.d; do
    [[ -f $d/VkLayer_khronos_validation.json ]] && { manifest=$d/VkLayer_khronos_validation.json; break; }
  done
  if [[ -n $layer && -n $manifest ]]; then
    cp "$layer" "$dir/lib/"
    strip --strip-unneeded "$dir/lib/libVkLayer_khronos_validation.so"
    copy_libraries "$layer" "$dir"
    sed 's|"library_path": *"[^"]*"|"library_path": "../lib/libVkLayer_khronos_validation.so"|' \
      "$manifest" > "$dir/layers/VkLayer_khronos_validation.json"
  else
    note "WARNING: no Khronos validation layer here; the bundle's smoke runs will be unvalidated"
  fi
  cp "$src/scripts/gpu-check.sh" "$dir/gpu-check.sh"
  chmod +x "$dir/gpu-check.sh"
  {
    echo "fovea $("$build/fovea" --version 2> /dev/null || echo '?') GPU check bundle"
    echo "source: $(git -C "$src" rev-parse --short HEAD 2> /dev/null || echo unknown)$(git -C "$src" diff --quiet 2> /dev/null || echo ' (with uncommitted changes)')"
    echo "made: $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(. /etc/os-release 2> /dev/null && echo "$PRETTY_NAME")"
    echo "needs on the target: x86-64 Linux, a Vulkan 1.3 driver and loader (libvulkan.so.1)"
    echo "run: ./gpu-check.sh run OUT"
    echo "libraries:"; (cd "$dir/lib" && ls -1 ./*.so* glibc/ | sed 's|^\./|  |; s|^|  |')
  } > "$dir/BUNDLE.txt"
  local parent base; parent=$(dirname "$dir"); base=$(basename "$dir")
  tar -C "$parent" -czf "$dir.tar.gz" "$base"
  note "bundle: $dir ($(du -sm "$dir" | cut -f1) MB unpacked, bin/fovea $(( $(stat -c %s "$dir/bin/fovea") / 1048576 )) MB)"
  note "archive: $dir.tar.gz ($(( $(stat -c %s "$dir.tar.gz") / 1048576 )) MB); on the target: tar xzf $base.tar.gz && $base/gpu-check.sh run results"
}

# ---------------------------------------------------------------------------------------------
# On the target.

BUNDLE=""
FOVEA=()

# The bundled executable with the bundled libraries; with the bundled glibc and its loader when
# the target's C library is older than the one fovea was built against.
choose_launcher() {
  local lib="$BUNDLE/lib"
  FOVEA=(env LD_LIBRARY_PATH="$lib" "$BUNDLE/bin/fovea")
  if "${FOVEA[@]}" --version > /dev/null 2>&1; then return; fi
  local loader="$lib/glibc/ld-linux-x86-64.so.2"
  [[ -x $loader || -f $loader ]] || die "bin/fovea does not start and the bundle has no glibc loader"
  FOVEA=("$loader" --library-path "$lib:$lib/glibc" "$BUNDLE/bin/fovea")
  "${FOVEA[@]}" --version > /dev/null 2>&1 ||
    die "bin/fovea does not start, with the target's or the bundled glibc: $("${FOVEA[@]}" --version 2>&1 | head -3)"
  note "the target's glibc is older than the bundle's: running through the bundled loader"
}

# run_graph NAME GRAPH SIZE FRAMES VALIDATION [extra fovea options...]: one fovea run into
# $OUT/runs/NAME with a time limit; appends a line to $OUT/runs.tsv.
run_graph() {
  local name=$1 graph=$2 size=$3 frames=$4 validation=$5; shift 5
  local left=$(( DEADLINE - $(date +%s) ))
  if (( left < 10 )); then
    printf '%s\t%s\t%s\t%s\tskipped (budget)\t0\n' "$name" "$graph" "$size" "$frames" >> "$OUT/runs.tsv"
    return
  fi
  local limit=$(( left < 120 ? left : 120 ))
  local dir="$OUT/runs/$name" start code status
  start=$(date +%s%N)
  set +e
  FOVEA_VALIDATION=$validation timeout "$limit" "${FOVEA[@]}" run "$BUNDLE/share/fovea/graphs/$graph" \
    --size "$size" --frames "$frames" --out "$dir" --overwrite --quiet ${DEVICE:+--device "$DEVICE"} "$@" \
    > "$OUT/runs/$name.log" 2>&1
  code=$?
  set -e
  local seconds; seconds=$(( ($(date +%s%N) - start) / 1000000 ))
  if (( code == 0 )); then status=ok; elif (( code == 124 )); then status="timeout ${limit}s"; else status="exit $code"; fi
  if [[ $validation == 1 ]] && grep -q "validation requested but" "$OUT/runs/$name.log"; then
    status="$status (validation layer missing: unvalidated)"
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$graph" "$size" "$frames" "$status" "$seconds" >> "$OUT/runs.tsv"
  note "$name: $status ($seconds ms)"
}

# summary.md from runs.tsv and the runs' report.json files (python3 when the target has it).
write_summary() {
  {
    echo "# fovea GPU check"
    echo
    echo '```'; cat "$OUT/devices.txt"; echo '```'
    echo
    echo "Bundle: $(head -2 "$BUNDLE/BUNDLE.txt" | tr '\n' ' ')"
    echo
  } > "$OUT/summary.md"
  if command -v python3 > /dev/null; then
    python3 - "$OUT" >> "$OUT/summary.md" << 'EOF'
import json, os, sys
out = sys.argv[1]
rows = [l.rstrip("\n").split("\t") for l in open(os.path.join(out, "runs.tsv"))]
print("| run | graph | size | frames | status | wall ms | build ms | frame GPU ms (median) | slowest passes (median GPU ms) |")
print("|---|---|---|---|---|---|---|---|---|")
for name, graph, size, frames, status, wall in rows:
    report = os.path.join(out, "runs", name, "report.json")
    build = frame = passes = ""
    if os.path.exists(report):
        r = json.load(open(report))
        build = "%.0f" % r.get("build_ms", 0)
        frame = "%.3f" % r["frame_ms"]["median"]
        ps = sorted(r["passes"], key=lambda p: -p["gpu_ms"]["median"])[:4]
        passes = ", ".join("%s %.3f" % (p["name"], p["gpu_ms"]["median"]) for p in ps)
    print(f"| {name} | {graph} | {size} | {frames} | {status} | {wall} | {build} | {frame} | {passes} |")
EOF
  else
    { echo "(no python3 on the target: raw rows; report.json per run under runs/)"; echo '```'; cat "$OUT/runs.tsv"; echo '```'; } >> "$OUT/summary.md"
  fi
}

run_check() {
  local quick=0 overwrite=0 budget=270
  OUT="" DEVICE=""
  while [[ $# -gt 0 ]]; do
    case "$1" in
      --quick) quick=1; shift ;;
      --overwrite) overwrite=1; shift ;;
      --device) DEVICE=${2:?--device needs a value}; shift 2 ;;
      --budget) budget=${2:?--budget needs seconds}; shift 2 ;;
      -*) die "run: unknown option $1" ;;
      *) [[ -z $OUT ]] || die "run: one output folder only"; OUT=$1; shift ;;
    esac
  done
  [[ -n $OUT ]] || die "usage: gpu-check.sh run OUT [--quick] [--device D] [--budget SECONDS] [--overwrite]"
  [[ $budget =~ ^[0-9]+$ ]] || die "--budget: '$budget' is not a number of seconds"
  BUNDLE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
  [[ -x $BUNDLE/bin/fovea ]] || die "$BUNDLE/bin/fovea not found: run this script from an unpacked bundle (gpu-check.sh bundle DIR)"
  claim_folder "$OUT" "$overwrite"
  OUT=$(cd "$OUT" && pwd)
  mkdir -p "$OUT/runs"
  : > "$OUT/runs.tsv"
  local start; start=$(date +%s)
  DEADLINE=$(( start + budget ))
  # The bundle's shaders and validation layer, whatever the target has installed.
  export FOVEA_SHADER_DIR="$BUNDLE/share/fovea/shaders"
  [[ -f $BUNDLE/layers/VkLayer_khronos_validation.json ]] && export VK_LAYER_PATH="$BUNDLE/layers"
  choose_launcher

  "${FOVEA[@]}" devices > "$OUT/devices.txt" 2>&1 || { cat "$OUT/devices.txt"; die "no usable Vulkan device"; }
  cat "$OUT/devices.txt"
  if grep -q "^default: .*\[cpu\]" "$OUT/devices.txt" && [[ $quick == 0 ]]; then
    note "WARNING: the default device is a CPU device: no GPU driver found (use --quick on lavapipe)"
  fi

  # 1. Smoke: every pipeline family with the validation layer on (any message fails the run).
  local s=96 f=3
  [[ $quick == 1 ]] && { s=32; f=2; }
  for g in demo pathtrace peres_base peres_nh3ld koskela_bmfr koskela_vp_bmfr koskela_vp_svgf \
           svgf svgf_diffuse_specular reblur reblur_diffuse_specular foveated_svgf; do
    run_graph "smoke_$g" "$g.json" "${s}x${s}" "$f" 1
  done
  run_graph smoke_preview_vp preview_vp.json "$(( 2 * s ))x${s}" "$f" 1  # equirect: 2:1

  # 2. Timing: the documents' pipelines at their sizes, validation off, GPU timestamps per pass
  # (report.json). Peres: FHD stereo, two 960x1080 eyes side by side with Table 1's radii
  # 144/288 px (seed 000 §4.2; docs/pipelines.md). Koskela: 720p and P5's 1280x1440.
  # ReBLUR and SVGF: 1080p (seed 004).
  local frames=32 div=1
  [[ $quick == 1 ]] && { frames=3; div=16; }
  sz() { echo "$(( $1 / div ))x$(( $2 / div ))"; }
  local radii=(--set "mask.r0=$(( 144 / div ))" --set "mask.r1=$(( 288 / div ))")
  run_graph peres_base_fhd peres_base.json "$(sz 1920 1080)" "$frames" 0
  run_graph peres_nh2ld_fhd peres_nh2ld.json "$(sz 1920 1080)" "$frames" 0 "${radii[@]}"
  run_graph peres_nh3ld_fhd peres_nh3ld.json "$(sz 1920 1080)" "$frames" 0 "${radii[@]}"
  run_graph koskela_bmfr_720p koskela_bmfr.json "$(sz 1280 720)" "$frames" 0
  run_graph koskela_vp_bmfr_720p koskela_vp_bmfr.json "$(sz 1280 720)" "$frames" 0
  run_graph koskela_bmfr_1280x1440 koskela_bmfr.json "$(sz 1280 1440)" "$frames" 0
  run_graph koskela_vp_bmfr_1280x1440 koskela_vp_bmfr.json "$(sz 1280 1440)" "$frames" 0
  run_graph svgf_1080p svgf.json "$(sz 1920 1080)" "$frames" 0
  run_graph reblur_1080p reblur.json "$(sz 1920 1080)" "$frames" 0
  run_graph svgf_split_1080p svgf_diffuse_specular.json "$(sz 1920 1080)" "$frames" 0
  run_graph reblur_split_1080p reblur_diffuse_specular.json "$(sz 1920 1080)" "$frames" 0

  write_summary
  local failed; failed=$(awk -F'\t' '$5 != "ok"' "$OUT/runs.tsv" | wc -l)
  note "done in $(( $(date +%s) - start )) s: $(wc -l < "$OUT/runs.tsv") runs, $failed not ok; results in $OUT (summary.md)"
  (( failed == 0 )) || exit 1
}

case "${1:-}" in
  bundle) shift; bundle "$@" ;;
  run) shift; run_check "$@" ;;
  *) die "usage: gpu-check.sh bundle DIR [--build BUILD] [--overwrite] | run OUT [--quick] [--device D] [--budget SECONDS] [--overwrite]" ;;
esac
