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

def builtin_environments() -> list[str]: ...
def project(
    environment: Environment,
    layout: str = "auto",
    face_size: int = 256,
    level: Optional[int] = None,
    max_error: float = 0.005,
    order: str = "auto",
    window: str = "none",
    error_metric: str = "peak",
) -> Projection:
    """Nine SH coefficients per channel and the seven constants, as `irrmap --coefficients-only`.

    environment: a file, a '{face}' pattern, a built-in name, or a float array: (6, N, N, 3) cube
    faces (D3D order) or an (H, 2H, 3) lat-long map.
    """

def irradiance_map(
    environment: Environment,
    layout: str = "auto",
    face_size: int = 256,
    level: Optional[int] = None,
    max_error: float = 0.005,
    order: str = "auto",
    window: str = "none",
    map_size: int = 32,
    engine: str = "jit",
    error_metric: str = "peak",
) -> npt.NDArray[np.float32]:
    """The (6, map_size, map_size, 3) irradiance cube map irrmap writes as irradiance.exr."""

def batch(
    paths: Iterable[str],
    threads: int = 0,
    layout: str = "auto",
    face_size: int = 256,
    level: Optional[int] = None,
    max_error: float = 0.005,
    error_metric: str = "peak",
) -> Generator[dict[str, Any], None, None]:
    """Yields `irrmap batch`'s records as the inputs finish (not in input order); unusable inputs warn.

    The work runs on threads of its own with the GIL released; closing the generator stops it.
    """
