"""Environments to spherical-harmonic irradiance: project, irradiance_map and batch (irrmap's library)."""
from ._vs11 import irradiance as _irradiance

Projection = _irradiance.Projection
project = _irradiance.project
irradiance_map = _irradiance.irradiance_map
batch = _irradiance.batch
builtin_environments = _irradiance.builtin_environments

__all__ = ["Projection", "project", "irradiance_map", "batch", "builtin_environments"]
