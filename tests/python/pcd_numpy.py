"""A small PCD reader of our own, independent of the module: the header's FIELDS, SIZE, TYPE and
COUNT as a NumPy dtype, the binary DATA as an array of it."""
import numpy as np


def read_pcd(path):
    with open(path, "rb") as f:
        blob = f.read()
    header = {}
    offset = 0
    while True:
        end = blob.index(b"\n", offset)
        line = blob[offset:end].decode("ascii").strip()
        offset = end + 1
        if not line or line.startswith("#"):
            continue
        key, *values = line.split()
        header[key] = values
        if key == "DATA":
            break
    assert header["DATA"] == ["binary"], f"{path}: DATA {header['DATA']}"
    kinds = {"F": "f", "U": "u", "I": "i"}
    formats = []
    for size, kind, count in zip(header["SIZE"], header["TYPE"], header.get("COUNT", ["1"] * len(header["FIELDS"]))):
        fmt = "<" + kinds[kind] + size
        formats.append(fmt if count == "1" else f"({count},){fmt}")
    dtype = np.dtype({"names": header["FIELDS"], "formats": formats})  # packed: PCD has no padding
    points = int(header["WIDTH"][0]) * int(header.get("HEIGHT", ["1"])[0])
    return np.frombuffer(blob, dtype=dtype, count=points, offset=offset)
