"""Helper of compare_irrmap_outputs.sh (standard library only): its inputs, and its JSON and EXR
comparisons.

make-inputs DIR: writes small environment files in every layout irrmap reads (PFM crosses, strips,
  six faces, a lat-long map and an angular probe; a Radiance lat-long map), and for vs11 run a
  constants file setting c0..c95 (constants.vsh) and 64 vertices of four columns (vertices.csv).
compare A B: compares two JSON files (or JSON Lines files, records matched by "input") with the
  fields that measure time left out, and prints each difference; exit 0 when none.
compare-exr A B: compares two OpenEXR files byte for byte but for the value of the capDate
  attribute (OpenImageIO stamps the second the file was written); exit 0 when they are the same.
"""
import re
import json
import math
import struct
import sys
from pathlib import Path

# Wall-clock measurements: they differ between any two runs of one build.
TIMING_FIELDS = {
    ("timings_ms",),
    ("levels", "*", "update_ms"),
    ("gpu", "ms"),
    ("mesh", "ms_per_evaluation"),
    ("mesh", "ns_per_vertex"),
}


def radiance(u, v, channel):
    """A smooth sky with a small bright lobe: band 2 matters, and so does the mip level."""
    sun = math.exp(-((u - 0.3) ** 2 + (v - 0.35) ** 2) / 0.004) * 40.0
    return 0.35 + 0.3 * channel + 0.5 * v + 0.25 * math.sin(6.0 * u) + sun * (1.0 - 0.3 * channel)


def write_pfm(path, width, height, pixel):
    rows = []
    for y in reversed(range(height)):  # PFM rows run bottom to top
        for x in range(width):
            rows.extend(pixel(x, y))
    header = f"PF\n{width} {height}\n-1.0\n".encode()
    path.write_bytes(header + struct.pack(f"<{len(rows)}f", *rows))


def rgbe(rgb):
    top = max(rgb)
    if top < 1e-32:
        return bytes(4)
    mantissa, exponent = math.frexp(top)
    scale = mantissa * 256.0 / top
    return bytes([int(c * scale) for c in rgb] + [exponent + 128])


def write_hdr(path, width, height, pixel):
    header = f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n".encode()
    body = b"".join(rgbe(pixel(x, y)) for y in range(height) for x in range(width))
    path.write_bytes(header + body)


def image_pixel(width, height):
    return lambda x, y: [radiance((x + 0.5) / width, (y + 0.5) / height, c) for c in range(3)]


def make_inputs(folder):
    folder = Path(folder)
    face = 16
    for name, width, height in [("latlong", 64, 32), ("hcross", 4 * face, 3 * face),
                                ("vcross", 3 * face, 4 * face), ("hstrip", 6 * face, face),
                                ("vstrip", face, 6 * face), ("angular", 32, 32)]:
        write_pfm(folder / f"{name}.pfm", width, height, image_pixel(width, height))
    write_hdr(folder / "latlong.hdr", 64, 32, image_pixel(64, 32))
    for index, name in enumerate(["px", "nx", "py", "ny", "pz", "nz"]):
        strip = image_pixel(6 * face, face)
        write_pfm(folder / f"face_{name}.pfm", face, face, lambda x, y, i=index: strip(x + i * face, y))
    # Every register a program may read is set, so that vs11 run needs no --missing (which older
    # builds lack) and reads no zeros.
    (folder / "constants.vsh").write_text("".join(
        f"def c{i}, {0.1 * (i % 7) - 0.3:.2f}, {0.05 * (i % 5) + 0.1:.2f}, {0.2 - 0.03 * (i % 11):.2f}, "
        f"{1.0 - 0.01 * i:.2f}\n" for i in range(96)))
    (folder / "vertices.csv").write_text("x,y,z,w\n" + "".join(
        f"{math.sin(0.37 * i):.6f},{math.cos(0.48 * i):.6f},{math.sin(0.26 * i + 1):.6f},{1 + 0.01 * i:.4f}\n"
        for i in range(64)))


def without_timings(value, path=()):
    if isinstance(value, dict):
        kept = {}
        for key, item in value.items():
            here = path + (key,)
            if any(len(f) == len(here) and all(a in ("*", b) for a, b in zip(f, here)) for f in TIMING_FIELDS):
                continue
            kept[key] = without_timings(item, here)
        return kept
    if isinstance(value, list):
        return [without_timings(item, path + ("*",)) for item in value]
    return value


def differences(a, b, where=""):
    if type(a) is not type(b):
        yield f"{where or '/'}: {json.dumps(a)[:120]} -> {json.dumps(b)[:120]}"
    elif isinstance(a, dict):
        for key in a:
            if key not in b:
                yield f"{where}/{key}: only in the base: {json.dumps(a[key])[:120]}"
            else:
                yield from differences(a[key], b[key], f"{where}/{key}")
        for key in b:
            if key not in a:
                yield f"{where}/{key}: only in the new: {json.dumps(b[key])[:120]}"
        if [k for k in a if k in b] != [k for k in b if k in a]:
            yield f"{where or '/'}: the fields come in another order"
    elif isinstance(a, list) and len(a) != len(b):
        yield f"{where}: {len(a)} items -> {len(b)}: {json.dumps(a)[:80]} -> {json.dumps(b)[:80]}"
    elif isinstance(a, list):
        for index, (x, y) in enumerate(zip(a, b)):
            yield from differences(x, y, f"{where}[{index}]")
    elif a != b:
        yield f"{where}: {json.dumps(a)} -> {json.dumps(b)}"


def load(path):
    text = Path(path).read_text()
    if path.endswith(".jsonl"):
        records = [json.loads(line) for line in text.splitlines() if line.strip()]
        # Threads finish files in any order: records are matched by input, in sorted order.
        return dict(sorted(((record.get("input", str(i)), record) for i, record in enumerate(records)),
                           key=lambda pair: pair[0]))
    return json.loads(text)


def compare(base_path, new_path):
    found = list(differences(without_timings(load(base_path)), without_timings(load(new_path))))
    for line in found[:12]:
        print(line)
    if len(found) > 12:
        print(f"... and {len(found) - 12} more")
    return 1 if found else 0


def without_capture_date(data):
    # An attribute: name NUL, type name NUL, 4-byte little-endian size, value.
    out = bytearray(data)
    for match in re.finditer(rb"capDate\0string\0(....)", data, re.DOTALL):
        size = struct.unpack("<i", match.group(1))[0]
        out[match.end():match.end() + size] = bytes(size)
    return bytes(out)


def compare_exr(base_path, new_path):
    same = without_capture_date(Path(base_path).read_bytes()) == without_capture_date(Path(new_path).read_bytes())
    return 0 if same else 1


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "make-inputs":
        make_inputs(sys.argv[2])
    elif len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(sys.argv[2], sys.argv[3]))
    elif len(sys.argv) == 4 and sys.argv[1] == "compare-exr":
        sys.exit(compare_exr(sys.argv[2], sys.argv[3]))
    else:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
