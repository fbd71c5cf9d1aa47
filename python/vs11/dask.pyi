# Type stubs of vs11.dask (needs Dask). Docstrings: help(vs11.dask.label_dataset) and so on.
import dataclasses
import os
from typing import Any, Callable, Iterable, Optional, Union

@dataclasses.dataclass
class LabelSummary:
    inputs: int
    already_done: int
    written: int
    failed: list[dict[str, str]]  # {"input", "path", "error"}, sorted by path
    parts: list[str]
    failed_files: list[str]

def input_key(path: str) -> str:
    """An input's identity, its record's "path": its folder's canonical path and its own name."""

def expand_inputs(paths: Iterable[str]) -> list[str]:
    """Paths and glob patterns expanded, de-duplicated and sorted, as irrmap batch does."""

def completed_keys(output_dir: str) -> set[str]:
    """The "path" of every record in the part files of output_dir."""

def label_dataset(
    client: Any,
    paths: Union[Iterable[str], Any],
    output_dir: Union[str, os.PathLike[str]],
    files_per_task: int = 16,
    resume: bool = True,
    progress: Union[bool, Callable[[int, int], None]] = True,
    threads: int = 1,
    layout: str = ...,
    face_size: int = ...,
    level: Optional[int] = None,
    max_error: float = ...,
    error_metric: str = ...,
) -> LabelSummary:
    """Labels every input (paths, patterns or a dask Bag) on a distributed cluster: one atomically
    written part-*.jsonl per task, failed inputs recorded in failed-*.jsonl, resumable."""
