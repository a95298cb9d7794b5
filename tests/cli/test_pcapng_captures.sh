#!/usr/bin/env bash
# pcapng captures (Wireshark's default format) import as their libpcap originals do (issue #34):
# the shared VLP-16 and Ouster captures, rewritten here as pcapng in either byte order and with
# nanosecond time stamps, give the same frames, byte for byte, and the same manifest but for the
# file recorded from. Skipped without the shared data.
# Usage: test_pcapng_captures.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
if [ ! -d "$shared_data/ouster" ] || [ ! -d "$shared_data/vlp16" ]; then skip "shared data not present: $shared_data"; finish "pcapng captures"; fi

# to_pcapng PCAP OUT BYTE_ORDER(< or >) NANOSECONDS(0 or 1): a section header, an Ethernet interface
# (if_tsresol 9 for nanoseconds), an enhanced packet block a record and an interface statistics
# block, as Wireshark saves a capture.
to_pcapng() {
  python3 - "$@" <<'PY'
import struct, sys
src, dst, order, ns = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4] == "1"
data = open(src, "rb").read()
magic, _, _, _, _, snaplen, link = struct.unpack_from("<IHHiIII", data, 0)
assert magic == 0xA1B2C3D4, "a little-endian microsecond libpcap file"
def block(kind, body):
    body += b"\0" * (-len(body) % 4)
    return struct.pack(order + "II", kind, len(body) + 12) + body + struct.pack(order + "I", len(body) + 12)
out = [block(0x0A0D0D0A, struct.pack(order + "IHHq", 0x1A2B3C4D, 1, 0, -1))]
options = struct.pack(order + "HH", 9, 1) + b"\x09\0\0\0" if ns else b""
out.append(block(1, struct.pack(order + "HHI", link, 0, snaplen) + options + struct.pack(order + "HH", 0, 0)))
off = 24
while off < len(data):
    sec, usec, caplen, wirelen = struct.unpack_from("<IIII", data, off)
    stamp = sec * 10**9 + usec * 1000 if ns else sec * 10**6 + usec
    out.append(block(6, struct.pack(order + "IIIII", 0, stamp >> 32, stamp & 0xFFFFFFFF, caplen, wirelen) + data[off + 16:off + 16 + caplen]))
    off += 16 + caplen
out.append(block(5, struct.pack(order + "IIIHH", 0, 0, 0, 0, 0)))
open(dst, "wb").write(b"".join(out))
PY
}

# same DIR_A DIR_B WHAT: the frames byte for byte, the manifests but for recorded_from.
same() {
  for f in "$1"/frames/*; do
    cmp -s "$f" "$2/frames/$(basename "$f")" || { fail "$3: $(basename "$f") differs from the libpcap import's"; return; }
  done
  [ "$(ls "$1/frames" | wc -l)" -eq "$(ls "$2/frames" | wc -l)" ] || fail "$3: not as many frame files as the libpcap import"
  python3 - "$1/manifest.json" "$2/manifest.json" <<'PY' || fail "$3: the manifest differs from the libpcap import's beyond recorded_from"
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
a.pop("recorded_from"), b.pop("recorded_from")
sys.exit(a != b)
PY
}

vlp="$shared_data/vlp16/velodyne_vlp16.pcap"
"$bin" import-velodyne "$vlp" --out "$work/vlp" >/dev/null 2>"$work/stderr" || fail "import-velodyne of the libpcap file failed: $(cat "$work/stderr")"
os1="$shared_data/ouster/OS-1-32-G_v2.1.1_1024x10"
"$bin" import-ouster "$os1.pcap" --metadata "$os1.json" --out "$work/os1" >/dev/null 2>"$work/stderr" ||
  fail "import-ouster of the libpcap file failed: $(cat "$work/stderr")"
for layout in "little < 0" "big > 0" "nanoseconds > 1"; do
  set -- $layout
  to_pcapng "$vlp" "$work/vlp-$1.pcapng" "$2" "$3"
  "$bin" import-velodyne "$work/vlp-$1.pcapng" --out "$work/vlp-$1" >"$work/stdout" 2>"$work/stderr" ||
    fail "import-velodyne of a $1 pcapng capture: $(cat "$work/stderr")"
  grep -q "decoded 2 frames" "$work/stdout" || fail "import-velodyne of a $1 pcapng capture: $(cat "$work/stdout")"
  same "$work/vlp" "$work/vlp-$1" "import-velodyne, $1 pcapng"
  to_pcapng "$os1.pcap" "$work/os1-$1.pcapng" "$2" "$3"
  "$bin" import-ouster "$work/os1-$1.pcapng" --metadata "$os1.json" --out "$work/os1-$1" >/dev/null 2>"$work/stderr" ||
    fail "import-ouster of a $1 pcapng capture: $(cat "$work/stderr")"
  same "$work/os1" "$work/os1-$1" "import-ouster, $1 pcapng"
done

# Neither format: one line naming the file.
echo "just text" >"$work/notes.pcapng"
"$bin" import-velodyne "$work/notes.pcapng" --out "$work/none" >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] && [ "$(wc -l <"$work/stderr")" -eq 1 ] && grep -q "notes.pcapng: magic: neither a libpcap nor a pcapng capture" "$work/stderr" ||
  fail "a file in neither format: exit $rc, $(cat "$work/stderr")"

finish "pcapng captures"
