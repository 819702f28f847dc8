"""Thermal monitoring (paper 002; pure core): what the fault-tolerant compensator of
:mod:`thermocomp.apps.deploy` sees and misses.  Monitoring uses deploy, never the reverse.

:mod:`.placement` — optimal sensor choice (QR pivoting, sequential covariance);
:mod:`.blind` — what a fault inside the bands costs the correction;
:mod:`.figures` — the monitor stage's figures.

The deployed pieces (POD reconstruction, surveillance, guard, the adaptive compensator) live in
:mod:`thermocomp.apps.deploy`; they are re-exported here, monitoring's vocabulary.
"""

from ..deploy.adaptive import AdaptiveCompensator
from ..deploy.guard import CorrectionGuard
from ..deploy.pod import ThermalPOD
from ..deploy.surveillance import STATES, SensorMonitor
from .blind import undetected_offset_um
from .placement import covariance_sensors, qr_sensors

__all__ = ["AdaptiveCompensator", "CorrectionGuard", "STATES", "SensorMonitor", "ThermalPOD",
           "covariance_sensors", "qr_sensors", "undetected_offset_um"]
