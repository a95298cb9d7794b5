# Sourced by the command-line tests: arguments LADARSIM_BINARY SOURCE_DIR, a scratch directory
# removed on exit, a failure counter, and the shared data (../shared/data beside the checkout, or
# under LADARSIM_SHARED_DIR from the environment).
set -u
bin=$(realpath "$1")
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
shared_data="${LADARSIM_SHARED_DIR:-$src/../shared}/data"
# A check that cannot run here (its data or a tool is missing) is said, and makes the test report
# skipped rather than passed: exit 77, the SKIP_RETURN_CODE of tests/CMakeLists.txt.
skipped=0
skip() { echo "SKIPPED: $*"; skipped=$((skipped + 1)); }
finish() {  # NAME: the verdict of the checks run so far, and the exit
  if [ "$failures" -ne 0 ]; then echo "$1: $failures failed"; exit 1; fi
  if [ "$skipped" -ne 0 ]; then echo "$1: the checks that ran passed, $skipped skipped"; exit 77; fi
  echo "$1: all checks passed"
  exit 0
}
