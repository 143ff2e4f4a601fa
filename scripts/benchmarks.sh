#!/usr/bin/env bash
# Reproduces the figures of docs/benchmarks.md on this machine: graph compile time, executor
# overhead and transient memory (chain20), BVH build, fovea BVH vs Embree on the same rays, and
# PathTrace / GBuffer GPU time. Needs a built tree (make build); BUILD=build by default.
# Benchmarks, not tests: nothing here asserts a speed.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
OUT=${OUT:-out/bench}
FOVEA="$BUILD/fovea"
HELMET=../shared/scenes/flight-helmet/FlightHelmet.gltf
mkdir -p "$OUT"
summary() {  # report.json -> one line per pass with its mean GPU ms
  python3 - "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print("  device:", r["device"]["name"], "| size", r["size"], "| frames", r["frames"], "| build_ms %.1f" % r["build_ms"])
print("  frame_ms mean %.2f median %.2f | frame_cpu_ms mean %.3f | executor_overhead_cpu_ms mean %.4f"
      % (r["frame_ms"]["mean"], r["frame_ms"]["median"], r["frame_cpu_ms"]["mean"], r["executor_overhead_cpu_ms"]["mean"]))
m = r["memory"]
print("  transient %d B (without aliasing %d B), persistent %d B" % (m["transient_bytes"], m["transient_bytes_without_aliasing"], m["persistent_bytes"]))
for p in r["passes"]:
    print("  %-6s %-10s %-9s gpu_ms mean %8.2f  %s" % (p["name"], p["type"], p["status"], p["gpu_ms"]["mean"], p.get("variant", "")))
if isinstance(r["scene"], dict):
    s = r["scene"]
    print("  scene %s: %d triangles, BVH %d nodes in %.1f ms, upload %.1f ms, %d GPU bytes" % (s["spec"], s["triangles"], s["bvh"]["nodes"], s["bvh"]["build_ms"], s["upload_ms"], s["gpu_bytes"]))
PY
}

echo "== graph compile (CPU plan stages), 20-pass chain"
for i in 1 2 3; do "$FOVEA" validate graphs/tests/chain20.json; done

echo "== chain20 256x256, 20 frames, with and without aliasing"
"$FOVEA" run graphs/tests/chain20.json --size 256x256 --frames 20 --save-frames none --quiet --overwrite --out "$OUT/chain20"
summary "$OUT/chain20/report.json"
"$FOVEA" run graphs/tests/chain20.json --size 256x256 --frames 20 --save-frames none --quiet --overwrite --no-aliasing --out "$OUT/chain20-noalias"
summary "$OUT/chain20-noalias/report.json"

echo "== 1 spp path tracing (graphs/pathtrace.json) at 640x360, 4 frames"
for scene in builtin:cornell builtin:forest; do
  "$FOVEA" run graphs/pathtrace.json --scene "$scene" --size 640x360 --frames 4 --save-frames none --quiet --overwrite --out "$OUT/pt-${scene#builtin:}"
  summary "$OUT/pt-${scene#builtin:}/report.json"
done

echo "== fovea BVH vs Embree 3 on the same rays (640x360)"
for scene in builtin:cornell "$HELMET" builtin:forest; do
  "$BUILD/tests/fovea_raybench" "$scene" 640x360 --repeats 3
done

echo "== PathTrace Mrays/s with exact ray counters (cornell, FlightHelmet + a directional light)"
"$BUILD/tests/fovea_tests" --gtest_also_run_disabled_tests \
  --gtest_filter='PathTraceTest.DISABLED_BenchmarkMraysPerSecond' | grep '\[ PathTrace \]'

echo "== Peres et al. Tables 3-4 (issue 4): 1024 spp references, then Base / NH2LD / NH3LD"
for scene in cornell forest; do
  ref="out/ref/${scene}_480x270/tm.ldr.frame1023.exr"
  if [ ! -f "$ref" ]; then
    "$FOVEA" reference --scene "builtin:$scene" --stereo --size 480x270 --spp 1024 \
      --set pt.maxBounces=1 --out "out/ref/${scene}_480x270" --overwrite --quiet
  fi
  "$FOVEA" bench "graphs/benches/peres_$scene.json" --out "$OUT/peres_$scene" --overwrite --quiet
  cat "$OUT/peres_$scene/bench.md"
done

echo "== Koskela P2 (BMFR + TAA) vs Peres Base along the Cornell dolly (issue 5)"
"$FOVEA" bench graphs/benches/koskela_vs_peres_cornell.json --out "$OUT/koskela_vs_peres_cornell" --overwrite --quiet
cat "$OUT/koskela_vs_peres_cornell/bench.md"

echo "== BMFR per-kernel GPU ms at 128x128 and 256x256 (P2 Table 4 layout)"
"$BUILD/tests/fovea_tests" --gtest_also_run_disabled_tests --gtest_filter='BMFRBench.*' | grep -v '^\[' || true

echo "== Koskela P5 (issue 11): Cartesian vs Visual-Polar BMFR+TAA (and SVGF at 128x128)"
for b in koskela_vp_vs_cartesian koskela_vp_cornell_256 koskela_vp_cornell_256_stereo \
  koskela_vp_forest_256 koskela_vp_forest_256_stereo koskela_vp_cornell_512 koskela_vp_forest_512 \
  koskela_vp_cornell_1280x1440 koskela_vp_forest_1280x1440 koskela_vp_reduction_cornell_1280x1440; do
  "$FOVEA" bench "graphs/benches/$b.json" --out "$OUT/$b" --overwrite --quiet
  cat "$OUT/$b/bench.md"
done
