r"""Online surveillance of the temperature sensors and the adaptive sensor set (paper 002, 2.2–2.3).

:class:`SensorMonitor` sees one sample of the ``n`` monitored sensors at a
time (absolute °C; it references them to the campaign's first sample as the
POD snapshots were) and returns the field the compensation model should see:
the measured value of every *active* sensor, the POD reconstruction
:math:`\Phi_r\,\Phi_r[a]^+ T_a` from the active set :math:`a` for the others.

Each sensor is judged by its windowed self-prediction error: the trailing mean
over ``window`` samples of its reading minus what the *other* active sensors
predict for it (the leave-one-out form :math:`E_s/(1-h_{ss})` of paper 002's
:math:`E_s`; with the sensor in its own fit, a fault shows only by the factor
:math:`1-h_{ss}` and leaks onto the others).  Bands: ``warning_c``, ``alarm_c``.

Detectors, each named in the event's reason:

* ``dropout`` — no finite value;
* ``out of range`` — outside the training range widened by ``range_margin_c``, unless the active
  sensors within range predict it beyond the same training edge too (a machine hotter than
  training, :meth:`SensorMonitor._hotter`);
* ``jump`` — a one-sample step larger than ``jump_factor`` × the largest step
  seen in training (across missing samples, the step since the last reading
  against that limit times the samples it spans), or a self-prediction error
  that steps past the alarm band in one sample; a jumping sensor is re-referenced by its step
  less its change as the other active sensors predict it -- several jumping in one sample, as
  the sensors that did not jump predict it (:meth:`SensorMonitor._unjumped_change`);
* ``common step`` — a one-sample step on most active sensors at once (at least ``COMMON_MIN``
  of them jumping, more than half of the active ones within ``COMMON_SPREAD`` × the median
  jump, same sign): the logger's fault, every
  sensor that took it re-referenced by its own step, none excluded
  (:meth:`SensorMonitor._common_step`);
* ``freeze`` — the reading does not change, for longer than its longest constant
  run in training (capped at ``window``), while its prediction from the other
  sensors moves by the warning band (for a sensor no other predicts: no change
  for longer than ``freeze_factor`` × that run; for a reading whose noise spans its resolution
  in training, ``dithered``: no change for that long whatever the field did, mon97);
* ``drift`` — the windowed self-prediction error leaves the band gradually.

Adaptive mode (paper 002, 2.3): the worst sensor (largest self-prediction error
of the paper's Eq. 7, the sensor against the field fitted to all active sensors;
a one-sample step blames the largest standardised step, always the faulty
sensor for a single fault) is excluded and the operator recomputed, while more than
``r + 1`` sensors remain active (the first at ``exclude_at``, any further one while
a sensor is out by its error only beyond the alarm band:
:meth:`SensorMonitor._field_level`); before it, a sensor no other predicts whose drift has
leaked onto the judged ones is excluded when it explains them
(:meth:`SensorMonitor._explaining`); an excluded sensor whose reading returns
within the warning band for a whole window is re-admitted, the sensors due back
at once judged together (:meth:`SensorMonitor._returning`: after a total dropout
none could pass alone).  A sensor no other predicts, out of range, comes back
only where its leak onto the others is within ``READMIT`` of their bands
(:meth:`SensorMonitor._leak_passes`).  While too few sensors are in to rebuild the field, a
sensor out only for a dropout gives its reading as it waits.  Every change of
state is an event ``{"time", "sensor", "from", "to", "reason"}``.

A new thermal state (``new_state``, :meth:`SensorMonitor._drift_vetoed`): a
source training never saw moves several sensors away from the field at once,
which self-prediction cannot pin on one of them.  A sensor is excluded for drift
only if, with it out of the fit, every other judged sensor is within its warning
band (when the largest error's sensor does not explain the others, another sensor out
of band that does, and is itself off the others' field by more than any error now, is
excluded as a lone fault: :meth:`SensorMonitor._lone_fault`, a drifting sensor behind
its coupled neighbour's larger error; a sensor within its band whose exclusion leaves one out
of band unjudged gives way to one out of band that explains the others and is the likelier
single fault); otherwise no exclusion and an event
``"to": "new thermal state"`` (sensor ``None``, the sensors out of band in ``sensors``).
A sensor within its band is not excluded for the others' excursion while that hovers (each
error out of band no larger a share of its sensor's rise than ``EXCURSION_GROWTH`` × its share
``EXCURSION_TAU_S`` seconds before, :mod:`.excursion`: a regime, not a fault); no event, the
sensors out of band warn.
A drift-excluded sensor (by the largest error, a lone fault or as explaining the others) is
re-admitted when, within ``window`` samples of its exclusion, ``new_state_others``
other judged sensors leave their warning band (the field followed it), which
calls the new state too; while it lasts no sensor is excluded for drift (the
fault signatures -- dropout, range, jump, freeze -- still exclude), and it ends,
with an event ``"to": "trained"``, once every judged sensor has been within its
warning band for a whole window.
"""

from .monitor import SensorMonitor
from .states import (
                     ALARM,
                     COMMON_MIN,
                     COMMON_SPREAD,
                     EXCLUDED,
                     MAX_BACKOFF,
                     NEW_STATE,
                     OK,
                     READMIT,
                     SPREAD_FACTOR,
                     STATES,
                     TRAINED,
                     WARNING,
)

__all__ = ["SensorMonitor", "OK", "WARNING", "ALARM", "EXCLUDED", "STATES", "NEW_STATE", "TRAINED",
           "COMMON_MIN", "COMMON_SPREAD", "MAX_BACKOFF", "READMIT", "SPREAD_FACTOR"]
