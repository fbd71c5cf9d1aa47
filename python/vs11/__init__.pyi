# Type stubs of the vs11 module (the C++ extension _vs11, re-exported). Docstrings: help(vs11.X).
import os
from typing import Any, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import irradiance as irradiance

__all__ = ["AssemblyError", "Program", "assemble", "load", "irradiance", "__version__"]

__version__: str  # CMake's project version of the build

Diagnostic = dict[str, Any]  # file, line, column, severity, message, word_offset, text
FloatArray = npt.NDArray[Union[np.float32, np.float64]]
Constants = Union[None, Mapping[Union[str, int], Sequence[float]], FloatArray]

class AssemblyError(ValueError):
    """A program did not assemble, load or validate; str() is every FILE:LINE:COLUMN diagnostic."""

    diagnostics: list[Diagnostic]

class Program:
    """A validated vs_1_1 program (from assemble or load)."""

    @property
    def name(self) -> str: ...
    @property
    def tokens(self) -> npt.NDArray[np.uint32]:
        """The D3D9 bytecode (a .vso file's words)."""
    @property
    def inputs(self) -> list[str]:
        """Input registers declared or read: ['v0', ...]."""
    @property
    def outputs(self) -> list[str]:
        """Output registers written, in run()'s order: ['oPos', 'oD0', ...]."""
    @property
    def fragment(self) -> bool: ...
    def disassemble(self) -> str:
        """Assembly text that re-assembles to the same tokens."""
    def validate(self) -> list[Diagnostic]:
        """The warnings; raises AssemblyError on errors."""
    def count(self) -> dict[str, int]:
        """instructions, slots, constants, temporaries, inputs, dynamic_instructions_per_vertex."""
    def run(
        self,
        inputs: Mapping[str, FloatArray],
        constants: Constants = None,
        engine: str = "jit",
        threads: int = 1,
        float_rules: str = "d3d9",
        missing: str = "error",
    ) -> dict[str, npt.NDArray[np.float32]]:
        """Runs the program over n vertices.

        inputs: {'v0' or a dcl usage name ('normal', 'texcoord1'): (n, 4) or (n, 3) float32/float64}.
        constants: {'c4' or 4: four numbers} or a (k, 4) array of c0..c(k-1).
        engine: 'jit', 'batch' or 'ref' (the same bits); threads: 1 to 256.
        float_rules: 'd3d9' (IEEE products: 0 * inf = NaN) or 'legacy' (0 * anything = 0).
        missing: 'error': a constant the program reads that nothing sets, or an input it reads that
        inputs lacks (a misspelt register), raises ValueError naming it; 'zeros': they read 0 (inputs
        0, 0, 0, 1) with a UserWarning each.
        Returns {output name: (n, 4) float32 view of the engine's output}; the GIL is released while
        the engine runs.
        """
    def trace(
        self,
        inputs: Mapping[str, FloatArray],
        constants: Constants = None,
        vertex: int = 0,
        engine: str = "jit",
        float_rules: str = "d3d9",
        missing: str = "error",
    ) -> dict[str, Any]:
        """One vertex instruction by instruction: the record `vs11 run --trace-json` writes."""

def assemble(
    source: str, name: str = "<string>", fragment: Optional[bool] = None, max_constants: int = 96
) -> Program:
    """Assembles and validates vs_1_1 source; raises AssemblyError, warns for warnings."""

def load(path: Union[str, os.PathLike[str]], fragment: Optional[bool] = None, max_constants: int = 96) -> Program:
    """Loads a .vsh or .vso file and validates it; raises AssemblyError."""
