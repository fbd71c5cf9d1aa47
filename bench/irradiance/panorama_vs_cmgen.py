#!/usr/bin/env python3
"""Panoramas and crosses, irrmap against Filament's cmgen, whole processes (the goals of issue #31).

Run by hand, from the source tree, after building irrmap, vs11_write_environments and the Python module:

  /usr/bin/python3 bench/irradiance/panorama_vs_cmgen.py [--build build] [--runs 5] [--work DIR]

Inputs (written into --work, deterministic):
  pano.exr, pano.hdr  a 2048 x 1024 sky panorama (a gradient, a horizon band and a sun of 1e3 at
                      a few pixels), written here from NumPy: EXR as uncompressed 32-bit float
                      scanlines, .hdr as flat (not run-length encoded) RGBE
  sky_hcross.exr      the built-in sky as a horizontal cross at faces 256 and 1024
                      (vs11_write_environments: 32-bit float, zip)

For each input, irrmap and cmgen run in turn (irrmap, cmgen, irrmap, ...), --runs times each:

  irrmap FILE [--face-size 256] --coefficients-only --no-ground-truth --out DIR
  cmgen -q --no-mirror --sh=3 --sh-window=no --sh-output=OUT.txt [--size 256] FILE

(--face-size and --size for the panorama only: a cross keeps its own face size). Printed: the median
wall time of each, their ratio (goal: irrmap <= 0.5 x cmgen), irrmap's own in-process total (the
sum of its stage times, i.e. the process's time less start-up and exit) and its `load` stage.

Then, on the same 2048 x 1024 panorama in memory:
  project   vs11.irradiance.project(array) (defaults: face_size 256, level by max_error) against a
            15-line float64 NumPy projection with per-row solid angles (numpy_project below),
            medians of --runs calls each; the two agree to 0.001 % at level 0 (checked; exit 1
            if not). Goal: project <= 0.2 x NumPy.
  per texel irrmap's level-0 projection time (coeffs.json levels[0].update_ms) against its `load`
            stage (reading and decoding the file), both over the same 2 M texels, medians over the
            irrmap runs above. Goal: projection <= 2 x reading.
"""
import argparse
import json
import os
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

WIDTH, HEIGHT = 2048, 1024


def panorama():
    """The 2048 x 1024 test panorama, float32 (H, W, 3), directions as irradiance/io/environment_io.h."""
    theta = np.pi * (np.arange(HEIGHT) + 0.5) / HEIGHT
    phi = 2.0 * np.pi * ((np.arange(WIDTH) + 0.5) / WIDTH - 0.5)
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    x, y, z = np.sin(phi)[None, :] * st, np.broadcast_to(ct, (HEIGHT, WIDTH)), np.cos(phi)[None, :] * st
    sun = np.array([0.5, 0.45, -0.3])
    sun /= np.linalg.norm(sun)
    lobe = 1e3 * np.exp(400.0 * (x * sun[0] + y * sun[1] + z * sun[2] - 1.0))
    sky = 0.5 + 0.5 * y + 0.2 * np.exp(-20.0 * y * y)
    return np.stack([sky + lobe, sky + 0.8 * lobe, 1.3 * sky + 0.5 * lobe], axis=-1).astype(np.float32)


def numpy_project(image):
    """The nine SH coefficients (9, 3) in float64: radiance x basis at pixel centres x per-row solid angles."""
    h, w = image.shape[:2]
    theta, phi = np.pi * (np.arange(h) + 0.5) / h, 2 * np.pi * ((np.arange(w) + 0.5) / w - 0.5)
    edges = np.pi * np.arange(h + 1) / h
    omega = (2 * np.pi / w) * (np.cos(edges[:-1]) - np.cos(edges[1:]))
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    x, y, z = np.sin(phi)[None, :] * st, np.broadcast_to(ct, (h, w)), np.cos(phi)[None, :] * st
    n0, n1, n2 = 0.5 / np.sqrt(np.pi), 0.5 * np.sqrt(3 / np.pi), 0.5 * np.sqrt(15 / np.pi)
    n3, n4 = 0.25 * np.sqrt(5 / np.pi), 0.25 * np.sqrt(15 / np.pi)
    basis = [np.full((h, w), n0), n1 * y, n1 * z, n1 * x, n2 * x * y, n2 * y * z, n3 * (3 * z * z - 1),
             n2 * x * z, n4 * (x * x - y * y)]
    weighted = image.astype(np.float64) * omega[:, None, None]
    return np.stack([np.einsum("hw,hwc->c", b, weighted) for b in basis])


def write_exr(path, image):
    """Uncompressed 32-bit float RGB OpenEXR scanlines (the format's minimal header)."""
    h, w = image.shape[:2]

    def attribute(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value

    channels = b"".join(c.encode() + b"\0" + struct.pack("<iBBBBii", 2, 0, 0, 0, 0, 1, 1) for c in "BGR") + b"\0"
    window = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = (struct.pack("<ii", 20000630, 2) + attribute("channels", "chlist", channels)
              + attribute("compression", "compression", b"\0") + attribute("dataWindow", "box2i", window)
              + attribute("displayWindow", "box2i", window) + attribute("lineOrder", "lineOrder", b"\0")
              + attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
              + attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
              + attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    line_bytes = 8 + 3 * 4 * w
    first = len(header) + 8 * h
    offsets = struct.pack(f"<{h}Q", *[first + y * line_bytes for y in range(h)])
    planar = np.ascontiguousarray(image[:, :, ::-1].transpose(0, 2, 1)).astype("<f4")  # B, G, R per line
    with open(path, "wb") as f:
        f.write(header + offsets)
        for y in range(h):
            f.write(struct.pack("<ii", y, 3 * 4 * w) + planar[y].tobytes())


def write_flat_hdr(path, image):
    """Radiance RGBE without run-length encoding."""
    h, w = image.shape[:2]
    largest = image.max(axis=-1)
    mantissa, exponent = np.frexp(largest)
    scale = np.where(largest > 1e-32, mantissa * 256.0 / np.maximum(largest, 1e-38), 0.0)
    rgbe = np.zeros((h, w, 4), np.uint8)
    rgbe[..., :3] = np.clip(image * scale[..., None], 0, 255).astype(np.uint8)
    rgbe[..., 3] = np.where(largest > 1e-32, exponent + 128, 0).astype(np.uint8)
    with open(path, "wb") as f:
        f.write(f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n".encode() + rgbe.tobytes())


def timed(command):
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    elapsed = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"failed ({done.returncode}): {' '.join(map(str, command))}\n{done.stderr}")
    return elapsed


def compare_processes(irrmap, name, path, face_size, runs, work):
    out = work / f"out_{name}"
    sh_file = work / f"cmgen_{name}.txt"
    ours = [str(irrmap), str(path), "--coefficients-only", "--no-ground-truth", "--out", str(out)]
    theirs = ["cmgen", "-q", "--no-mirror", "--sh=3", "--sh-window=no", f"--sh-output={sh_file}"]
    if face_size:
        ours[2:2] = ["--face-size", str(face_size)]
        theirs.append(f"--size={face_size}")
    theirs.append(str(path))
    wall_ours, wall_theirs, inside, load, level0 = [], [], [], [], []
    timed(ours), timed(theirs)  # warm the page cache
    for _ in range(runs):
        wall_ours.append(timed(ours))
        report = json.loads((out / "coeffs.json").read_text())
        # "projection" repeats the chosen level's time, which "level_updates" holds already.
        inside.append(sum(ms for stage, ms in report["timings_ms"].items() if stage != "projection") / 1e3)
        load.append(report["timings_ms"]["load"] / 1e3)
        level0.append(report["levels"][0]["update_ms"] / 1e3)
        wall_theirs.append(timed(theirs))
    row = {"input": name, "irrmap_s": statistics.median(wall_ours), "cmgen_s": statistics.median(wall_theirs),
           "irrmap_in_process_s": statistics.median(inside), "irrmap_load_s": statistics.median(load),
           "level0_projection_s": statistics.median(level0)}
    row["ratio"] = row["irrmap_s"] / row["cmgen_s"]
    return row


def compare_project(build, image, runs):
    sys.path.insert(0, str(build / "python"))
    import vs11  # noqa: E402  (the module built in --build)

    reference = numpy_project(image)
    exact = vs11.irradiance.project(image, level=0).coefficients
    agreement = np.abs(exact - reference).max() / np.abs(reference).max()
    ours, theirs = [], []
    for _ in range(runs):
        start = time.perf_counter()
        vs11.irradiance.project(image)
        ours.append(time.perf_counter() - start)
        start = time.perf_counter()
        numpy_project(image)
        theirs.append(time.perf_counter() - start)
    return {"project_s": statistics.median(ours), "numpy_s": statistics.median(theirs),
            "ratio": statistics.median(ours) / statistics.median(theirs), "agreement": agreement}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", type=Path, default=Path("build"))
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--work", type=Path, help="folder for the inputs and outputs (default: a temporary one)")
    args = parser.parse_args()
    if shutil.which("cmgen") is None:
        sys.exit("cmgen not found (Debian package libfilament-tools)")
    irrmap = args.build / "irradiance" / "irrmap"
    writer = args.build / "bench" / "vs11_write_environments"
    work = args.work or Path(tempfile.mkdtemp(prefix="panorama_vs_cmgen_"))
    work.mkdir(parents=True, exist_ok=True)
    image = panorama()
    write_exr(work / "pano.exr", image)
    write_flat_hdr(work / "pano.hdr", image)
    for face in (256, 1024):
        (work / f"cross{face}").mkdir(exist_ok=True)
        subprocess.run([str(writer), str(work / f"cross{face}"), "--face-size", str(face), "--env", "sky"], check=True,
                       stdout=subprocess.DEVNULL)
    inputs = [("panorama 2048x1024 exr", work / "pano.exr", 256), ("panorama 2048x1024 hdr", work / "pano.hdr", 256),
              ("cross 256 exr", work / "cross256" / "sky_hcross.exr", 0),
              ("cross 1024 exr", work / "cross1024" / "sky_hcross.exr", 0)]
    print(f"{'input':<24} {'irrmap s':>9} {'cmgen s':>8} {'ratio':>6} {'in-process s':>13} {'load s':>7} "
          f"{'level 0 s':>9} {'goal <= 0.5':>11}")
    rows = []
    for name, path, face in inputs:
        row = compare_processes(irrmap, name.replace(" ", "_"), path, face, args.runs, work)
        rows.append(row)
        print(f"{name:<24} {row['irrmap_s']:9.3f} {row['cmgen_s']:8.3f} {row['ratio']:6.2f} "
              f"{row['irrmap_in_process_s']:13.3f} {row['irrmap_load_s']:7.3f} {row['level0_projection_s']:9.4f} "
              f"{'met' if row['ratio'] <= 0.5 else 'missed':>11}")
    for row in rows[:2]:
        per_texel = row["level0_projection_s"] / row["irrmap_load_s"]
        print(f"per texel, {row['input']}: projection {1e9 * row['level0_projection_s'] / (WIDTH * HEIGHT):.2f} ns, "
              f"reading {1e9 * row['irrmap_load_s'] / (WIDTH * HEIGHT):.2f} ns: {per_texel:.2f} x "
              f"({'met' if per_texel <= 2 else 'missed'}, goal <= 2)")
    project = compare_project(args.build, image, args.runs)
    print(f"project(array) {project['project_s']:.4f} s, NumPy {project['numpy_s']:.4f} s: {project['ratio']:.3f} x "
          f"({'met' if project['ratio'] <= 0.2 else 'missed'}, goal <= 0.2); level 0 agrees with NumPy to "
          f"{100 * project['agreement']:.2g} % of the largest coefficient")
    if project["agreement"] > 1e-5:
        sys.exit("project() and the NumPy projection differ by more than 0.001 %")


if __name__ == "__main__":
    main()
