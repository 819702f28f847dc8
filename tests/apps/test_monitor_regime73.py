"""A sensor no other predicts, run hotter than training at training's rates, is a regime (range73).

stranger73's grinder: its healthy spindle (no other sensor predicts it) ran longer than in
training and climbed past its training maximum + 10 °C at the rates training saw, no jump; it was
excluded "out of range", held, and its fallback's correction went 26-173 µm off against 8-35 fixed.
Here three structure sensors warming together and a spindle of its own, heating and cooling in
training between 20 and 40 °C; in service it heats on to 58 °C, past 40 + 10."""

from __future__ import annotations

import numpy as np

from thermocomp.apps.deploy.surveillance import SensorMonitor

NAMES = ["T_a", "T_b", "T_c", "T_spindle"]
N = 600


def _spindle(target: np.ndarray) -> np.ndarray:
    """A first-order response (tau 40 samples) from 20 °C to ``target`` per sample."""
    out = np.full(len(target), 20.0)
    for i in range(1, len(target)):
        out[i] = out[i - 1] + (target[i] - out[i - 1]) / 40
    return out


def _record(seed: int, hot: float) -> np.ndarray:
    rng = np.random.default_rng(seed)
    warm = 3 * (1 - np.exp(-np.arange(N) / 200))
    structure = 20 + warm[:, None] * [0.8, 1.0, 1.2]
    target = np.repeat(rng.choice([20.0, hot], N // 100), 100)
    target[:100] = hot
    spindle = _spindle(target)
    return np.column_stack([structure, spindle]) + rng.normal(0, 0.01, (N, 4))


def _stream(record: np.ndarray) -> tuple[SensorMonitor, np.ndarray, list[dict]]:
    mon = SensorMonitor.from_training(None, NAMES, {"a": _record(0, 40.0), "b": _record(1, 40.0)})
    fields, events = [], []
    for i, row in enumerate(record):
        field, ev = mon.update(row, float(i))
        fields.append(field)
        events += ev
    return mon, np.array(fields), events


def test_a_spindle_run_hotter_at_its_training_rates_is_read_as_measured():
    record = _record(2, 40.0)
    record[:, 3] = _spindle(np.full(N, 60.0)) + 0.01 * np.sin(np.arange(N))
    mon, fields, events = _stream(record)
    assert not mon._predictable[3]                               # no other sensor predicts it
    assert record[:, 3].max() > mon.hi_c[3] + mon.range_margin_c  # 58 °C against 40 + 10
    assert not [e for e in events if e["to"] == "excluded"]       # before: out of range, held
    np.testing.assert_allclose(fields[:, 3], record[:, 3] - record[0, 3], atol=1e-9)


def test_a_jump_or_a_climb_faster_than_training_out_of_range_is_still_out():
    for fault in ("jump", "runaway"):
        record = _record(2, 40.0)
        if fault == "jump":
            record[300:, 3] += 30.0                     # past the range in one sample
        else:          # 1 °C a sample (training's fastest 0.5), no step a jump (limit 1.5)
            record[300:, 3] = record[300, 3] + np.arange(N - 300)
        _, _, events = _stream(record)
        out = [e for e in events if e["to"] == "excluded" and e["sensor"] == "T_spindle"]
        assert out[0]["reason"].startswith("out of range"), fault
