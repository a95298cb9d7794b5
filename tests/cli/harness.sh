# Sourced by the command-line tests: arguments LADARSIM_BINARY SOURCE_DIR, a scratch directory
# removed on exit, and a failure counter.
set -u
bin=$(realpath "$1")
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
