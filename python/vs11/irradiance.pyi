# Type stubs of vs11.irradiance. Docstrings: help(vs11.irradiance.project) and so on.
import os
from typing import Any, Generator, Iterable, Optional, Union

import numpy as np
import numpy.typing as npt

from . import Program

Environment = Union[str, os.PathLike[str], npt.NDArray[Union[np.float32, np.float64]]]

class Projection:
    """What project() computed (irrmap's coeffs.json, in arrays)."""

    coefficients: npt.NDArray[np.float64]  # (9, 3): L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22
    constants: npt.NDArray[np.float32]  # (7, 4): cAr cAg cAb cBr cBg cBb cC (Table 1)
    level: int
    level_size: int
    order: str  # order0, order1, zh3 or order2
    program: Program  # the chosen program
    program_constants: dict[str, list[float]]  # its constants: {'c0': [x, y, z, w], ...}
    errors: dict[str, Any]  # error_metric, estimated_error, error_vs_full_order2, levels
    warnings: list[str]
    metadata: dict[str, Any]  # schema_version, convention, provenance (as every batch record)

CONSTANT_NAMES: tuple[str, ...]  # ('cAr', 'cAg', 'cAb', 'cBr', 'cBg', 'cBb', 'cC'): the rows of constants

LAYOUTS: tuple[str, ...]  # irrmap's --layout names
ORDERS: tuple[str, ...]  # 'auto' and the programs' names
WINDOWS: tuple[str, ...]
ERROR_METRICS: tuple[str, ...]
DEFAULTS: dict[str, Any]  # every argument's default: layout, face_size, max_error, order, batch_order, ...

def builtin_environments() -> list[str]: ...
def project(
    environment: Environment,
    layout: str = ...,
    face_size: int = ...,
    level: Optional[int] = None,
    max_error: float = ...,
    order: str = ...,
    window: str = ...,
    error_metric: str = ...,
    window_width: float = ...,
) -> Projection:
    """Nine SH coefficients per channel and the seven constants, as `irrmap --coefficients-only`.

    environment: a file, a '{face}' pattern, a built-in name, or a float array: (6, N, N, 3) cube
    faces (D3D order) or an (H, 2H, 3) lat-long map. result.metadata: convention and provenance.
    """

def irradiance_map(
    environment: Environment,
    layout: str = ...,
    face_size: int = ...,
    level: Optional[int] = None,
    max_error: float = ...,
    order: str = ...,
    window: str = ...,
    map_size: int = ...,
    engine: str = ...,
    error_metric: str = ...,
    window_width: float = ...,
) -> npt.NDArray[np.float32]:
    """The (6, map_size, map_size, 3) irradiance cube map irrmap writes as irradiance.exr."""

class Dataset:
    """A labelled dataset: row i of coefficients and constants belongs to metadata[i]."""

    coefficients: npt.NDArray[np.float64]  # (N, 9, 3)
    constants: npt.NDArray[np.float32]  # (N, 7, 4)
    metadata: list[dict[str, Any]]  # the records without their numbers: input, path, level, provenance, ...
    failures: list[dict[str, str]]  # {'input', 'reason'}
    @classmethod
    def from_records(cls, records: Iterable[dict[str, Any]], failures: Iterable[dict[str, str]] = ()) -> Dataset:
        """Stacks records (iter_batch's, or irrmap batch's JSON lines); warns when level sizes differ."""

BatchInput = Union[str, os.PathLike[str], npt.NDArray[Union[np.float32, np.float64]]]

def batch(
    inputs: Iterable[BatchInput],
    threads: int = 0,
    layout: str = ...,
    face_size: int = ...,
    level: Optional[int] = None,
    max_error: float = ...,
    order: str = ...,
    window: str = ...,
    error_metric: str = ...,
    window_width: float = ...,
) -> Dataset:
    """Labels a dataset (paths, glob patterns, arrays) as project() labels one input: a Dataset.

    Pass level=K (and face_size) for one resolution; by default the level is each input's own, and
    a UserWarning says so when the level sizes differ. Unusable inputs warn and go to .failures.
    """

def iter_batch(
    inputs: Iterable[BatchInput],
    threads: int = 0,
    layout: str = ...,
    face_size: int = ...,
    level: Optional[int] = None,
    max_error: float = ...,
    order: str = ...,
    window: str = ...,
    error_metric: str = ...,
    window_width: float = ...,
) -> Generator[dict[str, Any], None, None]:
    """batch() as a stream of `irrmap batch`'s records (JSON-ready dicts) as the inputs finish.

    The work runs on threads of its own with the GIL released; closing the generator stops it.
    """
