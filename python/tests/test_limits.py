"""The module under an address-space limit and with environments beyond float range: an exception
or a warning, never a dead interpreter and never a non-finite number."""
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import vs11
import vs11.irradiance

from test_batch import write_pfm

# AddressSanitizer's shadow memory leaves no room for RLIMIT_AS (tests/resource_limits_test.cc says
# the same); the module is never built with it, but say why if it ever is.
UNDER_ASAN = "asan" in os.environ.get("LD_PRELOAD", "")


def run_limited(script, limit_mb, read_first=None):
    """`script` in a fresh interpreter whose address space is limited to `limit_mb` more than the
    interpreter with the module imported needs (and, with `read_first`, that file projected: the
    first file read maps OpenImageIO's module and its libraries, which `import vs11` does not)."""
    code = textwrap.dedent(
        """
        import resource, sys, warnings
        import vs11, vs11.irradiance
        if %r is not None:
            vs11.irradiance.project(%r, face_size=4)
        with open("/proc/self/statm") as f:
            used = int(f.read().split()[0]) * resource.getpagesize()
        limit = used + %d * 2**20
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
        """
        % (read_first, read_first, limit_mb)
    ) + textwrap.dedent(script)
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)


@pytest.mark.skipif(UNDER_ASAN, reason="ASan reserves terabytes of address space: RLIMIT_AS cannot be tested")
def test_batch_projects_a_lat_long_file_at_any_face_size_in_little_memory(tmp_path):
    # Before lat-long maps were projected in place, b_lat.pfm at face_size 4096 ran out of memory in
    # its resample to a cube (how this test reached batch's out-of-memory warning). Now it fits.
    small = tmp_path / "a_cross.pfm"  # a cube cross keeps its own face size
    write_pfm(small, np.full((12, 16, 3), 0.5))
    lat = tmp_path / "b_lat.pfm"
    write_pfm(lat, np.full((1, 2, 3), 0.5))
    result = run_limited(
        """
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            records = list(vs11.irradiance.iter_batch([%r, %r], face_size=4096, threads=1))
        print("records", len(records))
        print("warnings", [str(w.message) for w in caught])
        """
        % (str(small), str(lat)),
        200,
        read_first=str(lat),
    )
    assert result.returncode == 0, result.stderr
    assert "records 2" in result.stdout
    assert "out of memory" not in result.stdout


@pytest.mark.skipif(UNDER_ASAN, reason="ASan reserves terabytes of address space: RLIMIT_AS cannot be tested")
def test_project_out_of_memory_raises_memory_error_or_value_error():
    result = run_limited(
        """
        try:
            vs11.irradiance.project("sky", face_size=4096)
        except MemoryError as e:
            print("MemoryError", e)
        except ValueError as e:
            print("ValueError", e)
        """,
        200,
    )
    assert result.returncode == 0, result.stderr
    assert "out of memory" in result.stdout or "MemoryError" in result.stdout


def test_project_of_texels_beyond_float_range_raises_and_names_the_range():
    cube = np.full((6, 8, 8, 3), 3e38, dtype=np.float32)
    with pytest.raises(ValueError, match=r"beyond float range \(texels from 3e\+38 to 3e\+38\)"):
        vs11.irradiance.project(cube)


def test_batch_of_two_huge_neighbours_gives_finite_numbers(tmp_path):
    image = np.full((16, 32, 3), 0.5)
    image[5, 10] = image[5, 11] = 3e38
    path = tmp_path / "two.pfm"
    write_pfm(path, image)
    labels = vs11.irradiance.batch([str(path)], face_size=32, threads=1)
    assert len(labels) == 1
    assert np.all(np.isfinite(labels.coefficients)) and np.all(np.isfinite(labels.constants))


def test_a_square_file_needs_its_layout(tmp_path):
    path = tmp_path / "cube_px.pfm"
    write_pfm(path, np.full((16, 16, 3), 1.0))
    with pytest.raises(ValueError, match="cannot tell the layout of a square 16 x 16 image"):
        vs11.irradiance.project(str(path))
    assert vs11.irradiance.project(str(path), layout="angular", face_size=8).level >= 0
