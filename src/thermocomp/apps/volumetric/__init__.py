"""Volumetric thermal twin (papers 000 and 001): kinematic error model, artefact calibration,
the parameter series of a thermal test, and the calibration design study."""

from .artefact import SETUP_FILE, BallArray, Pose, Setup, position_set
from .kinematics import KinematicModel, Parameter, parameter_list

# the linearised measurement model is `identify.design`: the package's `design` is the
# calibration design study (submodule), which an import of it would rebind anyway
__all__ = ["SETUP_FILE", "ArtefactCalibration", "BallArray", "KinematicModel", "Parameter", "Pose",
           "Setup", "check_columns", "equivalent_truth", "load_setup",
           "parameter_list", "position_set"]


def __getattr__(name):   # SciPy and pandas at first use: the config schema reads artefact.py only
    if name in ("ArtefactCalibration", "equivalent_truth"):
        from . import identify
        return getattr(identify, name)
    if name in ("check_columns", "load_setup"):
        from . import series
        return getattr(series, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
