#!/usr/bin/env bash
# vs11_bench finds programs/ wherever it runs (bench/bench_common.h, ProgramsFolder): it reads the
# folder $VS11_PROGRAMS_DIR names, and without any programs folder it says where it looked and exits 2
# (it used to die of an uncaught std::filesystem::filesystem_error).
# Usage: programs_folder_test.sh VS11_BENCH SOURCE_DIR SCRATCH_DIR
set -uo pipefail
bench=$1 source_dir=$2 scratch=$3
failed=0
rm -rf "$scratch" && mkdir -p "$scratch/programs"
cp "$source_dir/programs/fog.vsh" "$scratch/programs/"

listed=$(cd "$scratch" && VS11_PROGRAMS_DIR="$scratch/programs" "$bench" --benchmark_list_tests 2>&1)
status=$?
if ((status != 0)) || ! grep -q '^BM_Program/fog/jit$' <<<"$listed" || grep -q '^BM_Program/skinning/' <<<"$listed"; then
  echo "FAIL: with VS11_PROGRAMS_DIR set, vs11_bench (exit $status) should list fog's benchmarks and no others':"
  printf '%s\n' "$listed" | grep '^BM_Program/' | head -20
  failed=1
fi

missing=$(cd "$scratch" && VS11_PROGRAMS_DIR="$scratch/no-such-folder" "$bench" --benchmark_list_tests 2>&1)
status=$?
if ((status != 2)) || ! grep -q "no-such-folder" <<<"$missing" || ! grep -q "VS11_PROGRAMS_DIR" <<<"$missing"; then
  echo "FAIL: without a programs folder vs11_bench should name where it looked and exit 2; it exited $status:"
  printf '%s\n' "$missing" | head -20
  failed=1
fi
exit $failed
