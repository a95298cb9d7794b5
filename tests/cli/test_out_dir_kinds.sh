#!/usr/bin/env bash
# --out as a symbolic link, the current directory or a mount point: each works or is refused
# before any rendering, with one line saying why.
# Usage: test_out_dir_kinds.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"

# One line on stderr, exit 2, no frame rendered, nothing staged.
expect_refusal() {
  local what=$1 word=$2 rc=$3 staged=$4
  [ "$rc" -eq 2 ] || fail "$what: exit $rc, expected 2"
  [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "$what: expected one line on stderr, got: $(cat "$work/stderr")"
  grep -q "$word" "$work/stderr" || fail "$what: the message does not say '$word': $(cat "$work/stderr")"
  grep -q "frame " "$work/stderr" && fail "$what: rendering started before the refusal"
  [ ! -e "$staged" ] || fail "$what: $staged was created"
}

# A link to an empty directory: the link stays, the dataset goes where it points.
mkdir -p "$work/target" && ln -s "$work/target" "$work/link"
"$bin" render "$good" --out "$work/link" --quiet >/dev/null 2>"$work/stderr" || fail "render into a link failed: $(cat "$work/stderr")"
[ -L "$work/link" ] || fail "the link was replaced"
[ -s "$work/target/manifest.json" ] && [ -d "$work/target/frames" ] || fail "the link's target stayed empty"
# Again, onto the dataset it now holds.
"$bin" render "$good" --out "$work/link" --frames 1 --quiet >/dev/null 2>"$work/stderr" || fail "re-render into a link failed: $(cat "$work/stderr")"
[ -L "$work/link" ] && [ "$(ls "$work/target/frames" | wc -l)" -eq 2 ] || fail "re-render through a link went wrong"

# A link to nothing: refused.
ln -s "$work/nowhere" "$work/dangling"
"$bin" render "$good" --out "$work/dangling" --quiet >/dev/null 2>"$work/stderr"
expect_refusal "a link to nothing" "symbolic link to nothing" $? "$work/dangling.partial"
[ -L "$work/dangling" ] || fail "the dangling link was replaced"

# --out . in an empty directory, then again onto the dataset it holds (with a file of the user's):
# the directory itself stays (same inode), its dataset is rebuilt.
mkdir -p "$work/here"
inode=$(stat -c %i "$work/here")
(cd "$work/here" && "$bin" render "$good" --out . --quiet >/dev/null 2>"$work/stderr") || fail "--out . failed: $(cat "$work/stderr")"
echo mine >"$work/here/NOTES.txt"
(cd "$work/here" && "$bin" render "$good" --out . --frames 1 --quiet >/dev/null 2>"$work/stderr") || fail "--out . onto a dataset failed: $(cat "$work/stderr")"
[ "$(stat -c %i "$work/here" 2>/dev/null)" = "$inode" ] || fail "--out . swapped out the current directory"
[ -s "$work/here/manifest.json" ] && [ -e "$work/here/NOTES.txt" ] || fail "--out . did not leave the dataset and the user's file"
[ ! -e "$work/here.partial" ] && [ ! -e "$work/here.old" ] || fail "--out . left staging directories"
# --out . in a directory that is not a dataset: refused, as any such directory.
mkdir -p "$work/mine" && echo x >"$work/mine/x.txt"
(cd "$work/mine" && "$bin" render "$good" --out . --quiet >/dev/null 2>"$work/stderr")
expect_refusal "--out . in a non-dataset directory" "refusing to replace" $? "$work/mine.partial"

# An empty mount point: refused before rendering (the dataset is staged beside it, on the parent's
# file system). Needs a private mount namespace (unshare); the detection itself is unit-tested
# (dataset: is_mount_point).
mkdir -p "$work/mnt"
if unshare -Urm true 2>/dev/null; then
  unshare -Urm sh -c 'mount -t tmpfs tmpfs "$1" && exec "$2" render "$3" --out "$1"' sh "$work/mnt" "$bin" "$good" >/dev/null 2>"$work/stderr"
  expect_refusal "an empty mount point" "mount point" $? "$work/mnt.partial"
else
  skip "no private mount namespace here (unshare -Urm); the mount point case is covered by the unit test only"
fi

finish "out dir kinds"
