#!/usr/bin/env python3
"""irrmap against Filament's cmgen (Debian package libfilament-tools) on the same environment files.

Writes the built-in environments with vs11_write_environments, then for each file runs, --runs times
each, as whole processes:

  cmgen -q --sh=3 --sh-window=no --sh-output=OUT.txt [--size N] FILE
  irrmap FILE --level 0 --coefficients-only --face-size N --out DIR

and compares the nine RGB coefficients. Files (N = --face-size):
  exr     NAME_hcross.exr   horizontal cross, float: both tools read the same texels
  hdr     NAME_hcross.hdr   the same cross in Radiance RGBE
  dds     NAME_cube.dds     8-bit sRGB DDS cube map for irrmap; cmgen reads no DDS, so it gets the
                            same bytes as a PNG cross (NAME_ldr.png); both decode sRGB to linear
  latlong NAME_latlong.exr  lat-long 4N x 2N, float, point-sampled from the cube: each tool
                            resamples it to an N cube its own way (cmgen --size N)

cmgen's conventions, found by experiment (Filament 1.9.25):
  * --sh=3 without -i prints the radiance coefficients L_lm themselves, in our (l, m) order and
    scale (-i multiplies band l by pi, 2 pi / 3, pi / 4; --sh-shader also folds in the basis
    constants and 1/pi). Nothing else to rescale.
  * Its basis carries the Condon-Shortley phase: (-1)^m on m = +-1 (L1-1, L11, L2-1, L21).
  * By default it mirrors the cube map left-right (x -> -x; --no-mirror skips it), which negates
    the coefficients odd in x (L11, L2-2, L21). Its cube frame is otherwise the D3D/OpenGL face
    table we use; its lat-long frame is ours too.
  * --sh-window defaults to "auto", which windows the coefficients even without -i: turned off.
  * Its Radiance HDR decoder takes a mantissa m as m + 0.5 (as Radiance's own colr_color does);
    OpenImageIO, and so irrmap, takes m: 0.2 to 0.4 % brighter, depending on the mantissa.
So ours = sign * cmgen per coefficient, the sign computed from the two sign rules (signs()).

Agreement: the largest |a - b| over the 27 numbers, divided by the largest |coefficient| of the
same colour channel (L00 in practice). For each file, irrmap against cmgen, and each tool against
the source cube's own coefficients (irrmap on NAME_hcross.exr). Exit status 1 if irrmap and cmgen
differ by more than --tolerance (0.5 % by default) on a file both read texel for texel (exr, hdr,
dds); the lat-long rows are reported, not gated, since there the tools' resamplers differ. Exit
status 2 if a tool fails.

Times are medians of --runs whole-process wall times (fork to exit), with the peak resident memory
(ru_maxrss from wait4) of the median run.

--datasets adds two throughput measurements after the table (goals of issue #14):
  batch   --batch-files copies of each built-in's NAME_hcross.exr at --face-size (100 files at 256 by
          default), coefficients from level 0 (the work cmgen does): one `irrmap batch` process (every
          core) against a shell-style loop of one cmgen process per file, and a loop of ten
          `irrmap --coefficients-only` processes (what per-file start-up costs irrmap)
  single  one sky EXR at --single-face-size (1024): `irrmap --level 0 --coefficients-only` and cmgen,
          each the median of --runs processes
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

# (l, m) in our coefficient order (irradiance/sh/sh9.h).
LM = [(0, 0), (1, -1), (1, 0), (1, 1), (2, -2), (2, -1), (2, 0), (2, 1), (2, 2)]
# Coefficients odd in x: y_lm(-x, y, z) = -y_lm(x, y, z) for x, xy, xz.
ODD_IN_X = {(1, 1), (2, -2), (2, 1)}


def signs(mirrored):
    """ours = sign * cmgen, per coefficient: Condon-Shortley phase, and the mirror when cmgen mirrors."""
    result = []
    for l, m in LM:
        s = -1.0 if m % 2 else 1.0
        if mirrored and (l, m) in ODD_IN_X:
            s = -s
        result.append(s)
    return result


CMGEN_LINE = re.compile(r"\(\s*([-+0-9.eE]+),\s*([-+0-9.eE]+),\s*([-+0-9.eE]+)\);\s*//\s*L(\d)(-?\d)")


def read_cmgen(path):
    rows = {}
    for line in Path(path).read_text().splitlines():
        match = CMGEN_LINE.search(line)
        if match:
            rows[(int(match.group(4)), int(match.group(5)))] = [float(match.group(i)) for i in (1, 2, 3)]
    if set(rows) != set(LM):
        raise RuntimeError(f"{path}: expected the nine l <= 2 coefficients, got {sorted(rows)}")
    return [rows[lm] for lm in LM]


def read_irrmap(path):
    import json
    return json.loads(Path(path).read_text())["coefficients"]


def run_timed(command):
    """Wall time (s) and peak RSS (MB) of one whole process; raises on failure."""
    start = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(process.pid, 0)
    elapsed = time.perf_counter() - start
    stderr = process.stderr.read().decode(errors="replace")
    process.stderr.close()
    process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, command))} failed ({process.returncode}): {stderr.strip()}")
    return elapsed, usage.ru_maxrss / 1024.0


def median_run(command, runs):
    results = sorted(run_timed(command) for _ in range(runs))
    return results[(len(results) - 1) // 2]


def agreement(ours, theirs, sign):
    worst = 0.0
    for channel in range(3):
        largest = max(abs(row[channel]) for row in ours)
        for row_ours, row_theirs, s in zip(ours, theirs, sign):
            worst = max(worst, abs(row_ours[channel] - s * row_theirs[channel]) / largest)
    return worst


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build", help="vs11 build folder (default: build)")
    parser.add_argument("--work", default="/tmp/vs11_compare_cmgen", help="scratch folder (replaced)")
    parser.add_argument("--face-size", type=int, default=256, help="cube face size (default 256)")
    parser.add_argument("--runs", type=int, default=3, help="runs of each command; the median is kept")
    parser.add_argument("--tolerance", type=float, default=0.005, help="agreement required (default 0.005)")
    parser.add_argument("--env", action="append", help="built-ins to compare (default: all)")
    parser.add_argument("--formats", default="exr,hdr,dds,latlong",
                        help="comma-separated, from exr, hdr, dds, latlong (exr first gives the source column)")
    parser.add_argument("--datasets", action="store_true",
                        help="also measure irrmap batch against a loop of cmgen processes, and one large file")
    parser.add_argument("--batch-files", type=int, default=100, help="files of the batch measurement (default 100)")
    parser.add_argument("--single-face-size", type=int, default=1024,
                        help="face size of the single-file measurement (default 1024)")
    args = parser.parse_args()

    build = Path(args.build)
    writer = build / "bench" / "vs11_write_environments"
    irrmap = build / "irradiance" / "irrmap"
    cmgen = shutil.which("cmgen")
    for tool in (writer, irrmap):
        if not tool.is_file():
            sys.exit(f"compare_cmgen: {tool} not built (ninja -C {build} irrmap vs11_write_environments)")
    if not cmgen:
        sys.exit("compare_cmgen: cmgen not found (apt-get install libfilament-tools)")

    work = Path(args.work)
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    command = [writer, work, "--face-size", str(args.face_size)]
    for name in args.env or []:
        command += ["--env", name]
    subprocess.run(command, check=True)
    names = args.env or sorted({p.name.split("_")[0] for p in work.glob("*_hcross.exr")})

    # key: (file irrmap reads, file cmgen reads, read texel for texel by both)
    formats = {
        "exr": ("hcross.exr", "hcross.exr", True),
        "hdr": ("hcross.hdr", "hcross.hdr", True),
        "dds": ("cube.dds", "ldr.png", True),
        "latlong": ("latlong.exr", "latlong.exr", False),
    }
    sign = signs(mirrored=True)
    unit = [1.0] * len(LM)
    print(f"face size {args.face_size}, median of {args.runs} runs each; differences = max |a - b| over the 27 "
          f"numbers / largest |coefficient| of the channel; source = irrmap on NAME_hcross.exr")
    print(f"{'environment':<11} {'irrmap reads':<20} {'cmgen reads':<20} {'irrmap-cmgen':>12} "
          f"{'irrmap-source':>13} {'cmgen-source':>12} {'irrmap s':>9} {'cmgen s':>8} {'irrmap MB':>10} "
          f"{'cmgen MB':>9}")
    failed = []
    for name in names:
        source = None
        for key in args.formats.split(","):
            ours_file, theirs_file, gated = formats[key]
            ours_path, theirs_path = work / f"{name}_{ours_file}", work / f"{name}_{theirs_file}"
            out = work / f"irrmap_{name}_{key}"
            cmgen_txt = work / f"cmgen_{name}_{key}.txt"
            irrmap_command = [irrmap, ours_path, "--level", "0", "--coefficients-only", "--face-size",
                              str(args.face_size), "--out", out]
            cmgen_command = [cmgen, "-q", "--sh=3", "--sh-window=no", f"--sh-output={cmgen_txt}"]
            if not gated:
                cmgen_command.append(f"--size={args.face_size}")
            cmgen_command.append(theirs_path)
            try:
                irrmap_time, irrmap_rss = median_run(irrmap_command, args.runs)
                cmgen_time, cmgen_rss = median_run(cmgen_command, args.runs)
            except RuntimeError as error:
                print(f"compare_cmgen: {error}", file=sys.stderr)
                return 2
            ours, theirs = read_irrmap(out / "coeffs.json"), read_cmgen(cmgen_txt)
            if key == "exr":
                source = ours
            difference = agreement(ours, theirs, sign)
            # The DDS/PNG pair holds the environment clamped to [0, 1] in 8 bits: another environment.
            comparable = source is not None and key != "dds"
            ours_vs_source = f"{100 * agreement(ours, source, unit):.4f}%" if comparable else "-"
            theirs_vs_source = f"{100 * agreement(source, theirs, sign):.4f}%" if comparable else "-"
            mark = "" if difference <= args.tolerance else ("  MISSED" if gated else "  (resampled: not gated)")
            if gated and difference > args.tolerance:
                failed.append(f"{name} {key}")
            print(f"{name:<11} {ours_path.name:<20} {theirs_path.name:<20} {100 * difference:>11.4f}% "
                  f"{ours_vs_source:>13} {theirs_vs_source:>12} {irrmap_time:>9.3f} {cmgen_time:>8.3f} "
                  f"{irrmap_rss:>10.1f} {cmgen_rss:>9.1f}{mark}")
    if args.datasets:
        status = measure_datasets(args, writer, irrmap, cmgen, work, sign)
        if status:
            return status
    if failed:
        print(f"agreement above {100 * args.tolerance:g} %: {', '.join(failed)}")
        return 1
    return 0


def run_loop(commands):
    """Wall time (s) of running `commands` one after the other, as a shell loop does."""
    start = time.perf_counter()
    for command in commands:
        run_timed(command)
    return time.perf_counter() - start


def measure_datasets(args, writer, irrmap, cmgen, work, sign):
    """The batch and single-file goals; returns 2 if a tool fails."""
    import json
    data = work / "dataset"
    data.mkdir()
    sources = sorted(work.glob("*_hcross.exr"))
    files = []
    for i in range(args.batch_files):
        target = data / f"env{i:04d}.exr"
        shutil.copyfile(sources[i % len(sources)], target)
        files.append(target)
    try:
        out = work / "batch.jsonl"
        batch_times = []
        for _ in range(args.runs):
            out.unlink(missing_ok=True)
            batch_times.append(run_timed([irrmap, "batch", str(data / "*.exr"), "-o", out, "--level", "0"])[0])
        cmgen_loop = [[cmgen, "-q", "--sh=3", "--sh-window=no", f"--sh-output={work / f'loop_{f.stem}.txt'}", f]
                      for f in files]
        # Per-file start-up is the same for every file: ten of them show it.
        irrmap_loop = [[irrmap, f, "--level", "0", "--coefficients-only", "--out", work / f"loop_{f.stem}"]
                       for f in files[:10]]
        cmgen_time = statistics.median(run_loop(cmgen_loop) for _ in range(args.runs))
        irrmap_loop_time = statistics.median(run_loop(irrmap_loop) for _ in range(args.runs))
    except RuntimeError as error:
        print(f"compare_cmgen: {error}", file=sys.stderr)
        return 2
    batch_time = statistics.median(batch_times)
    records = {Path(json.loads(line)["input"]).stem: json.loads(line)["coefficients"]
               for line in out.read_text().splitlines()}
    worst = max(agreement(records[f.stem], read_cmgen(work / f"loop_{f.stem}.txt"), sign) for f in files)
    n = len(files)
    print(f"\n{n} EXR maps at face {args.face_size}, level 0, medians of {args.runs} runs "
          f"({os.cpu_count()} cores; irrmap batch uses all, each cmgen process runs on its own):")
    print(f"  irrmap batch (1 process)      {batch_time:8.3f} s  {n / batch_time:7.1f} files/s")
    print(f"  cmgen loop ({n} processes)    {cmgen_time:8.3f} s  {n / cmgen_time:7.1f} files/s  "
          f"batch is {cmgen_time / batch_time:.2f}x faster (goal >= 3x)")
    m = len(irrmap_loop)
    print(f"  irrmap loop ({m} processes)    {irrmap_loop_time:8.3f} s  {m / irrmap_loop_time:7.1f} files/s  "
          f"per process {1000 * irrmap_loop_time / m:.0f} ms against {1000 * batch_time / n:.0f} ms per file in batch")
    print(f"  batch against cmgen: largest difference {100 * worst:.4f}% of L00")

    size = args.single_face_size
    single = work / "single"
    subprocess.run([writer, single, "--face-size", str(size), "--env", "sky"], check=True)
    exr = single / "sky_hcross.exr"
    try:
        ours_time, ours_rss = median_run([irrmap, exr, "--level", "0", "--coefficients-only", "--out",
                                          single / "irrmap"], args.runs)
        theirs_time, theirs_rss = median_run([cmgen, "-q", "--sh=3", "--sh-window=no",
                                              f"--sh-output={single / 'cmgen.txt'}", exr], args.runs)
    except RuntimeError as error:
        print(f"compare_cmgen: {error}", file=sys.stderr)
        return 2
    difference = agreement(read_irrmap(single / "irrmap" / "coeffs.json"), read_cmgen(single / "cmgen.txt"), sign)
    print(f"\none EXR at face {size}, level 0, --coefficients-only, median of {args.runs} processes:")
    print(f"  irrmap {ours_time:7.3f} s {ours_rss:7.1f} MB   cmgen {theirs_time:7.3f} s {theirs_rss:7.1f} MB   "
          f"irrmap/cmgen {ours_time / theirs_time:.2f} (goal <= 1)   difference {100 * difference:.4f}%")
    return 0


if __name__ == "__main__":
    sys.exit(main())
