#!/usr/bin/env bash
# Worst-case latency (issue 21): runs build/latency (studies/bench/latency.c) over 10^6 calls of
# each workload and writes its table, with the machine and its load, to
# studies/bench/latency-results.md (docs/latency.md quotes it). Twice: at the ordinary priority,
# where on a shared machine the tail is the scheduler's (other processes' time slices), and, if
# this user may (CAP_SYS_NICE), under SCHED_FIFO (`chrt -f 10`), where only interrupts and the
# hypervisor preempt. The load average before and after each row is part of the row, and a census
# of the machine's interruptions before and after the rows gives each row its noise floor.
# usage: [LATENCY_CPU=K] [LATENCY_CENSUS_SECONDS=10] studies/bench/latency.sh [BUILD_DIR=build]
#        [CALLS=1000000] [WORKLOAD...]
# LATENCY_CPU pins both runs to core K (taskset): on this VM the device interrupts that a build's
# disk traffic raises land on core 1, so core 0 is the quieter one.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$(realpath "${1:-build}")
calls=${2:-1000000}
workloads=("${@:3}")
pin=()
if [ -n "${LATENCY_CPU:-}" ]; then pin=(taskset -c "$LATENCY_CPU"); fi
[ -x "$build/latency" ] || { echo "latency.sh: $build/latency is missing: build first"; exit 2; }
out=studies/bench/latency-results.md
table=$(mktemp)
trap 'rm -f "$table"' EXIT

# One run: a heading, the load around it, the table.
run() {
  local title=$1
  shift
  local before after
  before=$(cut -d' ' -f1-3 /proc/loadavg)
  "$@" "${pin[@]+"${pin[@]}"}" "$build/latency" "$build/fmu" "$table" "$calls" \
    "${workloads[@]+"${workloads[@]}"}" >/dev/null
  after=$(cut -d' ' -f1-3 /proc/loadavg)
  echo "## $title"
  echo
  echo "Load average (1, 5, 15 min) before: $before; after: $after."
  echo
  cat "$table"
  echo
}

{
  echo "# Latency of one call (studies/bench/latency.sh)"
  echo
  echo "Written by studies/bench/latency.sh on $(date -u '+%Y-%m-%d %H:%M UTC'), commit" \
       "$(git rev-parse --short HEAD 2>/dev/null || echo '?')."
  echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'),"
  echo "Linux $(uname -r); build type $(grep -m1 CMAKE_BUILD_TYPE: "$build/CMakeCache.txt" | cut -d= -f2)."
  echo "Pinned to core: ${LATENCY_CPU:-no}."
  echo
  run "Ordinary priority (SCHED_OTHER)"
  if chrt -f 10 true 2>/dev/null; then
    run "SCHED_FIFO priority 10 (chrt -f 10)" chrt -f 10
  else
    echo "(SCHED_FIFO not permitted for this user: no real-time run.)"
  fi
} >"$out"
cat "$out"
