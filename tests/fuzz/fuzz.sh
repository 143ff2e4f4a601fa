#!/usr/bin/env bash
# The fuzz targets' corpora and runs (docs/testing.md "Fuzzing").
#   fuzz.sh replay BUILD TARGET          every seed and regression input once (ctest fuzz.replay.*)
#   fuzz.sh fuzz BUILD SECONDS [TARGET...]  libFuzzer for SECONDS per target, two at a time
#                                         (a FOVEA_FUZZ build); fails on any crash, leak,
#                                         timeout (> 2 s per input) or out-of-memory (> 2 GB)
# Seeds come from the project (graphs/, test fixtures, tests/fuzz/seeds/) and ../shared/scenes/,
# copied into BUILD/fuzz/seeds/TARGET. New inputs libFuzzer finds go to BUILD/fuzz/corpus/TARGET
# (kept between runs); a crashing input is written to BUILD/fuzz/artifacts/TARGET/, and belongs in
# tests/fuzz/regressions/TARGET/ once fixed. FUZZ_SEED (default 0: random) fixes libFuzzer's seed;
# CI sets 1 so that a run's mutations, and so its verdict, depend on the code, not on chance.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
shared="$root/../shared/scenes"
targets=(graph camera_path bench_file gltf image cli)

# Prints the seed files of one target, smallest formats first; files over the size cap are left
# out (libFuzzer mutates small inputs faster, and -max_len would cut them anyway).
seed_files() {
    local small=(-type f -size -64k)
    case "$1" in
        graph) find "$root/graphs" "$root/tests/graph/bad" -name '*.json' "${small[@]}" \
                   -not -path '*/cameras/*' -not -path '*/benches/*' ;;
        camera_path) find "$root/graphs/cameras" -name '*.json' "${small[@]}" ;;
        bench_file) find "$root/graphs/benches" -name '*.json' "${small[@]}" ;;
        gltf) [ -d "$shared" ] && find "$shared" \( -name '*.glb' -o -name '*.gltf' \) "${small[@]}" ;;
        image) find "$root/tests/goldens" -name '*.exr' -size -40k
               [ -d "$shared" ] && find "$shared" \( -name '*.png' -o -name '*.jpg' -o -name '*.hdr' \) \
                   "${small[@]}" ;;
        cli) ;;
    esac
    [ -d "$here/seeds/$1" ] && find "$here/seeds/$1" -type f
    return 0
}

prepare_seeds() {  # BUILD TARGET -> prints the seed folder
    local dir="$1/fuzz/seeds/$2"
    rm -rf "$dir" && mkdir -p "$dir"
    local i=0
    while IFS= read -r f; do
        cp "$f" "$dir/$(printf '%04d' $i)-$(basename "$f")"
        i=$((i + 1))
    done < <(seed_files "$2" | sort)
    echo "$dir"
}

replay() {  # BUILD TARGET
    local bin="$1/tests/fuzz/fovea_fuzz_$2" seeds
    seeds="$(prepare_seeds "$1" "$2")"
    local dirs=("$seeds")
    [ -d "$here/regressions/$2" ] && dirs+=("$here/regressions/$2")
    local files
    mapfile -t files < <(find "${dirs[@]}" -type f | sort)
    [ ${#files[@]} -gt 0 ] || { echo "fuzz.sh: no inputs for $2" >&2; exit 1; }
    echo "fuzz.sh: replaying ${#files[@]} inputs through $(basename "$bin")"
    # Under libFuzzer, file arguments run once each; the replay main does the same.
    printf '%s\0' "${files[@]}" | xargs -0 -n 200 "$bin" > "$1/fuzz/replay-$2.log" 2>&1 ||
        { tail -n 40 "$1/fuzz/replay-$2.log"; exit 1; }
}

fuzz_one() {  # BUILD SECONDS TARGET
    local build="$1" seconds="$2" t="$3"
    local bin="$build/tests/fuzz/fovea_fuzz_$t" seeds corpus="$build/fuzz/corpus/$t"
    local artifacts="$build/fuzz/artifacts/$t/"
    seeds="$(prepare_seeds "$build" "$t")"
    mkdir -p "$corpus" "$artifacts"
    local dict=() regressions=()
    [ -f "$here/dict/$t.dict" ] && dict=("-dict=$here/dict/$t.dict")
    [ -d "$here/regressions/$t" ] && regressions=("$here/regressions/$t")
    # Leaks are findings here (no Vulkan loader or llvmpipe in a fuzz target); the suppressions
    # (lsan.supp) would name leaks inside Debian libraries (none at present).
    local asan="detect_leaks=1:allocator_may_return_null=1"
    # -entropic=0: libFuzzer 14's entropic schedule spends ~90 % of the time updating feature
    # frequencies on targets this large (the glTF target: 13 executions/s with it, 535 without).
    ASAN_OPTIONS="$asan" LSAN_OPTIONS="suppressions=$here/lsan.supp:print_suppressions=0" \
        "$bin" -max_total_time="$seconds" -timeout=2 -rss_limit_mb=2048 -max_len=65536 \
        -entropic=0 -seed="${FUZZ_SEED:-0}" -print_final_stats=1 -artifact_prefix="$artifacts" "${dict[@]}" \
        "$corpus" "$seeds" "${regressions[@]}" > "$build/fuzz/fuzz-$t.log" 2>&1
}

fuzz() {  # BUILD SECONDS TARGET...
    local build="$1" seconds="$2"
    shift 2
    local list=("$@")
    [ ${#list[@]} -gt 0 ] || list=("${targets[@]}")
    mkdir -p "$build/fuzz"
    local failed=() pids=() names=()
    for t in "${list[@]}"; do
        fuzz_one "$build" "$seconds" "$t" & pids+=($!); names+=("$t")
        if [ ${#pids[@]} -ge 2 ]; then
            wait "${pids[0]}" || failed+=("${names[0]}")
            pids=("${pids[@]:1}"); names=("${names[@]:1}")
        fi
    done
    for i in "${!pids[@]}"; do wait "${pids[$i]}" || failed+=("${names[$i]}"); done
    for t in "${list[@]}"; do
        local stats
        stats="$(grep -E 'stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb' \
            "$build/fuzz/fuzz-$t.log" | awk '{printf "%s %s  ", $1, $2}' || true)"
        local cov
        cov="$(grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [0-9]+' "$build/fuzz/fuzz-$t.log" | tail -n 1 || true)"
        echo "fuzz $t: $cov  $stats"
    done
    if [ ${#failed[@]} -gt 0 ]; then
        for t in "${failed[@]}"; do
            echo "fuzz.sh: $t FAILED (log: $build/fuzz/fuzz-$t.log; input in $build/fuzz/artifacts/$t/)"
            grep -m 1 -A 30 -E 'ERROR|fuzz .*: not an InputError|deadly signal|Timeout|out-of-memory' \
                "$build/fuzz/fuzz-$t.log" || tail -n 30 "$build/fuzz/fuzz-$t.log"
        done
        exit 1
    fi
}

case "${1:-}" in
    replay) [ $# -eq 3 ] || { echo "usage: fuzz.sh replay BUILD TARGET" >&2; exit 2; }; replay "$2" "$3" ;;
    fuzz) [ $# -ge 3 ] || { echo "usage: fuzz.sh fuzz BUILD SECONDS [TARGET...]" >&2; exit 2; }
          fuzz "$2" "$3" "${@:4}" ;;
    *) echo "usage: fuzz.sh replay BUILD TARGET | fuzz BUILD SECONDS [TARGET...]" >&2; exit 2 ;;
esac
