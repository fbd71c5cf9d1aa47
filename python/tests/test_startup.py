"""`import vs11` loads OpenImageIO (through the OpenImageIO module) only when an image file is read."""
import os
import struct
import subprocess
import sys

import vs11


def _maps_after(code, tmp_path):
    """Runs `code` in a fresh interpreter that imports vs11; its shared objects from /proc/self/maps."""
    script = ("import vs11\n" + code + "\n"
              "print('\\n'.join(sorted({l.split()[-1] for l in open('/proc/self/maps') if '.so' in l})))\n")
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(vs11.__file__)))
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env,
                         cwd=tmp_path, check=True)
    return run.stdout


def test_import_and_a_built_in_environment_load_no_openimageio(tmp_path):
    maps = _maps_after("vs11.irradiance.project('sky', face_size=16)", tmp_path)
    assert "_vs11" in maps  # the extension itself is listed
    assert "libOpenImageIO" not in maps
    assert "libvs11_image_io" not in maps


def test_reading_an_image_file_loads_the_module_and_openimageio(tmp_path):
    # A 4:3 cross of 4 x 4 faces as PFM, which OpenImageIO reads.
    with open(tmp_path / "cross.pfm", "wb") as f:
        f.write(b"PF\n16 12\n-1.0\n" + struct.pack("<576f", *([0.5] * 576)))
    maps = _maps_after("vs11.irradiance.project('cross.pfm')", tmp_path)
    assert "libvs11_image_io.so" in maps
    assert "libOpenImageIO" in maps
