"""vs11.irradiance.batch: a generator of `irrmap batch`'s records as they finish, stoppable by close()."""
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


def irrmap_batch_lines(irrmap_tool, inputs, out, threads):
    subprocess.run([str(irrmap_tool), "batch", *inputs, "-o", str(out), "--threads", str(threads),
                    "--face-size", "8"], capture_output=True, check=False)
    return [json.loads(line) for line in out.read_text().splitlines() if line]


def test_batch_is_a_generator_of_the_records_irrmap_batch_writes_at_any_thread_count(irrmap_tool, tmp_path):
    paths = lat_long_files(tmp_path, 6)
    (tmp_path / "broken.pfm").write_bytes(b"PF\n")
    inputs = paths + [str(tmp_path / "broken.pfm")]
    expected = irrmap_batch_lines(irrmap_tool, inputs, tmp_path / "cli.jsonl", 1)
    assert [r["input"] for r in expected] == sorted(paths)
    for threads in (1, 2, 3):
        records = vs11.irradiance.batch(inputs, threads=threads, face_size=8)
        assert isinstance(records, types.GeneratorType)
        with pytest.warns(UserWarning, match="broken.pfm"):
            got = list(records)
        if threads == 1:
            assert got == expected  # one input at a time: the same records in the same order
        assert sorted(got, key=lambda r: r["input"]) == expected, "threads=%d" % threads


def test_records_equal_single_projections(tmp_path):
    for record in vs11.irradiance.batch(lat_long_files(tmp_path, 2), threads=2, face_size=8):
        single = vs11.irradiance.project(record["input"], face_size=8, level=record["level"])
        np.testing.assert_array_equal(np.array(record["coefficients"]), single.coefficients)
        np.testing.assert_array_equal(np.array(list(record["constants"].values()), np.float32), single.constants)


def test_closing_the_generator_stops_the_work(tmp_path, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))  # where the run's scratch folder goes
    env = tmp_path / "env.pfm"
    write_pfm(env, np.ones((64, 128, 3), np.float32))
    links = []
    for i in range(200):  # 200 inputs (links to one file: the paths differ) on one thread
        links.append(tmp_path / ("link%03d.pfm" % i))
        links[-1].symlink_to(env)
    stream = vs11.irradiance._irradiance._BatchStream([str(p) for p in links], 1, "auto", 32, None, 0.005)
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

    generator = vs11.irradiance.batch([str(p) for p in links], threads=2, face_size=32)
    assert next(generator)["level"] >= 0
    generator.close()  # returns: no hang
    with pytest.raises(StopIteration):
        next(generator)
    unstarted = vs11.irradiance.batch([str(p) for p in links], threads=2, face_size=32)
    del unstarted  # dropped before its first record: the stream's destructor stops the run
    assert [r["input"] for r in vs11.irradiance.batch([str(env)], face_size=8)] == [str(env)]


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

    generator = vs11.irradiance.batch([str(tmp_path / "big.pfm")], threads=1, face_size=128)
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
        vs11.irradiance.batch(["x.hdr"], threads=-1)
    with pytest.raises(ValueError, match="matches no file"):
        next(vs11.irradiance.batch([str(tmp_path / "*.hdr")]))
    with pytest.raises(ValueError, match="unknown layout"):
        next(vs11.irradiance.batch([str(tmp_path / "a.hdr")], layout="sideways"))
    # The messages name the Python argument, not irrmap's flag.
    for options, message in [({"max_error": 2.0}, r"^max_error=2 is out of range"),
                             ({"face_size": 3}, r"^face_size=3 must be a power of two"),
                             ({"level": -1}, r"^level=-1 is out of range")]:
        with pytest.raises(ValueError, match=message):
            next(vs11.irradiance.batch([str(tmp_path / "a.hdr")], **options))
