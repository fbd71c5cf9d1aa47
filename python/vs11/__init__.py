"""The Direct3D 8/9 vs_1_1 vertex-shader machine and the irradiance environment-map pipeline.

    import numpy as np, vs11
    program = vs11.load("programs/sh9_irradiance.vsh")
    result = vs11.irradiance.project("sky", face_size=64)
    lit = program.run({"v0": normals}, result.constants)["oD0"]

assemble() and load() give a Program (tokens, disassemble(), validate(), count(), run(), trace());
vs11.irradiance projects environments onto nine SH coefficients per channel (project,
irradiance_map, batch for datasets, iter_batch to stream them). See help() of each.
vs11.__version__ is the version of the vs11 build (CMake's project version).
"""
from ._vs11 import AssemblyError, Program, __version__, assemble, load
from . import irradiance

__all__ = ["AssemblyError", "Program", "assemble", "load", "irradiance", "__version__"]
