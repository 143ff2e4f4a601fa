#!/usr/bin/env bash
# Sharded references and benches on a real Slurm (docs/cluster.md): a one-node cluster on the
# loopback (slurm_cluster.sh) runs scripts/slurm/submit.sh's jobs, and the merged results must
# equal the unsharded ones. Then one array task is cancelled mid-run (scancel) and a resubmission
# must rerun only that task. Every daemon started here is stopped by pid on exit.
#
#   SlurmShardTest.sh FOVEA_EXECUTABLE REPOSITORY
# Exit 0 pass, 1 fail, 77 skipped (ctest SKIP_RETURN_CODE): no Slurm/munge or not root.
set -euo pipefail
fovea=$(realpath "$1")
repo=$(realpath "$2")
submit="$repo/scripts/slurm/submit.sh"

for tool in sbatch squeue scancel sinfo slurmctld slurmd munged; do
  if ! command -v "$tool" > /dev/null; then
    echo "SKIPPED: '$tool' not found (apt-get install slurm-wlm munge; .ci/run installs them)"
    exit 77
  fi
done
if [[ $(id -u) != 0 ]]; then echo "SKIPPED: slurmd must run as root here"; exit 77; fi

tmp=$(mktemp -d /tmp/fovea-slurm.XXXXXX)
# shellcheck source=tests/cluster/slurm_cluster.sh
source "$repo/tests/cluster/slurm_cluster.sh"
trap 'slurm_stop; rm -rf "$tmp"' EXIT

fail() {
  echo "FAIL: $*"
  for log in "$tmp"/*/slurm/logs/*.out "$tmp/cluster/log/slurmctld.log"; do
    [[ -f $log ]] && { echo "--- $log"; tail -n 20 "$log"; }
  done
  exit 1
}

# Waits until the queue is empty (at most $1 seconds).
wait_queue() {
  local deadline=$((SECONDS + $1))
  while [[ -n $(squeue -h -o '%i' 2> /dev/null) ]]; do
    ((SECONDS < deadline)) || fail "jobs still queued after $1 s: $(squeue -h)"
    sleep 0.5
  done
}

# The RMSE % of image $1 against $2 (fovea compare).
rmse_percent() {
  "$fovea" compare "$1" "$2" --json --no-flip | grep '"rmse_percent"' | grep -o '[0-9.e+-]*' | tail -1
}

# bench.csv without the columns that time decides (frame/pass ms, speed-up, Pareto).
csv_without_times() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) keep[i] = ($i !~ /_ms/ && $i != "speedup" && $i != "pareto") }
           { line = ""; for (i = 1; i <= NF; ++i) if (keep[i]) line = line $i ","; print line }' "$1"
}

slurm_start "$tmp/cluster" || fail "the local Slurm did not start"
echo "slurm up: $(sinfo -h -o '%P %D %T')"

# --- 1. A reference sharded 4 ways equals the single run (float rounding) ----------------------
ref_args=(--spp 8 --size 48x32)
"$fovea" reference "${ref_args[@]}" --out "$tmp/single" --quiet
start=$SECONDS
"$submit" reference --shards 4 --out "$tmp/ref" --fovea "$fovea" -- "${ref_args[@]}"
wait_queue 300
echo "4-shard reference on Slurm: $((SECONDS - start)) s wall"
merged="$tmp/ref/merged/acc.mean.frame0007.exr"
[[ -f $merged ]] || fail "no merged reference ($merged)"
grep -q '"finished": true' "$tmp/ref/merged/report.json" || fail "merged report.json unfinished"
err=$(rmse_percent "$merged" "$tmp/single/acc.mean.frame0007.exr")
awk -v e="$err" 'BEGIN { exit !(e < 1e-3) }' || fail "merged reference differs: RMSE $err %"
echo "merged vs single reference: RMSE $err %"

# --- 2. A 2-graph x 2-seed bench collected on Slurm equals the one-process bench --------------
cat > "$tmp/b.json" << JSON
{"version": 1, "name": "slurm", "scene": "builtin:cornell", "size": [48, 32], "frames": 3,
 "warmup": 1, "seeds": [1, 2], "output": "acc.mean", "reference": {"render": {"spp": 4}},
 "graphs": [{"label": "1 spp", "file": "$repo/graphs/demo.json", "set": ["pt.spp=1"]},
            {"label": "2 spp", "file": "$repo/graphs/demo.json", "set": ["pt.spp=2"]}]}
JSON
"$submit" bench "$tmp/b.json" --out "$tmp/bench" --fovea "$fovea"
wait_queue 300
grep -q '"finished": true' "$tmp/bench/bench.json" || fail "the collected bench is unfinished"
"$fovea" bench "$tmp/b.json" --out "$tmp/whole" --quiet
diff <(csv_without_times "$tmp/whole/bench.csv") <(csv_without_times "$tmp/bench/bench.csv") ||
  fail "bench.csv of the Slurm bench differs from the one-process bench"
echo "Slurm bench equals the one-process bench (apart from times)"

# --- 3. Cancel one array task mid-run; resubmitting reruns only that task ----------------------
slow=(--spp 256 --size 128x128)
"$submit" reference --shards 4 --out "$tmp/slow" --fovea "$fovea" -- "${slow[@]}" > "$tmp/ids"
shard_job=$(awk '/^shards/ { print $2 }' "$tmp/ids")
[[ -n $shard_job ]] || fail "no shard job id: $(cat "$tmp/ids")"
deadline=$((SECONDS + 120))
until [[ $(squeue -h -j "${shard_job}_0" -o '%t' 2> /dev/null) == R ]]; do
  ((SECONDS < deadline)) || fail "shard 0 never ran"
  sleep 0.1
done
scancel "${shard_job}_0"
wait_queue 300
[[ ! -f $tmp/slow/shard0/shard.json ]] || fail "shard 0 finished before it was cancelled"
for i in 1 2 3; do
  [[ -f $tmp/slow/shard$i/shard.json ]] || fail "shard $i did not finish"
done
[[ ! -f $tmp/slow/merged/report.json ]] || fail "merged although shard 0 was cancelled"
before=$(stat -c '%Y %n' "$tmp"/slow/shard[123]/shard.json)
"$submit" reference --shards 4 --out "$tmp/slow" --fovea "$fovea" -- "${slow[@]}" \
  2> "$tmp/resubmit.err" > /dev/null
grep -q "1 of 4 shards to render: 0$" "$tmp/resubmit.err" ||
  fail "the resubmission did not pick shard 0 alone: $(cat "$tmp/resubmit.err")"
wait_queue 300
[[ -f $tmp/slow/shard0/shard.json ]] || fail "shard 0 was not rerun"
[[ $(stat -c '%Y %n' "$tmp"/slow/shard[123]/shard.json) == "$before" ]] ||
  fail "finished shards were rendered again"
grep -q '"finished": true' "$tmp/slow/merged/report.json" || fail "no merge after the rerun"
echo "cancelled shard 0 rerun alone; merged"
echo "PASS"
