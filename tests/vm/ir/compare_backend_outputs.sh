#!/bin/sh
# Compares what two builds' back ends make of the same programs, byte for byte: the jit's machine code
# (AVX2, and AVX-512 where the CPU has it) and the translator's GLSL and SPIR-V, under both float rules
# (tests/vm/ir/backend_output_dump_test.cc lists the cases). For a change to vm/ir/ or a back end that
# should not change their output: build the base commit into one build directory and the change into
# another, then
#   tests/vm/ir/compare_backend_outputs.sh BASE_BUILD NEW_BUILD
# Exits 0 when every file is identical, 1 (listing the files that differ) otherwise, 2 on misuse.
set -eu
if [ $# -ne 2 ]; then
  echo "usage: $0 BASE_BUILD NEW_BUILD (build directories holding tests/vs11_tests)" >&2
  exit 2
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for side in base new; do
  if [ "$side" = base ]; then build=$1; else build=$2; fi
  VS11_BACKEND_DUMP="$out/$side" "$build/tests/vs11_tests" --gtest_also_run_disabled_tests \
    --gtest_filter='BackendOutputDump.*' >"$out/$side.log" 2>&1 || { cat "$out/$side.log" >&2; exit 1; }
done
echo "$(ls "$out/base" | wc -l) files from the base build, $(ls "$out/new" | wc -l) from the new one"
if diff -rq "$out/base" "$out/new"; then
  echo "identical"
else
  exit 1
fi
