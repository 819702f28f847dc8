"""What ``model=auto`` keeps per target is exported as code (export57).

``model=auto`` streams as the estimator it kept per target (``estimator_``): one family's, or a
blend ``sum_i w_i * member_i`` of several, its members streamed side by side.  The export
refused it ("AutoRegressor is not one of the linear families"), so the model the README
recommends could not reach the machine.  Now a target's law is the family auto chose, or the
weighted sum of its blend's members' laws (intercepts, gains, input histories, lag banks' taus
side by side with weighted gains; the clamp's gain the weighted gains); a member feeding back
its own output (an AR term) is a law of its own, summed into the target.  A member that is no
linear system is refused naming it and the weights.  The compiled C, the Structured Text and the numpy
reference equal ``replay`` (one test sensor pushed out of the envelope: the clamp acts).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from cbuild import LEVEL
from conftest import refused
from test_export import (
    EVERY_EXCURSION,
    PUSH_C,
    StructuredText,
    _compiled,
    _compose,
    _make_dataset,
    _stdin,
    _streamed,
    needs_cc,
)
from test_export_guard import _spindle_dataset
from thermocomp.apps.deploy.export import NotExportable, Simulator, exported_files, not_in_code, state_space
from thermocomp.apps.deploy.streaming import replay
from thermocomp.core.models import ARX, MLR, PCR, Hammerstein, LagBank
from thermocomp.core.models.auto import AutoRegressor
from thermocomp.core.models.blend import Blend
from thermocomp.shell.builders import build_compensator, deploy_stream
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import save_model
from thermocomp.shell.source import read_streamed

TOLERANCE_UM = 1e-9
# one candidate: auto keeps that family (the spindle record for hammerstein: it reads a state)
SINGLE = {"mlr": (MLR, []), "pcr": (PCR, []),
          "arx": (ARX, ["model.candidate_params={arx:{ar:true,delays:[2]}}"]),
          "lagbank": (LagBank, ["model.candidate_params={lagbank:{n_taus:3}}"]),
          # (stable67: on these 4 short train runs its 2 folds validate no correction lower, 0.77
          # against 0.97 µm: kept as the family this test exports)
          "hammerstein": (Hammerstein, ["model.candidate_params={hammerstein:{lagbank:{n_taus:3}}}",
                                        "model.estimator.uncompensated=keep"])}


@pytest.fixture(scope="module")
def data(tmp_path_factory) -> dict:
    root = tmp_path_factory.mktemp("auto")
    return {"machine": _make_dataset(root / "machine"), "spindle": _spindle_dataset(root / "spindle")}


def deployed(path, *overrides, pushed: str | None = None):
    """``(plain stream as replay deploys it, test campaigns with ``pushed`` (the stream's first
    input by default) pushed out of the envelope half-way, the fitted compensator)``."""
    cfg = _compose(f"data.path={path}", "track=false", "monitor.adaptive=false", EVERY_EXCURSION,
                   *overrides)
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds).fit(train)
    stream = deploy_stream(cfg, comp, train)
    tests = []
    for c in test_ids:
        df = ds.campaigns[c].reset_index(drop=True).copy()
        df.loc[len(df) // 2:, pushed or stream.columns_[0]] += PUSH_C
        tests.append(df)
    return stream, tests, comp


def _deployed(data, dataset: str, *overrides):
    """:func:`deployed` of ``model=auto`` on one of the module's datasets."""
    return deployed(data[dataset], "model=auto", *overrides)


def _proved(stream, tests, folder) -> float:
    """The largest |difference| of the compiled C, the Structured Text and the numpy reference
    from ``replay`` (µm), the clamp acting in every test campaign."""
    streamed = [replay(stream, df) for df in tests]
    assert all(s["n_clamped"].iloc[len(s) // 2:].gt(0).all() for s in streamed)
    expected = np.vstack([-s[stream.targets_].to_numpy(float) for s in streamed])
    cols = stream.columns_
    got = [_streamed(_compiled(stream, folder, LEVEL), _stdin(stream, tests)).to_numpy(float)]
    sim, rows = Simulator(state_space(stream)), []
    fb = StructuredText(exported_files(stream, "st")["compensator.st"])
    st = []
    for df in tests:
        sim.reset()
        for k, (u, t) in enumerate(zip(df[cols].to_numpy(float), df["time"])):
            rows.append(sim.step(u, t))
            st.append(fb(u, t, k == 0))
    got += [np.array(rows), np.array(st)]
    return max(float(np.max(np.abs(g - expected))) for g in got)


@needs_cc
@pytest.mark.parametrize("family", SINGLE)
def test_auto_that_kept_one_family_exports_as_that_family(data, tmp_path, family):
    dataset = "spindle" if family == "hammerstein" else "machine"
    kind, params = SINGLE[family]
    stream, tests, _ = _deployed(data, dataset, f"model.candidates=[{family}]", *params)
    for _, est, _ in stream._plan:
        assert isinstance(est, AutoRegressor) and type(est.estimator_) is kind
    ss = state_space(stream)                                  # refused before
    assert ss.provenance["laws"] == {t: family for t in stream.targets_}
    assert (family == "arx") == (ss.depth == 2) == any(a != 0 for a in ss.ar)
    assert (family in ("lagbank", "hammerstein")) == bool(ss.taus)
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_auto_that_kept_a_blend_exports_the_weighted_sum_of_its_members(data, tmp_path):
    """The folds' votes keep a blend of MLR and the lag bank for at least one target here (as
    voted, ``fallback=none``: with the one-SE fallback no target keeps a blend here)."""
    stream, tests, _ = _deployed(data, "machine", "model.candidates=[mlr,lagbank]",
                                 "model.candidate_params={lagbank:{n_taus:3}}",
                                 "model.estimator.fallback=none")
    blends = {t: est.estimator_ for t, est, _ in stream._plan if isinstance(est.estimator_, Blend)}
    assert blends and all(len(b.estimators_) == 2 for b in blends.values())
    ss = state_space(stream)
    for t, b in blends.items():
        assert ss.provenance["laws"][t] == "blend " + " + ".join(
            f"{n} {w:.4g}" for n, w in zip(b.estimators_, b.weights_))
        i = ss.targets.index(t)          # the intercepts and the clamp's gains, weighted
        assert np.isclose(ss.intercept[i], sum(w * float(e.intercept_) for w, e in
                                               zip(b.weights_, b.estimators_.values())))
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_a_blend_of_every_kind_of_linear_member_streams_as_replay(data, tmp_path):
    """A blend of the chosen weights (``model.estimator.chosen``, as a refit of auto's choice
    fits it): an ARX without AR reading x(t-2), a lag bank, PCR; and a Hammerstein beside MLR."""
    stream, tests, _ = _deployed(
        data, "machine", "model.candidates=[mlr,pcr,arx,lagbank]",
        "model.candidate_params={arx:{ar:false,delays:[2]},lagbank:{n_taus:3}}",
        "+model.estimator.chosen={E_X:{arx:0.5,lagbank:0.3,pcr:0.2},E_Z:{mlr:0.25,lagbank:0.75}}")
    ss = state_space(stream)
    assert ss.depth == 2 and ss.taus and ss.provenance["laws"]["E_Z"] == "blend mlr 0.25 + lagbank 0.75"
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    stream, tests, _ = _deployed(data, "spindle", "model.candidates=[mlr,hammerstein]",
                                 "model.candidate_params={hammerstein:{lagbank:{n_taus:3}}}",
                                 "+model.estimator.chosen={E_X:{mlr:0.4,hammerstein:0.6}}")
    ss = state_space(stream)     # the member's machine state held when missing, in the code too
    assert ss.powers and ss.held[ss.powers[0][0]] == 1
    assert not not_in_code(stream)
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_blend_members_that_feed_back_their_own_outputs_are_laws_of_their_own(data, tmp_path):
    """An ARX and a lag bank with AR terms beside MLR: each member's feedback is on its own
    output (``w a y_i(t-1)``), not on the blend's, so each is a law of its own summed into the
    target; MLR's law carries no feedback."""
    stream, tests, _ = _deployed(
        data, "machine", "model.candidates=[mlr,arx,lagbank]",
        "model.candidate_params={arx:{ar:true,delays:[2]},lagbank:{n_taus:3,ar:true}}",
        "+model.estimator.chosen={E_X:{mlr:0.3,lagbank:0.3,arx:0.4},E_Z:{mlr:0.5,arx:0.5}}")
    fed = {t: {n: e.ar_coef_ for n, e in est.estimators_.items() if getattr(e, "ar_coef_", 0.0)}
           for t, est, _ in stream._plan}
    assert set(fed["E_X"]) == {"arx", "lagbank"} and set(fed["E_Z"]) == {"arx"}
    ss = state_space(stream)                 # refused before: one feedback per target
    assert ss.law_target == [0, 0, 0, 1, 1] and ss.ar[0] == ss.ar[3] == 0.0
    assert sorted(ss.ar[1:3]) == sorted(fed["E_X"].values()) and ss.ar[4] == fed["E_Z"]["arx"]
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


# (exportrest62: arx_rf exports, its forest as arrays; lstmexport62: lstm too, its network as
# arrays; exportati63: both within the ATI wrapper, test_export_ati63.py: every family auto
# blends exports, and a family the export does not know is what is left)
class OwnPCR(PCR):
    """A lab's own estimator: the export knows the families by their exact type (a subclass may
    stream otherwise), so this PCR is a family it does not know."""


def _own_family(est) -> None:
    """``est`` (a fitted PCR) made an :class:`OwnPCR`, all it learned kept."""
    assert type(est) is PCR
    est.__class__ = OwnPCR


def test_a_blend_member_that_does_not_export_is_refused_naming_it_and_the_weights(data):
    stream, _, _ = _deployed(data, "machine", "model.candidates=[mlr,pcr]",
                             "+model.estimator.chosen={E_X:mlr,E_Z:{mlr:0.7,pcr:0.3}}")
    blend = {t: est for t, est, _ in stream._plan}["E_Z"]
    _own_family(getattr(blend, "estimator_", blend).estimators_["pcr"])
    with pytest.raises(NotExportable) as err:
        state_space(stream)
    says = ("blend mlr 0.7 + pcr 0.3 for E_Z", "member pcr (weight 0.3) does not export",
            "OwnPCR is not one of the linear families")
    assert all(s in str(err.value) for s in says), str(err.value)


def test_export_says_what_auto_kept_per_target(data, tmp_path, capsys):
    _, _, comp = _deployed(data, "machine", "model.candidates=[mlr,lagbank]",
                           "model.candidate_params={lagbank:{n_taus:3}}")
    pkl = save_model(comp, tmp_path / "model.pkl")
    out = tmp_path / "plc"
    assert main(["export", f"data.path={data['machine']}", f"export.model={pkl}",
                 "export.format=st", f"out={out}", "track=false"]) == 0
    said = capsys.readouterr().err
    laws = json.loads((out / "compensator.json").read_text())["provenance"]["laws"]
    assert set(laws) == set(comp.targets_)
    for t, est in comp.estimators_.items():
        weights = est.report()["weights"]
        kept = est.family_ if len(weights) == 1 else "blend " + " + ".join(
            f"{n} {w:.4g}" for n, w in zip(est.estimator_.estimators_, est.estimator_.weights_))
        assert laws[t] == kept
        assert f"{t} {kept}" in (out / "compensator.st").read_text() and f"{t} {kept}" in said


def test_auto_that_kept_a_family_the_export_does_not_know_is_refused_naming_it(data, tmp_path,
                                                                              capsys):
    """Not exportable families are still refused, saying auto chose them (exportrest62: not
    arx_rf any more, which exports; lstmexport62: nor lstm; exportati63: nor either within ATI)."""
    _, _, comp = _deployed(data, "machine", "model.candidates=[pcr]")
    _own_family(comp.estimators_["E_X"].estimator_)
    pkl = save_model(comp, tmp_path / "model.pkl")
    refused(["export", f"data.path={data['machine']}", f"export.model={pkl}",
             f"out={tmp_path / 'code'}", "track=false"], capsys, "(auto) cannot be exported",
            "model=auto chose pcr for E_X", "OwnPCR is not one of the linear families")
