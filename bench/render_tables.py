#!/usr/bin/env python3
"""Prints the markdown tables of bench/README.md from one vs11_bench JSON run.

    build/bench/vs11_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
        --benchmark_format=json --benchmark_out=bench/results.json
    python3 bench/render_tables.py bench/results.json

Every number is the median of the run's repetitions (the run must have aggregates).
"""
import json
import re
import sys

NS_PER_UNIT = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def medians(path):
    with open(path) as f:
        run = json.load(f)
    found = {}
    for b in run["benchmarks"]:
        if b.get("aggregate_name") == "median":
            found[re.sub(r"/real_time$", "", b["run_name"])] = b
    if not found:
        sys.exit(f"{path}: no medians; run vs11_bench with --benchmark_repetitions=3")
    return run["context"], found


def ns_per_item(b):
    return 1e9 / b["items_per_second"]


def ms(b, time="real_time"):
    return b[time] * NS_PER_UNIT[b["time_unit"]] / 1e6


def irradiance(found):
    print("| N | Reference | Batch | Jit | NativeScalar | NativeSimd | Batch / NativeSimd | Jit / NativeSimd (goal >= 0.5) | Jit / Reference |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n in (1024, 65536, 1048576):
        t = {e: ns_per_item(found[f"BM_Irradiance_{e}/{n}"]) for e in ("Reference", "Batch", "Jit", "NativeScalar", "NativeSimd")}
        print(f"| {n} | {t['Reference']:.1f} | {t['Batch']:.2f} | {t['Jit']:.2f} | {t['NativeScalar']:.2f} | "
              f"{t['NativeSimd']:.2f} | {t['NativeSimd'] / t['Batch']:.2f}x | **{t['NativeSimd'] / t['Jit']:.2f}x** | "
              f"{t['Reference'] / t['Jit']:.0f}x |")


def programs(found):
    names = sorted({m.group(1) for k in found if (m := re.match(r"BM_Program/(\w+)/ref$", k))})
    print("| program | slots | ref | batch | jit | batch speed-up | jit speed-up |")
    print("|---|---|---|---|---|---|---|")
    for name in names:
        t = {e: ns_per_item(found[f"BM_Program/{name}/{e}"]) for e in ("ref", "batch", "jit")}
        slots = int(found[f"BM_Program/{name}/ref"]["slots"])
        print(f"| {name} | {slots} | {t['ref']:.1f} | {t['batch']:.2f} | {t['jit']:.2f} | "
              f"{t['ref'] / t['batch']:.0f}x | {t['ref'] / t['jit']:.0f}x |")


def coefficients(found):
    print("| level | face 256: ms | face 1024: ms |")
    print("|---|---|---|")
    for level in range(11):
        cells = []
        for face in (256, 1024):
            b = found.get(f"BM_Coefficients/{face}/{level}")
            cells.append(f"{ms(b):.4g}" if b else "")
        print(f"| {level} | {cells[0]} | {cells[1]} |")
    print()
    print("| other | face 256 ms | face 1024 ms |")
    print("|---|---|---|")
    for name in ("BM_EnvMips", "BM_EnvMipsRefill", "BM_Coefficients_ScalarDouble", "BM_Coefficients_PlainLoop"):
        cells = [f"{ms(found[f'{name}/{face}']):.4g}" if f"{name}/{face}" in found else "" for face in (256, 1024)]
        print(f"| `{name}` | {cells[0]} | {cells[1]} |")
    for threads in (1, 2):
        cells = [f"{ms(found[k]):.4g}" if (k := f"BM_BasisPyramidBuild/{face}/{threads}") in found else ""
                 for face in (256, 1024)]
        print(f"| `BM_BasisPyramidBuild`, {threads} thread{'s' if threads > 1 else ''} (once per face size) | "
              f"{cells[0]} | {cells[1]} |")
    level0, level2 = ms(found["BM_Coefficients/256/0"]), ms(found["BM_Coefficients/256/2"])
    scalar = ms(found["BM_Coefficients_ScalarDouble/256"])
    plain = found.get("BM_Coefficients_PlainLoop/256")
    build = found.get("BM_BasisPyramidBuild/256/2")
    print()
    print(f"Goals: `/256/2` {level0 / level2:.1f}x faster than `/256/0` (>= 12x); level 0 "
          f"{scalar / level0:.1f}x faster than ScalarDouble at 256 (>= 4x).")
    if plain and build:
        print(f"Level 0 and the plain loop read a basis pyramid built once per face size ({ms(build):.4g} ms at 256, "
              f"2 threads); ScalarDouble needs none. Against the plain loop over the same weights, level 0 is "
              f"{ms(plain) / level0:.1f}x faster.")


def frame(found):
    direct = found["BM_Frame/direct_cpu"]
    plain = found.get("BM_Frame/plain_cpu")
    print("| case | wall ms / frame | CPU ms / frame | ratio to direct_cpu (CPU) | ratio to plain_cpu (CPU) | paper fps | "
          "paper ratio | mean rel. error |")
    print("|---|---|---|---|---|---|---|---|")
    paper = {"direct_cpu": 21, "plain_cpu": None, "vm_full": 34, "vm_64": 45, "vm_16": 56}
    for case, fps in paper.items():
        b = found.get(f"BM_Frame/{case}")
        if b is None:
            continue
        to_plain = f"{ms(plain, 'cpu_time') / ms(b, 'cpu_time'):.1f}" if plain else ""
        paper_cells = f"{fps} | {fps / paper['direct_cpu']:.2f}" if fps else " | "
        print(f"| {case} | {ms(b):.2f} | {ms(b, 'cpu_time'):.2f} | {ms(direct, 'cpu_time') / ms(b, 'cpu_time'):.1f} | "
              f"{to_plain} | {paper_cells} | {100 * b['error_mean_rel']:.2f} % |")
    build = found.get("BM_BasisPyramidBuild/256/2")
    if build:
        print()
        print(f"Every case but direct_cpu reads the 256 basis pyramid, built once before the first frame "
              f"({ms(build):.4g} ms, 2 threads; `BM_BasisPyramidBuild/256/2`), not in these frame times.")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    context, found = medians(sys.argv[1])
    print(f"Run: {context.get('date')}, {context.get('num_cpus')} CPUs at {context.get('mhz_per_cpu')} MHz, "
          f"load average {context.get('load_avg')}.\n")
    for title, table in (("Irradiance evaluation (ns per vertex, 1 thread)", irradiance),
                         ("Every program (65 536 vertices, ns per vertex)", programs),
                         ("Coefficients (wall time per update)", coefficients),
                         ("Frame (section 3.3)", frame)):
        print(f"### {title}\n")
        table(found)
        print()


if __name__ == "__main__":
    main()
