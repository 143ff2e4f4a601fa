#!/usr/bin/env bash
# Reproduces the current tables of docs/benchmarks.md (one "table" per paper claim) with
# `fovea bench`, and prints each bench's figures from its bench.json as a Markdown table.
#
#   scripts/benchmarks.sh            every table (hours on lavapipe: references are rendered first)
#   scripts/benchmarks.sh peres      one table: peres, koskela, vp, reblur, cost, embree or engine
#   scripts/benchmarks.sh --list     "<table> graphs/benches/<file>.json" per bench file; runs nothing
#
# FOVEA=build/fovea by default; results go to out/benchmarks/<bench name>/ (bench.json, bench.md
# with per-pass GPU ms, bench.csv, bench.svg). Two tables use no bench file and so are not in
# --list: "cost" (the per-size `fovea run` loop behind ReBLUR's cost and P2 Table 5) and "embree"
# (build/tests/fovea_raybench, built only where Embree 3 is installed; skipped without it), and
# "engine" (graph compile time, executor overhead and aliasing on chain20, 1 spp path tracing,
# PathTrace Mrays/s and BMFR's per-kernel times, docs/results/render-graph-and-bvh.md).
# Benchmarks, not tests: nothing here asserts a speed or an error.
set -euo pipefail
cd "$(dirname "$0")/.."
FOVEA=${FOVEA:-build/fovea}
OUT=out/benchmarks

BENCHES="
peres peres_cornell
peres peres_forest
peres peres_speed_cornell_240
peres peres_speed_cornell_960
peres peres_speed_forest_480
koskela p2_table2_cornell
koskela p2_table2_forest
koskela p2_table2_helmet
koskela koskela_vs_peres_cornell
vp koskela_vp_cornell_1280x1440
vp koskela_vp_forest_1280x1440
vp koskela_vp_reduction_cornell_1280x1440
vp koskela_vp_cornell_512
vp koskela_vp_forest_512
vp koskela_vp_cornell_256
vp koskela_vp_forest_256
vp koskela_vp_cornell_256_stereo
vp koskela_vp_forest_256_stereo
vp koskela_vp_vs_cartesian
vp koskela_vp_coherence
vp koskela_vp_speed_cornell_384
vp koskela_vp_speed_cornell_1280x1440
reblur denoisers_bevy_128
reblur denoisers_bevy_256
reblur denoisers_glossy_combined_128
reblur denoisers_glossy_combined_256
reblur denoisers_helmet_256
"
TABLES="peres koskela vp reblur"
EXTRA="cost embree engine"

if [ "${1:-}" = "--list" ]; then
  while read -r table file; do
    if [ -n "$table" ]; then echo "$table graphs/benches/$file.json"; fi
  done <<< "$BENCHES"
  exit 0
fi
SELECT=${1:-all}
case " $TABLES $EXTRA all " in
  *" $SELECT "*) ;;
  *) all="$TABLES $EXTRA"; echo "usage: $0 [--list | ${all// /|}]" >&2; exit 2 ;;
esac

summary() {  # bench.json -> Markdown table of its graphs' figures
  python3 - "$1" <<'PY'
import json, sys
b = json.load(open(sys.argv[1]))
def f(v, fmt):
    return fmt % v if isinstance(v, (int, float)) else "—"
print("\n**%s** (%s, %s frames, seed %s)\n" % (b.get("name", ""), b.get("device", {}).get("name", "?"),
      b.get("frames", "?"), b.get("seeds", b.get("seed", "?"))))
print("| Graph | Frame ms (median) | Speed-up | RMSE % | SSIM | Temporal error | ꟻLIP (flip_mean) |")
print("|---|---:|---:|---:|---:|---:|---:|")
for g in b["graphs"]:
    e = g.get("errors") or {}
    m = e.get("mean") or {}
    print("| %s | %s | %s | %s | %s | %s | %s |" % (
        g["label"], f((g.get("frame_ms") or {}).get("median"), "%.1f"), f(g.get("speedup"), "%.2fx"),
        f(m.get("rmse_percent"), "%.3f"), f(m.get("ssim"), "%.3f"), f(e.get("temporal_error"), "%.4f"),
        f(m.get("flip_mean"), "%.4f")))
PY
}

peres_reference() {  # the 1024 spp references peres_{cornell,forest}.json name (about 10 and 20 min)
  local scene=$1 ref="out/ref/${1}_480x270"
  if [ ! -f "$ref/tm.ldr.frame1023.exr" ]; then
    "$FOVEA" reference --scene "builtin:$scene" --stereo --size 480x270 --spp 1024 \
      --set pt.maxBounces=1 --out "$ref" --overwrite --quiet < /dev/null
  fi
}

run_table() {
  local want=$1
  while read -r table file; do
    [ "$table" = "$want" ] || continue
    echo "== $table: graphs/benches/$file.json"
    # peres_speed_* render and cache their own references (bench "render").
    case $file in peres_speed_*) ;; peres_*) peres_reference "${file#peres_}" ;; esac
    "$FOVEA" bench "graphs/benches/$file.json" --out "$OUT/$file" --overwrite --quiet < /dev/null
    summary "$OUT/$file/bench.json"
  done <<< "$BENCHES"
}

run_cost() {  # ReBLUR / SVGF / BMFR denoiser GPU ms at 4 sizes (builtin:cornell dolly, 6 frames)
  echo "== cost: denoiser passes' median GPU ms (graphs/{svgf,koskela_bmfr,reblur}.json)"
  for s in 128x72 256x144 512x288 1024x576; do
    for g in svgf koskela_bmfr reblur; do
      "$FOVEA" run "graphs/$g.json" --size "$s" --frames 6 --seed 1 --mono --save-frames none \
        --out "$OUT/cost/${g}_$s" --overwrite --quiet < /dev/null
    done
  done
  python3 - "$OUT/cost" <<'PY'
import json, sys
den = {"SVGF", "BMFR", "RecurrentBlur", "HistoryFix"}
print("\n| Size | SVGF ms | BMFR ms | ReBLUR ms | SVGF/BMFR | ReBLUR/SVGF |\n|---|---:|---:|---:|---:|---:|")
for s in ["128x72", "256x144", "512x288", "1024x576"]:
    ms = {}
    for g in ["svgf", "koskela_bmfr", "reblur"]:
        r = json.load(open("%s/%s_%s/report.json" % (sys.argv[1], g, s)))
        ms[g] = sum(p["gpu_ms"]["median"] for p in r["passes"] if p["type"] in den)
    print("| %s | %.1f | %.1f | %.1f | %.2f | %.2f |" % (s, ms["svgf"], ms["koskela_bmfr"], ms["reblur"],
          ms["svgf"] / ms["koskela_bmfr"], ms["reblur"] / ms["svgf"]))
PY
}

run_embree() {  # fovea's compute BVH vs Embree 3 on the same rays, 640x360, median of 3
  local raybench
  raybench="$(dirname "$FOVEA")/tests/fovea_raybench"
  if [ ! -x "$raybench" ]; then echo "== embree: $raybench not built (libembree-dev), skipped"; return; fi
  echo "== embree: $raybench"
  for scene in builtin:cornell ../shared/scenes/flight-helmet/FlightHelmet.gltf builtin:forest; do
    "$raybench" "$scene" 640x360 --repeats 3
  done
}

run_engine() {  # the render graph and the path tracer themselves (docs/results/)
  local tests
  tests="$(dirname "$FOVEA")/tests/fovea_tests"
  echo "== engine: graph compile (CPU plan stages), 20-pass chain"
  for i in 1 2 3; do "$FOVEA" validate graphs/tests/chain20.json; done
  for alias in "" --no-aliasing; do
    "$FOVEA" run graphs/tests/chain20.json --size 256x256 --frames 20 --save-frames none --quiet \
      --overwrite $alias --out "$OUT/chain20$alias" < /dev/null
    python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); m=r["memory"]; print("chain20", sys.argv[2], "frame_ms median %.2f, executor overhead %.4f ms, transient %d B" % (r["frame_ms"]["median"], r["executor_overhead_cpu_ms"]["mean"], m["transient_bytes"]))' \
      "$OUT/chain20$alias/report.json" "${alias:-aliasing}"
  done
  for scene in builtin:cornell builtin:forest; do
    "$FOVEA" run graphs/pathtrace.json --scene "$scene" --size 640x360 --frames 4 --save-frames none \
      --quiet --overwrite --out "$OUT/pt-${scene#builtin:}" < /dev/null
    python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); print(sys.argv[2], "1 spp 640x360: frame_ms median %.2f" % r["frame_ms"]["median"])' \
      "$OUT/pt-${scene#builtin:}/report.json" "$scene"
  done
  "$tests" --gtest_also_run_disabled_tests --gtest_filter='PathTraceTest.DISABLED_BenchmarkMraysPerSecond' |
    grep '\[ PathTrace \]' || true
  "$tests" --gtest_also_run_disabled_tests --gtest_filter='BMFRBench.*' | grep -v '^\[' || true
}

mkdir -p "$OUT"
for t in $TABLES $EXTRA; do
  if [ "$SELECT" = "$t" ] || [ "$SELECT" = all ]; then
    case $t in
      cost) run_cost ;;
      embree) run_embree ;;
      engine) run_engine ;;
      *) run_table "$t" ;;
    esac
  fi
done
