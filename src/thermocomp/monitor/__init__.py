"""Thermal monitoring and the fault-tolerant compensator (paper 002; pure core).

:mod:`.pod` — POD of the temperature field, reconstruction from any subset;
:mod:`.placement` — optimal sensor choice (QR pivoting, sequential covariance);
:mod:`.surveillance` — self-prediction error, detectors, adaptive sensor set;
:mod:`.guard` — bounded, rate-limited correction;
:mod:`.adaptive` — the deployable compensator that combines them;
:mod:`.blind` — what a fault inside the bands costs the correction.
"""

from .adaptive import AdaptiveCompensator
from .blind import undetected_offset_um
from .guard import CorrectionGuard
from .placement import covariance_sensors, qr_sensors
from .pod import ThermalPOD
from .surveillance import STATES, SensorMonitor

__all__ = ["AdaptiveCompensator", "CorrectionGuard", "STATES", "SensorMonitor", "ThermalPOD",
           "covariance_sensors", "qr_sensors", "undetected_offset_um"]
