#!/usr/bin/env bash
# Instructions of PROGRAM ARGS... inside FUNCTION (a symbol of a PIE executable, as nm names it),
# counted by single-stepping (studies/bench/step_count.c; valgrind runs no AVX-512). Prints the
# total and the count inside. Instructions per pose of a kernel: inside / rows, e.g.
#   studies/bench/step_count.sh closed_form_quad_avx512vl_run build/bench-batch 400 --once 0 avx512vl
set -euo pipefail
function=$1
shift
program=$1
tool=$(mktemp -d)
trap 'rm -rf "$tool"' EXIT
cc -O2 "$(dirname "$0")/step_count.c" -o "$tool/step_count"
read -r start size < <(nm -S "$program" | awk -v f="$function" '$4 ~ f {print $1, $2; exit}')
base=0x555555554000  # where Linux loads a PIE executable without address randomisation (x86-64)
low=$(printf '%x' $((base + 0x$start)))
high=$(printf '%x' $((base + 0x$start + 0x$size)))
setarch -R "$tool/step_count" "$low" "$high" "$@"
