"""A re-admission's reason says how it was judged (stranger80): a jig borer's X nut thermocouple,
which no other sensor predicts (its own heat: the axis' moves), lost for 20 samples and back:
its reason said "re-admitted: within ±10.4 °C for 10 samples", a band nothing had compared (a
sensor no other predicts comes back on calm alone); a sensor the others predict still says its
band."""

from __future__ import annotations

import numpy as np

from thermocomp.apps.deploy.surveillance import SensorMonitor

NAMES = [f"T_{k}" for k in range(6)] + ["T_nut"]


def nut_field(m: int, seed: int, follow: float = 0.0) -> np.ndarray:
    """Six sensors of a warming machine and a nut heated by its own axis (the last column);
    ``follow``: how much of the nut's heat the others near it take up (0: none, no other predicts
    the nut), falling off from the first to the sixth."""
    rng = np.random.default_rng(seed)
    t = np.arange(m)
    warm = 3 * (1 - np.exp(-t / 80)) + 0.5 * np.sin(t / 37)
    gradient = 1.5 * np.sin(t / 53 + seed)
    nut = 2.5 * np.clip(np.sin(t / (23 + 5 * seed) + 2 * seed), 0, None)   # the axis' own heat
    near = follow * nut[:, None] * np.linspace(1, 0, 6)
    x = np.c_[warm[:, None] + gradient[:, None] * np.linspace(-0.5, 0.5, 6) + near, nut]
    return 20 + np.round(x + rng.normal(scale=0.02, size=x.shape), 2)


def _back(sensor: int) -> tuple[SensorMonitor, list[dict]]:
    mon = SensorMonitor.from_training(None, NAMES, {"a": nut_field(400, 0), "b": nut_field(400, 1)})
    record = nut_field(300, 5)
    record[150:170, sensor] = np.nan
    events = []
    for i, row in enumerate(record):
        events += mon.update(row, float(i))[1]
    return mon, [e for e in events if e["sensor"] == NAMES[sensor] and e["to"] == "ok"]


def test_a_sensor_no_other_predicts_comes_back_on_calm_and_says_so():
    mon, back = _back(6)
    assert not mon._predictable[6] and mon._predictable[:6].all()
    assert len(back) == 1, back
    assert back[0]["reason"] == ("re-admitted: no detector fired for 10 samples (no other sensor "
                                 "predicts it: no band judges its reading)"), back
    assert "±" not in back[0]["reason"]


def test_a_sensor_the_others_predict_still_says_the_band_it_came_back_within():
    mon, back = _back(2)
    assert len(back) == 1, back
    band = mon._readmit_c()[2]
    assert back[0]["reason"].startswith(f"re-admitted: within ±{band:.3g} °C for "), back
