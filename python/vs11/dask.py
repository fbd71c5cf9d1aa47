"""Labelling a dataset on a Dask `distributed` cluster: vs11.irradiance.iter_batch() over chunks of files.

    from dask.distributed import Client, LocalCluster
    import vs11.dask
    with LocalCluster(n_workers=8, threads_per_worker=1) as cluster, Client(cluster) as client:
        summary = vs11.dask.label_dataset(client, ["panoramas/*.exr"], "labels/", face_size=128, level=2)

Each task labels one chunk of files on a worker and writes its records into OUTPUT_DIR as one part,
part-NNNNN-HASH.jsonl (records sorted by "path"), atomically: a part is there complete or not at all.
The inputs of a chunk that fail are written to failed-NNNNN-HASH.jsonl ({"input", "path", "error"})
and the job goes on. Running again with resume=True (the default) skips every input whose record is
already in a part, so an interrupted run (a lost worker, a stopped client) is finished by running it
again; failed inputs are tried again. `irrmap batch-merge --parts 'OUTPUT_DIR/part-*.jsonl' INPUT...`
checks that every input is there exactly once and writes one sorted file.

This module needs Dask (Debian's python3-dask and python3-distributed); `import vs11` does not.
"""
import dataclasses
import glob
import hashlib
import json
import os
import re
import tempfile
import time
import warnings
from typing import Any, Callable, Iterable, Optional, Union

from dask import bag as _bag
from dask import delayed
from dask import distributed as _distributed

from . import irradiance as _irradiance

_DEFAULTS = _irradiance.DEFAULTS

PART_PATTERN = re.compile(r"^part-(\d+)-[0-9a-f]+\.jsonl$")
FAILED_PATTERN = re.compile(r"^failed-(\d+)-(?:[0-9a-f]+|task)\.jsonl$")


@dataclasses.dataclass
class LabelSummary:
    """What label_dataset() did: counts of inputs, the parts it wrote and the inputs that failed."""

    inputs: int = 0  # distinct inputs given
    already_done: int = 0  # skipped: their records were in OUTPUT_DIR already (resume)
    written: int = 0  # records written by this run
    failed: list[dict[str, str]] = dataclasses.field(default_factory=list)  # {"input", "path", "error"}
    parts: list[str] = dataclasses.field(default_factory=list)  # the part files this run wrote
    failed_files: list[str] = dataclasses.field(default_factory=list)  # the failed-*.jsonl it wrote


def input_key(path: str) -> str:
    """An input's identity, its record's "path", as irrmap batch computes it: the canonical path of
    its folder (absolute, links resolved) and its own name."""
    absolute = os.path.abspath(path)
    return os.path.join(os.path.realpath(os.path.dirname(absolute)), os.path.basename(absolute))


def expand_inputs(paths: Iterable[str]) -> list[str]:
    """Paths and glob patterns expanded, de-duplicated by input_key() and sorted, as irrmap batch does
    (a pattern that matches nothing is a ValueError; a missing plain path is that input's failure)."""
    expanded = []
    for path in paths:
        path = os.fspath(path)
        if any(c in path for c in "*?["):
            matches = glob.glob(path)
            if not matches:
                raise ValueError("pattern '%s' matches no file" % path)
            expanded.extend(matches)
        else:
            expanded.append(path)
    seen = set()
    distinct = []
    for path in sorted(expanded):
        key = input_key(path)
        if key not in seen:
            seen.add(key)
            distinct.append(path)
    return distinct


def completed_keys(output_dir: str) -> set[str]:
    """The "path" of every record in OUTPUT_DIR's parts (every part is complete: they are written
    atomically). A line that is not a record is a ValueError naming the part and line."""
    keys = set()
    for name in sorted(os.listdir(output_dir)):
        if not PART_PATTERN.match(name):
            continue
        part = os.path.join(output_dir, name)
        with open(part, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                try:
                    keys.add(_record_key(json.loads(line)))
                except (ValueError, KeyError, TypeError) as error:
                    raise ValueError("%s:%d: not a record of vs11 (%s)" % (part, number, error)) from None
    return keys


def label_dataset(
    client: Any,
    paths: Union[Iterable[str], Any],
    output_dir: Union[str, os.PathLike[str]],
    files_per_task: int = 16,
    resume: bool = True,
    progress: Union[bool, Callable[[int, int], None]] = True,
    threads: int = 1,
    layout: str = _DEFAULTS["layout"],
    face_size: int = _DEFAULTS["face_size"],
    level: Optional[int] = None,
    max_error: float = _DEFAULTS["max_error"],
    error_metric: str = _DEFAULTS["error_metric"],
) -> LabelSummary:
    """Labels every input on the cluster `client` is connected to, one part file per task, and
    returns a LabelSummary once every task is done.

    paths: files and glob patterns (expanded on the client, as expand_inputs()), split into chunks
      of files_per_task consecutive inputs, one task each; or a dask.bag.Bag of paths, one task per
      partition (its elements are paths, not patterns).
    output_dir: created if needed. Without resume, one that already holds parts is a
      FileExistsError; with it, inputs whose records are in its parts are skipped.
    progress: True shows dask.distributed.progress (a text bar, or a widget in a notebook); a
      callable is called as progress(done_tasks, total_tasks) as each task finishes; False: nothing.
    threads: inputs each task projects at once (1 suits one worker thread per core).
    layout, face_size, level, max_error, error_metric: as for vs11.irradiance.iter_batch(); the records
      are the ones iter_batch() yields, whichever worker made them.

    An input that cannot be read or used is recorded with its error (failed-*.jsonl, summary.failed)
    and the others go on; so is every input of a task Dask gave up on (KilledWorker: its workers
    died running it more than allowed-failures times), or for a bag the partition. A task whose worker dies is run again elsewhere and
    writes the same part, replacing it, so no record is lost or written twice.
    """
    output_dir = os.fspath(output_dir)
    os.makedirs(output_dir, exist_ok=True)
    done = completed_keys(output_dir)
    if done and not resume:
        raise FileExistsError("%s holds parts of an earlier run: pass resume=True to finish it, or use "
                              "an empty folder" % output_dir)
    options = dict(threads=threads, layout=layout, face_size=face_size, level=level, max_error=max_error,
                   error_metric=error_metric)
    summary = LabelSummary()
    first = _next_part_number(output_dir)
    if isinstance(paths, _bag.Bag):
        scattered = client.scatter(done, broadcast=True) if done else None
        label = delayed(_label_chunk, pure=False)
        futures = client.compute([label(chunk, first + i, output_dir, scattered, options)
                                  for i, chunk in enumerate(paths.to_delayed(optimize_graph=True))])
        inputs_of = {f.key: (first + i, None) for i, f in enumerate(futures)}
    else:
        inputs = expand_inputs(paths)
        summary.inputs = len(inputs)
        todo = [path for path in inputs if input_key(path) not in done]
        summary.already_done = len(inputs) - len(todo)
        size = max(1, int(files_per_task))
        chunks = [todo[start:start + size] for start in range(0, len(todo), size)]
        # pure=False: a key of its own for every task of every run.
        futures = [client.submit(_label_chunk, chunk, first + i, output_dir, None, options, pure=False)
                   for i, chunk in enumerate(chunks)]
        inputs_of = {f.key: (first + i, chunk) for i, (f, chunk) in enumerate(zip(futures, chunks))}
    _report_progress(futures, progress)
    for future in futures:
        result = _result(future, *inputs_of[future.key], output_dir)
        summary.written += result["written"]
        summary.already_done += result["already_done"]
        if isinstance(paths, _bag.Bag):
            summary.inputs += result["inputs"]
        summary.failed.extend(result["failed"])
        summary.parts.extend(result["parts"])
        summary.failed_files.extend(result["failed_files"])
    tried = {failure["path"] for failure in summary.failed}
    _remove_stale_failures(output_dir, tried, summary.failed_files)
    summary.failed.sort(key=lambda failure: failure["path"])
    return summary


def _report_progress(futures: list[Any], progress: Union[bool, Callable[[int, int], None]]) -> None:
    if progress is True and futures:
        _distributed.progress(futures)  # blocks until every task is done (a widget in a notebook)
        # The scheduler's side of the bar sends every 100 ms until a send finds the bar gone; a
        # cluster closed before that logs the cancelled sender as an error (distributed 2022.12).
        time.sleep(0.3)
    elif callable(progress):
        total = len(futures)
        for done, _ in enumerate(_distributed.as_completed(futures), 1):
            progress(done, total)


def _result(future: Any, number: int, chunk: Optional[list[str]], output_dir: str) -> dict[str, Any]:
    """A task's result. A task Dask gave up on (KilledWorker: workers died running it
    allowed_failures times; or its part could not be written) fails every input of its chunk, or,
    for a bag (whose partition may be what kills the worker: not computed again here), the
    partition; the failures are written to a failure file here, on the client."""
    try:
        return future.result()
    except Exception as error:
        reason = "its task failed: %s: %s" % (type(error).__name__, error)
        if chunk is None:
            failed = [{"input": "<partition %d of the bag>" % number, "path": "", "error": reason}]
        else:
            failed = [{"input": p, "path": input_key(p), "error": reason} for p in chunk]
        failed_file = os.path.join(output_dir, "failed-%05d-task.jsonl" % number)
        _write_atomically(failed_file, failed)
        return {"written": 0, "already_done": 0, "inputs": len(chunk or []), "parts": [],
                "failed_files": [failed_file], "failed": failed}


def _label_chunk(paths: Iterable[str], number: int, output_dir: str, done: Optional[set[str]],
                 options: dict[str, Any]) -> dict[str, Any]:
    """On a worker: labels `paths` (less those in `done`) and writes their part and failure file."""
    paths = list(paths)
    todo = [p for p in paths if done is None or input_key(p) not in done]
    result = {"written": 0, "already_done": len(paths) - len(todo), "inputs": len(paths), "parts": [],
              "failed_files": [], "failed": []}
    if not todo:
        return result
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        records = list(_irradiance.iter_batch(todo, **options))
    failed = _failures(todo, records, caught)
    # The name holds the chunk's inputs: a task run again (its worker died) writes the same names,
    # replacing the first attempt's part; a later run's part for other inputs gets a name of its own.
    digest = hashlib.sha1("\n".join(input_key(p) for p in todo).encode()).hexdigest()[:16]
    stem = "%05d-%s" % (number, digest)
    if failed:
        failed_file = os.path.join(output_dir, "failed-%s.jsonl" % stem)
        _write_atomically(failed_file, failed)
        result["failed_files"].append(failed_file)
    if records:
        records.sort(key=_record_key)
        part = os.path.join(output_dir, "part-%s.jsonl" % stem)
        _write_atomically(part, records)
        result["parts"].append(part)
    result["written"] = len(records)
    result["failed"] = failed
    return result


def _failures(todo: list[str], records: list[dict[str, Any]], caught: list[Any]) -> list[dict[str, str]]:
    """Every input of `todo` without a record, with the reason iter_batch() warned of."""
    recorded = {record["input"] for record in records}
    reasons = {}
    for warning in caught:
        text = str(warning.message)
        for path in todo:
            if text.startswith(path + ": "):
                reasons[path] = text[len(path) + 2:]
    return [{"input": p, "path": input_key(p), "error": reasons.get(p, "no record came back")}
            for p in todo if p not in recorded]


def _record_key(record: dict[str, Any]) -> str:
    key = record.get("path") or input_key(record["input"])
    if not isinstance(key, str) or "coefficients" not in record:
        raise ValueError("no input path or no coefficients")
    return key


def _write_atomically(path: str, records: list[dict[str, Any]]) -> None:
    """JSON Lines into a temporary beside `path`, flushed to disk, then renamed over it."""
    folder, name = os.path.split(path)
    fd, temporary = tempfile.mkstemp(dir=folder, prefix="." + name + ".tmp-")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            for record in records:
                f.write(json.dumps(record, separators=(",", ":")) + "\n")
            f.flush()
            os.fsync(f.fileno())
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise


def _next_part_number(output_dir: str) -> int:
    numbers = [int(m.group(1)) for m in map(PART_PATTERN.match, os.listdir(output_dir)) if m]
    numbers += [int(m.group(1)) for m in map(FAILED_PATTERN.match, os.listdir(output_dir)) if m]
    return max(numbers) + 1 if numbers else 0


def _remove_stale_failures(output_dir: str, failed_now: set[str], written_now: list[str]) -> None:
    """Failure files of earlier runs whose inputs this run has either labelled or seen fail again (in
    a failure file of its own): every input without a record was tried again."""
    done = completed_keys(output_dir)
    kept = {os.path.basename(path) for path in written_now}
    for name in os.listdir(output_dir):
        if not FAILED_PATTERN.match(name) or name in kept:
            continue
        path = os.path.join(output_dir, name)
        with open(path, encoding="utf-8") as f:
            failures = [json.loads(line) for line in f if line.strip()]
        # A bag's partition has no path (""): every partition runs again on resume.
        if all(not failure["path"] or failure["path"] in done or failure["path"] in failed_now for failure in failures):
            os.unlink(path)


__all__ = ["LabelSummary", "label_dataset", "expand_inputs", "input_key", "completed_keys"]
