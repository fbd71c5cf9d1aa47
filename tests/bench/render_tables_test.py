#!/usr/bin/env python3
"""bench/render_tables.py renders any vs11_bench JSON run: with aggregates, without repetitions,
with repetitions but no aggregates, filtered to one group, or empty. Run by ctest:
    python3 tests/bench/render_tables_test.py SOURCE_DIR
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(sys.argv.pop(1) if len(sys.argv) > 1 else ".", "bench", "render_tables.py")


def entry(name, real_time, run_type="iteration", aggregate=None, repetitions=1, **counters):
    b = {"name": name + (f"_{aggregate}" if aggregate else ""), "run_name": name, "run_type": run_type,
         "repetitions": repetitions, "iterations": 10, "real_time": real_time, "cpu_time": real_time,
         "time_unit": "ns"}
    if aggregate:
        b["aggregate_name"] = aggregate
    b.update(counters)
    return b


def frame_entries(**kwargs):
    return [entry(f"BM_Frame/{case}", t * 1e6, error_mean_rel=0.08, **kwargs)
            for case, t in (("direct_cpu", 60.0), ("vm_full", 3.0), ("vm_64", 1.0), ("vm_16", 0.9))]


def render(benchmarks):
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump({"context": {"date": "today", "num_cpus": 2}, "benchmarks": benchmarks}, f)
    try:
        result = subprocess.run([sys.executable, SCRIPT, f.name], capture_output=True, text=True)
    finally:
        os.unlink(f.name)
    return result


class RenderTables(unittest.TestCase):
    def assert_renders(self, result):
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn("Traceback", result.stderr)

    def test_single_run_without_repetitions(self):
        result = render(frame_entries() + [
            entry("BM_Irradiance_Batch/65536", 1e6, items_per_second=5e8),
            entry("BM_Irradiance_Jit/65536", 1e6, items_per_second=1e9),
            entry("BM_Program/fog/ref", 1e6, items_per_second=1e7, slots=21),
            entry("BM_Program/fog/jit", 1e6, items_per_second=1e8, slots=21),
            entry("BM_Coefficients/256/0/real_time", 3e6, texels=1),
        ])
        self.assert_renders(result)
        self.assertIn("one measurement each (no repetitions)", result.stdout)
        self.assertIn("| 65536 |  | 2.00 | 1.00 |", result.stdout)
        self.assertIn("| fog | 21 | 100.0 |  | 10.00 |  | 10x |", result.stdout)
        self.assertIn("| vm_full | 3.00 | 3.00 | 20.0 |  | 34 | 1.62 | 8.00 % |", result.stdout)
        self.assertIn("| 0 | 3 |  |", result.stdout)

    def test_repetitions_without_aggregates_take_the_median(self):
        runs = [entry("BM_Frame/direct_cpu", t * 1e6, repetitions=3, error_mean_rel=0.08) for t in (50, 70, 60)]
        result = render(runs)
        self.assert_renders(result)
        self.assertIn("medians of 3 repetitions", result.stdout)
        self.assertIn("| direct_cpu | 60.00 | 60.00 | 1.0 |", result.stdout)

    def test_aggregates_use_the_median(self):
        result = render([entry("BM_Frame/vm_16", 9e6, "aggregate", "mean", 3, error_mean_rel=0.1),
                         entry("BM_Frame/vm_16", 1e6, "aggregate", "median", 3, error_mean_rel=0.1)])
        self.assert_renders(result)
        self.assertIn("| vm_16 | 1.00 | 1.00 |  |", result.stdout)

    def test_filtered_run_says_no_data_for_the_other_tables(self):
        result = render(frame_entries())
        self.assert_renders(result)
        self.assertEqual(result.stdout.count("no data"), 4)  # irradiance, programs, both coefficient tables
        self.assertIn("| vm_64 |", result.stdout)

    def test_empty_run(self):
        result = render([])
        self.assert_renders(result)
        self.assertEqual(result.stdout.count("no data"), 5)


if __name__ == "__main__":
    unittest.main()
