#!/usr/bin/env bash
# Sharded references and benches on Slurm, or locally in parallel (docs/cluster.md).
#
#   scripts/slurm/submit.sh reference --shards N --out DIR [options] -- [fovea reference args]
#   scripts/slurm/submit.sh reference --frame-shards N --out DIR [options] -- \
#       --camera PATH --path-frames A:B [fovea reference args]
#   scripts/slurm/submit.sh bench BENCH.json --out DIR [options]
#
# reference: an sbatch array of N shards (`fovea reference ARGS --shard I/N --out DIR/shardI`,
#            or with --frame-shards `--frames-of I/N`: blocks of the path frames), then a job
#            `fovea merge DIR/shard* --out DIR/merged` after all of them succeeded.
# bench:     an array of the bench's reference items, an array of its runs after them, then
#            `fovea bench --collect DIR` (items and order from `fovea bench --plan`).
#
# Resumable: an item whose done marker exists (a shard's shard.json, a bench item's result.json
# with this bench's key; both written last) is skipped, so resubmitting after a pre-empted,
# cancelled or failed task reruns only what is missing. Stages with nothing left are skipped.
#
# Options:
#   --fovea PATH       the executable (default: fovea on PATH, else build/fovea of this tree)
#   --local J          run the same plan here, J items at a time, instead of submitting
#   --gres G           e.g. gpu:1, passed to every array task
#   --partition P      --time T  --cpus C  (per task; default 1 CPU)   --account A
#   --sbatch-arg X     any further sbatch argument (repeatable)
#   --dry-run          write the job scripts and print the sbatch commands, submit nothing
# Prints the job ids (or "nothing to do"); exits non-zero on bad arguments or a failed sbatch.
set -euo pipefail

die() { echo "submit.sh: $*" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)

[[ $# -ge 1 ]] || die "usage: submit.sh reference|bench ... (see the header of this script)"
mode=$1; shift
bench="" out="" shards="" split=--shard local_jobs="" fovea="" dry=0
sbatch_args=(--cpus-per-task=1)
fovea_args=()
if [[ $mode == bench ]]; then
  [[ $# -ge 1 ]] || die "bench needs a bench file"
  bench=$(realpath "$1"); shift
  [[ -f $bench ]] || die "bench file '$bench' not found"
elif [[ $mode != reference ]]; then
  die "unknown mode '$mode' (reference or bench)"
fi
while [[ $# -gt 0 ]]; do
  case $1 in
    --out) out=$2; shift 2 ;;
    --shards) shards=$2; shift 2 ;;
    --frame-shards) shards=$2; split=--frames-of; shift 2 ;;
    --fovea) fovea=$2; shift 2 ;;
    --local) local_jobs=$2; shift 2 ;;
    --gres) sbatch_args+=("--gres=$2"); shift 2 ;;
    --partition) sbatch_args+=("--partition=$2"); shift 2 ;;
    --time) sbatch_args+=("--time=$2"); shift 2 ;;
    --account) sbatch_args+=("--account=$2"); shift 2 ;;
    --cpus) sbatch_args[0]="--cpus-per-task=$2"; shift 2 ;;
    --sbatch-arg) sbatch_args+=("$2"); shift 2 ;;
    --dry-run) dry=1; shift ;;
    --) shift; fovea_args=("$@"); break ;;
    *) die "unknown option '$1'" ;;
  esac
done
[[ -n $out ]] || die "--out DIR is required"
if [[ -n $local_jobs && ! $local_jobs =~ ^[1-9][0-9]*$ ]]; then die "--local needs a count >= 1"; fi
if [[ -z $fovea ]]; then
  fovea=$(command -v fovea || true)
  [[ -n $fovea ]] || fovea="$here/../../build/fovea"
fi
fovea=$(realpath "$fovea")
[[ -x $fovea ]] || die "fovea executable '$fovea' not found (--fovea PATH)"
mkdir -p "$out"
out=$(realpath "$out")
jobs_dir="$out/slurm"
mkdir -p "$jobs_dir/logs"

q() { printf '%q ' "$@"; }  # a command line, quoted for a job script
q1() { printf '%q' "$1"; }  # one word, quoted, no trailing space

# Writes a job script running `command` (for arrays, $SLURM_ARRAY_TASK_ID is the item) and
# submits it: prints its job id. The commands `exec` fovea, so the job's process is fovea itself:
# a cancelled or pre-empted task's SIGTERM reaches it, and no fovea outlives its shell (Slurm's
# linuxproc tracking loses a child whose shell died first, which then finished and wrote its done
# marker after the cancel: seen in CI). Args: name, array list ("" = no array), dependency id
# ("" = none), command...
submit() {
  local name=$1 array=$2 after=$3; shift 3
  local script="$jobs_dir/$name.sh"
  {
    echo "#!/usr/bin/env bash"
    echo "set -euo pipefail"
    echo "$*"
  } > "$script"
  chmod +x "$script"
  local args=(--parsable --job-name="fovea-$name" --output="$jobs_dir/logs/$name-%A_%a.out"
              "${sbatch_args[@]}")
  [[ -z $array ]] || args+=(--array="$array")
  # A merge whose shards failed can never run: let Slurm drop it instead of waiting forever.
  [[ -z $after ]] || args+=(--dependency="afterok:$after" --kill-on-invalid-dep=yes)
  if [[ $dry == 1 ]]; then
    echo "sbatch ${args[*]} $script" >&2
    echo "DRY"
    return
  fi
  local id
  id=$(sbatch "${args[@]}" "$script") || { echo "submit.sh: sbatch failed for $name" >&2; exit 1; }
  echo "${id%%;*}"
}

# Runs `command` with ITEM replaced by each of `items` (a comma list), J at a time.
run_local() {
  local items=$1; shift
  [[ -z $items ]] && return 0
  tr ',' '\n' <<< "$items" |
    xargs -P "$local_jobs" -I ITEM bash -c "$*" \
      || { echo "submit.sh: a local item failed (logs above)" >&2; exit 1; }
}

join() { local IFS=,; echo "$*"; }

if [[ $mode == reference ]]; then
  [[ $shards =~ ^[1-9][0-9]*$ ]] || die "reference needs --shards N or --frame-shards N (N >= 1)"
  pending=()
  for ((i = 0; i < shards; ++i)); do
    [[ -f $out/shard$i/shard.json ]] || pending+=("$i")
  done
  shard_cmd="$(q "$fovea" reference "${fovea_args[@]}") $split \$I/$shards --out $(q1 "$out")/shard\$I --overwrite --quiet"
  merge_cmd="$(q "$fovea" merge) $(for ((i = 0; i < shards; ++i)); do q "$out/shard$i"; done) --out $(q "$out/merged") --overwrite"
  echo "submit.sh: ${#pending[@]} of $shards shards to render: $(join "${pending[@]}")" >&2
  if [[ -n $local_jobs ]]; then
    run_local "$(join "${pending[@]}")" "I=ITEM; ${shard_cmd}"
    eval "$merge_cmd"
    exit 0
  fi
  shard_job=""
  if [[ ${#pending[@]} -gt 0 ]]; then
    shard_job=$(submit reference-shards "$(join "${pending[@]}")" "" "I=\$SLURM_ARRAY_TASK_ID; exec $shard_cmd")
    echo "shards $shard_job"
  fi
  echo "merge $(submit reference-merge "" "$shard_job" "exec $merge_cmd")"
  exit 0
fi

# bench: the plan's items; reference items (no needs) first, runs after, collect last.
plan=$("$fovea" bench "$bench" --plan) || die "fovea bench --plan failed (the bench file?)"
key=$(grep -o '"bench_key": *"[0-9a-f]*"' <<< "$plan" | head -1 | grep -o '[0-9a-f]\{16\}')
refs=() runs=()
while read -r index kind result; do
  done_marker="$out/$result"
  if [[ -f $done_marker ]] && grep -q "\"bench_key\": *\"$key\"" "$done_marker"; then continue; fi
  if [[ $kind == run ]]; then runs+=("$index"); else refs+=("$index"); fi
done < <(tr -d '\n' <<< "$plan" | grep -o '{[^{}]*"index"[^{}]*}' |
         sed -E 's/.*"index": *([0-9]+).*"kind": *"([a-z_]+)".*"result": *"([^"]+)".*/\1 \2 \3/')
item_cmd="$(q "$fovea" bench "$bench") --out $(q "$out") --item \$I --quiet"
collect_cmd="$(q "$fovea" bench "$bench") --collect $(q "$out") --quiet"
echo "submit.sh: references to render: $(join "${refs[@]}"); runs: $(join "${runs[@]}")" >&2
if [[ -n $local_jobs ]]; then
  run_local "$(join "${refs[@]}")" "I=ITEM; ${item_cmd}"
  run_local "$(join "${runs[@]}")" "I=ITEM; ${item_cmd}"
  eval "$collect_cmd"
  exit 0
fi
ref_job="" run_job=""
if [[ ${#refs[@]} -gt 0 ]]; then
  ref_job=$(submit bench-references "$(join "${refs[@]}")" "" "I=\$SLURM_ARRAY_TASK_ID; exec $item_cmd")
  echo "references $ref_job"
fi
if [[ ${#runs[@]} -gt 0 ]]; then
  run_job=$(submit bench-runs "$(join "${runs[@]}")" "$ref_job" "I=\$SLURM_ARRAY_TASK_ID; exec $item_cmd")
  echo "runs $run_job"
fi
echo "collect $(submit bench-collect "" "${run_job:-$ref_job}" "exec $collect_cmd")"
