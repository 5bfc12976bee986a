"""stewart: the Stewart platform solver on numpy arrays, its FMUs, and sweeps on Dask.

>>> import numpy as np, stewart
>>> platform = stewart.Platform(payload_mass=50)
>>> sol = platform.solve(np.array([[0, 0, 0.5, 0, 0, 0]]), fidelity="massless")
>>> sol.length.shape
(1, 6)

``Platform.forward`` (lengths to poses) and ``Platform.simulate`` (forces to motion) return
ForwardSolution and Simulation in the same way.
"""
from importlib.metadata import PackageNotFoundError, version as _version

from .errors import ParameterError
from .fmus import FMI_VERSIONS, fmu_path, fmu_paths
from .forward import ForwardSolution
from .params import parameters
from .platform import Fidelity, Platform, Solution
from .simulate import Method, Simulation

try:
    __version__ = _version("stewart")
except PackageNotFoundError:  # imported from a source tree, not installed
    __version__ = "unknown"

__all__ = ["Platform", "Solution", "ForwardSolution", "Simulation", "Fidelity", "Method", "ParameterError", "fmu_path", "fmu_paths",
           "FMI_VERSIONS", "parameters", "__version__"]
