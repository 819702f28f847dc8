"""Thermal monitoring (paper 002): POD, placement, detectors, the adaptive compensator, `monitor`."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from hydra.utils import instantiate
from omegaconf import OmegaConf

from conftest import ROOT, influence, thermocomp
from covering import covering
from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.deploy.surveillance import NEW_STATE
from thermocomp.apps.monitor import (
    AdaptiveCompensator,
    ThermalPOD,
    covariance_sensors,
    qr_sensors,
    undetected_offset_um,
)
from thermocomp.core import io
from thermocomp.core.compensator import Compensator

FAULTS = ("jump", "freeze", "dropout", "drift", "spike_ref", "jump50")


# -- POD and placement ------------------------------------------------------------------------
def _field(seed=0, n=12, m=400, r=3):
    rng = np.random.default_rng(seed)
    modes = np.linalg.qr(rng.normal(size=(n, r)))[0]
    coef = np.cumsum(rng.normal(size=(m, r)), axis=0) * [5.0, 2.0, 1.0][:r]
    return coef @ modes.T, modes


def test_pod_reconstructs_a_field_in_its_span_from_any_subset_of_r_sensors():
    X, _ = _field()
    pod = ThermalPOD(energy=0.999999, fit_band_c=None, min_redundancy=1).fit(X)
    assert pod.n_modes_ == 3
    for subset in ([0, 1, 2], [3, 7, 11], list(range(12))):
        full = pod.reconstruct(X[:, subset], subset)
        assert np.allclose(full, X, atol=1e-8)
    assert np.allclose(pod.self_prediction(X), 0, atol=1e-8)


def test_pod_modes_grow_until_the_training_field_is_self_predicted_within_the_band():
    X, _ = _field(r=3)
    X = X + np.random.default_rng(1).normal(scale=0.01, size=X.shape)
    low = ThermalPOD(energy=0.5, fit_band_c=None).fit(X)
    fitted = ThermalPOD(energy=0.5, fit_band_c=0.1).fit(X)
    assert low.n_modes_ == 1 and low.train_band_c_ > 0.1
    assert fitted.n_modes_ > low.n_modes_ and fitted.train_band_c_ <= 0.1


@pytest.mark.parametrize("rank", [qr_sensors, "covariance"])
def test_placement_picks_sensors_that_determine_the_modes(rank):
    X, modes = _field(n=10, r=3)
    pod = ThermalPOD(modes=3).fit(X)
    order = (qr_sensors(pod.phi_, 3) if rank is qr_sensors else
             covariance_sensors(pod.phi_, pod.singular_values_, len(X), 3))
    assert len(set(order)) == 3
    worst = min((np.linalg.svd(pod.phi_[list(c)], compute_uv=False)[-1]
                 for c in [[0, 1, 2], [7, 8, 9], [2, 5, 8]]))
    assert np.linalg.svd(pod.phi_[order], compute_uv=False)[-1] >= 0.5 * worst


# -- the adaptive compensator on the default scenario -------------------------------------------
@pytest.fixture(scope="session")
def deployed(default_dataset):
    ds, _ = io.read_dataset(default_dataset, {})
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    est = instantiate(OmegaConf.load(ROOT / "conf/model/mlr.yaml").estimator)
    comp = Compensator(est).fit(train)
    adaptive = AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train), train)
    # the most influential sensor: the largest change of the test predictions per °C
    effect = influence(comp, test)
    sensor = max((c for c in effect if not c.startswith("T_amb")), key=effect.get)
    return adaptive, comp, test, sensor


def _stream(model, df):
    model.reset()
    X, t = df[model.columns_].to_numpy(float), df["time"].to_numpy(float)
    y, events = [], []
    for i in range(len(X)):
        y.append(model._step(X[i], t[i])[0])
        events += [dict(e, row=i) for e in model.last_events_]
    return np.array(y), events


@pytest.fixture(scope="module")
def healthy_streams(deployed):
    """Per test campaign, the deployed compensator's stream of it as recorded: ``(y, events)``
    (``_stream`` resets first, so it is the same whatever streamed before).  Every fault test
    scores its faulty stream against it; the arrays are read-only."""
    adaptive, _, test, _ = deployed
    streams = {cid: _stream(adaptive, df) for cid, df in test.items()}
    for y, _ in streams.values():
        y.flags.writeable = False
    return streams


@pytest.fixture(scope="module")
def second_sensor(deployed) -> str:
    """The second most influential sensor, as the fixture ranks the first (its influence)."""
    _, comp, test, sensor = deployed
    effect = influence(comp, test)
    return max((c for c in effect if not c.startswith("T_amb") and c != sensor), key=effect.get)


def _faulty(df, sensor, kind):
    df, n = df.copy(), len(df)
    k0 = n // 2
    v = df[sensor].to_numpy(float).copy()
    hours = (df["time"].to_numpy(float) - df["time"].to_numpy(float)[k0]) / 3600
    if kind == "jump":
        v[k0:] += 3.0
    elif kind == "jump50":
        v[k0:] += 50.0
    elif kind == "freeze":
        v[k0:] = v[k0]
    elif kind == "dropout":
        v[k0:] = np.nan
    elif kind == "drift":
        v[k0:] += 1.0 * hours[k0:]
    elif kind == "spike_ref":
        v[0] += 3.0
        k0 = 0
    df[sensor] = v
    return df, k0


def test_healthy_test_campaigns_raise_no_event_and_change_nothing(deployed, healthy_streams):
    adaptive, comp, test, _ = deployed
    fixed = adaptive.streaming
    for cid, df in test.items():
        y, events = healthy_streams[cid]
        assert events == [], (cid, events[:3])
        batch = comp.predict({cid: df})[cid][adaptive.targets_].to_numpy()
        assert np.allclose(y, batch, atol=1e-9)
    fixed.reset()


@pytest.mark.parametrize("kind", FAULTS)
def test_a_fault_on_the_most_influential_sensor_is_reported_bounded_and_compensated(deployed, kind,
                                                                                   healthy_streams):
    adaptive, comp, test, sensor = deployed
    measured = comp.measured(test)
    g = adaptive.guard
    ratios = []
    for cid, df in test.items():
        faulty, k0 = _faulty(df, sensor, kind)
        y, events = _stream(adaptive, faulty)
        assert np.isfinite(y).all() and (y >= g.lo - 1e-9).all() and (y <= g.hi + 1e-9).all()
        mine = [e for e in events if e["sensor"] == sensor]
        assert mine, f"{cid}: {kind} on {sensor} never reported"
        if kind in ("jump", "jump50", "dropout", "spike_ref"):   # observable at once
            assert mine[0]["row"] - max(k0, 1) <= 10, mine[0]
            assert mine[0]["to"] in (("re-referenced", "excluded") if kind == "spike_ref" else ("excluded",))
        if kind == "dropout":
            assert "dropout" in mine[0]["reason"]
        m = measured[cid][adaptive.targets_].to_numpy()
        healthy, _ = healthy_streams[cid]
        ratios.append(np.sqrt(np.mean((m - y) ** 2, 0)) / np.sqrt(np.mean((m - healthy) ** 2, 0)))
    assert np.max(ratios) <= 1.5, (kind, ratios)   # drift too: no runtime xfail hiding a regression


# Faults of other shapes and sizes than the simulator's (off our happy path): each on the most
# influential sensor, or on it and the second one, at mid-campaign
def _other_fault(df, sensors, kind, rng):
    df, n = df.copy(), len(df)
    k0 = n // 2
    v = df[sensors[0]].to_numpy(float).copy()
    hours = (df["time"].to_numpy(float) - df["time"].to_numpy(float)[k0]) / 3600
    if kind == "spike":                       # one sample off, then back
        v[k0] += 3.0
    elif kind == "spikes":                    # every 10th sample off
        v[k0::10] += 2.0
    elif kind == "jump_small":                # +1 °C: not a jump by the raw step detector
        v[k0:] += 1.0
    elif kind == "jump_down":
        v[k0:] -= 3.0
    elif kind == "stuck_at_zero":
        v[k0:] = 0.0
    elif kind == "short_dropout":             # 5 samples missing, then back
        v[k0:k0 + 5] = np.nan
    elif kind == "frozen_from_start":
        v[1:] = v[0]
        k0 = 1
    elif kind == "noisy":                     # ±0.5 °C noise, a loose contact
        v[k0:] += rng.normal(0.0, 0.5, n - k0)
    elif kind in ("two_jumps", "two_dropouts"):
        w = df[sensors[1]].to_numpy(float).copy()
        w[k0:] = w[k0:] + 3.0 if kind == "two_jumps" else np.nan
        v[k0:] = v[k0:] + 3.0 if kind == "two_jumps" else np.nan
        df[sensors[1]] = w
    elif kind.startswith("drift_"):           # slower than the simulator's 1 K/h
        v[k0:] += float(kind.split("_")[1]) * hours[k0:]
    df[sensors[0]] = v
    return df, k0


SLOW_DRIFT = pytest.mark.xfail(strict=True, reason=(
    "known gap: a slow drift is read as temperature until it leaves the band, and the model leans "
    "on T_motor2 (half the band: 4.9 µm on E_Z, undetected_offset_um); once out, its coupled partner "
    "T_motor1 goes out too (worst 1.7-1.8x, pooled 1.04x; 1.71x with T_motor1 kept in)"))


@pytest.mark.parametrize("kind", ["spike", "spikes", "jump_small", "jump_down", "stuck_at_zero",
                                  "short_dropout", "frozen_from_start", "noisy", "two_dropouts",
                                  "two_jumps",
                                  pytest.param("drift_0.5", marks=SLOW_DRIFT),
                                  pytest.param("drift_0.2", marks=SLOW_DRIFT)])
def test_faults_of_other_shapes_stay_bounded_and_cost_at_most_1_5x_the_healthy_error(
        deployed, kind, healthy_streams, second_sensor):
    adaptive, comp, test, sensor = deployed
    second = second_sensor
    measured, g, rng = comp.measured(test), adaptive.guard, np.random.default_rng(7)
    worst = 0.0
    for cid, df in test.items():
        faulty, _ = _other_fault(df, (sensor, second), kind, rng)
        y, events = _stream(adaptive, faulty)
        assert np.isfinite(y).all() and (y >= g.lo - 1e-9).all() and (y <= g.hi + 1e-9).all()
        if kind != "noisy":                    # the noise stays within the bands on some campaigns
            assert any(e["sensor"] in (sensor, second) for e in events), (cid, kind)
        m = measured[cid][adaptive.targets_].to_numpy()
        healthy, _ = healthy_streams[cid]
        ratio = np.sqrt(np.mean((m - y) ** 2, 0)) / np.sqrt(np.mean((m - healthy) ** 2, 0))
        worst = max(worst, float(ratio.max()))
    assert worst <= 1.5, worst


# reading x sensor: make test keeps the covering set (tests/covering.py), and -50 on T_amb, the
# case the test was written for (below)
@pytest.mark.parametrize("reading, sensor", covering(
    "the same out-of-range handling on another reading or sensor", keep=[("-50.0", "T_amb")],
    reading={"50.0": 50.0, "-50.0": -50.0, "open": "open"}, sensor=["T_amb", "most_influential"]))
def test_an_out_of_range_reading_is_no_measurement_and_its_return_no_jump(deployed, sensor, reading,
                                                                         healthy_streams):
    # a one-sample spike far outside the training range (or an open circuit reading 850 °C for
    # 5 samples): the sensor is out while it lasts and comes back as it was.  Before, the
    # spike became the previous value, its return read as a jump, and the ambient sensor (which
    # no other predicts) was re-referenced by -50 °C and re-admitted so: 6.5x the healthy error
    adaptive, comp, test, influential = deployed
    sensor = influential if sensor == "most_influential" else sensor
    measured, g = comp.measured(test), adaptive.guard
    worst = 0.0
    for cid, df in test.items():
        v = df[sensor].to_numpy(float).copy()
        k0 = len(v) // 2
        if reading == "open":
            v[k0:k0 + 5] = 850.0
        else:
            v[k0] += reading
        y, events = _stream(adaptive, df.assign(**{sensor: v}))
        assert np.isfinite(y).all() and (y >= g.lo - 1e-9).all() and (y <= g.hi + 1e-9).all()
        out = [e for e in events if e["to"] == "excluded"]
        assert {e["sensor"] for e in out} == {sensor}, (cid, events)
        # the ambient sensor is its own mode: its exclusion says it is held, not rebuilt
        unpredictable = not adaptive.monitor._predictable[adaptive.monitor.names.index(sensor)]
        assert unpredictable == (sensor == "T_amb")
        assert all(("no other sensor predicts it" in e["reason"]) == unpredictable for e in out)
        assert not any(e["to"] == "re-referenced" or e["reason"].startswith("jump") for e in events)
        assert adaptive.excluded_inputs == []          # back in by the end of the campaign
        m = measured[cid][adaptive.targets_].to_numpy()
        healthy, _ = healthy_streams[cid]
        ratio = np.sqrt(np.mean((m - y) ** 2, 0)) / np.sqrt(np.mean((m - healthy) ** 2, 0))
        worst = max(worst, float(ratio.max()))
    assert worst <= 1.25, worst


def test_an_offset_inside_the_band_moves_the_correction_by_the_reported_cost_and_no_more(deployed,
                                                                                        healthy_streams):
    # what monitor.json's undetected_offset_um says: the fault the monitor cannot see, priced
    adaptive, comp, test, sensor = deployed
    mon = adaptive.monitor
    offset = 0.5 * mon.warning_c[mon.names.index(sensor)]
    cost = undetected_offset_um(comp, test, {sensor: offset})[sensor]
    assert set(cost) == set(adaptive.targets_)
    unseen = []
    for cid, df in test.items():
        faulty = df.assign(**{sensor: df[sensor] + offset * (np.arange(len(df)) > 0)})
        y, events = _stream(adaptive, faulty)
        if any(e["to"] == "excluded" for e in events):
            continue                 # the offset plus the model error left the band here
        healthy, _ = healthy_streams[cid]
        unseen.append(np.abs(y - healthy).max(axis=0))
    assert len(unseen) >= len(test) - 2
    change = np.max(unseen, axis=0)
    bound = np.array([cost[t] for t in adaptive.targets_])
    assert (change <= bound * (1 + 1e-9) + 1e-9).all(), (change, bound)
    assert np.allclose(change, bound, rtol=0.05), (change, bound)   # the bound is reached
    # the model leans on the most influential sensor: half a band costs microns on some target
    assert bound.max() > 1.0


def test_freeze_and_drift_are_reported_within_10_samples_of_becoming_observable(deployed):
    adaptive, comp, test, sensor = deployed
    mon = adaptive.monitor
    j = mon.names.index(sensor)
    checked = {"freeze": 0, "drift": 0}
    for kind in checked:
        for cid, df in test.items():
            faulty, k0 = _faulty(df, sensor, kind)
            # observable: the sensor's reading departs from the healthy one by the warning band
            dev = np.abs(faulty[sensor].to_numpy() - df[sensor].to_numpy())
            seen = np.flatnonzero(dev >= mon.warning_c[j])
            if not len(seen):                  # a freeze on a campaign whose sensor stays put
                continue
            _, events = _stream(adaptive, faulty)
            mine = [e for e in events if e["sensor"] == sensor or e["to"] == "excluded"]
            assert mine and mine[0]["row"] - seen[0] <= 10, (cid, kind, seen[0], mine[:2])
            checked[kind] += 1
    assert all(checked.values()), checked      # each kind judged on some campaign, not skipped


@pytest.mark.parametrize("sensor, kind, bound", [
    ("T_amb", "first_row_missing", 1.25), ("most_influential", "first_row_missing", 1.5),
    ("T_amb", "noise_burst", 1.25)])
def test_a_sensor_missing_at_the_start_or_noisy_for_a_while_comes_back_as_it_reads(
        deployed, sensor, kind, bound, healthy_streams):
    # missing at the reference sample: it was never referenced, so it stayed out for good and
    # the ambient sensor, which no other predicts, was held at the start value (9.5x the healthy
    # error); a ±0.5 °C noise burst of 10 samples on it: each noisy step beyond the jump limit
    # re-referenced it, and it came back offset (1.6x here, 6.7x on an outside probe's data)
    adaptive, comp, test, influential = deployed
    sensor = influential if sensor == "most_influential" else sensor
    measured, g, rng = comp.measured(test), adaptive.guard, np.random.default_rng(0)
    sq, sq_healthy, caught = [], [], 0
    for cid, df in test.items():
        v = df[sensor].to_numpy(float).copy()
        k0 = len(v) // 2
        if kind == "first_row_missing":
            v[0] = np.nan
        else:
            v[k0:k0 + 10] += rng.normal(0.0, 0.5, 10)
        y, events = _stream(adaptive, df.assign(**{sensor: v}))
        assert np.isfinite(y).all() and (y >= g.lo - 1e-9).all() and (y <= g.hi + 1e-9).all()
        out = {e["sensor"] for e in events if e["to"] == "excluded"}
        assert out <= {sensor}, (cid, events)          # a burst may stay within the limits
        caught += bool(out)
        assert adaptive.excluded_inputs == [], (cid, events)         # back in
        j = adaptive.monitor.names.index(sensor)
        if kind == "noise_burst":        # back as it reads: no noisy step kept as an offset
            assert adaptive.monitor._ref[j] == v[0], (cid, events)
        else:
            assert np.isfinite(adaptive.monitor._ref[j])
        m = measured[cid][adaptive.targets_].to_numpy()
        healthy, _ = healthy_streams[cid]
        sq.append((m - y) ** 2)
        sq_healthy.append((m - healthy) ** 2)
    pooled = np.sqrt(np.mean(np.vstack(sq), 0) / np.mean(np.vstack(sq_healthy), 0))
    assert pooled.max() <= bound, pooled
    assert caught >= len(test) - 2, caught


def test_a_model_of_absolute_readings_sees_a_late_sensor_as_read(deployed, default_dataset):
    # data.reference=none: the model reads temperatures, not changes, so once a sensor missing
    # at the start is back it must see exactly its reading (it saw the training's mean start
    # value plus a change, and the sensor never came back: 5.4x on long_record for one cell)
    _, _, test, sensor = deployed
    ds, _ = io.read_dataset(default_dataset, {})
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    est = instantiate(OmegaConf.load(ROOT / "conf/model/mlr.yaml").estimator)
    comp = Compensator(est, reference="none").fit(train)
    adaptive = AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train), train)
    for cid, df in test.items():
        v = df[sensor].to_numpy(float).copy()
        v[0] = np.nan
        y, events = _stream(adaptive, df.assign(**{sensor: v}))
        healthy, _ = _stream(adaptive, df)
        back = [e["row"] for e in events if e["sensor"] == sensor and e["to"] == "ok"]
        assert back, (cid, events)
        assert np.abs(y[back[0]:] - healthy[back[0]:]).max() < 1e-9, cid


def test_bad_time_is_substituted_and_reported(deployed):
    adaptive, comp, test, _ = deployed
    df = next(iter(test.values())).copy()
    t = df["time"].to_numpy(float).copy()
    t[5], t[9] = np.nan, t[8] - 100.0
    y, events = _stream(adaptive, df.assign(time=t))
    assert np.isfinite(y).all()
    reasons = [e["reason"] for e in events if e["sensor"] == "time"]
    assert any("no finite value" in r for r in reasons) and any("does not increase" in r for r in reasons)
    assert events[-1]["sensor"] != "time" or events[-1]["to"] == "ok"


def test_a_swapped_pair_of_rows_is_one_substituted_time_then_the_record_again(deployed):
    adaptive, comp, test, _ = deployed
    df = next(iter(test.values()))
    order = np.arange(len(df))
    order[[20, 21]] = order[[21, 20]]
    y, events = _stream(adaptive, df.iloc[order].reset_index(drop=True))
    changes = [(e["row"], e["to"]) for e in events if e["sensor"] == "time"]
    assert changes == [(21, "substituted"), (22, "ok")], changes
    assert np.isfinite(y).all()


def test_predict_reports_excluded_inputs_and_events_per_row(deployed):
    adaptive, comp, test, sensor = deployed
    df, k0 = _faulty(next(iter(test.values())), sensor, "jump50")
    adaptive.reset()
    out = adaptive.predict(df)
    assert sensor in out["excluded_inputs"].iloc[-1].split(",")
    first = json.loads(out["events"].iloc[k0])
    assert first and first[0]["sensor"] == sensor
    assert first[0]["reason"].startswith(("jump", "out of range"))
    adaptive.reset()


# -- column_moving_source: the never-trained source Q3 ------------------------------------------
@pytest.fixture(scope="session")
def column(tmp_path_factory):
    path = tmp_path_factory.mktemp("col") / "column"
    thermocomp("simulate", "sim=column_moving_source", f"data.path={path}", "track=false")
    out = path.parent / "mon"
    thermocomp("monitor", "sim=column_moving_source", f"data.path={path}", f"out={out}", "track=false")
    truth = json.loads(path.with_name(path.name + ".truth.json").read_text())
    return json.loads((out / "monitor.json").read_text()), truth, out


def test_column_monitor_alarms_only_once_the_new_source_is_on_nearest_sensor_first(column):
    report, truth, out = column
    on = truth["campaigns"]["test_cycle"]["q3_on_s"][0][0]
    bad = [e for e in report["events"]
           if e["to"] in ("alarm", "excluded") and e["sensor"] in report["sensors"]]
    assert bad and min(e["time"] for e in bad) >= on
    # Q3 sits on an unmeasured node: the sensors fewest links away from it
    nearest = truth["novel_sources"][0]["nearest_sensors"]
    assert nearest and bad[0]["sensor"] in nearest
    for t in report["targets"].values():
        assert t["all_finite"] and set(t) >= {"rmse_fixed", "rmse_adaptive", "max_abs_correction"}
    assert {p.name for p in (out / "monitor").iterdir()} >= {"self_prediction.png", "sensor_map.png",
                                                             "compensation.png"}


def test_column_new_source_is_a_new_thermal_state_and_the_deployed_correction_as_scored(column):
    report, truth, _ = column
    on, off = truth["campaigns"]["test_cycle"]["q3_on_s"][0]
    # Q3 moves the sensors either side of it and a far one together: one new thermal state while
    # it is on, not a chain of sensors blamed for it (before: T_right3, T_right4, T_right5,
    # T_edge5, T_right2 excluded, E_X 21.5 -> 29.9 µm, the mid-height point better, paper 002's
    # Fig. 11); whatever went out meanwhile is back before Q3 switches off
    novel = [e for e in report["events"] if e["to"] == NEW_STATE]
    assert len(novel) == 1 and on < novel[0]["time"] < off
    nearest = truth["novel_sources"][0]["nearest_sensors"]
    assert set(nearest) & set(novel[0]["sensors"])
    out = [e for e in report["events"] if e["to"] == "excluded" and e["sensor"] in report["sensors"]]
    back = {e["sensor"] for e in report["events"] if e["from"] == "excluded" and e["time"] < off}
    assert back == {e["sensor"] for e in out}
    # so the deployed correction is the model's: within 5 % of the plain stream on every target
    for t, r in report["targets"].items():
        assert abs(r["rmse_adaptive"] - r["rmse_fixed"]) <= 0.05 * r["rmse_fixed"], t


def _bytes_stdin(text: str):
    """A process's stdin holding ``text``: bytes under a text layer, as ``sys.stdin`` is (the
    monitor decodes ``sys.stdin.buffer`` itself)."""
    import io as text_io

    return text_io.TextIOWrapper(text_io.BytesIO(text.encode()), encoding="utf-8")


def test_monitor_reads_csv_rows_from_stdin(default_dataset, tmp_path, monkeypatch):
    """In this process (a real pipe into a fresh ``thermocomp monitor``: test_docs'
    test_every_key_of_a_real_monitor_json_is_in_the_cli_reference)."""
    test = pd.read_csv(default_dataset / "campaigns.csv").query("split == 'test'")["file"].iloc[0]
    df = pd.read_csv(default_dataset / test)
    df.loc[40:, "T_motor2"] += 50.0
    monkeypatch.setattr("sys.stdin", _bytes_stdin(df.to_csv(index=False)))
    proc = thermocomp("monitor", "monitor.input=-", f"data.path={default_dataset}", f"out={tmp_path}",
                      "track=false", "plots=none", check=False)
    assert proc.returncode == 0, proc.stderr
    report = json.loads((tmp_path / "monitor.json").read_text())
    assert report["campaigns"] == ["stdin"]
    assert report["sensors"]["T_motor2"]["first_alarm"]["campaign"] == "stdin"
    monkeypatch.setattr("sys.stdin", _bytes_stdin("a,b\n1,2\n"))
    proc = thermocomp("monitor", "monitor.input=-", f"data.path={default_dataset}",
                      f"out={tmp_path / 'x'}", "track=false", check=False)
    assert proc.returncode == 2 and "stdin" in proc.stderr and not (tmp_path / "x").exists()
