"""vs11.dask.label_dataset on a LocalCluster of two worker processes: the records are iter_batch()'s, bit
for bit; a killed worker's tasks are done again with no record lost or written twice; resume.

ctest runs this file as its own test (python.dask): `python3 test_dask.py` exits 77 (skipped) where
Dask is not installed, and runs pytest on itself otherwise."""
import json
import os
import pathlib
import signal
import sys

import numpy as np
import pytest

if __name__ == "__main__":
    try:
        import dask.distributed  # noqa: F401
    except ImportError as missing:
        print("skipped: Dask is not installed (%s); .ci/setup installs python3-distributed" % missing)
        sys.exit(77)
    sys.exit(pytest.main([__file__, "-q", "-p", "no:cacheprovider"]))

distributed = pytest.importorskip("dask.distributed")
import cloudpickle  # noqa: E402  (Dask's own dependency)
import dask  # noqa: E402
import dask.bag  # noqa: E402

import vs11.dask  # noqa: E402
import vs11.irradiance  # noqa: E402
from test_batch import lat_long_files, write_pfm  # noqa: E402

FACE_SIZE = 8

# The workers cannot import this test file: functions of it that run there travel by value.
cloudpickle.register_pickle_by_value(sys.modules[__name__])


@pytest.fixture(scope="module")
def client():
    # The worker processes import vs11 from where this process does.
    os.environ["PYTHONPATH"] = os.pathsep.join([str(pathlib.Path(vs11.__file__).parents[1])] + sys.path[1:])
    # Fewer deaths before a task is given up (KilledWorker) than Dask's 3: the poisoned input's test
    # is quicker. The kill-once tests need at least one.
    dask.config.set({"distributed.scheduler.allowed-failures": 2})
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                                  silence_logs=40) as cluster, distributed.Client(cluster) as connected:
        yield connected


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    """Eight lat-long maps, four horizontal crosses (face size 8) and a file that is no image."""
    folder = tmp_path_factory.mktemp("dataset")
    paths = lat_long_files(folder, 8, height=FACE_SIZE)
    rng = np.random.default_rng(7)
    for i in range(4):
        cross = np.zeros((3 * FACE_SIZE, 4 * FACE_SIZE, 3), np.float32)
        cross[FACE_SIZE:2 * FACE_SIZE, :] = rng.uniform(0.0, 3.0, size=(FACE_SIZE, 4 * FACE_SIZE, 3))
        for column in (1,):
            cross[:FACE_SIZE, column * FACE_SIZE:(column + 1) * FACE_SIZE] = rng.uniform(0.0, 1.0, (FACE_SIZE, FACE_SIZE, 3))
            cross[2 * FACE_SIZE:, column * FACE_SIZE:(column + 1) * FACE_SIZE] = rng.uniform(0.0, 1.0, (FACE_SIZE, FACE_SIZE, 3))
        path = folder / ("cross%d.pfm" % i)
        write_pfm(path, cross)
        paths.append(str(path))
    broken = folder / "broken.pfm"
    broken.write_bytes(b"PF\n3 3\n")
    return sorted(paths), str(broken)


@pytest.fixture(scope="module")
def expected(dataset):
    """iter_batch()'s records in this process, by input key."""
    paths, broken = dataset
    with pytest.warns(UserWarning, match="broken.pfm"):
        records = list(vs11.irradiance.iter_batch(paths + [broken], threads=1, face_size=FACE_SIZE))
    assert len(records) == len(paths)
    return {record["path"]: record for record in records}


def read_parts(folder):
    """Every record of the parts, as (part name, record); each part's records sorted by path."""
    found = []
    for part in sorted(pathlib.Path(folder).glob("part-*.jsonl")):
        records = [json.loads(line) for line in part.read_text().splitlines()]
        assert [r["path"] for r in records] == sorted(r["path"] for r in records), part.name
        found.extend((part.name, record) for record in records)
    return found


def assert_every_record_once_bit_for_bit(folder, expected):
    found = read_parts(folder)
    keys = [record["path"] for _, record in found]
    assert len(keys) == len(set(keys)), "duplicated: %s" % sorted({k for k in keys if keys.count(k) > 1})
    assert set(keys) == set(expected), "missing: %s" % sorted(set(expected) - set(keys))
    for _, record in found:
        # repr() writes every float with all its bits (and -0.0 as such): equal text, equal numbers.
        assert repr(record) == repr(expected[record["path"]])
    assert not [p.name for p in pathlib.Path(folder).iterdir() if p.name.startswith(".")], "a temporary is left"


def test_a_labelled_dataset_holds_batch_records_bit_for_bit_and_resumes(client, dataset, expected, tmp_path, capsys):
    paths, broken = dataset
    inputs = [os.path.join(os.path.dirname(broken), "*.pfm")]
    calls = []
    summary = vs11.dask.label_dataset(client, inputs, tmp_path, files_per_task=3, face_size=FACE_SIZE,
                                      progress=lambda done, total: calls.append((done, total)))
    assert calls == [(i, 5) for i in range(1, 6)]  # 13 inputs in chunks of 3: five tasks
    assert (summary.inputs, summary.written, summary.already_done) == (13, 12, 0)
    assert len(summary.parts) == 5
    assert [f["input"] for f in summary.failed] == [broken]
    assert summary.failed[0]["error"].startswith("cannot read")  # iter_batch()'s reason
    assert_every_record_once_bit_for_bit(tmp_path, expected)
    failed_files = sorted(tmp_path.glob("failed-*.jsonl"))
    assert [json.loads(line)["input"] for f in failed_files for line in f.read_text().splitlines()] == [broken]

    # Again: nothing is labelled twice, the failed input is tried again and its failure file replaced.
    again = vs11.dask.label_dataset(client, inputs, tmp_path, files_per_task=3, face_size=FACE_SIZE, progress=True)
    assert (again.inputs, again.written, again.already_done) == (13, 0, 12)
    assert [f["input"] for f in again.failed] == [broken]
    assert len(list(tmp_path.glob("failed-*.jsonl"))) == 1 and not failed_files[0].exists()
    assert_every_record_once_bit_for_bit(tmp_path, expected)
    assert "100%" in capsys.readouterr().out  # dask.distributed.progress's text bar

    # A lost part (deleted) is made again, only its inputs.
    lost = sorted(tmp_path.glob("part-*.jsonl"))[1]
    lost_count = len(lost.read_text().splitlines())
    lost.unlink()
    third = vs11.dask.label_dataset(client, inputs, tmp_path, files_per_task=3, face_size=FACE_SIZE, progress=False)
    assert (third.written, third.already_done) == (lost_count, 12 - lost_count)
    assert_every_record_once_bit_for_bit(tmp_path, expected)

    with pytest.raises(FileExistsError, match="resume=True"):
        vs11.dask.label_dataset(client, inputs, tmp_path, resume=False, face_size=FACE_SIZE, progress=False)


def kill_own_worker_once(path, marker, victim):
    """Kills the worker process it runs in (SIGKILL: no clean-up), the first time it sees `victim`."""
    if path == victim and not os.path.exists(marker):
        pathlib.Path(marker).write_text(str(os.getpid()))
        os.kill(os.getpid(), signal.SIGKILL)
    return path


def die_after_writing_the_part_of(victim, marker):
    """Run on every worker: its process is killed right after it wrote the part holding `victim`'s
    record, before the task returns, once (the replacement worker has no such hook)."""
    import vs11.dask as module
    write = module._write_atomically

    def write_then_die(path, records):
        write(path, records)
        if any(record.get("input") == victim for record in records) and not os.path.exists(marker):
            kill_own_worker_once(victim, marker, victim)

    module._write_atomically = write_then_die


def test_a_task_whose_worker_died_after_writing_its_part_is_done_again_without_duplicates(
        client, dataset, expected, tmp_path):
    paths, broken = dataset
    marker = str(tmp_path / "killed.pid")
    client.run(die_after_writing_the_part_of, paths[6], marker)
    summary = vs11.dask.label_dataset(client, paths + [broken], tmp_path / "labels", files_per_task=2,
                                      face_size=FACE_SIZE, progress=False)
    assert os.path.exists(marker), "no worker was killed"
    assert int(pathlib.Path(marker).read_text()) not in client.run(os.getpid).values(), "the killed worker is back"
    assert (summary.inputs, summary.written, [f["input"] for f in summary.failed]) == (13, 12, [broken])
    assert_every_record_once_bit_for_bit(tmp_path / "labels", expected)
    assert len(summary.parts) == 7  # 13 inputs, two per task


def test_a_killed_workers_tasks_are_done_again_with_no_record_missing_or_twice(client, dataset, expected, tmp_path):
    paths, broken = dataset
    marker = str(tmp_path / "killed.pid")
    out = tmp_path / "labels"
    # Twelve paths in six partitions: the seventh path is met when about half of the tasks are done,
    # and the dead worker's finished results (held in its memory) are lost with it too.
    bag = dask.bag.from_sequence(paths + [broken], npartitions=6).map(kill_own_worker_once, marker, paths[6])
    summary = vs11.dask.label_dataset(client, bag, out, face_size=FACE_SIZE, progress=False)
    assert os.path.exists(marker), "no worker was killed"
    assert int(pathlib.Path(marker).read_text()) not in client.run(os.getpid).values(), "the killed worker is back"
    assert [f["input"] for f in summary.failed] == [broken]
    assert (summary.inputs, summary.written) == (13, 12)
    assert_every_record_once_bit_for_bit(out, expected)

    # Resuming from a bag: its inputs already labelled are skipped on the workers.
    again = vs11.dask.label_dataset(client, dask.bag.from_sequence(paths + [broken], npartitions=4), out,
                                    face_size=FACE_SIZE, progress=False)
    assert (again.inputs, again.written, again.already_done) == (13, 0, 12)
    assert_every_record_once_bit_for_bit(out, expected)


def kill_own_worker_always(path, victim):
    if path == victim:
        os.kill(os.getpid(), signal.SIGKILL)
    return path


def test_a_partition_that_kills_every_worker_is_recorded_as_failed_and_the_others_are_written(
        client, dataset, expected, tmp_path):
    paths, _ = dataset
    bag = dask.bag.from_sequence(paths, npartitions=4).map(kill_own_worker_always, paths[0])
    summary = vs11.dask.label_dataset(client, bag, tmp_path, face_size=FACE_SIZE, progress=False)
    # Partition 0 kills every worker that runs it. A dying worker takes the tasks queued on it
    # along, which Dask counts against them too, so another partition may be given up as well.
    failed = [f["input"] for f in summary.failed]
    assert "<partition 0 of the bag>" in failed
    assert all("KilledWorker" in f["error"] and f["path"] == "" for f in summary.failed)
    assert summary.written == 12 - 3 * len(failed)
    failed_file = tmp_path / "failed-00000-task.jsonl"
    assert json.loads(failed_file.read_text())["error"] == summary.failed[0]["error"]
    records = read_parts(tmp_path)
    assert len(records) == summary.written and paths[0] not in [r["input"] for _, r in records]
    for _, record in records:
        assert repr(record) == repr(expected[record["path"]])

    # Resumed without the poison: only the lost partition runs, and its failure file goes.
    again = vs11.dask.label_dataset(client, dask.bag.from_sequence(paths, npartitions=4), tmp_path,
                                    face_size=FACE_SIZE, progress=False)
    assert (again.written, again.already_done, again.failed) == (12 - summary.written, summary.written, [])
    assert not list(tmp_path.glob("failed-*.jsonl"))
    assert_every_record_once_bit_for_bit(tmp_path, expected)


def test_the_stub_matches_the_module():
    from test_stubs import pybind_arguments, stub_functions
    checked = 0
    for name, function, stub_names in stub_functions("dask.pyi", vs11.dask):
        assert pybind_arguments(function) == stub_names, name
        assert len(function.__doc__.strip()) > 20, "%s has no docstring" % name
        checked += 1
    assert checked == 4
