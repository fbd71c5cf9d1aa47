"""vs11.irradiance: project and irradiance_map against irrmap's own outputs and physics (batch: test_batch.py)."""
import importlib.util
import json
import inspect
import math
import re
import subprocess

import numpy as np
import pytest

import vs11

# A constant radiance of 1 projects to L00 = 4 pi Y00 = 2 sqrt(pi), and lights every normal with E = pi.
UNIT_L00 = 2.0 * math.sqrt(math.pi)


@pytest.mark.parametrize("environment", ["sky", "studio", "spot", "gradient", "constant"])
def test_project_equals_irrmap_coeffs_json(environment, irrmap_tool, tmp_path):
    subprocess.run([str(irrmap_tool), environment, "--face-size", "32", "--coefficients-only", "--out",
                    str(tmp_path)], capture_output=True, check=True)
    expected = json.loads((tmp_path / "coeffs.json").read_text())
    result = vs11.irradiance.project(environment, face_size=32)
    np.testing.assert_array_equal(result.coefficients, np.array(expected["coefficients"]))
    np.testing.assert_array_equal(result.constants, np.array(list(expected["constants"].values()), np.float32))
    assert (result.level, result.level_size, result.order) == (expected["level"], expected["level_size"],
                                                               expected["order"])
    assert result.program.name == expected["program"]["file"]
    program_constants = {k: list(map(np.float32, v)) for k, v in result.program_constants.items()}
    assert list(program_constants.values()) == [list(map(np.float32, v))
                                                for v in expected["program"]["constants"].values()]
    assert result.errors["estimated_error"] == expected["program"]["estimated_error"]


@pytest.mark.parametrize("metric", ["peak", "rms", "relative"])
def test_error_metric_is_irrmaps(metric, irrmap_tool, tmp_path):
    # The spot: its levels differ by metric, since the relative error is ruled by its unlit half.
    subprocess.run([str(irrmap_tool), "spot", "--face-size", "64", "--coefficients-only", "--error-metric", metric,
                    "--out", str(tmp_path)], capture_output=True, check=True)
    expected = json.loads((tmp_path / "coeffs.json").read_text())
    result = vs11.irradiance.project("spot", face_size=64, error_metric=metric)
    assert expected["error_metric"] == metric
    assert result.errors["error_metric"] == metric
    assert (result.level, result.order) == (expected["level"], expected["order"])
    assert [row["estimated_error"] for row in result.errors["levels"]] == [
        row["estimated_error"] for row in expected["levels"]]
    with pytest.raises(ValueError, match="unknown error metric 'worst'"):
        vs11.irradiance.project("spot", face_size=8, error_metric="worst")


def test_default_error_metric_is_peak():
    assert vs11.irradiance.project("spot", face_size=16).errors["error_metric"] == "peak"


def test_constant_faces_project_to_l00_only():
    faces = np.ones((6, 8, 8, 3), np.float32)
    result = vs11.irradiance.project(faces, level=0, order="order2")
    np.testing.assert_allclose(result.coefficients[0], [UNIT_L00] * 3, rtol=1e-5)
    np.testing.assert_allclose(result.coefficients[1:], 0.0, atol=1e-5)


def test_lat_long_array_is_projected_where_it_lies():
    latlong = np.ones((16, 32, 3))
    result = vs11.irradiance.project(latlong, face_size=8, level=0)
    np.testing.assert_allclose(result.coefficients[0], [UNIT_L00] * 3, rtol=1e-5)


def numpy_projection(image):
    """The benchmark's 15-line float64 NumPy projection with per-row solid angles (one copy of it)."""
    from conftest import SOURCE_DIR
    spec = importlib.util.spec_from_file_location("panorama_vs_cmgen",
                                                  SOURCE_DIR / "bench" / "irradiance" / "panorama_vs_cmgen.py")
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    return bench.numpy_project(image)


@pytest.mark.parametrize("layout", ["c", "strided", "float64"])
def test_lat_long_array_level_0_is_its_exact_projection(layout):
    rng = np.random.default_rng(7)
    image = rng.uniform(0.0, 1.0, (64, 128, 3)).astype(np.float32)
    image[20:23, 40:44] = 500.0
    given = {"c": image, "strided": np.asfortranarray(image), "float64": image.astype(np.float64)}[layout]
    result = vs11.irradiance.project(given, face_size=16, level=0)
    expected = numpy_projection(image)
    assert np.abs(result.coefficients - expected).max() <= 1e-6 * np.abs(expected).max()
    assert [level["size"] for level in result.errors["levels"]] == [16, 8, 4, 2, 1]
    with pytest.raises(ValueError, match="level"):
        vs11.irradiance.project(given, face_size=16, level=5)


def test_irradiance_map_of_a_constant_environment_is_pi():
    irradiance = vs11.irradiance.irradiance_map(np.full((6, 4, 4, 3), 1.0), map_size=4)
    assert irradiance.shape == (6, 4, 4, 3) and irradiance.dtype == np.float32
    np.testing.assert_allclose(irradiance, math.pi, rtol=2e-5)


def test_chosen_program_runs_with_its_constants():
    result = vs11.irradiance.project("spot", face_size=32)
    normals = np.array([[0.0, 1.0, 0.0], [0.0, -1.0, 0.0]])
    lit = result.program.run({"v0": normals}, result.program_constants)
    assert result.program.outputs[0] in lit


@pytest.mark.parametrize("array,message", [
    (np.ones((6, 8, 8, 4), np.float32), r"shape \(6, 8, 8, 4\)"),
    (np.ones((8, 8, 3), np.float32), r"shape \(8, 8, 3\)"),
    (np.ones((6, 8, 8, 3), np.int16), r"dtype int16"),
    (np.full((6, 4, 4, 3), np.nan), r"finite and >= 0, found nan"),
    (np.full((4, 8, 3), -1.0), r"finite and >= 0, found -1"),
    (np.ones((6, 6, 6, 3)), r"power of two"),
])
def test_bad_environment_arrays_are_value_errors(array, message):
    with pytest.raises(ValueError, match=message):
        vs11.irradiance.project(array)


@pytest.mark.parametrize("options,message", [
    ({"max_error": 1.0}, r"^max_error=1 is out of range"),
    ({"max_error": float("nan")}, r"^max_error=nan is out of range"),
    ({"face_size": 3}, r"^face_size=3 must be a power of two"),
    ({"level": -1}, r"^level=-1 is out of range"),
    ({"level": 9, "face_size": 8}, r"^level=9 is out of range"),
    ({"map_size": 0}, r"^map_size=0 is out of range"),
])
def test_option_errors_name_the_python_argument(options, message):
    call = vs11.irradiance.irradiance_map if "map_size" in options else vs11.irradiance.project
    with pytest.raises(ValueError, match=message) as error:
        call("sky", **options)
    assert "--" not in str(error.value)


def test_environment_arrays_too_large_to_copy_are_value_errors():
    # Broadcast views cost NumPy nothing; their sizes wrapped around the int sizes of the copy.
    faces = np.broadcast_to(np.float32(1), (6, 2**20, 2**20, 3))
    with pytest.raises(ValueError, match="above the largest face size"):
        vs11.irradiance.project(faces)
    latlong = np.broadcast_to(np.float32(1), (2**29, 2**30, 3))
    with pytest.raises(ValueError, match="more than the .* pixels of the largest image"):
        vs11.irradiance.project(latlong)


def test_bad_options_and_files_are_value_errors(tmp_path):
    with pytest.raises(ValueError, match="neither an existing file nor a built-in"):
        vs11.irradiance.project(str(tmp_path / "missing.hdr"))
    with pytest.raises(ValueError, match="unknown order"):
        vs11.irradiance.project("sky", face_size=8, order="order9")


@pytest.mark.parametrize("argument,names", [
    ("layout", vs11.irradiance.LAYOUTS), ("order", vs11.irradiance.ORDERS),
    ("window", vs11.irradiance.WINDOWS), ("error_metric", vs11.irradiance.ERROR_METRICS)])
def test_an_unknown_choice_lists_the_names_irrmap_accepts(argument, names):
    listed = ", ".join(names[:-1]) + " or " + names[-1]
    for call in (lambda: vs11.irradiance.project("sky", face_size=8, **{argument: "bogus"}),
                 lambda: vs11.irradiance.irradiance_map("sky", face_size=8, map_size=2, **{argument: "bogus"}),
                 lambda: vs11.irradiance.batch(["sky.exr"], **{argument: "bogus"})):
        with pytest.raises(ValueError, match=re.escape("%s='bogus': unknown " % argument) + ".*" +
                           re.escape("'bogus' (use %s)" % listed)):
            call()


def test_defaults_come_from_the_module():
    defaults = vs11.irradiance.DEFAULTS
    assert defaults["order"] == "auto" and defaults["order"] in vs11.irradiance.ORDERS
    assert defaults["batch_order"] in vs11.irradiance.ORDERS and defaults["window"] in vs11.irradiance.WINDOWS
    assert inspect.signature(vs11.irradiance.project).parameters["max_error"].default == defaults["max_error"]
    assert inspect.signature(vs11.irradiance.batch).parameters["order"].default == defaults["batch_order"]
