#!/usr/bin/env bash
# A test of CI itself: when the README's test command fails (here: configuring fails, through
# VS11_CI_BREAK_CONFIGURE, which only this test sets), .ci/run must exit non-zero and must not start
# the sanitizer stages (.ci/sanitize, .ci/tsan). Cheap: the broken configure fails at once and
# nothing is built.
# Usage: ci_run_test.sh SOURCE_DIR
set -uo pipefail
source_dir=$1

output=$(VS11_CI_BREAK_CONFIGURE=1 bash "$source_dir/.ci/run" 2>&1)
status=$?
printf '%s\n' "$output"
failed=0
if ((status == 0)); then
  echo "FAIL: .ci/run exited 0 although configuring failed"
  failed=1
fi
if grep -q "^\(sanitize\|tsan\): stage reached" <<<"$output"; then
  echo "FAIL: .ci/run went on to the sanitizer stage after the test command failed"
  failed=1
fi
if ! grep -q "No Such Generator" <<<"$output"; then
  echo "FAIL: configuring did not fail the way VS11_CI_BREAK_CONFIGURE asks, so this test proves nothing"
  failed=1
fi
# CI runs the README's test command (its second Quick start line) as it is written there.
readme_test_command=$(grep -m1 '^bash .ci/setup --tests && ctest ' "$source_dir/README.md")
if [[ -z $readme_test_command ]] || ! grep -qF "($readme_test_command)" "$source_dir/.ci/run"; then
  echo "FAIL: .ci/run does not run the README's test command '${readme_test_command}' verbatim"
  failed=1
fi
((failed == 0)) && echo "PASS: .ci/run exited $status and stopped before the sanitizer stage, and runs the README's test command"
exit "$failed"
