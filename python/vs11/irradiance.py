"""Environments to spherical-harmonic irradiance: project, irradiance_map and batch (irrmap's library)."""
from typing import Any, Generator, Iterable, Optional

from ._vs11 import irradiance as _irradiance

Projection = _irradiance.Projection
project = _irradiance.project
irradiance_map = _irradiance.irradiance_map
builtin_environments = _irradiance.builtin_environments


def batch(
    paths: Iterable[str],
    threads: int = 0,
    layout: str = "auto",
    face_size: int = 256,
    level: Optional[int] = None,
    max_error: float = 0.005,
    error_metric: str = "peak",
) -> Generator[dict[str, Any], None, None]:
    """Projects many environment files as `irrmap batch` does and yields its records as they finish.

    paths: files or glob patterns, expanded, de-duplicated and sorted as irrmap batch does.
    threads: inputs processed at once (0: every core); the records do not depend on it.
    layout, face_size, level, max_error, error_metric: as for project().

    The work starts at once, on threads of its own, with the GIL released; the generator yields
    each record as irrmap batch writes it, in the order the inputs finish (not input order), as a
    dict: input, path (its canonical path), face_size, layout, level, level_size, estimated_error, error_metric,
    coefficients (9 x [r, g, b])
    and constants ({'cAr': [x, y, z, w], ...}). An input that cannot be used is a UserWarning
    naming it and why, issued when the generator reaches it. Errors of the run itself (a pattern
    that matches nothing, a bad layout) raise ValueError from the first next(); threads < 0 raises
    at the call. Closing the generator (close(), a break out of a for loop once the generator is
    dropped, garbage collection) stops the run: no input starts after it, and close() returns once
    the inputs already running are done.

    Example:
      for record in vs11.irradiance.batch(['envs/*.hdr'], threads=2):
          print(record['input'], record['level'])
    """
    stream = _irradiance._BatchStream(list(paths), threads, layout, face_size, level, max_error, error_metric)
    return _records(stream)


def _records(stream: Any) -> Generator[dict[str, Any], None, None]:
    try:
        yield from stream
    finally:
        stream.close()


__all__ = ["Projection", "project", "irradiance_map", "batch", "builtin_environments"]
