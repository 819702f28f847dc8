"""A real excursion beyond training read as a sensor fault? The adaptive compensator on an overspeed.

Stop 55 (``bench_state_envelope.py``, aside) found the ADAPTIVE deployed compensator 1.2-6.8 x the
PLAIN stream's Σ² vs truth on the ``long_record`` overspeeds (long4253 lagbank 4.40 against 0.648
µm²), and took the cause for the ``out of range`` exclusion of the hot motor.  Here, on the same
records (``bench_state_envelope.py``'s ``long4253``, ``long7717``, its ``--root`` cache), the
mechanism is measured and a rule on ``out of range`` is scored.

Rules, written before scoring them (stop 56):

* ``R1`` (the brief's): an out-of-range reading excludes its sensor only when no other active
  sensor predicts it (leverage >= ``pod.max_leverage`` in the active set) or when its
  leave-one-out self-prediction error is beyond its alarm band; otherwise it stays in (the stream's
  envelope then handles it as in plain mode).
* ``R3`` (the field explains the excursion, whatever the leverage): an out-of-range reading stays
  in when the other active sensors' prediction of it lies beyond the same training edge, and the
  reading is nearer that prediction than half its distance from the edge; a spike, a unit change,
  a drifting or stuck sensor leave the others' prediction inside the training range: out.

Adopted only if every bar of the brief holds (overspeed: adaptive no worse than plain or much
closer; injected faults caught as before; healthy records as quiet; strict xfails as they are).
"""
