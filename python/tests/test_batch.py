"""vs11.irradiance.batch (a dataset in arrays) and iter_batch (a generator of `irrmap batch`'s records as they
finish, stoppable by close()); every record reproduces itself from its own metadata."""
import hashlib
import json
import subprocess
import threading
import time
import types

import numpy as np
import pytest

import vs11
import vs11.irradiance


def write_pfm(path, image):
    """A little-endian RGB PFM (rows bottom to top, as the format stores them)."""
    height, width, _ = image.shape
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        f.write(np.ascontiguousarray(image[::-1], dtype="<f4").tobytes())


def lat_long_files(folder, count, height=8, seed=3):
    rng = np.random.default_rng(seed)
    paths = []
    for i in range(count):
        path = folder / ("env%03d.pfm" % i)
        write_pfm(path, rng.uniform(0.0, 2.0, size=(height, 2 * height, 3)))
        paths.append(str(path))
    return paths


def irrmap_batch_lines(irrmap_tool, inputs, out, threads, *flags):
    subprocess.run([str(irrmap_tool), "batch", *inputs, "-o", str(out), "--threads", str(threads),
                    "--face-size", "8", *flags], capture_output=True, check=False)
    return [json.loads(line) for line in out.read_text().splitlines() if line]


def test_iter_batch_yields_the_records_irrmap_batch_writes_at_any_thread_count(irrmap_tool, tmp_path):
    paths = lat_long_files(tmp_path, 6)
    (tmp_path / "broken.pfm").write_bytes(b"PF\n")
    inputs = paths + [str(tmp_path / "broken.pfm")]
    expected = irrmap_batch_lines(irrmap_tool, inputs, tmp_path / "cli.jsonl", 1)
    assert [r["input"] for r in expected] == sorted(paths)
    for threads in (1, 2, 3):
        records = vs11.irradiance.iter_batch(inputs, threads=threads, face_size=8)
        assert isinstance(records, types.GeneratorType)
        with pytest.warns(UserWarning, match="broken.pfm"):
            got = list(records)
        if threads == 1:
            assert got == expected  # one input at a time: the same records in the same order
        assert sorted(got, key=lambda r: r["input"]) == expected, "threads=%d" % threads


def test_batch_gives_arrays_in_input_order_with_a_table_of_metadata(irrmap_tool, tmp_path):
    paths = lat_long_files(tmp_path, 3)
    (tmp_path / "broken.pfm").write_bytes(b"PF\n")
    stack = np.random.default_rng(5).uniform(0.0, 1.0, size=(2, 8, 16, 3)).astype(np.float32)
    inputs = [paths[2], str(tmp_path / "broken.pfm"), stack[0], str(tmp_path / "env00[01].pfm"), paths[2], *stack]
    with pytest.warns(UserWarning, match="broken.pfm"):
        labels = vs11.irradiance.batch(inputs, threads=2, face_size=8, level=1)
    assert isinstance(labels, vs11.irradiance.Dataset) and len(labels) == 6
    assert labels.coefficients.shape == (6, 9, 3) and labels.coefficients.dtype == np.float64
    assert labels.constants.shape == (6, 7, 4) and labels.constants.dtype == np.float32
    # Rows follow the inputs; a pattern gives its matches sorted; a file named twice is one row.
    assert [row["input"] for row in labels.metadata] == [paths[2], "array[2]", paths[0], paths[1], "array[5]",
                                                         "array[6]"]
    assert [f["input"] for f in labels.failures] == [str(tmp_path / "broken.pfm")]
    assert {row["level_size"] for row in labels.metadata} == {4}
    for i, environment in enumerate([paths[2], stack[0], paths[0], paths[1], stack[0], stack[1]]):
        single = vs11.irradiance.project(environment, face_size=8, level=1)
        np.testing.assert_array_equal(labels.coefficients[i], single.coefficients)
        np.testing.assert_array_equal(labels.constants[i], single.constants)
    # The JSON Lines of irrmap batch stack into the same arrays.
    lines = irrmap_batch_lines(irrmap_tool, paths, tmp_path / "cli.jsonl", 2, "--level", "1")
    from_cli = vs11.irradiance.Dataset.from_records(sorted(lines, key=lambda r: r["input"]))
    np.testing.assert_array_equal(from_cli.coefficients, labels.coefficients[[2, 3, 0]])
    np.testing.assert_array_equal(from_cli.constants, labels.constants[[2, 3, 0]])


def test_a_record_reproduces_itself_from_its_own_metadata(tmp_path):
    paths = lat_long_files(tmp_path, 3)
    cube = tmp_path / "cube_{face}.pfm"
    for face in ("px", "nx", "py", "ny", "pz", "nz"):
        write_pfm(str(cube).replace("{face}", face), np.full((8, 8, 3), 0.5, np.float32))
    with pytest.warns(UserWarning, match="different resolutions"):  # each input at its own level
        labels = vs11.irradiance.batch(paths + [str(cube)], face_size=8, window="hanning", max_error=0.01)
    for i, row in enumerate(labels.metadata):
        assert row["schema_version"] == 2
        provenance, convention = row["provenance"], row["convention"]
        assert provenance["vs11_version"] == vs11.__version__
        assert convention["quantity"] == "radiance" and convention["frame"] == "direct3d_cube"
        assert convention["coefficient_order"][:3] == ["L00", "L1-1", "L10"]
        assert convention["window"] == "hanning"
        for file in provenance["files"]:
            data = open(file["path"], "rb").read()
            assert file["size_bytes"] == len(data)
            assert file["sha256"] == hashlib.sha256(data).hexdigest()
        again = vs11.irradiance.project(provenance["input"], **provenance["options"])
        np.testing.assert_array_equal(again.coefficients, labels.coefficients[i])  # bit for bit
        np.testing.assert_array_equal(again.constants, labels.constants[i])
        assert again.metadata == {k: row[k] for k in ("schema_version", "convention", "provenance")}
    kinds = [(row["provenance"]["input_kind"], row["convention"]["source_kind"]) for row in labels.metadata]
    assert kinds == [("latlong", "latlong")] * 3 + [("faces", "cube")]
    assert len(labels.metadata[3]["provenance"]["files"]) == 6


def test_level_sizes_that_differ_warn_and_one_level_labels_alike(tmp_path):
    flat, busy = tmp_path / "flat.pfm", tmp_path / "busy.pfm"
    write_pfm(flat, np.ones((16, 32, 3), np.float32))
    write_pfm(busy, np.random.default_rng(1).uniform(0.0, 8.0, size=(16, 32, 3)))
    with pytest.warns(UserWarning, match="different resolutions"):
        labels = vs11.irradiance.batch([str(flat), str(busy)], face_size=16)
    assert len({row["level_size"] for row in labels.metadata}) == 2
    with pytest.warns(UserWarning, match="level size"):
        list(vs11.irradiance.iter_batch([str(flat), str(busy)], face_size=16, threads=1))
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        labels = vs11.irradiance.batch([str(flat), str(busy)], face_size=16, level=2)
    assert [row["level_size"] for row in labels.metadata] == [4, 4]


def test_resume_refuses_an_output_of_another_schema_version(irrmap_tool, tmp_path):
    paths = lat_long_files(tmp_path, 2)
    out = tmp_path / "out.jsonl"
    irrmap_batch_lines(irrmap_tool, paths[:1], out, 1)
    for version in ('"schema_version":1,', '"schema_version":3,', ''):
        text = out.read_text().replace('"schema_version":2,', version)
        out.write_text(text)
        run = subprocess.run([str(irrmap_tool), "batch", *paths, "-o", str(out), "--face-size", "8", "--resume"],
                             capture_output=True, text=True)
        assert run.returncode == 1 and "out.jsonl:1:" in run.stderr, run.stderr
        assert "schema version %s" % (version[17] if version else "1") in run.stderr
        assert out.read_text() == text  # untouched
        out.write_text(text.replace(version, '"schema_version":2,') if version else text)
        if not version:
            break


def test_closing_the_generator_stops_the_work(tmp_path, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))  # where the run's scratch folder goes
    env = tmp_path / "env.pfm"
    write_pfm(env, np.ones((64, 128, 3), np.float32))
    links = []
    for i in range(200):  # 200 inputs (links to one file: the paths differ) on one thread
        links.append(tmp_path / ("link%03d.pfm" % i))
        links[-1].symlink_to(env)
    stream = vs11.irradiance._irradiance._BatchStream([str(p) for p in links], 1, "auto", 32, None, 0.005, "peak",
                                                      "order2", "none", 4.0)
    first = next(stream)
    assert first["input"] == str(links[0])
    stream.close()
    done = stream.finished
    assert done < 100, "close() let the run go on (%d of 200 inputs done)" % done
    time.sleep(0.2)
    assert stream.finished == done  # nothing runs after close() returned
    with pytest.raises(StopIteration):
        next(stream)
    assert not list(tmp_path.glob("vs11-batch-*")), "the scratch folder outlived the run"

    generator = vs11.irradiance.iter_batch([str(p) for p in links], threads=2, face_size=32)
    assert next(generator)["level"] >= 0
    generator.close()  # returns: no hang
    with pytest.raises(StopIteration):
        next(generator)
    unstarted = vs11.irradiance.iter_batch([str(p) for p in links], threads=2, face_size=32)
    del unstarted  # dropped before its first record: the stream's destructor stops the run
    assert [r["input"] for r in vs11.irradiance.iter_batch([str(env)], face_size=8)] == [str(env)]


def test_the_gil_is_released_while_the_generator_waits(tmp_path):
    # A cross of 512-texel faces: its mip and basis pyramids take a while (a lat-long map would not:
    # it is projected where it lies, in a few milliseconds).
    write_pfm(tmp_path / "big.pfm", np.ones((3 * 512, 4 * 512, 3), np.float32))
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.002)

    generator = vs11.irradiance.iter_batch([str(tmp_path / "big.pfm")], threads=1, face_size=128)
    ticker = threading.Thread(target=tick)
    ticker.start()
    try:
        start = time.perf_counter()
        next(generator)  # waits for the input's record, which takes a while
        end = time.perf_counter()
    finally:
        stop.set()
        ticker.join()
    during = [t for t in ticks if start < t < end]
    # Holding the GIL through the wait, next() would let the ticker run only at its few
    # interpreter switch points; released, the ticker runs all along.
    assert end - start > 0.05, "the input took too little time to tell (%.3f s)" % (end - start)
    assert len(during) >= max(5, 0.1 * (end - start) / 0.002), (len(during), end - start)


def test_errors_of_the_run_are_value_errors(tmp_path):
    with pytest.raises(ValueError, match="threads=-1"):
        vs11.irradiance.iter_batch(["x.hdr"], threads=-1)
    with pytest.raises(ValueError, match="matches no file"):
        vs11.irradiance.batch([str(tmp_path / "*.hdr")])
    with pytest.raises(ValueError, match="unknown layout"):
        next(vs11.irradiance.iter_batch([str(tmp_path / "a.hdr")], layout="sideways"))
    with pytest.raises(ValueError, match="unknown window"):
        vs11.irradiance.batch([str(tmp_path / "a.hdr")], window="square")
    # The messages name the Python argument, not irrmap's flag.
    for options, message in [({"max_error": 2.0}, r"^max_error=2 is out of range"),
                             ({"face_size": 3}, r"^face_size=3 must be a power of two"),
                             ({"level": -1}, r"^level=-1 is out of range")]:
        with pytest.raises(ValueError, match=message):
            next(vs11.irradiance.iter_batch([str(tmp_path / "a.hdr")], **options))
