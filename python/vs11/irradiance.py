"""Environments to spherical-harmonic irradiance: project, irradiance_map, batch and iter_batch (irrmap's library).

project() labels one environment; batch() labels a dataset (arrays of shape (N, 9, 3) and (N, 7, 4)
with a table of per-input metadata); iter_batch() streams the same records as they finish, for sets
too large to hold. All three take the same options and give the same numbers for the same input:
every record lists the options it was made with (metadata['provenance']['options']), and project()
with those options reproduces it bit for bit.
"""
import hashlib
import os
import warnings
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Generator, Iterable, Optional

import numpy as np

from ._vs11 import irradiance as _irradiance

Projection = _irradiance.Projection
irradiance_map = _irradiance.irradiance_map
builtin_environments = _irradiance.builtin_environments
# The names irrmap's --layout, --order, --window and --error-metric accept, and its defaults: the
# module's own, read from its tables instead of repeated here.
LAYOUTS = _irradiance.LAYOUTS
ORDERS = _irradiance.ORDERS
WINDOWS = _irradiance.WINDOWS
ERROR_METRICS = _irradiance.ERROR_METRICS
DEFAULTS = _irradiance.DEFAULTS
_DEFAULTS = DEFAULTS

CONSTANT_NAMES = ("cAr", "cAg", "cAb", "cBr", "cBg", "cBb", "cC")
_ARRAY_FIELDS = ("coefficients", "constants")


def project(
    environment: Any,
    layout: str = _DEFAULTS["layout"],
    face_size: int = _DEFAULTS["face_size"],
    level: Optional[int] = None,
    max_error: float = _DEFAULTS["max_error"],
    order: str = _DEFAULTS["order"],
    window: str = _DEFAULTS["window"],
    error_metric: str = _DEFAULTS["error_metric"],
    window_width: float = _DEFAULTS["window_width"],
) -> Projection:
    result = _irradiance.project(environment, layout, face_size, level, max_error, order, window, error_metric,
                                 window_width)
    if isinstance(environment, np.ndarray):
        result.metadata["provenance"]["array"] = _array_identity(environment)
    return result


project.__doc__ = _irradiance.project.__doc__.split("\n", 1)[1].lstrip() + (
    "\n\nresult.metadata says what the numbers are (convention) and where they came from (provenance),\n"
    "as every batch record does.")


class Dataset:
    """A labelled dataset: row i of coefficients and constants belongs to metadata[i].

    coefficients: (N, 9, 3) float64, L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22 per channel.
    constants: (N, 7, 4) float32, cAr cAg cAb cBr cBg cBb cC (Table 1) per input.
    metadata: one dict per row, the record without its numbers: input, path, schema_version,
      face_size, layout, level, level_size, estimated_error, error_metric, order, convention,
      provenance (files with size and SHA-256, vs11's version, the options).
    failures: [{'input', 'reason'}] of the inputs that gave no row.
    """

    def __init__(self, coefficients: np.ndarray, constants: np.ndarray, metadata: list, failures: list):
        self.coefficients = coefficients
        self.constants = constants
        self.metadata = metadata
        self.failures = failures

    @classmethod
    def from_records(cls, records: Iterable[dict], failures: Iterable[dict] = ()) -> "Dataset":
        """Stacks records (iter_batch's, or the JSON lines of `irrmap batch`) in the order given.
        Warns (UserWarning) when the rows come from different resolutions (level_size)."""
        records = list(records)
        count = len(records)
        coefficients = np.array([r["coefficients"] for r in records], dtype=np.float64).reshape(count, 9, 3)
        constants = np.array([[r["constants"][name] for name in CONSTANT_NAMES] for r in records],
                             dtype=np.float32).reshape(count, 7, 4)
        metadata = [{k: v for k, v in r.items() if k not in _ARRAY_FIELDS} for r in records]
        _warn_if_resolutions_vary(metadata, stacklevel=3)
        return cls(coefficients, constants, metadata, list(failures))

    def __len__(self) -> int:
        return len(self.metadata)

    def __repr__(self) -> str:
        return "<vs11.irradiance.Dataset of %d inputs, %d failed>" % (len(self), len(self.failures))


def batch(
    inputs: Iterable[Any],
    threads: int = 0,
    layout: str = _DEFAULTS["layout"],
    face_size: int = _DEFAULTS["face_size"],
    level: Optional[int] = None,
    max_error: float = _DEFAULTS["max_error"],
    order: str = _DEFAULTS["batch_order"],
    window: str = _DEFAULTS["window"],
    error_metric: str = _DEFAULTS["error_metric"],
    window_width: float = _DEFAULTS["window_width"],
) -> Dataset:
    """Labels a dataset: every input projected as project() does, on `threads` threads; a Dataset.

    inputs: paths, glob patterns ('envs/*.exr', expanded and sorted as irrmap batch does) and NumPy
      arrays as project() takes them (a stacked (N, H, 2H, 3) array is N lat-long maps); rows
      follow this order, an input named twice (however spelt) once.
    threads: inputs projected at once (0: every core); the numbers do not depend on it.
    layout, face_size, level, max_error, order, window, error_metric, window_width: as for
      project(). order defaults to 'order2' here: the nine coefficients are the label, and 'auto'
      may choose a cheaper program and so a coarser level.

    One resolution for a whole dataset: pass level=K (with face_size=F, which sets the faces of
    every lat-long and angular input): every input's coefficients then come from K. By default
    each input's level is the coarsest within max_error, which may differ between inputs; a
    UserWarning then says how the level sizes are spread (a level that fits every input can only be
    chosen after all of them are projected, which a streaming or resumed run cannot do).

    An input that cannot be used is a UserWarning naming it and why, and an entry of .failures;
    the others go on. Bad options and a pattern that matches nothing raise ValueError.

    Example:
      labels = vs11.irradiance.batch(['laval/*.exr'], level=2, face_size=256)
      labels.coefficients.shape  # (N, 9, 3)
    """
    failures: list = []
    rows = _rows(inputs)
    _check_threads(threads)
    options = _options(layout, face_size, level, max_error, order, window, error_metric, window_width)
    by_key = dict(_run(_start(rows, threads, options), rows, threads, options, failures))
    return Dataset.from_records([by_key[key] for key, _ in rows if key in by_key], failures)


def iter_batch(
    inputs: Iterable[Any],
    threads: int = 0,
    layout: str = _DEFAULTS["layout"],
    face_size: int = _DEFAULTS["face_size"],
    level: Optional[int] = None,
    max_error: float = _DEFAULTS["max_error"],
    order: str = _DEFAULTS["batch_order"],
    window: str = _DEFAULTS["window"],
    error_metric: str = _DEFAULTS["error_metric"],
    window_width: float = _DEFAULTS["window_width"],
) -> Generator[dict[str, Any], None, None]:
    """batch() as a stream: yields each input's record as it finishes (files first, in the order they
    finish, then arrays), holding nothing but the records not yet taken. Arguments as batch().

    A record is a dict as `irrmap batch` writes it (JSON-ready: lists, not arrays): input, path,
    schema_version, face_size, layout, level, level_size, estimated_error, error_metric, order,
    coefficients (9 x [r, g, b]), constants ({'cAr': [x, y, z, w], ...}), convention, provenance.
    Dataset.from_records() stacks records into arrays. The files run on threads of their own with
    the GIL released; closing the generator (close(), garbage collection) stops them: no input starts
    after it. An unusable input is a UserWarning; a level size other than the first record's warns
    once. Bad options raise ValueError from the first next(); a pattern that matches nothing and
    threads < 0 at the call.
    """
    rows = _rows(inputs)
    _check_threads(threads)
    options = _options(layout, face_size, level, max_error, order, window, error_metric, window_width)
    return _warning_once_sizes_differ(_run(_start(rows, threads, options), rows, threads, options, []))


def _warning_once_sizes_differ(records: Generator[tuple, None, None]) -> Generator[dict[str, Any], None, None]:
    first_size = None
    try:
        for _, record in records:
            if first_size is None:
                first_size = record["level_size"]
            elif first_size != -1 and record["level_size"] != first_size:
                warnings.warn("%s: coefficients from level size %d, the first record's from %d: pass level= for "
                              "one resolution" % (record["input"], record["level_size"], first_size), UserWarning, 2)
                first_size = -1
            yield record
    finally:
        records.close()


def _check_threads(threads: int) -> None:
    if threads < 0:
        raise ValueError("threads=%d must be >= 0 (0: every core)" % threads)


def _options(layout, face_size, level, max_error, order, window, error_metric, window_width) -> dict:
    return dict(layout=layout, face_size=face_size, level=level, max_error=max_error, order=order, window=window,
                error_metric=error_metric, window_width=window_width)


def _rows(inputs: Iterable[Any]) -> list:
    """[(key, what)]: a file's key is its record's 'path', an array's ('array', i)."""
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    rows, seen = [], set()
    for index, item in enumerate(inputs):
        if isinstance(item, np.ndarray):
            rows.append((("array", index), item))
            continue
        for path in _irradiance._expand_inputs([os.fspath(item)]):
            key = _irradiance._input_key(path)
            if key not in seen:
                seen.add(key)
                rows.append((key, path))
    return rows


def _start(rows: list, threads: int, options: dict) -> Any:
    """The files' run, started (on threads of its own), or None when there are no files."""
    paths = [what for key, what in rows if not isinstance(key, tuple)]
    if not paths:
        return None
    return _irradiance._BatchStream(paths, threads, options["layout"], options["face_size"], options["level"],
                                    options["max_error"], options["error_metric"], options["order"],
                                    options["window"], options["window_width"])


def _run(stream: Any, rows: list, threads: int, options: dict, failures: list) -> Generator[tuple, None, None]:
    """(key, record) of every row that worked, files (`stream`) first as they finish; failures appended."""
    if stream is not None:
        try:
            for record in stream:
                yield record["path"], record
        finally:
            stream.close()
        failures.extend({"input": i, "reason": r} for i, r in stream.failures)
    arrays = [(key, what) for key, what in rows if isinstance(key, tuple)]
    if not arrays:
        return
    with ThreadPoolExecutor(max_workers=threads or os.cpu_count() or 1) as pool:
        results = [pool.submit(project, array, **options) for _, array in arrays]
        for (key, _), result in zip(arrays, results):
            name = "array[%d]" % key[1]
            try:
                yield key, _array_record(result.result(), name)
            except ValueError as error:
                failures.append({"input": name, "reason": str(error)})
                warnings.warn("%s: %s" % (name, error), UserWarning, 3)


def _array_identity(array: np.ndarray) -> dict:
    contiguous = np.ascontiguousarray(array)
    return {"shape": list(array.shape), "dtype": str(array.dtype),
            "sha256": hashlib.sha256(contiguous.tobytes()).hexdigest()}


def _array_record(projection: Projection, name: str) -> dict:
    """The record iter_batch gives a file, for an array's projection."""
    levels = projection.errors["levels"]
    metadata = projection.metadata
    return {"input": name, "path": None, "schema_version": metadata["schema_version"],
            "face_size": levels[0]["size"], "layout": metadata["provenance"]["input_kind"],
            "level": projection.level, "level_size": projection.level_size,
            "estimated_error": levels[projection.level]["estimated_error"],
            "error_metric": projection.errors["error_metric"], "order": projection.order,
            "coefficients": projection.coefficients.tolist(),
            "constants": dict(zip(CONSTANT_NAMES, projection.constants.tolist())),
            "convention": metadata["convention"], "provenance": metadata["provenance"]}


def _warn_if_resolutions_vary(metadata: list, stacklevel: int) -> None:
    sizes: dict = {}
    for row in metadata:
        sizes.setdefault(row["level_size"], []).append(row["input"])
    if len(sizes) < 2:
        return
    spread = ", ".join("%dx%d: %d (%s%s)" % (size, size, len(names), ", ".join(names[:2]),
                                              ", ..." if len(names) > 2 else "")
                       for size, names in sorted(sizes.items(), reverse=True))
    warnings.warn("the coefficients come from different resolutions (level sizes %s); pass level= (and face_size=) "
                  "to label every input at one level" % spread, UserWarning, stacklevel)


__all__ = ["Projection", "Dataset", "project", "irradiance_map", "batch", "iter_batch", "builtin_environments",
           "CONSTANT_NAMES"]
