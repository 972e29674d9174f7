#!/usr/bin/env bash
# MPI scaling of octrace render (issue 16, docs/multi_gpu.md): time to a
# fixed number of samples with 1, 2, 4 ranks (`mpirun -np K octrace render`),
# speedup and efficiency against one rank, where each rank's time went
# (set-up, waiting for the other ranks, batches, waiting for rank 0's
# answers, gaps), and the merge overhead: reducing a 3840x2160 state between
# 2 ranks (rank 1's state handed to rank 0 in slices, through a shared-memory
# window or as messages, each merged while the next arrives), with its parts
# (times_ms.reduce_*).
# Each rank renders on its node-local GPU (local rank modulo the node's
# GPUs): on a host with one GPU the ranks share it, which measures what the
# split and the reduce cost. Needs only the binary, mpirun and a shell (no
# Python): run it where the binary runs.
#
#   tools/mpi_scaling.sh OCTRACE_BINARY OUT_DIR [RUNS]
#
# Settings through the environment (defaults in brackets): SIZE [1200x800],
# SPP [1000], RANKS ["1 2 4"; "none": only the merge], BATCH_MS [250: the
# --batch-ms values to run, e.g. "250 2000"], SCENE_FLAGS [the default
# scene], TURNS ["auto off": the --device-turns values to run: ranks sharing
# a GPU take turns, or render at once], MERGE_SIZE [3840x2160],
# MERGE_SPP [1], REDUCE ["shared messages": the reduce through the host's
# shared-memory window, or as messages, OCTRACE_MPI_REDUCE], MPIRUN
# [mpirun], MPIRUN_FLAGS [-q --oversubscribe --bind-to none; e.g. add
# "--mca btl self,vader --mca btl_vader_single_copy_mechanism cma" to
# compare OpenMPI's transports for the messages]. On lavapipe, set
# LP_NUM_THREADS (the threads of each rank) so that the ranks do not fight
# for the cores.
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 OCTRACE_BINARY OUT_DIR [RUNS]" >&2; exit 2; }
bin=$1 out=$2 runs=${3:-3}
size=${SIZE:-1200x800} spp=${SPP:-1000} ranks_list=${RANKS:-"1 2 4"} scene_flags=${SCENE_FLAGS:-}
batch_list=${BATCH_MS:-250} turns_list=${TURNS:-"auto off"} reduce_list=${REDUCE:-"shared messages"}
[ "$ranks_list" = none ] && ranks_list=""
merge_size=${MERGE_SIZE:-3840x2160} merge_spp=${MERGE_SPP:-1}
mpirun=${MPIRUN:-mpirun}
# --bind-to none: OpenMPI binds each of up to 2 ranks to one core by default,
# which leaves a rank one core for its host threads (and lavapipe's).
read -r -a mpirun_flags <<< "${MPIRUN_FLAGS:--q --oversubscribe --bind-to none}"
# OpenMPI refuses root unless told (containers, the GPU machine).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out"

# A number from octrace's --json summary: the first "KEY": VALUE.
field() { grep -o "\"$2\": [-0-9.e+]*" "$1" | head -1 | awk '{print $2}'; }
# The first N values of KEY, one a line: the ranks' entries (the summary's
# keys are sorted, so "ranks" comes before "samples" and "times_ms").
fields() { grep -o "\"$2\": [-0-9.e+]*" "$1" | head -"$3" | awk '{print $2}'; }
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
now() { date +%s.%N; }

{
  echo "date      $(date -u +'%Y-%m-%d %H:%M UTC')"
  echo "binary    $bin"
  echo "host      $(hostname)"
  echo "mpirun    $("$mpirun" --version 2>&1 | head -1)"
  echo "devices   $("$bin" devices | grep -E '^[0-9]+ ' | tr '\n' ';')"
  echo "settings  --size $size --spp $spp $scene_flags, median of $runs runs after a warm-up"
} | tee "$out/summary.txt"

echo "render wall: from the job's first batch to the last pass (times_ms.render_wall); job: the whole mpirun command, set-up, reduce and write included." | tee -a "$out/summary.txt"
for t in $turns_list; do
for b in $batch_list; do
  echo "--device-turns $t --batch-ms $b:" | tee -a "$out/summary.txt"
  echo "| ranks | render wall s | job s | reduce ms | speedup (render / job) | efficiency (render / job) |" | tee -a "$out/summary.txt"
  echo "|---:|---:|---:|---:|---:|---:|" | tee -a "$out/summary.txt"
  w1="" j1=""
  for k in $ranks_list; do
    # shellcheck disable=SC2086
    "$mpirun" "${mpirun_flags[@]}" -np "$k" "$bin" render $scene_flags --size "$size" --spp "$spp" --batch-ms "$b" \
      --device-turns "$t" --quiet --out "$out/warm.pfm"
    : > "$out/wall-$t-$b-$k.txt"; : > "$out/job-$t-$b-$k.txt"; : > "$out/reduce-$t-$b-$k.txt"
    for r in $(seq "$runs"); do
      s=$(now)
      # shellcheck disable=SC2086
      "$mpirun" "${mpirun_flags[@]}" -np "$k" "$bin" render $scene_flags --size "$size" --spp "$spp" --batch-ms "$b" \
        --device-turns "$t" --json --quiet --out "$out/ranks-$k.pfm" > "$out/ranks-$t-$b-$k-$r.json"
      e=$(now)
      awk -v a="$s" -v b="$e" 'BEGIN {print b - a}' >> "$out/job-$t-$b-$k.txt"
      awk -v w="$(field "$out/ranks-$t-$b-$k-$r.json" render_wall)" 'BEGIN {print w / 1000}' >> "$out/wall-$t-$b-$k.txt"
      red=$(field "$out/ranks-$t-$b-$k-$r.json" reduce)
      echo "${red:-0}" >> "$out/reduce-$t-$b-$k.txt"
    done
    w=$(median < "$out/wall-$t-$b-$k.txt") j=$(median < "$out/job-$t-$b-$k.txt") red=$(median < "$out/reduce-$t-$b-$k.txt")
    [ -z "$w1" ] && w1=$w && j1=$j
    awk -v k="$k" -v w="$w" -v j="$j" -v red="$red" -v w1="$w1" -v j1="$j1" 'BEGIN {
      printf "| %d | %.3f | %.3f | %.1f | %.2fx / %.2fx | %.1f%% / %.1f%% |\n", k, w, j, red, w1 / w, j1 / j, 100 * w1 / (k * w), 100 * j1 / (k * j)
    }' | tee -a "$out/summary.txt"
  done
  # Where each rank's time went, in the last run of each rank count (ms;
  # set-up: device, accel build, upload, pipeline; wall: from the job's
  # first batch to the rank's last; of it: in batches (submission to
  # completion), waiting for rank 0's answers (of it, waiting for the turn
  # of the device: requests that waited, and the time), the rest idle).
  echo "where the time went, --device-turns $t --batch-ms $b, last run of each (ms):" | tee -a "$out/summary.txt"
  echo "| ranks | rank | spp | batches | device | wall | in batches | waiting for answers | of it for turns (count) | idle | longest gap | waiting at start | set-up (device / accel / upload / pipeline) |" | tee -a "$out/summary.txt"
  echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|" | tee -a "$out/summary.txt"
  for k in $ranks_list; do
    f="$out/ranks-$t-$b-$k-$runs.json"
    paste <(fields "$f" samples "$k") <(fields "$f" batches "$k") <(fields "$f" render_ms "$k") \
      <(fields "$f" render_wall_ms "$k") <(fields "$f" passes_wall_ms "$k") <(fields "$f" batch_wait_ms "$k") \
      <(fields "$f" max_gap_ms "$k") <(fields "$f" start_wait_ms "$k") <(fields "$f" setup_ms "$k") \
      <(fields "$f" device_init "$k") <(fields "$f" accel_build "$k") <(fields "$f" upload "$k") \
      <(fields "$f" pipeline "$k") <(fields "$f" turn_wait_ms "$k") <(fields "$f" turns_waited "$k") |
      awk -v k="$k" '{printf "| %d | %d | %d | %d | %.1f | %.1f | %.1f | %.1f | %.1f (%d) | %.1f | %.1f | %.1f | %.1f (%.1f / %.1f / %.1f / %.1f) |\n",
        k, NR - 1, $1, $2, $3, $4, $5, $6, $14, $15, $4 - $5 - $6, $7, $8, $9, $10, $11, $12, $13}' | tee -a "$out/summary.txt"
  done
done
done

# The merge overhead: 2 ranks, a MERGE_SIZE state each, for each way the
# state reaches rank 0 (OCTRACE_MPI_REDUCE: shared, the host's shared-memory
# window; messages, OpenMPI's transport as between hosts).
parts="reduce reduce_alloc reduce_receive reduce_merge reduce_merge_wait reduce_send"
for m in $reduce_list; do
  echo "merge overhead, 2 ranks, $merge_size, $merge_spp spp, OCTRACE_MPI_REDUCE=$m: rank 1's state (3 x 16 bytes per pixel) reaches rank 0 in slices ($m) and rank 0 merges each slice into its own state while the next arrive (times_ms.reduce and its parts, which overlap; median of $runs):" | tee -a "$out/summary.txt"
  for p in $parts; do : > "$out/$p-$m.txt"; done
  for r in $(seq "$runs"); do
    # shellcheck disable=SC2086
    OCTRACE_MPI_REDUCE=$m "$mpirun" "${mpirun_flags[@]}" -np 2 "$bin" render $scene_flags --size "$merge_size" \
      --spp "$merge_spp" --json --quiet --out "$out/merge.pfm" > "$out/merge-$m-$r.json"
    for p in $parts; do field "$out/merge-$m-$r.json" "$p" >> "$out/$p-$m.txt"; done
  done
  {
    echo "| reduce ms | allocating | waiting for data | merging (busiest thread) | waiting for the merging threads | rank 1 sending |"
    echo "|---:|---:|---:|---:|---:|---:|"
    line="|"
    for p in $parts; do line="$line $(median < "$out/$p-$m.txt" | awk '{printf "%.1f", $1}') |"; done
    echo "$line"
  } | tee -a "$out/summary.txt"
done
rm -f "$out/merge.pfm"
rm -f "$out/warm.pfm"
