"""A gap in the record's time is no one-sample step (probe61).

A machine's log with hours missing between two rows (the logger stopped; or, in ``replay``, a
continued chain whose campaign starts where its probe first measured, the rows before it not
read): the machine warmed meanwhile, every sensor moved by about as much.  The monitor judged
that as a one-sample step shared by most sensors -- the logger's fault -- and re-referenced every
sensor by it, so the deployed correction was off by the warm-up for the rest of the stream
(bench_probe61: the test week's RMSE 4.87 / 7.29 / 5.26 µm against 0.52 / 0.52 / 1.69 for the
plain stream, no event in the report: it happened while the stream was warmed).  Over a gap of
k sampling periods a sensor may move k one-sample steps, as over its own missing samples.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.deploy import AdaptiveCompensator, StreamingCompensator
from thermocomp.apps.deploy.report import stream_rows
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR

N, DT, SENSORS = 360, 60.0, 8


def _campaign(seed: int) -> pd.DataFrame:
    """Eight sensors warming together (gains 0.8-1.2), a gradient; E_X linear in two of them."""
    rng = np.random.default_rng(seed)
    t = np.arange(N) * DT
    warm = 4 * (1 - np.exp(-t / 4000)) + 0.3 * np.sin(t / 2500 + seed)
    gains = np.linspace(0.8, 1.2, SENSORS)
    temps = 20 + warm[:, None] * gains + rng.normal(0, 0.02, (N, SENSORS))
    frame = pd.DataFrame(temps, columns=[f"T_{j}" for j in range(SENSORS)])
    frame.insert(0, "time", t)
    frame["E_X"] = 2.0 * (frame["T_1"] - frame["T_1"][0]) - 1.0 * (frame["T_6"] - frame["T_6"][0]) \
        + rng.normal(0, 0.05, N)
    return frame


@pytest.fixture(scope="module")
def deployed():
    train = {f"K{i}": _campaign(i) for i in range(3)}
    comp = Compensator(MLR()).fit(train)
    stream = StreamingCompensator.from_training(comp, train)
    return stream, AdaptiveCompensator.from_training(stream, train)


@pytest.mark.parametrize("block", [False, True])
def test_rows_after_hours_unlogged_are_not_re_referenced(deployed, block):
    """Rows 20-139 (2 h) not logged, every sensor 0.8-2 K warmer after them: no re-reference, no
    exclusion, the adaptive correction the plain stream's (row by row, and in one go as a
    lead-in is streamed)."""
    stream, adaptive = deployed
    whole = _campaign(7)
    gapped = pd.concat([whole.iloc[:20], whole.iloc[140:]], ignore_index=True)
    step = gapped.iloc[20, 1:1 + SENSORS].to_numpy(float) - gapped.iloc[19, 1:1 + SENSORS].to_numpy(float)
    assert (step > 0.5).all()                 # the warm-up the gap hides: a shared step
    if block:
        adaptive.reset()
        y, _ = adaptive.run_rows(gapped[adaptive.columns_].to_numpy(float),
                                 gapped["time"].to_numpy(float))
        events, got = [], y            # (the block's events are the rows' own: compared below)
    else:
        run = stream_rows(adaptive, gapped)
        events, got = run.events, run.y
    plain = stream_rows(stream, gapped).y
    assert not events, events                # before: 8 sensors re-referenced at the gap's end
    np.testing.assert_allclose(got, plain, atol=1e-9)


def _chain():
    """One record in two files whose second was trimmed where its error was first measured:
    its rows 180-299 (2 h) not read, its time kept on its file's clock (from 10800 s)."""
    from thermocomp.core.io.contract import Dataset

    whole = _campaign(7)
    first = whole.iloc[:180].reset_index(drop=True)
    second = whole.iloc[300:].reset_index(drop=True).assign(time=lambda d: d["time"] - 180 * DT)
    manifest = pd.DataFrame({"split": ["train", "test"],
                             "start": ["2026-11-02T00:00:00", "2026-11-02T03:00:00"]},
                            index=pd.Index(["A", "B"], name="campaign"))
    return Dataset(manifest, {"A": first, "B": second}, name="chain")


def test_a_chain_keeps_the_rows_it_did_not_read_as_a_gap(deployed):
    """The chain joined on its own clock (its ``start``s): 2 h between the two rows read, not
    one sample period; the adaptive stream warmed on it (replay's lead-in) is the plain one."""
    from thermocomp.core.continuation import joined, lead_in

    ds = _chain()
    t = joined(ds, ["A", "B"])["time"].to_numpy(float)
    assert t[180] - t[179] == pytest.approx(121 * DT)       # before: 60 s
    stream, adaptive = deployed
    lead = lead_in(ds, ["A", "B"])
    assert ds.campaigns["B"]["time"].iloc[0] - lead["time"].iloc[-1] == pytest.approx(121 * DT)
    run = stream_rows(adaptive, ds.campaigns["B"], "B", None, lead)
    plain = stream_rows(stream, ds.campaigns["B"], "B", None, lead).y
    assert not run.events and not run.excluded
    np.testing.assert_allclose(run.y, plain, atol=1e-9)       # before: re-referenced in the lead-in


def test_an_abutting_chain_is_joined_as_before():
    """Files that abut on their clock (a record cut in two): one sample period between them."""
    from thermocomp.core.continuation import joined

    ds = _chain()
    ds.campaigns["B"] = _campaign(7).iloc[180:].reset_index(drop=True).assign(
        time=lambda d: d["time"] - 180 * DT)
    t = joined(ds, ["A", "B"])["time"].to_numpy(float)
    assert np.allclose(np.diff(t), DT)


def test_two_machines_weeks_in_one_folder_are_not_chained_across_machines(caplog):
    """Two machines' weekly files (a fleet in one folder, no data.group_by): each week starts
    where both machines' weeks before it end.  Which continues which the times cannot say: none
    is linked, and a line says so (before: PG32's weeks continued PG31's, its state carried over
    from another machine); one machine's weeks alone are chained as before."""
    from thermocomp.core.continuation import predecessors
    from thermocomp.core.io.contract import Dataset

    week = 7 * 86400.0
    frame = pd.DataFrame({"time": np.arange(0.0, week, 3600.0), "T_0": 20.0, "E_X": 0.0})
    ids = [f"{m}_KW{w}" for m in ("PG31", "PG32") for w in (45, 46, 47)]
    starts = [f"2026-11-{2 + 7 * k:02d}T00:00:00" for k in range(3)] * 2
    manifest = pd.DataFrame({"split": "train", "start": starts, "machine": [i[:4] for i in ids]},
                            index=pd.Index(ids, name="campaign"))
    fleet = Dataset(manifest, {c: frame.copy() for c in ids}, name="fleet")
    assert predecessors(fleet) == {}
    assert "which campaign continues which the times cannot say" in caplog.text
    one = Dataset(manifest.iloc[:3], {c: frame.copy() for c in ids[:3]}, name="one")
    assert predecessors(one) == {"PG31_KW46": "PG31_KW45", "PG31_KW47": "PG31_KW46"}
