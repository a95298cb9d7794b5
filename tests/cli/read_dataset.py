"""Independent readers for the CLI tests: ladarsim's EXR range images (scanline, ZIP or none) and
binary PCD frames, in plain Python (no OpenEXR or PCL bindings needed)."""
import struct
import zlib


def read_exr(path):
    """Returns (width, height, {channel: [row lists]}, attribute names)."""
    d = open(path, "rb").read()
    assert d[:4] == b"\x76\x2f\x31\x01", path + ": not an EXR file"
    pos, attrs = 8, {}
    while d[pos] != 0:
        end = d.index(b"\0", pos); name = d[pos:end].decode(); pos = end + 1
        end = d.index(b"\0", pos); pos = end + 1
        size, = struct.unpack_from("<i", d, pos); pos += 4
        attrs[name] = d[pos:pos + size]; pos += size
    pos += 1
    channels, chl, p = [], attrs["channels"], 0
    while chl[p] != 0:
        end = chl.index(b"\0", p); name = chl[p:end].decode(); p = end + 1
        pixel_type, = struct.unpack_from("<i", chl, p); p += 16
        channels.append((name, {0: "I", 1: "e", 2: "f"}[pixel_type]))
    xmin, ymin, xmax, ymax = struct.unpack("<4i", attrs["dataWindow"])
    width = xmax - xmin + 1
    compression = attrs["compression"][0]
    lines_per_block = {0: 1, 2: 1, 3: 16}[compression]
    blocks = (ymax - ymin + lines_per_block) // lines_per_block
    offsets = struct.unpack_from("<%dQ" % blocks, d, pos)
    out = {name: [] for name, _ in channels}
    for offset in offsets:
        y, size = struct.unpack_from("<ii", d, offset)
        raw = d[offset + 8:offset + 8 + size]
        lines = min(lines_per_block, ymax + 1 - y)
        full = lines * width * sum(struct.calcsize(f) for _, f in channels)
        if compression != 0 and size < full:
            t = bytearray(zlib.decompress(raw))
            for i in range(1, len(t)):
                t[i] = (t[i - 1] + t[i] - 128) & 0xFF
            half = (len(t) + 1) // 2
            raw = bytearray(len(t)); raw[0::2] = t[:half]; raw[1::2] = t[half:]
        p = 0
        for _ in range(lines):
            for name, f in channels:
                out[name].append(list(struct.unpack_from("<%d%s" % (width, f), raw, p)))
                p += width * struct.calcsize(f)
    return width, ymax - ymin + 1, out, set(attrs)


def read_pcd(path):
    """A binary PCD as {field: list}."""
    data = open(path, "rb").read()
    head, _, body = data.partition(b"DATA binary\n")
    h = dict(line.split(" ", 1) for line in head.decode().splitlines() if " " in line and not line.startswith("#"))
    fields, sizes, types = h["FIELDS"].split(), list(map(int, h["SIZE"].split())), h["TYPE"].split()
    n, step = int(h["POINTS"]), sum(sizes)
    codes = {("F", 4): "f", ("F", 8): "d", ("U", 1): "B", ("U", 2): "H", ("U", 4): "I", ("I", 4): "i"}
    out = {}
    for k, name in enumerate(fields):
        code, at = codes[(types[k], sizes[k])], sum(sizes[:k])
        out[name] = [struct.unpack_from("<" + code, body, i * step + at)[0] for i in range(n)]
    return out
