"""Program.run and Program.trace: results, bit equality with `vs11 run`, zero copy, the GIL, errors."""
import csv
import io
import subprocess
import sys
import threading
import time
import tracemalloc
import warnings

import numpy as np
import pytest

import vs11

# Ramamoorthi & Hanrahan (2001) eq. (7) constants, as the paper prints them.
C1, C2, C3, C4, C5 = 0.429043, 0.511664, 0.743125, 0.886227, 0.247708


def sphere_normals(n, seed=7):
    v = np.random.default_rng(seed).normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def equation7(L, n):
    """Irradiance from nine coefficients (L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22) in double."""
    x, y, z = (n[:, i : i + 1] for i in range(3))
    return (C1 * L[8] * (x * x - y * y) + C3 * L[6] * z * z + C4 * L[0] - C5 * L[6]
            + 2 * C1 * (L[4] * x * y + L[7] * x * z + L[5] * y * z)
            + 2 * C2 * (L[3] * x + L[1] * y + L[2] * z))


def test_paper_program_on_normals_matches_equation_7(programs_dir):
    program = vs11.load(programs_dir / "sh9_irradiance.vsh")
    sky = vs11.irradiance.project("sky", face_size=16, order="order2")
    normals = sphere_normals(500)
    lit = program.run({"v0": normals}, sky.constants)["oD0"]
    assert lit.shape == (500, 4) and lit.dtype == np.float32
    expected = equation7(sky.coefficients, normals)
    np.testing.assert_allclose(lit[:, :3], expected, rtol=0, atol=2e-5 * np.abs(expected).max())


def test_engines_and_input_forms_agree_bit_for_bit(programs_dir):
    program = vs11.load(programs_dir / "sh9_irradiance.vsh")
    constants = vs11.irradiance.project("studio", face_size=16, order="order2").constants
    normals = sphere_normals(300)
    reference = program.run({"v0": normals.astype(np.float32)}, constants, engine="ref")["oD0"]
    as_dict = {"c%d" % i: list(row) for i, row in enumerate(constants)}
    four = np.hstack([normals, np.ones((300, 1))])
    for out in (program.run({"v0": normals}, constants, engine="batch"),
                program.run({"v0": np.asfortranarray(four)}, as_dict, engine="jit", threads=2),
                program.run({"v0": four[::-1][::-1]}, {i: row for i, row in enumerate(constants)})):
        np.testing.assert_array_equal(out["oD0"].view(np.uint32), reference.view(np.uint32))


def test_dcl_usage_names_select_input_registers():
    program = vs11.assemble("vs_1_1\ndcl_position v0\ndcl_texcoord1 v5\nmov oPos, v0\nmov oT0, v5\n")
    uv = np.arange(12, dtype=np.float32).reshape(3, 4)
    out = program.run({"position": np.zeros((3, 3)), "texcoord1": uv})
    np.testing.assert_array_equal(out["oT0"], uv)
    np.testing.assert_array_equal(out["oPos"][:, 3], np.ones(3, np.float32))  # (n, 3): w = 1


def write_csv(path, rows):
    path.write_text("".join(",".join("%.9g" % v for v in row) + "\n" for row in rows))


def parse_cli_csv(text):
    reader = csv.reader(io.StringIO(text))
    header = next(reader)
    rows = np.array([[np.float32(float(v)) for v in row] for row in reader], dtype=np.float32)
    return header, rows


def same_bits(a, b):
    both_nan = np.isnan(a) & np.isnan(b)
    return bool(np.all(both_nan | (a.view(np.uint32) == b.view(np.uint32))))


def test_every_program_matches_vs11_run_bit_for_bit(programs_dir, vs11_tool, tmp_path):
    rng = np.random.default_rng(11)
    programs = sorted(programs_dir.glob("*.vsh"))
    assert len(programs) > 10
    constants = rng.uniform(-2, 2, size=(96, 4)).astype(np.float32)
    consts_file = tmp_path / "constants.txt"
    consts_file.write_text("".join("c%d = %s\n" % (i, " ".join("%.9g" % v for v in row))
                                   for i, row in enumerate(constants)))
    compared = 0
    for path in programs:
        program = vs11.load(path)
        inputs, flags = {}, []
        for name in program.inputs or ["v0"]:  # a program without inputs still runs n vertices
            values = rng.uniform(-2, 2, size=(300, 4)).astype(np.float32)  # a whole batch and a part
            write_csv(tmp_path / (name + ".csv"), values)
            inputs[name] = values
            flags += ["--input", "%s=%s" % (name, tmp_path / (name + ".csv"))]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the def lines a program overrides are warned about
            ours = program.run(inputs, constants)
        cli = subprocess.run([str(vs11_tool), "run", str(path), "--consts", str(consts_file)] + flags,
                             capture_output=True, text=True, check=True)
        header, rows = parse_cli_csv(cli.stdout)
        for column, name in enumerate(header):
            register, lane = name.split(".")
            got = ours[register][:, "xyzw".index(lane)]
            assert same_bits(got, rows[:, column]), "%s %s: %s vs %s" % (path.name, name, got, rows[:, column])
            compared += 1
    assert compared > 2 * len(programs)  # output lanes compared, every program's


def test_outputs_are_views_of_one_engine_buffer():
    program = vs11.assemble("vs_1_1\ndcl_position v0\nmov oPos, v0\nmov oD0, v0\nmov oT0, v0\n")
    out = program.run({"position": np.ones((1000, 4), np.float32)})
    assert all(not array.flags.owndata for array in out.values())
    bases = {id(array.base) for array in out.values()}
    assert len(bases) == 1 and next(iter(out.values())).base is not None


@pytest.mark.parametrize("dtype,columns", [(np.float32, 4), (np.float64, 3)])
def test_inputs_are_not_copied_into_numpy_arrays(dtype, columns):
    program = vs11.assemble("vs_1_1\ndcl_position v0\nmov oPos, v0\n")
    positions = np.ones((200_000, columns), dtype)
    tracemalloc.start()
    try:
        program.run({"position": positions})
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < positions.nbytes // 8, "run() made a NumPy copy of its input (%d bytes traced)" % peak


# run() on 2^20 vertices in a fresh process (so that the peak resident size before it is this
# input's, not an earlier test's): the growth of the peak is what run() allocated and touched.
NO_COPY_PROBE = r"""
import resource
import numpy as np
import vs11
program = vs11.assemble("vs_1_1\ndcl_position v0\nmov oPos, v0\n")
inputs = np.ones((1 << 20, %d), np.float32)
program.run({"position": inputs[:1000]})  # the engine's first-call setup, on a small slice
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
out = program.run({"position": inputs})
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print((after - before) * 1024, out["oPos"].nbytes, inputs.nbytes, int(out["oPos"][-1, 3]))
"""


def test_c_contiguous_float32_inputs_are_read_in_place():
    # (n, 4), the case; (n, 3) takes the same path (a stride-0 w), checked bit for bit below.
    probe = subprocess.run([sys.executable, "-c", NO_COPY_PROBE % 4], capture_output=True, text=True, check=True)
    growth, output_bytes, input_bytes, w = map(int, probe.stdout.split())
    assert w == 1
    # The output (16 bytes a vertex) and a few KB of workspace; a copy of the input into the
    # engines' layout would add 16 bytes a vertex more.
    assert growth < output_bytes + input_bytes // 2, "run() grew the peak by %d bytes: a copy of the input" % growth


@pytest.mark.parametrize("engine", ["ref", "batch", "jit"])
def test_float32_views_read_in_place_give_the_bits_of_a_converted_copy(programs_dir, engine):
    program = vs11.load(programs_dir / "sh9_irradiance.vsh")
    constants = vs11.irradiance.project("studio", face_size=16, order="order2").constants
    base = np.random.default_rng(5).uniform(-1, 1, size=(1000, 8)).astype(np.float32)
    views = [base[:, :4], base[::-1, 2:6], base[::3, 1:4], np.asfortranarray(base[:, 4:8]),
             np.ascontiguousarray(base[:, :3]), base[:, 5:1:-1]]
    for view in views:
        got = program.run({"v0": view}, constants, engine=engine, threads=2)["oD0"]
        converted = program.run({"v0": view.astype(np.float64)}, constants, engine=engine)["oD0"]
        assert got.view(np.uint32).tolist() == converted.view(np.uint32).tolist(), view.strides


def test_gil_is_released_so_python_runs_beside_an_engine(programs_dir):
    program = vs11.load(programs_dir / "sh9_irradiance.vsh")
    constants = np.full((7, 4), 0.5, np.float32)
    normals = sphere_normals(100_000).astype(np.float32)
    span = {}
    running = threading.Event()

    def work():
        running.set()
        span["start"] = time.perf_counter()
        program.run({"v0": normals}, constants, engine="ref")
        span["end"] = time.perf_counter()

    # No forced switches: a thread gives up the GIL only where it blocks (this loop's sleep) or
    # releases it. Had run() held the GIL from its call to its return, this thread could take no
    # time stamp in between, however the machine is loaded; with the GIL released it takes them while
    # the engine works. (Timing how two runs overlap instead failed now and then on a loaded machine.)
    stamps = []
    interval = sys.getswitchinterval()
    sys.setswitchinterval(30.0)
    try:
        thread = threading.Thread(target=work)
        thread.start()
        running.wait()
        while thread.is_alive():
            stamps.append(time.perf_counter())
            time.sleep(0.0005)
        thread.join()
    finally:
        sys.setswitchinterval(interval)
    inside = [t for t in stamps if span["start"] < t < span["end"]]
    assert inside, "no Python ran during run() (%.3f s): the GIL was held" % (span["end"] - span["start"])


def test_unset_constants_and_missing_inputs_are_errors_unless_asked_for_as_in_the_cli(programs_dir, vs11_tool,
                                                                                      tmp_path):
    program = vs11.load(programs_dir / "sh9_irradiance.vsh")
    with pytest.raises(ValueError, match=r"sh9_irradiance.vsh: the program reads c0, c1, .*c6, which neither"):
        program.run({"v0": sphere_normals(4)})
    constants = {"c%d" % i: [0.5, 0.5, 0.5, 0.5] for i in range(7)}
    misspelt = dict(constants, c44=constants.pop("c4"))
    with pytest.raises(ValueError, match=r"reads c4, which neither .* \(they set c44, which it never reads\)"):
        program.run({"v0": sphere_normals(4)}, misspelt)
    with pytest.raises(ValueError, match=r"reads c4.*missing='zeros'"):
        program.trace({"v0": sphere_normals(4)}, misspelt)
    two_inputs = vs11.assemble("vs_1_1\ndcl_position v0\ndcl_normal v3\nmov oPos, v0\nmov oD0, v3\n")
    with pytest.raises(ValueError, match=r"reads v3, which no entry of inputs supplies \(given: v0\)"):
        two_inputs.run({"v0": np.zeros((2, 4))})
    with pytest.raises(ValueError, match="missing='nothing': use 'error'"):
        two_inputs.run({"v0": np.zeros((2, 4))}, missing="nothing")
    # Asked for: the old behaviour, the warnings `vs11 run --missing zeros` prints.
    with pytest.warns(UserWarning, match=r"sh9_irradiance.vsh: warning: .*c0"):
        out = program.run({"v0": sphere_normals(4)}, missing="zeros")
    assert np.all(out["oD0"][:, :3] == 0)
    with pytest.warns(UserWarning, match="v3"):
        out = two_inputs.run({"v0": np.zeros((2, 4))}, missing="zeros")
    np.testing.assert_array_equal(out["oD0"], [[0, 0, 0, 1]] * 2)
    # The CLI: the same case is an error (exit 2) naming the register, unless --missing zeros.
    normals = tmp_path / "n.csv"
    normals.write_text("0,0,1\n")
    cli = [str(vs11_tool), "run", str(programs_dir / "sh9_irradiance.vsh"), "--input", "v0=%s" % normals]
    refused = subprocess.run(cli, capture_output=True, text=True)
    assert refused.returncode == 2 and "reads c0, c1, c2, c3, c4, c5, c6, which neither" in refused.stderr
    allowed = subprocess.run(cli + ["--missing", "zeros"], capture_output=True, text=True)
    assert allowed.returncode == 0 and "warning: the program reads c0" in allowed.stderr


@pytest.mark.parametrize("inputs,message", [
    ({"v0": np.zeros((4, 2), np.float32)}, r"inputs\['v0'\]: shape \(4, 2\)"),
    ({"v0": np.zeros((4, 4), np.int32)}, r"inputs\['v0'\]: dtype int32"),
    ({"v0": [[0, 0, 1, 1]]}, r"inputs\['v0'\]: expected a NumPy array"),
    ({"v0": np.zeros((4, 4)), "normal": np.zeros((3, 4))}, r"has 3 vertices"),
    ({"tangent": np.zeros((4, 4))}, r"not an input register"),
    ({}, r"no arrays"),
])
def test_bad_inputs_are_value_errors(inputs, message):
    program = vs11.assemble("vs_1_1\ndcl_position v0\ndcl_normal v1\nmov oPos, v0\nmov oD0, v1\n")
    with pytest.raises(ValueError, match=message):
        program.run(inputs)


@pytest.mark.parametrize("constants,message", [
    ({"c96": [0, 0, 0, 0]}, r"c96 is out of range"),
    ({"x4": [0, 0, 0, 0]}, r"not a constant register"),
    ({2**70: [0, 0, 0, 0]}, r"constants\[1180591620717411303424\]: c1180591620717411303424 is out of range"),
    ({-2**70: [0, 0, 0, 0]}, r"is out of range"),
    ({-1: [0, 0, 0, 0]}, r"constants\[-1\]: c-1 is out of range"),
    ({96: [0, 0, 0, 0]}, r"constants\[96\]: c96 is out of range"),
    ({4: [1, 2, 3]}, r"expected 4 numbers"),
    (np.zeros((97, 4)), r"97 rows"),
    (np.zeros((3, 3)), r"shape \(3, 3\)"),
])
def test_bad_constants_are_value_errors(constants, message):
    program = vs11.assemble("vs_1_1\ndcl_position v0\nadd oPos, v0, c4\n")
    with pytest.raises(ValueError, match=message):
        program.run({"v0": np.zeros((2, 4))}, constants)


def test_vertex_counts_whose_arrays_cannot_exist_are_value_errors():
    # A broadcast view of 2^58 rows costs NumPy nothing; the four output registers' size wrapped
    # around to a few floats, which the engine then wrote far beyond.
    program = vs11.assemble("vs_1_1\ndcl_position v0\nmov oPos, v0\nmov oD0, v0\nmov oD1, v0\nmov oT0, v0\n")
    huge = np.broadcast_to(np.zeros(4, np.float32), (2**58, 4))
    with pytest.raises(ValueError, match="would not fit in the address space"):
        program.run({"v0": huge})


def test_bad_engine_and_threads_are_value_errors():
    program = vs11.assemble("vs_1_1\ndcl_position v0\nmov oPos, v0\n")
    with pytest.raises(ValueError, match="engine='gpu'"):
        program.run({"v0": np.zeros((2, 4))}, engine="gpu")
    with pytest.raises(ValueError, match="threads=0"):
        program.run({"v0": np.zeros((2, 4))}, threads=0)
    with pytest.raises(ValueError, match=r"threads=1180591620717411303424 is out of range"):
        program.run({"v0": np.zeros((2, 4))}, threads=2**70)
    with pytest.raises(TypeError):
        program.run({"v0": np.zeros((2, 4))}, threads=2.0)
    # The gl engine lives in the tools (it links EGL); the module says so instead of returning NaN.
    with pytest.raises(ValueError, match="engine='gl': the gl engine runs in the vs11 and irrmap tools only"):
        program.run({"v0": np.zeros((2, 4))}, engine="gl")


@pytest.mark.parametrize("engine", ["ref", "batch", "jit"])
def test_float_rules_decide_infinity_times_zero(engine):
    program = vs11.assemble("vs_1_1\ndcl_position v0\nmul oD0, c0, v0\n", fragment=True)
    zero_lanes = {"v0": np.array([[0.0, -0.0, 2.0, 0.0]], np.float32)}
    infinite = {"c0": [np.inf, np.inf, np.inf, -np.inf]}
    d3d9 = program.run(zero_lanes, infinite, engine=engine)["oD0"][0]
    legacy = program.run(zero_lanes, infinite, engine=engine, float_rules="legacy")["oD0"][0]
    assert np.isnan(d3d9[[0, 1, 3]]).all() and d3d9[2] == np.inf
    # The zero operand keeps its sign: +0, -0, then inf * 2, then +0 (-inf * +0).
    assert [np.signbit(x) for x in legacy] == [False, True, False, False]
    assert legacy[0] == 0 and legacy[1] == 0 and legacy[2] == np.inf and legacy[3] == 0
    trace = program.trace(zero_lanes, infinite, engine=engine, float_rules="legacy")
    assert trace["identical"] and trace["outputs"][0]["reference"][0] == 0
    with pytest.raises(ValueError, match="float_rules='strict'"):
        program.run(zero_lanes, infinite, float_rules="strict")


def test_trace_is_what_vs11_run_trace_json_writes(programs_dir, vs11_tool, tmp_path):
    path = programs_dir / "sh9_irradiance.vsh"
    program = vs11.load(str(path))
    normals = sphere_normals(3).astype(np.float32)
    constants = np.linspace(-1, 1, 28, dtype=np.float32).reshape(7, 4)
    trace = program.trace({"v0": normals}, constants, vertex=2)
    assert len(trace["steps"]) == 11 and trace["identical"]
    write_csv(tmp_path / "n.csv", normals)
    (tmp_path / "c.txt").write_text("".join("c%d = %s\n" % (i, " ".join("%.9g" % v for v in row))
                                            for i, row in enumerate(constants)))
    subprocess.run([str(vs11_tool), "run", str(path), "--input", "v0=%s" % (tmp_path / "n.csv"), "--consts",
                    str(tmp_path / "c.txt"), "--trace", "2", "--trace-json", str(tmp_path / "t.json")],
                   capture_output=True, check=True)
    import json
    assert json.loads((tmp_path / "t.json").read_text())["vertices"][0] == trace
    with pytest.raises(IndexError, match="there are 3 vertices"):
        program.trace({"v0": normals}, constants, vertex=3)
    with pytest.raises(IndexError, match="vertex 1180591620717411303424: there are 3 vertices"):
        program.trace({"v0": normals}, constants, vertex=2**70)


def test_trace_follows_a_later_models_flow(vs11_tool, tmp_path):
    # A loop of two iterations over c0[aL] (aL = 10, 14), then a call under if b0.
    path = tmp_path / "flow.vsh"
    path.write_text("vs_2_0\ndefi i0, 2, 10, 4, 0\ndefb b0, true\ndcl_position v0\nmov r0, v0\n"
                    "loop aL, i0\nadd r0, r0, c0[aL]\nendloop\nif b0\ncall l0\nendif\nmov oPos, r0\nret\n"
                    "label l0\nmul r0, r0, c1\nret\n")
    program = vs11.load(str(path))
    positions = np.array([[0, 0, 0, 1], [1, 2, 3, 1]], dtype=np.float32)
    constants = np.zeros((18, 4), dtype=np.float32)
    constants[1] = [2, 2, 2, 1]
    constants[10] = [1, 0, 0, 0]
    constants[14] = [0, 1, 0, 0]
    trace = program.trace({"v0": positions}, constants, vertex=1)
    assert [step["flow"] for step in trace["steps"] if "flow" in step] == [
        "2 iterations, aL = 10, step 4", "next iteration, aL = 14", "the loop ends", "true: runs the block",
        "calls l0 at line 15", "returns to line 11", "the program ends"]
    assert [step["line"] for step in trace["steps"]] == [5, 6, 7, 8, 7, 8, 9, 10, 15, 16, 11, 12, 13]
    assert trace["outputs"][0]["reference"] == [4, 6, 6, 1] and trace["identical"]
    write_csv(tmp_path / "p.csv", positions)
    (tmp_path / "c.txt").write_text("c1 = 2 2 2 1\nc10 = 1 0 0 0\nc14 = 0 1 0 0\n")
    subprocess.run([str(vs11_tool), "run", str(path), "--input", "v0=%s" % (tmp_path / "p.csv"), "--consts",
                    str(tmp_path / "c.txt"), "--missing", "zeros", "--trace", "1", "--trace-json",
                    str(tmp_path / "t.json")], capture_output=True, check=True)
    import json
    assert json.loads((tmp_path / "t.json").read_text())["vertices"][0] == trace
