"""stewart: the Stewart platform solver on numpy arrays, its FMUs, and sweeps on Dask.

>>> import numpy as np, stewart
>>> platform = stewart.Platform(payload_mass=50)
>>> sol = platform.solve(np.array([[0, 0, 0.5, 0, 0, 0]]), fidelity="massless")
>>> sol.length.shape
(1, 6)

`forward` (lengths to pose) and `simulate` (forces to motion) are not here yet: they come with
the library's forward kinematics and plant.
"""
from importlib.metadata import PackageNotFoundError, version as _version

from .errors import ParameterError
from .fmus import FMI_VERSIONS, fmu_path, fmu_paths
from .params import parameters
from .platform import Fidelity, Platform, Solution

try:
    __version__ = _version("stewart")
except PackageNotFoundError:  # imported from a source tree, not installed
    __version__ = "unknown"

__all__ = ["Platform", "Solution", "Fidelity", "ParameterError", "fmu_path", "fmu_paths",
           "FMI_VERSIONS", "parameters", "__version__"]
