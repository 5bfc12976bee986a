"""stewart: the Stewart platform solver on numpy arrays, its FMUs, and sweeps on Dask.

>>> import numpy as np, stewart
>>> platform = stewart.Platform(payload_mass=50)
>>> sol = platform.inverse(np.array([[0, 0, 0.5, 0, 0, 0]]), fidelity="massless")
>>> sol.length.shape
(1, 6)

One direction per method and module: ``Platform.inverse`` (poses to lengths and forces,
inverse.py), ``Platform.forward`` (lengths to poses, forward.py) and ``Platform.simulate``
(forces to motion, simulate.py) return InverseSolution, ForwardSolution and Simulation.
``stewart.calibrate`` identifies a built machine's geometry from measured poses and
``stewart.calibration_poses`` says where to measure (calibration.py, docs/calibration.md).
``stewart.view`` writes a self-contained HTML page that shows a platform and a result in 3D
(view.py, docs/view.md).
``stewart.perception`` filters a motion through a model of the vestibular system (what a seated
person feels, vestibular.py, docs/perception.md); ``stewart.cueing_scores`` compares what a vehicle
and a platform make one feel (scores.py); ``stewart.manoeuvre`` loads the vehicle manoeuvres
shipped as data (manoeuvres.py, manoeuvres/README.md); ``stewart.head_motion`` gives what a
platform's poses make the head feel, for the same comparison (head_motion.py, docs/cueing.md).
"""
from importlib.metadata import PackageNotFoundError, version as _version

from .angles import convert_angles, rotation_matrix
from .calibration import Calibration, UnobservableError, calibrate, observability
from .calibration_poses import calibration_poses
from .check import HomeCheck
from .cueing import ALGORITHMS as CUEING_ALGORITHMS, Cueing, cueing
from .choices import Fidelity
from .errors import ParameterError
from .head_motion import HeadMotion, head_motion
from .fmus import FMI_VERSIONS, FMU_NAMES, fmu_path, fmu_paths, fmu_start_values, ssp_path
from .forward import ForwardSolution
from .inverse import InverseSolution
from .manoeuvres import manoeuvre, manoeuvre_files, random_vehicle
from .feasibility import Feasibility, feasibility
from .moves import Move, MoveError, move
from .params import parameters, platform_files
from .vestibular import Perceived, VestibularModel, perception
from .platform import Platform
from .scores import CueingScores, cueing_scores
from .simulate import Method, PlantInput, Simulation
from .sizing import SizingReport, sizing
from .view import view

try:
    __version__ = _version("stewart")
except PackageNotFoundError:  # imported from a source tree, not installed
    __version__ = "unknown"

__all__ = ["Platform", "InverseSolution", "ForwardSolution", "Simulation", "HomeCheck",
           "Fidelity", "Method", "ParameterError", "PlantInput", "fmu_path", "fmu_paths", "fmu_start_values",
           "ssp_path", "FMI_VERSIONS", "FMU_NAMES", "parameters", "calibrate",
           "calibration_poses", "observability", "Calibration", "UnobservableError",
           "platform_files", "view", "convert_angles", "rotation_matrix", "move", "Move",
           "MoveError", "feasibility", "Feasibility", "perception", "Perceived",
           "VestibularModel", "cueing_scores", "CueingScores", "manoeuvre",
           "manoeuvre_files", "random_vehicle", "cueing", "Cueing", "CUEING_ALGORITHMS",
           "head_motion", "HeadMotion",
           "sizing", "SizingReport",
           "__version__"]
