"""A healthy offset the logger's last digit flips across the band: warned, not excluded (mon83).

Eight sensors on a 0.1 K logger.  After the warm-up one sensor, ``T_0``, settles 0.3 K warmer
than training's field has it (a regime: its error stands just within its band), and half an hour
later the sensor that weighs most in its prediction sits on a rounding threshold, so its reading
flips by the last digit and ``T_0``'s error flips beyond the band and back by less than what the
readings' rounding can move it (``rounding_c``).  The drift judgement used to exclude ``T_0``
on two such samples (trunnion 8342's healthy table, ``benchmarks/bench_mon83.py``); it now holds
a culprit beyond its band by less than its rounding bound whose field memory (30 min) stood
within that bound of the band and whose excursion hovers, and still warns.  A drift from a clean
field goes out at the same sample as before."""

from __future__ import annotations

import numpy as np
import pytest

from thermocomp.apps.deploy.adaptive import AdaptiveCompensator
from thermocomp.apps.deploy.export.watch import DRIFT_OUT, EXCLUDED, NOT_IN_CODE, CodeMonitor, monitor_fields
from thermocomp.apps.deploy.surveillance import SensorMonitor

NAMES = [f"T_{k}" for k in range(6)] + ["T_a", "T_b"]
J = 0          # the sensor at an offset
PERIOD = 20.0  # s per sample


def _training(seed: int, m: int = 400, q: float | None = 0.1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    t = np.arange(m)
    warm = 3 * (1 - np.exp(-t / 80)) + 0.5 * np.sin(t / 37)
    gradient = 1.5 * np.sin(t / 53 + seed)
    spindle = 2.0 * np.sin(t / (29 + 3 * seed) + seed) + 0.02 * t
    x = np.c_[warm[:, None] + gradient[:, None] * np.linspace(-0.5, 0.5, 6),
              warm + spindle, warm + 0.8 * spindle]
    x = 20 + x + rng.normal(scale=0.02, size=x.shape)
    return x if q is None else np.round(x, 1)


TRAIN = {"a": _training(0), "b": _training(1)}


def _monitor(**options) -> SensorMonitor:
    return SensorMonitor.from_training(None, NAMES, TRAIN, **options)


def _record(mon: SensorMonitor, kind: str) -> np.ndarray:
    """1000 samples: a warm-up to a field training held (``TRAIN['a']``'s at sample 300), then
    ``offset`` ``T_0`` ramped in over 20 min from sample 400 and, from 600 on, its most weighty
    predictor on a rounding threshold; ``drift``: ``T_0`` +1 K/h from 600 on, no offset."""
    M, h = mon.pod.operator(np.ones(len(NAMES), dtype=bool))
    S = (np.eye(len(NAMES)) - M) / (1 - h)[:, None]     # each error per referenced reading
    field = np.round(TRAIN["a"][300] - TRAIN["a"][0], 1)
    t = np.arange(1000)
    x = 20 + (1 - np.exp(-t / 80))[:, None] * field
    if kind == "drift":
        x[600:, J] += (t[600:] - 600) * PERIOD / 3600
        return np.round(x, 1)
    band, bound = mon.warning_c[J], mon.rounding_c[J]
    offset = 0.1 * np.ceil((band - 0.1 - S[J] @ field) / 0.1)   # error within 0.1 of the band
    k = int(np.argmax(np.where(np.arange(len(NAMES)) == J, 0.0, np.abs(S[J]))))
    flip = 0.1 * np.sign(S[J, k])                                 # the digit that raises it
    held = S[J] @ field + offset
    # the scenario: held within the band and within the bound of it, flipped beyond it by less
    assert band - bound <= held < band <= held + abs(S[J, k]) * 0.1 < band + bound
    x[:, J] += offset * np.clip((t - 400) / 60, 0, 1)
    x[600:, k] += flip / 2 + np.random.default_rng(0).normal(scale=0.02, size=400)
    return np.round(x, 1)


def _run(mon: SensorMonitor, record: np.ndarray) -> list[dict]:
    events = []
    for i, row in enumerate(record):
        events += mon.update(row, PERIOD * i)[1]
    return events


def _excluded(events: list[dict]) -> list[tuple[float, str]]:
    return [(e["time"], e["sensor"]) for e in events if e["to"] == "excluded"]


def test_the_rounding_bound_is_the_loggers_digit_and_about_none_on_a_continuous_reading():
    M, h = _monitor().pod.operator(np.ones(len(NAMES), dtype=bool))
    weight = np.abs(np.eye(len(NAMES)) - M).sum(axis=1) / (1 - h)
    assert _monitor().rounding_c == pytest.approx(0.05 * weight)
    continuous = SensorMonitor.from_training(
        None, NAMES, {c: _training(s, q=None) for c, s in (("a", 0), ("b", 1))})
    assert continuous.rounding_c.max() < 1e-3


def test_a_healthy_offset_the_last_digit_flips_across_the_band_is_warned_not_excluded():
    record = _record(_monitor(), "offset")
    shipped = _excluded(_run(_monitor(rounding_c=0.0), record))    # the judgement before mon83
    assert [s for _, s in shipped] == [NAMES[J]]
    events = _run(_monitor(), record)
    assert not _excluded(events)
    warned = [e for e in events if e["sensor"] == NAMES[J] and e["to"] == "warning"]
    assert warned and warned[0]["time"] == shipped[0][0]            # said where it went out


def test_a_drift_from_a_clean_field_goes_out_at_the_same_sample_as_before():
    mon = _monitor()
    record = _record(mon, "drift")
    before = _excluded(_run(_monitor(rounding_c=0.0), record))
    assert before and before[0][1] == NAMES[J]
    assert _excluded(_run(mon, record)) == before


def _code(mon: SensorMonitor, record: np.ndarray) -> list[tuple[float, str]]:
    """The exported monitor's numpy mirror (``export/watch.py``, the C's arithmetic) on
    ``record``: its drift exclusions; it must flag nothing it does not hold."""
    deployed = AdaptiveCompensator.__new__(AdaptiveCompensator)     # its monitor is all it reads
    deployed.monitor, deployed.period_s = mon, PERIOD
    code = CodeMonitor(monitor_fields(deployed, NAMES)["monitor"])
    out = []
    for i, row in enumerate(record):
        code.step(row, i == 0, PERIOD)
        assert not code.flags & NOT_IN_CODE, (i, code.missed)
        if code.flags & EXCLUDED and code.rule == DRIFT_OUT:
            out.append((PERIOD * i, NAMES[code.sensor]))
    return out


@pytest.mark.parametrize("kind", ["offset", "drift"])
def test_the_exported_monitor_holds_and_excludes_as_served(kind):
    record = _record(_monitor(), kind)
    for options in ({}, {"rounding_c": 0.0}):
        assert _code(_monitor(**options), record) == _excluded(_run(_monitor(**options), record))
