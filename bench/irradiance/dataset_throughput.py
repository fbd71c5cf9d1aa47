#!/usr/bin/env python3
"""Labelling throughput on 2048x1024 EXR panoramas, in one run (issue 35):

  decode      vs11_decode_images --reader oiio: OpenImageIO alone, read as float RGB
  read        vs11_decode_images --reader vs11: vs11's reader (checks, OpenImageIO, RGB image)
  batch       vs11.irradiance.iter_batch(files, threads=1): read, the lat-long pyramid (projected in place), project
              every level, pick the level, the record (what a Dask task runs)
  cluster/1   vs11.dask.label_dataset on a LocalCluster of one worker process (one thread)
  cluster/2   the same on two worker processes

Each measurement runs --repetitions times, the kinds taken in turn (so a change of load touches all
of them), and the medians are reported: files per second of wall time, and files per CPU second
(user + system of every thread: per core). Goals: batch's time beyond decoding ("projection and
bookkeeping") under 20 % of decode's; cluster/2 at least 1.8x cluster/1.

The panoramas are the built-in environments written by vs11_write_environments (--face-size 512:
2048x1024 lat-long, 32-bit float EXR), copied to --files names; deterministic.

    python3 bench/irradiance/dataset_throughput.py --build build --files 16 --json out.json
"""
import argparse
import json
import os
import pathlib
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve()

BATCH_SCRIPT = """
import json, resource, sys, time
import vs11.irradiance
files = sys.argv[1:]
before, start = resource.getrusage(resource.RUSAGE_SELF), time.perf_counter()
records = list(vs11.irradiance.iter_batch(files, threads=1, face_size=256))
wall, after = time.perf_counter() - start, resource.getrusage(resource.RUSAGE_SELF)
assert len(records) == len(files), "only %d records" % len(records)
cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
print(json.dumps({"seconds": wall, "cpu_seconds": cpu}))
"""


def make_panoramas(build, work, count):
    source = work / "source"
    if not source.exists():
        subprocess.run([str(build / "bench" / "vs11_write_environments"), str(source), "--face-size", "512"],
                       check=True, stdout=subprocess.DEVNULL)
    originals = sorted(source.glob("*_latlong.exr"))
    data = work / "data"
    data.mkdir(exist_ok=True)
    files = []
    for i in range(count):
        target = data / ("pano%03d.exr" % i)
        if not target.exists():
            shutil.copyfile(originals[i % len(originals)], target)
        files.append(str(target))
    return files


def run_child(command, env):
    """(wall seconds the child reports, CPU seconds of the child and its threads)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    result = subprocess.run(command, check=True, capture_output=True, text=True, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    report = json.loads(result.stdout.strip().splitlines()[-1])
    return report["seconds"], (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def cluster_run(client, files, out):
    import vs11.dask
    shutil.rmtree(out, ignore_errors=True)
    workers_cpu_before = sum(client.run(_cpu_seconds).values())
    start = time.perf_counter()
    summary = vs11.dask.label_dataset(client, files, out, files_per_task=2, face_size=256, progress=False)
    wall = time.perf_counter() - start
    assert summary.written == len(files) and not summary.failed, summary
    return wall, sum(client.run(_cpu_seconds).values()) - workers_cpu_before


def _cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def machine():
    model = "unknown"
    try:
        for line in subprocess.run(["lscpu"], capture_output=True, text=True).stdout.splitlines():
            if line.startswith("Model name:"):
                model = line.split(":", 1)[1].strip()
    except OSError:
        pass
    flags = pathlib.Path("/proc/cpuinfo").read_text() if pathlib.Path("/proc/cpuinfo").exists() else ""
    return {"cpu": model, "cores": os.cpu_count(), "avx512f": " avx512f" in flags, "system": platform.platform()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default="build", type=pathlib.Path, help="the build folder")
    parser.add_argument("--files", default=16, type=int, help="panoramas per measurement")
    parser.add_argument("--repetitions", default=3, type=int)
    parser.add_argument("--work", type=pathlib.Path, help="where the panoramas go (default BUILD/bench-dataset)")
    parser.add_argument("--json", type=pathlib.Path, help="also write the results here")
    args = parser.parse_args()
    build = args.build.resolve()
    work = (args.work or build / "bench-dataset").resolve()
    work.mkdir(parents=True, exist_ok=True)
    files = make_panoramas(build, work, args.files)
    env = dict(os.environ, PYTHONPATH=str(build / "python"))
    sys.path.insert(0, str(build / "python"))
    os.environ["PYTHONPATH"] = env["PYTHONPATH"]  # the cluster's worker processes import vs11 too

    from dask.distributed import Client, LocalCluster
    load_before = os.getloadavg()
    decode = [str(build / "bench" / "vs11_decode_images")]
    kinds = {
        "decode": lambda: run_child(decode + ["--reader", "oiio"] + files, env),
        "read": lambda: run_child(decode + ["--reader", "vs11"] + files, env),
        "batch": lambda: run_child([sys.executable, "-c", BATCH_SCRIPT] + files, env),
    }
    samples = {kind: [] for kind in list(kinds) + ["cluster/1", "cluster/2"]}
    options = dict(threads_per_worker=1, processes=True, dashboard_address=":0", silence_logs=40)
    with LocalCluster(n_workers=1, **options) as one, Client(one) as client1, \
            LocalCluster(n_workers=2, **options) as two, Client(two) as client2:
        for client in (client1, client2):  # warm-up: vs11 imported in every worker
            cluster_run(client, files[:4], work / "warm-up")
        for _ in range(args.repetitions):
            for kind, measure in kinds.items():
                samples[kind].append(measure())
            samples["cluster/1"].append(cluster_run(client1, files, work / "labels-1"))
            samples["cluster/2"].append(cluster_run(client2, files, work / "labels-2"))
    load_after = os.getloadavg()

    results = {}
    for kind, runs in samples.items():
        wall = statistics.median(r[0] for r in runs)
        cpu = statistics.median(r[1] for r in runs)
        results[kind] = {"seconds": wall, "cpu_seconds": cpu, "files_per_second": len(files) / wall,
                         "files_per_cpu_second": len(files) / cpu if cpu > 0 else None}
    beyond_decode = results["batch"]["cpu_seconds"] / results["decode"]["cpu_seconds"] - 1.0
    speedup = results["cluster/1"]["seconds"] / results["cluster/2"]["seconds"]
    report = {"machine": machine(), "load_before": load_before, "load_after": load_after, "files": len(files),
              "repetitions": args.repetitions, "results": results,
              "projection_and_bookkeeping_over_decode": beyond_decode, "two_workers_speedup": speedup}

    print("%d files of 2048x1024 EXR, medians of %d; %s, %d cores, AVX-512 %s; load %.2f before, %.2f after"
          % (len(files), args.repetitions, report["machine"]["cpu"], report["machine"]["cores"],
             "yes" if report["machine"]["avx512f"] else "no", load_before[0], load_after[0]))
    # cores busy: CPU over wall time, the cores the run got (on a shared machine, fewer than it has).
    print("%-10s %10s %10s %12s %14s %11s" % ("", "wall s", "CPU s", "files/s", "files/CPU s", "cores busy"))
    for kind, r in results.items():
        print("%-10s %10.3f %10.3f %12.2f %14.2f %11.2f" % (kind, r["seconds"], r["cpu_seconds"], r["files_per_second"],
                                                              r["files_per_cpu_second"] or 0.0,
                                                              r["cpu_seconds"] / r["seconds"]))
    read_share = results["read"]["cpu_seconds"] / results["decode"]["cpu_seconds"] - 1.0
    print("batch beyond decoding (CPU): %+.0f %% of decode (goal < 20 %%); vs11's reader beyond OpenImageIO: %+.0f %%"
          % (100 * beyond_decode, 100 * read_share))
    print("two workers against one: %.2fx (goal >= 1.8x)" % speedup)
    if args.json:
        args.json.write_text(json.dumps(report, indent=2) + "\n")


if __name__ == "__main__":
    main()
