"""The climate room's lean level laws export as the ambient law's block (diag107b,
benchmarks/bench_diag107b.py).

diag107 made ``diagnose`` take ``ambient_scaled`` (``(A0 - 20) x . w``, ``w`` learned at fit) or
``ambient_mean`` (``w = 1/k``) where the wide law ``x (A0 - 20)`` saturates the campaigns;
``export`` refused them by name, so what diagnose scored could not reach the machine.  One column
``(A0 - 20) x . w`` is the block ``x (A0 - 20)`` with coefficients ``b w``: the code holds it as it
holds the wide law.  On diag107's record (test_diagnose_level107's ``_room``: diagnose takes
``ambient_scaled`` there) the C, the ST and the JSON read back equal ``replay`` to 1e-9 µm, the
clamp acting, alone, beside a lag around a lag bank (its lags of the lean column: the block's), and
beside a step around an ATI model with its interaction (``x (A0 - 20)^2``).
"""

from __future__ import annotations

import io
import json
import subprocess

import numpy as np
import pandas as pd
import pytest

from test_diagnose_level107 import _room
from test_export import StructuredText, _compose, built_stream, needs_cc
from test_export_auto57 import TOLERANCE_UM, _proved
from test_export_effects59 import _json_proved
from thermocomp.apps.deploy.export import NotExportable, exported_files, state_space
from thermocomp.apps.diagnose import AugmentedRegressor
from thermocomp.core.models import MLR, LagBank
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.shell.builders import build_compensator, deploy_stream
from thermocomp.shell.source import read_streamed

SCALED = {"kind": "ambient_interval", "transform": "ambient_scaled"}
MEAN = {"kind": "ambient_interval", "transform": "ambient_mean"}
LAG = {"kind": "dynamics", "transform": "first_order_lag", "column": "T_2", "tau_s": 1800.0}
STEP = {"kind": "ambient_interval", "transform": "ambient_step", "threshold_c": 24.0}


@pytest.fixture(scope="module")
def room(tmp_path_factory):
    """diag107's record (7 sensors and the air, 12 campaigns at 14-34 °C) as files."""
    root = tmp_path_factory.mktemp("lean") / "data"
    root.mkdir()
    ds = _room(7)
    for cid, df in ds.campaigns.items():
        df.to_csv(root / f"{cid}.csv", index=False)
    ds.manifest.reset_index().to_csv(root / "campaigns.csv", index=False)
    return root


def _stream(room, effects: list, base=None) -> tuple:
    """``(stream as replay deploys it, test campaigns with T_1 pushed out half-way)`` of ``base``
    (MLR) with ``effects`` for E_X, the way diagnose's written config builds it."""
    cfg = _compose(f"data.path={room}", "track=false", "monitor.adaptive=false",
                   "promote.envelope.pattern=false")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds).set_params(estimator=AugmentedRegressor(
        base if base is not None else MLR(), effects={"E_X": effects})).fit(train)
    tests = [ds.campaigns[c].reset_index(drop=True).copy() for c in test_ids]
    for df in tests:
        df.loc[len(df) // 2:, "T_1"] += 30.0
    return deploy_stream(cfg, comp, train), tests


@needs_cc
@pytest.mark.parametrize("effects, base, ambient", [
    ([SCALED], None, [0, 1]),
    ([MEAN, LAG], LagBank(n_taus=2), [0, 1]),
    ([STEP, SCALED], ATIRegressor(MLR(), n_intervals=2, ambient_interaction=True), None)],
    ids=["scaled", "mean-lag-lagbank", "step-scaled-ati-interaction"])
def test_a_lean_level_law_exports_as_the_ambient_block_and_equals_replay(room, tmp_path, effects,
                                                                         base, ambient):
    stream, tests = _stream(room, effects, base)
    ss = state_space(stream)                                  # refused before
    if ambient is not None:
        assert ss.law_ambient == ambient                      # the ambient law's, times A0 - 20
    else:                                                     # its block under the interaction
        assert 2 in ss.law_ambient
    assert not any(ss.clamp_outright)                         # clamped by its gain, as streamed
    assert "x (ambient_c0 - 20 degC)" in exported_files(stream, "st")["compensator.st"].split("*)")[0]
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM   # C, ST, numpy; the clamp acting
    assert _json_proved(stream, tests) <= TOLERANCE_UM


def test_an_lstm_under_a_lean_level_law_is_refused_naming_it():
    """Its network reads the one column ``(A0 - 20) x . w``, a sum of the code's features, where
    ``lstm_in`` names one source per column: refused before any array is read (the served model
    runs it)."""
    from thermocomp.apps.deploy.export.derived import Derived, canonical_order
    from thermocomp.apps.deploy.export.recurrent import net_reads
    from thermocomp.apps.diagnose.features import as_effect

    order, factor = canonical_order([as_effect(MEAN)], 2, [0], [None])
    assert order == [0, 1, 2, 2] and factor == [1.0, 1.0, 0.5, 0.5]
    with pytest.raises(NotExportable, match="an lstm under a lean level law"):
        net_reads(None, [0, 1], ["T_1", "T_2"], {}, False, Derived(order=order, factor=factor), 0.0, 0.0)


def _deployed_scaled(data) -> tuple:
    """``(MLR with ambient_scaled on E_X, deployed as export deploys it with its monitor, the
    first test campaign)`` of the record in ``data``."""
    from thermocomp.shell.builders import deployable

    cfg = _compose(f"data.path={data}", "track=false")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds).set_params(estimator=AugmentedRegressor(
        MLR(), effects={"E_X": [SCALED]})).fit(train)
    return deployable(cfg, deploy_stream(cfg, comp, train), train, ds), \
        ds.campaigns[test_ids[0]].reset_index(drop=True)


@needs_cc
def test_the_air_beyond_its_range_from_the_first_sample_gives_the_c_replays_a0(room, tmp_path):
    """(dep108) The monitored air T_amb +30 °C on every row from the campaign's first: replay's
    monitor takes no reference of it and the model reads the training's first reading
    (``first_c``) rebuilt from the others, the campaign's A0 too; the C read the reading itself
    as A0 (11.5 µm off on diag107's record, flagged not in the code).  (dep108f) Where the air
    reads within range again (row 40) replay references it late, its change the field's, and
    re-admits it a window on: the C too (before, 0.064 µm off from row 40 and flagged there), the
    JSON mirror the C's.  No flag in either case.  (st109) The ST starts and references the air
    as the C (before: rows 0-39 refused, the air taken afresh at row 40, 4.3-8.0 um off the C
    there, st108d's ``mon_unsure`` on every row)."""
    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.streaming import replay

    deployed, df = _deployed_scaled(room)
    files = exported_files(deployed, "c")
    inputs = json.loads(files["compensator.json"])["inputs"]
    binary = built_stream(tmp_path, files)
    ss = state_space(deployed, monitor=True)
    for rows in (slice(None), slice(0, 39)):
        pushed = df.copy()
        pushed.loc[rows, "T_amb"] += 30.0
        expected = -replay(deployed, pushed)["E_X"].to_numpy(float)
        feed = pushed[["time", *inputs]].to_csv(index=False, float_format="%.17g")
        out = pd.read_csv(io.StringIO(subprocess.run([str(binary), "--flags"], input=feed, text=True,
                                                     capture_output=True, check=True).stdout))
        c = out["C_X"].to_numpy(float)
        assert np.max(np.abs(c - expected)) <= TOLERANCE_UM
        assert not (out["mon_not_in_code"].to_numpy() > 0).any()
        if rows.stop is not None:
            sim = Simulator(ss)
            sim.reset()
            mirror = [sim.step(u, t)[0] for u, t in zip(pushed[ss.inputs].to_numpy(float),
                                                         pushed["time"].to_numpy(float))]
            assert np.max(np.abs(np.asarray(mirror) - c)) <= TOLERANCE_UM
            # (st109) the ST reads T_amb as the C: its stand-in rebuilt, referenced late at row 40
            st = StructuredText(exported_files(deployed, "st")["compensator.st"])
            readings = zip(pushed[ss.inputs].to_numpy(float), pushed["time"].to_numpy(float))
            off = [abs(st(u, t, i == 0)[0] - mirror[i]) for i, (u, t) in enumerate(readings)]
            assert max(off) <= TOLERANCE_UM
    # (st109b) T_1 +30 on rows 0-39: in range at the first sample, beyond it on rows 18-39, read on by
    # the C (a machine hotter than training) and re-referenced at row 40: the ST says mon_unsure on
    # every row it is off the C (before: rows 60-119 unflagged, 9.8-21.1 um off)
    pushed = df.copy()
    pushed.loc[:39, "T_1"] += 30.0
    sim = Simulator(ss)
    sim.reset()
    unflagged = []
    for i, (u, t) in enumerate(zip(pushed[ss.inputs].to_numpy(float), pushed["time"].to_numpy(float))):
        off = np.max(np.abs(st(u, t, i == 0) - sim.step(u, t)))
        if off > TOLERANCE_UM and not (st.vars["mon_flag"] or st.vars["mon_unsure"] or st.vars["refused"]):
            unflagged.append(i)
    assert unflagged == []



@pytest.fixture(scope="module")
def twinned_room(tmp_path_factory):
    """diag107's record with T_1, T_3, T_5 each read again by a second sensor beside it (T_8-T_10):
    11 monitored (min_active 8 of them), so that the air and two others out leave enough in
    to rebuild it (the served monitor's ``_rebuilds``)."""
    root = tmp_path_factory.mktemp("twinned") / "data"
    root.mkdir()
    ds, noise = _room(7, n_campaigns=6), np.random.default_rng(9)
    for cid, df in ds.campaigns.items():
        for i, twin in ((1, 8), (3, 9), (5, 10)):
            df.insert(df.columns.get_loc("E_X"), f"T_{twin}",
                      df[f"T_{i}"] + 0.02 * noise.standard_normal(len(df)))
        df.to_csv(root / f"{cid}.csv", index=False)
    ds.manifest.reset_index().to_csv(root / "campaigns.csv", index=False)
    return root


@needs_cc
def test_two_sensors_back_from_a_jump_on_the_air_s_return_row_are_no_spike_there(twinned_room, tmp_path):
    """(dep109) The air beyond range from the first sample (rows 0-39), T_1 and T_3 each out for
    a +3 °C jump before its return (rows 34 / 35), both back on row 40 where the air reads within
    range: replay tries no spike's return on a sample with a value not finite (the air's, until
    its late reference) and reads the pair's step as two jumps; the C and its JSON mirror tried
    each as a spike's return first and took them back in (1.44 µm off replay from row 40,
    unflagged, on 348af997)."""
    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.streaming import replay

    deployed, df = _deployed_scaled(twinned_room)
    files, ss = exported_files(deployed, "c"), state_space(deployed, monitor=True)
    df = df.copy()
    df.loc[:39, "T_amb"] += 30.0
    df.loc[34:39, "T_1"] += 3.0
    df.loc[35:39, "T_3"] += 3.0
    expected = -replay(deployed, df)["E_X"].to_numpy(float)
    feed = df[["time", *json.loads(files["compensator.json"])["inputs"]]].to_csv(
        index=False, float_format="%.17g")
    out = pd.read_csv(io.StringIO(subprocess.run([str(built_stream(tmp_path, files)), "--flags"], input=feed,
                                                 text=True, capture_output=True, check=True).stdout))
    sim = Simulator(ss)
    sim.reset()
    mirror = [sim.step(u, t)[0] for u, t in zip(df[ss.inputs].to_numpy(float), df["time"].to_numpy(float))]
    assert not (out["mon_not_in_code"].to_numpy() > 0).any()
    assert np.max(np.abs(out["C_X"].to_numpy(float) - expected)) <= TOLERANCE_UM
    assert np.max(np.abs(np.asarray(mirror) - expected)) <= TOLERANCE_UM
