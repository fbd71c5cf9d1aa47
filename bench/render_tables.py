#!/usr/bin/env python3
"""Prints the markdown tables of bench/README.md from one vs11_bench JSON run.

    build/bench/vs11_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
        --benchmark_format=json --benchmark_out=bench/results.json
    python3 bench/render_tables.py bench/results.json

Any run renders: with repetitions each number is the median of them (Google Benchmark's median
aggregate, or the median of the repetitions when the run kept no aggregates); a single run shows
its one measurement. A filtered run fills the tables it has data for; the others say "no data",
and so does a cell or row whose benchmark the run left out.
"""
import json
import re
import statistics
import sys

NS_PER_UNIT = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}
NO_DATA = "no data"


def measurements(path):
    """run_name -> one benchmark entry: the median aggregate, else the per-field median of the
    iterations (one iteration: itself)."""
    with open(path) as f:
        run = json.load(f)
    medians, iterations = {}, {}
    for b in run.get("benchmarks", []):
        name = re.sub(r"/real_time$", "", b.get("run_name", b["name"]))
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                medians[name] = b
        else:
            iterations.setdefault(name, []).append(b)
    found = dict(medians)
    for name, runs in iterations.items():
        if name in found:
            continue
        entry = dict(runs[0])
        for key, value in runs[0].items():
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                entry[key] = statistics.median(r[key] for r in runs if key in r)
        found[name] = entry
    return run.get("context", {}), found


def ns_per_item(b):
    return 1e9 / b["items_per_second"] if b and b.get("items_per_second") else None


def ms(b, time="real_time"):
    return b[time] * NS_PER_UNIT[b["time_unit"]] / 1e6 if b else None


def fmt(value, spec, suffix=""):
    return "" if value is None else f"{value:{spec}}{suffix}"


def ratio(a, b, spec, suffix="x"):
    return "" if a is None or b is None or b == 0 else f"{a / b:{spec}}{suffix}"


def bold(cell):
    return f"**{cell}**" if cell else cell


def print_table(header, rows):
    """rows: lists of cells; rows with no measured cell (only the label) are left out."""
    rows = [r for r in rows if any(c != "" for c in r[1:])]
    if not rows:
        print(NO_DATA)
        return False
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for r in rows:
        print("| " + " | ".join(r) + " |")
    return True


def irradiance(found):
    engines = ("Reference", "Batch", "Jit", "NativeScalar", "NativeSimd")
    sizes = sorted({int(m.group(1)) for k in found if (m := re.match(r"BM_Irradiance_\w+/(\d+)$", k))})
    rows = []
    for n in sizes:
        t = {e: ns_per_item(found.get(f"BM_Irradiance_{e}/{n}")) for e in engines}
        rows.append([str(n), fmt(t["Reference"], ".1f"), fmt(t["Batch"], ".2f"), fmt(t["Jit"], ".2f"),
                     fmt(t["NativeScalar"], ".2f"), fmt(t["NativeSimd"], ".2f"),
                     ratio(t["NativeSimd"], t["Batch"], ".2f"), bold(ratio(t["NativeSimd"], t["Jit"], ".2f")),
                     ratio(t["Reference"], t["Jit"], ".0f")])
    print_table(["N", "Reference", "Batch", "Jit", "NativeScalar", "NativeSimd", "Batch / NativeSimd",
                 "Jit / NativeSimd (goal >= 0.5)", "Jit / Reference"], rows)


def programs(found):
    names = sorted({m.group(1) for k in found if (m := re.match(r"BM_Program/(\w+)/(?:ref|batch|jit)$", k))})
    rows = []
    for name in names:
        entries = {e: found.get(f"BM_Program/{name}/{e}") for e in ("ref", "batch", "jit")}
        t = {e: ns_per_item(b) for e, b in entries.items()}
        slots = next((str(int(b["slots"])) for b in entries.values() if b and "slots" in b), "")
        rows.append([name, slots, fmt(t["ref"], ".1f"), fmt(t["batch"], ".2f"), fmt(t["jit"], ".2f"),
                     ratio(t["ref"], t["batch"], ".0f"), ratio(t["ref"], t["jit"], ".0f")])
    print_table(["program", "slots", "ref", "batch", "jit", "batch speed-up", "jit speed-up"], rows)


def coefficients(found):
    faces = (256, 1024)
    levels = sorted({int(m.group(1)) for k in found if (m := re.match(r"BM_Coefficients/\d+/(\d+)$", k))})
    print_table(["level", "face 256: ms", "face 1024: ms"],
                [[str(level)] + [fmt(ms(found.get(f"BM_Coefficients/{face}/{level}")), ".4g") for face in faces]
                 for level in levels])
    print()
    print_table(["other", "face 256 ms", "face 1024 ms"],
                [[f"`{name}`"] + [fmt(ms(found.get(f"{name}/{face}")), ".4g") for face in faces]
                 for name in ("BM_EnvMips", "BM_EnvMipsRefill", "BM_Coefficients_ScalarDouble",
                              "BM_Coefficients_PlainLoop")] +
                [[f"`BM_BasisPyramidBuild`, {threads} thread{'s' if threads > 1 else ''} (once per face size)"] +
                 [fmt(ms(found.get(f"BM_BasisPyramidBuild/{face}/{threads}")), ".4g") for face in faces]
                 for threads in (1, 2)])
    level0, level2 = ms(found.get("BM_Coefficients/256/0")), ms(found.get("BM_Coefficients/256/2"))
    scalar = ms(found.get("BM_Coefficients_ScalarDouble/256"))
    plain = ms(found.get("BM_Coefficients_PlainLoop/256"))
    build = ms(found.get("BM_BasisPyramidBuild/256/2"))
    goals = []
    if level0 and level2:
        goals.append(f"`/256/2` {level0 / level2:.1f}x faster than `/256/0` (>= 12x)")
    if level0 and scalar:
        goals.append(f"level 0 {scalar / level0:.1f}x faster than ScalarDouble at 256 (>= 4x)")
    if goals:
        print()
        print("Goals: " + "; ".join(goals) + ".")
    if level0 and plain and build:
        print(f"Level 0 and the plain loop read a basis pyramid built once per face size ({build:.4g} ms at 256, "
              f"2 threads); ScalarDouble needs none. Against the plain loop over the same weights, level 0 is "
              f"{plain / level0:.1f}x faster.")


def frame(found):
    direct = found.get("BM_Frame/direct_cpu")
    plain = found.get("BM_Frame/plain_cpu")
    paper = {"direct_cpu": 21, "plain_cpu": None, "vm_full": 34, "vm_64": 45, "vm_16": 56}
    rows = []
    for case, fps in paper.items():
        b = found.get(f"BM_Frame/{case}")
        error = b.get("error_mean_rel") if b else None
        rows.append([case, fmt(ms(b), ".2f"), fmt(ms(b, "cpu_time"), ".2f"),
                     ratio(ms(direct, "cpu_time"), ms(b, "cpu_time"), ".1f", ""),
                     ratio(ms(plain, "cpu_time"), ms(b, "cpu_time"), ".1f", ""),
                     str(fps) if b and fps else "", f"{fps / paper['direct_cpu']:.2f}" if b and fps else "",
                     fmt(None if error is None else 100 * error, ".2f", " %")])
    printed = print_table(["case", "wall ms / frame", "CPU ms / frame", "ratio to direct_cpu (CPU)",
                           "ratio to plain_cpu (CPU)", "paper fps", "paper ratio", "mean rel. error"], rows)
    build = found.get("BM_BasisPyramidBuild/256/2")
    if printed and build:
        print()
        print(f"Every case but direct_cpu reads the 256 basis pyramid, built once before the first frame "
              f"({ms(build):.4g} ms, 2 threads; `BM_BasisPyramidBuild/256/2`), not in these frame times.")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    context, found = measurements(sys.argv[1])
    repetitions = max((b.get("repetitions", 1) for b in found.values()), default=0)
    print(f"Run: {context.get('date')}, {context.get('num_cpus')} CPUs at {context.get('mhz_per_cpu')} MHz, "
          f"load average {context.get('load_avg')}; "
          + (f"medians of {repetitions} repetitions." if repetitions > 1 else "one measurement each (no repetitions).")
          + "\n")
    for title, table in (("Irradiance evaluation (ns per vertex, 1 thread)", irradiance),
                         ("Every program (65 536 vertices, ns per vertex)", programs),
                         ("Coefficients (wall time per update)", coefficients),
                         ("Frame (section 3.3)", frame)):
        print(f"### {title}\n")
        table(found)
        print()


if __name__ == "__main__":
    main()
