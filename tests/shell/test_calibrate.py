"""`thermocomp calibrate`: the round trip (core and CLI), and bad artefact data."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import ROOT, refused, simulated
from covering import covering
from thermocomp.apps.sim.volumetric import LargeMillVolumetric, simulate_distances
from thermocomp.apps.volumetric import (
    SETUP_FILE,
    ArtefactCalibration,
    BallArray,
    KinematicModel,
    Setup,
    equivalent_truth,
    position_set,
)
from thermocomp.core import io
from thermocomp.shell.cli import main

# --- core: random geometry -> distances -> parameters -----------------------------------------

@pytest.fixture(scope="session")
def default_calibration():
    model = KinematicModel()
    setup = Setup(model, BallArray(), position_set(ranges=model.ranges, tool=model.tool))
    return setup, ArtefactCalibration(setup).fit()


def test_round_trip_random_parameters_within_2u(default_calibration):
    """Machines drawn at random, each measured with its own artefact (ball errors) and probing
    noise through the full HTM model: >= 95 % of the identified values are within 2 standard
    uncertainties of the truth they can be compared with, and the uncertainties are the spread."""
    setup, cal = default_calibration
    rng = np.random.default_rng(20240)
    truths, distances = [], []
    for _ in range(60):
        truth = rng.normal(0.0, 10.0, (2, len(setup.model.names)))      # µm, µm/m
        balls = setup.ball_um * rng.standard_normal((setup.array.n_balls, 3))
        truths.append(truth)
        distances.append(simulate_distances(setup, truth, rng, balls))
    # the 120 cycles identified at once: each cycle's fit is its own, and one call factorises
    # the noise covariance once instead of 60 times (1.5 s of CPU -> 0.4)
    P, flagged = cal.identify(np.vstack(distances))
    assert not flagged
    z = (P - equivalent_truth(cal, np.vstack(truths))) / cal.uncertainty_
    assert np.mean(np.abs(z) <= 2.0) >= 0.95
    assert 0.9 < np.std(z) < 1.1
    assert np.all(0.75 < np.std(z, axis=0)) and np.all(np.std(z, axis=0) < 1.3)


def test_unidentifiable_parameters_are_named_with_what_they_hide_behind(default_calibration):
    setup, cal = default_calibration
    names = setup.model.names
    assert sorted(cal.names_ + list(cal.unidentifiable_)) == sorted(names)
    basis = setup.model.basis(np.random.default_rng(0).uniform([0, 0, 0], [4000, 1600, 1600], (50, 3)))
    for name, confounded in cal.unidentifiable_.items():
        assert set(confounded) <= set(cal.names_)
        if not confounded:       # no effect on the TCP at all, wherever it is
            assert np.allclose(basis[..., names.index(name)], 0.0)
    # every translation (positioning, straightness, squareness) is seen by S1+S2+S3
    assert all(p.angular for p in setup.model.parameters if p.name in cal.unidentifiable_)


@pytest.mark.parametrize("prior", [False, True])
def test_the_outlier_search_equals_refitting_without_the_distances_it_leaves_out(default_calibration,
                                                                                 prior):
    """A left-out distance is a free offset of its own in the search: the estimate and the
    residuals are those of the GLS (or posterior) refitted from the other distances, with gaps."""
    setup, cal = default_calibration
    if prior:
        from thermocomp.apps.volumetric.design import MachineFamily

        cal = ArtefactCalibration(setup, prior_sd=MachineFamily(setup.model).sd()).fit()
    rng = np.random.default_rng(3)
    truth = rng.normal(0.0, 5.0, (1, len(setup.model.names)))
    d = simulate_distances(setup, truth, rng, setup.ball_um * rng.standard_normal((11, 3)))[0]
    gross = rng.choice(d.size, 6, replace=False)
    d[gross[:4]] += [900.0, -700.0, 300.0, -1000.0]
    d[gross[4:]] = np.nan                                          # not measured
    p, out, capped = cal._robust_cycle(d, np.isfinite(d))
    cols = cal.design_.columns
    assert not capped and {o["column"] for o in out} == {cols[i] for i in gross[:4]}
    keep = np.isfinite(d)
    keep[gross[:4]] = False
    direct, resid, z = cal._masked(d, keep)
    np.testing.assert_allclose(p, direct, rtol=1e-8, atol=1e-9)
    assert np.max(np.abs(z)) <= cal.outlier_z


def test_cycles_with_the_same_gaps_share_one_factorisation(monkeypatch):
    """A column left out of every cycle (excluded, or never measured) gives every cycle the same
    gaps: the noise covariance on them is factorised once, however many cycles are searched
    (it was once per cycle searched: 1 s each for 1430 distances)."""
    from thermocomp.apps.volumetric import identify

    model = KinematicModel()
    setup = Setup(model, BallArray(9, 1500.0, 8.0), position_set(["S2", "S3"], model.ranges, (0.25, 0.75),
                                                                               model.tool))
    factorised, cholesky = [], identify.linalg.cholesky

    def counted(a, **kw):
        factorised.append(a.shape)
        return cholesky(a, **kw)

    monkeypatch.setattr(identify.linalg, "cholesky", counted)
    rng = np.random.default_rng(4)
    D = simulate_distances(setup, rng.normal(0.0, 5.0, (3, len(model.names))), rng,
                           setup.ball_um * rng.standard_normal((9, 3)))
    D[:, 0] = np.nan                                   # never measured
    D[:, 7] += 1000.0                                  # a gross error in every cycle: searched
    counts = []
    for cycles in (1, 3):
        cal = ArtefactCalibration(setup).fit()
        factorised.clear()
        _, flagged = cal.identify(D[:cycles])
        assert [f["cycle"] for f in flagged] == list(range(cycles))
        counts.append(len(factorised))
    assert counts[0] == counts[1]


@pytest.mark.parametrize("prior", [False, True])
def test_many_lone_gross_errors_are_found_by_the_closure_test_when_they_swamp_the_fit(prior):
    """A 9-ball bar in 20 poses (720 distances), 39 of them 1 mm off: the studentised search
    leaves out good distances with them (and reaches the cap without a prior); the mean-shift
    (closure) test finds exactly the 39, and the estimate is the refit without them."""
    from thermocomp.apps.volumetric.design import MachineFamily

    model = KinematicModel()
    setup = Setup(model, BallArray(9, 1500.0, 8.0), position_set(["S2", "S3"], model.ranges, (0.25, 0.75),
                                                                               model.tool))
    cal = ArtefactCalibration(setup, prior_sd=MachineFamily(model).sd() if prior else None).fit()
    rng = np.random.default_rng(0)
    for _ in range(3):
        truth = rng.normal(0.0, 5.0, (1, len(model.names)))
        d = simulate_distances(setup, truth, rng, setup.ball_um * rng.standard_normal((9, 3)))[0]
        bad = rng.choice(d.size, 39, replace=False)
        d[bad] += 1000.0
        mask = np.isfinite(d)
        _, first, capped, swamped = cal._marginal_search(d, mask, cal._whitener(mask))
        # swamped: the studentised search reaches the cap, or (a prior holding the fit) leaves
        # out good distances with the bad, and says so
        assert swamped and (capped or len(first) > len(bad))
        p, out, capped = cal._robust_cycle(d, mask)
        assert not capped and {o["column"] for o in out} == {cal.design_.columns[i] for i in bad}
        keep = mask.copy()
        keep[bad] = False
        np.testing.assert_allclose(p, cal._masked(d, keep)[0], rtol=1e-6, atol=1e-6)


def test_the_closure_test_is_the_mean_shift_t_of_each_distance():
    """The incremental closure search against the test computed from scratch at every step:
    t_i = w_i' r / sqrt(w_i' (I - H) w_i), w_i the whitened unit vector of distance i, H the hat
    matrix of the whitened design with a column per distance left out."""
    model = KinematicModel()
    setup = Setup(model, BallArray(9, 1500.0, 8.0), position_set(["S2", "S3"], model.ranges, (0.25, 0.75),
                                                                               model.tool))
    cal = ArtefactCalibration(setup).fit()
    rng = np.random.default_rng(5)
    d = simulate_distances(setup, rng.normal(0.0, 5.0, (1, len(model.names))), rng,
                           setup.ball_um * rng.standard_normal((9, 3)))[0]
    d[rng.choice(d.size, 12, replace=False)] += rng.uniform(-50.0, 50.0, 12)
    mask = np.isfinite(d)
    linv = cal._whitener(mask)
    _, out, _ = cal._closure_search(d, mask, linv)
    A = cal.design_.A[:, cal.kept_]
    cols = cal.design_.columns
    left = []
    for o in out:
        E = np.eye(d.size)[:, left]
        Q, _ = np.linalg.qr(linv @ np.hstack([A, E]))
        r = linv @ d - Q @ (Q.T @ (linv @ d))
        with np.errstate(divide="ignore", invalid="ignore"):       # the left out: no test
            t = (linv.T @ r) / np.sqrt(np.sum(linv ** 2, 0) - np.sum((Q.T @ linv) ** 2, 0))
        t[left] = 0.0
        worst = int(np.argmax(np.abs(t)))
        assert cols[worst] == o["column"] and t[worst] == pytest.approx(o["z"], rel=1e-6)
        left.append(worst)
    assert len(out) >= 10


def test_a_prior_shares_what_the_poses_cannot_see_and_its_uncertainties_hold():
    """Machines drawn from a family, measured with the sparse aligned S2 set (15 of 33
    parameters seen): with the family as prior every parameter is estimated, the error over
    the volume is a fraction of GLS's (which leaves the unseen at 0 and gives the faintly seen
    the noise), and the posterior uncertainties are the spread of the errors."""
    from thermocomp.apps.volumetric.design import MachineFamily, measure
    from thermocomp.apps.volumetric.kinematics import workspace_grid

    model = KinematicModel()
    family = MachineFamily(model)
    truth = family.draw([(5, i) for i in range(40)])
    setup = Setup(model, BallArray(11, 1500.0, 0.0), position_set(["S2"], model.ranges, (0.25, 0.75),
                                                                             model.tool))
    D = measure(model, truth, setup, [np.random.default_rng((6, i)) for i in range(len(truth))])
    basis = model.basis(workspace_grid(model, (10, 5, 5)))
    vce, z = {}, None
    for name, prior in (("gls", None), ("prior", family.sd())):
        cal = ArtefactCalibration(setup, outlier_z=np.inf, prior_sd=prior).fit()
        est = cal.full(cal.identify(D)[0])
        err = np.einsum("nip,kp->kni", basis, est - truth)
        vce[name] = np.median(np.sqrt(np.mean(np.sum(err ** 2, -1), -1)))
        if prior is not None:
            assert cal.names_ == model.names and len(cal.seen_) < len(model.names) / 2
            z = (est - truth) / cal.uncertainty_
    assert vce["prior"] < 0.5 * vce["gls"]
    assert 0.8 < np.std(z) < 1.2 and np.mean(np.abs(z) <= 2) >= 0.95
    with pytest.raises(ValueError, match="prior_sd"):
        ArtefactCalibration(setup, prior_sd=np.ones(3)).fit()


def test_a_prior_narrower_than_the_machine_biases_what_the_poses_see():
    """Noiseless distances of machines every pose set sees (S1+S2+S3, 15°): GLS recovers the
    volume's error exactly, the family's own prior nearly so, a prior ten times too narrow
    pulls the parameters towards 0 against the distances."""
    from thermocomp.apps.volumetric.design import MachineFamily, measure
    from thermocomp.apps.volumetric.kinematics import workspace_grid

    model = KinematicModel()
    family = MachineFamily(model)
    truth = family.draw([(7, i) for i in range(10)])
    setup = Setup(model, BallArray(11, 1500.0, 15.0), position_set(["S1", "S2", "S3"], model.ranges,
                                                                    (0.25, 0.75), model.tool), 0.0, 0.0)
    D = measure(model, truth, setup, [np.random.default_rng((8, i)) for i in range(len(truth))])
    basis = model.basis(workspace_grid(model, (10, 5, 5)))

    def vce(prior):
        cal = ArtefactCalibration(setup, outlier_z=np.inf, prior_sd=prior).fit()
        err = np.einsum("nip,kp->kni", basis, cal.full(cal.identify(D)[0]) - truth)
        return np.median(np.sqrt(np.mean(np.sum(err ** 2, -1), -1)))

    assert vce(None) < 0.01 and vce(family.sd()) < 0.05 and vce(family.sd() / 10) > 0.5


# --- the CLI on a small simulated dataset ------------------------------------------------------

@pytest.fixture(scope="session")
def raw(tmp_path_factory):
    """A small volumetric dataset (6 h + 4 h, a cycle every 20 min) and its truth."""
    gen = LargeMillVolumetric(train_hours=6.0, test_hours=4.0, seed=0)
    return simulated(gen, tmp_path_factory.mktemp("vol") / "raw")


def copy(raw, tmp_path, truth=True):
    dest = tmp_path / "raw"
    shutil.copytree(raw, dest)
    if truth:
        shutil.copy(f"{raw}.truth.json", f"{dest}.truth.json")
    return dest


def calibrate(data, out, *extra):
    code = main(["calibrate", f"data.path={data}", f"out={out}", "track=false", *extra])
    assert code in (0, None)
    return json.loads((out / "calibration.json").read_text())


def run(data, out, *extra):
    """`thermocomp run` of the volumetric experiment, without figures, the slow baselines or the
    validation folds (what is asserted here is the calibration's, and that the run fits)."""
    assert main(["run", "experiment=volumetric_large_mill", f"data.path={data}", f"out={out}",
                 "track=false", "plots=none", "eval.mutual_prediction=false", "eval.ati_baselines=false",
                 "eval.validation=false", *extra]) == 0


def edit(data, campaign, fn):
    f = data / f"{campaign}.parquet"
    df = pd.read_parquet(f)
    fn(df)
    df.to_parquet(f, index=False)


def assign(df, columns, values) -> None:
    """``df[columns] = values`` written at once: pandas sets a list of columns one by one (and
    ``df.update`` is slower still), ~0.5 s of CPU on a campaign's 1430 distance columns."""
    df.loc[:, columns] = values


def _setup(raw):
    return Setup.from_dict(json.loads((raw / SETUP_FILE).read_text()))


@pytest.fixture(scope="session")
def clean(raw, tmp_path_factory):
    out = tmp_path_factory.mktemp("clean")
    return calibrate(raw, out), out


def test_calibration_json_and_the_parameter_dataset(raw, clean, capsys):
    report, out = clean
    setup = _setup(raw)
    cal = ArtefactCalibration(setup).fit()
    assert list(report)[:2] == ["parameters", "roundtrip"]
    assert set(report["parameters"]) == set(cal.names_)
    for name, p in report["parameters"].items():
        assert p["unit"] == ("µm/m" if name[2] in "ABC" else "µm") and p["uncertainty"] > 0
    assert set(report["roundtrip"]) >= {"n_parameters", "max_abs_z", "share_within_2u"}
    assert {k: set(v) for k, v in report["unidentifiable"].items()} == {
        k: set(v) for k, v in cal.unidentifiable_.items()}        # (ties in any order)
    assert report["outliers"] == [] and report["excluded"] == []
    assert report["poses"] == [p.name for p in setup.poses]
    ds, _ = io.read_dataset(out / "parameters")
    raw_ds, _ = io.read_dataset(raw)
    assert list(ds.manifest.index) == list(raw_ds.manifest.index)
    assert dict(ds.manifest["split"]) == {"train_week": "train", "validation_week": "test"}
    truth = json.loads(raw.with_name("raw.truth.json").read_text())
    z = []
    for cid, df in ds.campaigns.items():
        assert [c for c in df.columns if c.startswith("E_")] == cal.names_
        T = [c for c in raw_ds.campaigns[cid].columns if c.startswith("T_")]
        assert np.array_equal(df[T].to_numpy(), raw_ds.campaigns[cid][T].to_numpy())
        full = np.column_stack([truth["campaigns"][cid]["parameters"][n] for n in setup.model.names])
        z.append((df[cal.names_].to_numpy() - equivalent_truth(cal, full)) / cal.uncertainty_)
    z = np.vstack(z)
    rt = report["roundtrip"]
    # the round trip is the dataset's against its truth, every parameter and cycle
    assert rt["n_parameters"] == len(cal.names_)
    assert rt["max_abs_z"] == pytest.approx(np.max(np.abs(z)))
    assert rt["share_within_2u"] == pytest.approx(np.mean(np.abs(z) <= 2))
    # one artefact for the whole dataset: its ball errors bias each parameter for every cycle,
    # so the dataset's z spread is that of ~22 draws; still of unit size
    assert 0.6 < rt["z_sd"] < 1.5


def test_a_prior_estimates_every_parameter_and_fits_the_distances_as_well(raw, clean, tmp_path, capsys):
    report, _ = clean
    out = tmp_path / "out"
    capsys.readouterr()
    prior = calibrate(raw, out, "calibrate.prior=${design.ranges}")
    assert "all 33 parameters estimated with calibrate.prior (11 not seen" in capsys.readouterr().out
    setup = _setup(raw)
    ranges = yaml.safe_load((ROOT / "conf" / "design" / "default.yaml").read_text())["ranges"]
    assert prior["prior"] == ranges and report["prior"] is None
    assert list(prior["parameters"]) == setup.model.names
    assert prior["unidentifiable"] == report["unidentifiable"]       # what the distances see
    assert prior["roundtrip"]["n_parameters"] == len(setup.model.names)
    # the prior shares out what the distances cannot tell apart; it does not fight them
    assert prior["residual_rms_um"] < 1.1 * report["residual_rms_um"]
    ds, _ = io.read_dataset(out / "parameters")
    assert [c for c in ds.campaigns["train_week"].columns if c.startswith("E_")] == setup.model.names


def test_the_residual_scatter_is_checked_against_the_declared_uncertainties(raw, clean, tmp_path, capsys):
    # distances in mm calibrated silently (residual 0.001 µm against 0.5 µm probing), and
    # uncertainties declared 4x too small flagged thousands of "outliers", without a word
    fit = clean[0]["fit"]
    assert fit["consistent"] and 0.8 < fit["rms_ratio"] < 1.25      # seeds 0-7: 0.89-1.19
    assert fit["rms_ratio"] == pytest.approx(clean[0]["residual_rms_um"] / fit["expected_rms_um"])
    lo, hi = fit["accepted"]
    assert lo == pytest.approx(0.5, abs=0.05) and hi == 2.0      # the factor 2 decides here
    data = copy(raw, tmp_path, truth=False)
    for cid in ("train_week", "validation_week"):
        edit(data, cid, lambda df: assign(df, cols := list(df.filter(like="E_S")), df[cols] / 1e3))
    capsys.readouterr()
    fit = calibrate(data, tmp_path / "mm")["fit"]
    assert not fit["consistent"] and fit["rms_ratio"] < 0.01
    assert "another unit than µm" in capsys.readouterr().err
    run(data, tmp_path / "run")
    assert "another unit than µm" in capsys.readouterr().err
    # declared 2.5x too small: the outlier search leaves out what they make look gross, the
    # rest still scatter 2.7x; 4x too small, a tenth of the distances are "gross": refused
    data = copy(raw, tmp_path / "small_u", truth=False)
    setup = json.loads((data / SETUP_FILE).read_text())
    for u, says in ((0.2, None), (0.125, "uncertainty_um (declared too small?)")):
        setup["uncertainty_um"] = {"probing": u, "ball": u}
        (data / SETUP_FILE).write_text(json.dumps(setup))
        if says:
            refused(["calibrate", f"data.path={data}", f"out={tmp_path / 'u'}", "track=false"], capsys, says)
            continue
        fit = calibrate(data, tmp_path / "u")["fit"]
        assert not fit["consistent"] and fit["rms_ratio"] > 2
        assert "or the uncertainties in volumetric.json wrong" in capsys.readouterr().err


def test_no_truth_no_round_trip(raw, tmp_path):
    data = copy(raw, tmp_path, truth=False)
    report = calibrate(data, tmp_path / "out")
    assert "roundtrip" not in report and "parameters" in report


@pytest.mark.parametrize("truth", ["{oops", "[]"])
def test_a_malformed_truth_file_costs_the_round_trip_not_the_run(raw, tmp_path, capsys, truth):
    # a traceback (JSONDecodeError, 'list' object has no attribute 'get'), exit 1, before
    data = copy(raw, tmp_path, truth=False)
    Path(f"{data}.truth.json").write_text(truth)
    report = calibrate(data, tmp_path / "out")
    assert "roundtrip" not in report and "parameters" in report
    assert f"{data}.truth.json is no" in capsys.readouterr().err


def test_one_distance_off_by_1_mm_is_an_outlier_of_its_cycle(raw, clean, tmp_path):
    data = copy(raw, tmp_path)
    column = "E_S2x1d3_B04_B09"
    edit(data, "validation_week",
         lambda df: df.__setitem__(column, df[column] + np.r_[0, 0, 1000.0, np.zeros(len(df) - 3)]))
    report = calibrate(data, tmp_path / "out")
    [o] = report["outliers"]
    assert (o["campaign"], o["row"], o["pose"], o["balls"], o["column"]) == (
        "validation_week", 3, "S2x1d3", [4, 9], column)
    assert o["residual_um"] == pytest.approx(1000.0, abs=20) and o["z"] > 6
    assert report["excluded"] == []
    # the cycle is identified from its other distances: as without the bad one
    ref, ref_out = clean
    names = list(ref["parameters"])
    u = np.array([ref["parameters"][n]["uncertainty"] for n in names])
    a = pd.read_parquet(tmp_path / "out" / "parameters" / "validation_week.parquet")[names]
    b = pd.read_parquet(ref_out / "parameters" / "validation_week.parquet")[names]
    assert np.all(np.abs(a.iloc[2] - b.iloc[2]) < 0.5 * u)
    assert np.array_equal(a.drop(index=2).to_numpy(), b.drop(index=2).to_numpy())


def _misprobed(setup, pose_index, ball, shift_um):
    """The distance deviations (column -> µm) of ball ``ball`` (0-based) probed ``shift_um`` off
    in pose ``pose_index``: every distance to it moves along its own direction."""
    pose = setup.poses[pose_index]
    balls = pose.balls(setup.array)
    hit = {}
    for j in range(setup.array.n_balls):
        if j != ball:
            i1, j1 = sorted((ball, j))
            u = (balls[j1] - balls[i1]) / np.linalg.norm(balls[j1] - balls[i1])
            hit[f"E_{pose.name}_B{i1 + 1:02d}_B{j1 + 1:02d}"] = (1 if j1 == ball else -1) * u @ shift_um
    return hit


def _corrupt_one_cycle(raw, tmp_path, hit):
    """Calibrate a copy of ``raw`` whose 4th training cycle has ``hit`` (column -> µm) added;
    check that exactly those distances are outliers, all of that cycle; the report."""
    data = copy(raw, tmp_path)

    def corrupt(df):
        for col, dd in hit.items():
            df.loc[3, col] += dd
    edit(data, "train_week", corrupt)
    report = calibrate(data, tmp_path / "out")
    assert {o["column"] for o in report["outliers"]} == set(hit)
    assert {(o["campaign"], o["row"]) for o in report["outliers"]} == {("train_week", 4)}
    return report


def _cycle_as_clean(clean, out, campaign, row):
    """Max |identified - clean| / u over the parameters in one cycle (0-based row)."""
    ref, ref_out = clean
    names = list(ref["parameters"])
    u = np.array([ref["parameters"][n]["uncertainty"] for n in names])
    a = pd.read_parquet(out / "parameters" / f"{campaign}.parquet")[names]
    b = pd.read_parquet(ref_out / "parameters" / f"{campaign}.parquet")[names]
    return float(np.max(np.abs(a.iloc[row] - b.iloc[row]) / u))


def test_a_ball_probed_50_um_off_flags_its_distances_in_that_pose_and_cycle_only(raw, clean, tmp_path):
    """A mis-probed centre moves every distance of its ball in that pose, each along its own
    direction: those ten are the cycle's outliers, and the cycle is identified without them."""
    setup = _setup(raw)
    hit = _misprobed(setup, 5, 4, 50.0 * np.array([1.0, -1.0, 0.5]) / 1.5)   # ball 5, |shift| 50 µm
    _corrupt_one_cycle(raw, tmp_path, hit)
    assert _cycle_as_clean(clean, tmp_path / "out", "train_week", 3) < 0.5


def test_mis_probed_balls_and_lone_errors_in_one_cycle_are_told_apart(raw, clean, tmp_path):
    """One cycle with two balls mis-probed in two poses, a third mis-probed in a pose that also
    has a lone 1 mm error, and six lone 1 mm errors elsewhere: exactly those 37 distances are
    its outliers, no other cycle has any, and the cycle is identified as without them."""
    setup = _setup(raw)
    hit = {**_misprobed(setup, 5, 4, 50.0 * np.array([1.0, -1.0, 0.5]) / 1.5),
           **_misprobed(setup, 12, 7, 40.0 * np.array([-0.3, 1.0, 1.0]) / 1.45)}
    third = _misprobed(setup, 20, 2, 60.0 * np.array([0.6, 0.5, 0.62]))
    assert min(abs(v) for v in third.values()) > 30             # along the bar, not across it
    hit.update(third)
    lone = f"E_{setup.poses[20].name}_B05_B09"                  # not a distance to ball 3
    hit[lone] = 1000.0
    columns = setup.columns()
    rng = np.random.default_rng(0)
    for c in rng.choice([c for c in columns if c not in hit], 6, replace=False):
        hit[c] = float(rng.choice([-1000.0, 1000.0]))
    assert len(hit) == 37
    report = _corrupt_one_cycle(raw, tmp_path, hit)
    assert report["excluded"] == []
    assert _cycle_as_clean(clean, tmp_path / "out", "train_week", 3) < 0.5


def test_a_whole_column_off_by_1_mm_is_excluded_and_named(raw, clean, tmp_path):
    data = copy(raw, tmp_path)
    column = "E_S1x2d1_B01_B11"
    for cid in ("train_week", "validation_week"):
        edit(data, cid, lambda df: df.__setitem__(column, df[column] - 1000.0))
    report = calibrate(data, tmp_path / "out")
    [x] = report["excluded"]
    assert (x["column"], x["pose"], x["balls"]) == (column, "S1x2d1", [1, 11])
    assert x["cycles_flagged"] == report["n_cycles"] and x["share"] == 1.0
    assert report["outliers"] == []             # once excluded, no cycle flags it again
    ref, _ = clean
    u = np.array([ref["parameters"][n]["uncertainty"] for n in ref["parameters"]])
    for cid in ("train_week", "validation_week"):
        a = pd.read_parquet(tmp_path / "out" / "parameters" / f"{cid}.parquet")[list(ref["parameters"])]
        b = pd.read_parquet(clean[1] / "parameters" / f"{cid}.parquet")[list(ref["parameters"])]
        assert np.all(np.abs(a.to_numpy() - b.to_numpy()) < 0.5 * u)
    # with a share above what the column reached, it is flagged cycle by cycle instead
    report = calibrate(data, tmp_path / "out2", "calibrate.column_share=1.0")
    assert report["excluded"] == [] and len(report["outliers"]) == report["n_cycles"]
    assert {o["column"] for o in report["outliers"]} == {column}


def test_a_twentieth_of_the_columns_off_in_every_cycle_are_all_excluded(raw, clean, tmp_path):
    """72 of the 1430 columns off by +-1 mm in every cycle (each cycle's search leaves out 72
    distances): every one is excluded and named, no other, and the parameters are the clean
    dataset's."""
    data = copy(raw, tmp_path)
    ref, ref_out = clean
    cols = list(np.random.default_rng(11).choice(
        [c for c in pd.read_parquet(raw / "train_week.parquet").columns if c.startswith("E_")], 72,
        replace=False))
    sign = np.where(np.arange(72) % 2, 1000.0, -1000.0)
    for cid in ("train_week", "validation_week"):
        edit(data, cid, lambda df: assign(df, cols, df[cols] + sign))
    report = calibrate(data, tmp_path / "out")
    assert sorted(x["column"] for x in report["excluded"]) == sorted(cols)
    assert report["outliers"] == []
    names = list(ref["parameters"])
    u = np.array([ref["parameters"][n]["uncertainty"] for n in names])
    for cid in ("train_week", "validation_week"):
        a = pd.read_parquet(tmp_path / "out" / "parameters" / f"{cid}.parquet")[names]
        b = pd.read_parquet(ref_out / "parameters" / f"{cid}.parquet")[names]
        assert np.all(np.abs(a.to_numpy() - b.to_numpy()) < 0.5 * u)


def test_distances_that_do_not_fit_the_setup_at_all_are_refused_before_every_cycle_is_searched(
        raw, tmp_path, capsys):
    # deviations against a wrong certificate: every column off by its own 0.2-1 mm, every cycle
    data = copy(raw, tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    (out / "calibration.json").write_text("old")
    rng = np.random.default_rng(0)
    cols = [c for c in pd.read_parquet(data / "train_week.parquet").columns if c.startswith("E_S")]
    offset = dict(zip(cols, rng.choice([-1, 1], len(cols)) * rng.uniform(200, 1000, len(cols))))
    for cid in ("train_week", "validation_week"):
        edit(data, cid, lambda df: assign(df, cols, df[cols] + pd.Series(offset)))
    line = refused(["calibrate", f"data.path={data}", f"out={out}", "track=false"], capsys,
                   "do not fit", SETUP_FILE, "campaign train_week, row 1", "calibrate.outlier_z=inf")
    pose, i, j = re.search(r"worst pose (\w+) balls (\d+)-(\d+)", line).groups()
    assert f"E_{pose}_B{int(i):02d}_B{int(j):02d}" in offset
    _untouched(out)
    # fitted as they are on request: nothing flagged, and the residual shows the misfit
    report = calibrate(data, out, "calibrate.outlier_z=inf")
    assert report["outliers"] == [] and report["residual_rms_um"] > 100


def test_gaps_in_a_cycle_are_fitted_from_what_was_measured_and_an_empty_cycle_is_refused_by_row(
        raw, clean, tmp_path, capsys):
    data = copy(raw, tmp_path)
    df = pd.read_parquet(data / "validation_week.parquet")
    pose = [c for c in df.columns if c.startswith("E_S2x1d2_")]
    ball = [c for c in df.columns if c.startswith("E_S3x2d1_") and "_B05" in c]

    def blank(df):
        df.loc[3, pose] = np.nan                      # a pose not measured in one cycle
        df.loc[5:8, ball] = np.nan                    # a ball not probed in four

    edit(data, "validation_week", blank)
    report = calibrate(data, tmp_path / "out")
    names = list(report["parameters"])
    a = pd.read_parquet(tmp_path / "out" / "parameters" / "validation_week.parquet")[names]
    b = pd.read_parquet(clean[1] / "parameters" / "validation_week.parquet")[names]
    u = np.array([clean[0]["parameters"][n]["uncertainty"] for n in names])
    gaps = [3, 5, 6, 7, 8]
    assert np.isfinite(a.to_numpy()).all()
    assert np.all(np.abs(a.iloc[gaps] - b.iloc[gaps]) < 3 * u)         # from the other distances
    assert np.array_equal(a.drop(index=gaps).to_numpy(), b.drop(index=gaps).to_numpy())
    # a cycle with no distance at all: refused naming its file and row, nothing written
    every = [c for c in df.columns if c.startswith("E_S")]

    def empty(df):
        df.loc[11, every] = np.nan

    edit(data, "validation_week", empty)
    out = tmp_path / "out2"
    refused(["calibrate", f"data.path={data}", f"out={out}", "track=false"], capsys,
            "validation_week.parquet", "row 12", f"0 of the {len(every)} distances")
    _untouched(out)


def test_an_empty_temperature_cell_follows_the_rules_of_any_dataset(raw, clean, tmp_path, capsys):
    # an empty T_ cell is no distance left unmeasured: it was written into the parameter series
    # (then `run` crashed in the fit) and `ingest` named its own temporary file
    data = copy(raw, tmp_path)
    col = next(c for c in pd.read_parquet(data / "train_week.parquet").columns if c.startswith("T_"))
    edit(data, "train_week", lambda df: df.__setitem__(col, df[col].where(df.index != 5)))
    for args in (["calibrate", f"out={tmp_path / 'out'}"], ["ingest", f"data.interim={tmp_path / 'int'}"],
                 ["run", "experiment=volumetric_large_mill", f"out={tmp_path / 'run'}"]):
        refused([*args, f"data.path={data}", "track=false"], capsys,
                f"{data / 'train_week.parquet'}", f"column '{col}'", "row 6", "data.max_gap_samples=0")
    _untouched(tmp_path / "out")
    # interpolated as for any dataset when data.max_gap_samples allows it
    report = calibrate(data, tmp_path / "out", "data.max_gap_samples=1")
    assert report["repairs"] == {col: 1} and report["trimmed"] == {}
    series = pd.read_parquet(tmp_path / "out" / "parameters" / "train_week.parquet")
    before = pd.read_parquet(raw / "train_week.parquet")[col]
    assert series[col][5] == pytest.approx((before[4] + before[6]) / 2)
    names = list(report["parameters"])
    assert np.array_equal(series[names].to_numpy(),
                          pd.read_parquet(clean[1] / "parameters" / "train_week.parquet")[names].to_numpy())
    # an empty first cell is an incomplete edge: trimmed on request, the rows named are the file's
    edit(data, "train_week", lambda df: df.__setitem__(col, df[col].where(df.index != 0)))
    edit(data, "train_week", lambda df: df.__setitem__("E_S1x1d1_B01_B02", df["E_S1x1d1_B01_B02"]
                                                        + np.where(df.index == 2, 1e3, 0.0)))
    report = calibrate(data, tmp_path / "out2", "data.max_gap_samples=1", "data.max_edge_samples=1")
    assert report["trimmed"] == {"train_week": {"start": 1, "end": 0}}
    assert report["campaigns"]["train_week"] == len(before) - 1
    assert [o["row"] for o in report["outliers"]] == [3]        # the file's row, not the cycle's
    run(data, tmp_path / "run", "data.max_gap_samples=1", "data.max_edge_samples=1")


def _untouched(out):
    assert not out.exists() or (out / "calibration.json").read_text() == "old"


@pytest.mark.parametrize("name, says", [
    ("E_S1x1d1_B00_B05", "ball 0: the balls are numbered 1 to 11"),
    ("E_S1x1d1_B07_B03", "balls 7 and 3: write the lower ball first (E_S1x1d1_B03_B07)"),
    ("E_S1x1d1_B3_B7", "balls 3 and 7: ball numbers have 2 digits (E_S1x1d1_B03_B07)"),
    ("E_S1x1d1_B04_B04", "ball 4 twice"),
    ("E_S9x1d1_B01_B02", "pose S9x1d1 not declared"),
    # were dropped unsaid: an offset column, a lower-case b
    ("E_Xoffset", "is a distance deviation named E_<pose>_B<i>_B<j>"),
    ("E_S1x1d1_b01_b02", "is a distance deviation named E_<pose>_B<i>_B<j>"),
])
def test_a_misnamed_distance_column_is_named_with_what_is_wrong(raw, tmp_path, capsys, name, says):
    data = copy(raw, tmp_path, truth=False)
    right = "E_S1x1d1_B03_B07"
    edit(data, "train_week", lambda df: df.rename(columns={right: name} if name.startswith(
        ("E_S1x1d1_B07", "E_S1x1d1_B3_")) else {}, inplace=True) or df.__setitem__(name, 0.0))
    refused(["calibrate", f"data.path={data}", f"out={tmp_path / 'out'}", "track=false"], capsys,
            f"file {data / 'train_week.parquet'}", f"column '{name}'", says)
    _untouched(tmp_path / "out")


def test_a_missing_pose_is_refused_naming_it(raw, tmp_path, capsys):
    data = copy(raw, tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    (out / "calibration.json").write_text("old")
    edit(data, "validation_week",
         lambda df: df.drop(columns=[c for c in df.columns if c.startswith("E_S3x2d4_")], inplace=True))
    refused(["calibrate", f"data.path={data}", f"out={out}", "track=false"], capsys,
            "pose S3x2d4", "validation_week.parquet")
    _untouched(out)
    assert not (out / "parameters").exists()


def _keep_poses(data, keep):
    setup = json.loads((data / SETUP_FILE).read_text())
    setup["poses"] = [p for p in setup["poses"] if p["name"] in keep]
    (data / SETUP_FILE).write_text(json.dumps(setup))
    for cid in ("train_week", "validation_week"):
        edit(data, cid, lambda df: df.drop(columns=[c for c in df.columns if c.startswith("E_")
                                                    and c.split("_")[1] not in keep], inplace=True))


def test_too_few_poses_are_refused_naming_what_they_cannot_see(raw, tmp_path, capsys):
    data = copy(raw, tmp_path)
    out = tmp_path / "out"
    _keep_poses(data, {"S1x1d1", "S1x1d2", "S1x1d3"})            # the three axes, once
    line = refused(["calibrate", f"data.path={data}", f"out={out}", "track=false"], capsys,
                   "S1x1d1, S1x1d2, S1x1d3", "cannot see", "E_XY1 (straightness)", SETUP_FILE)
    assert "E_XX1" not in line                   # the positioning errors the axes do see
    _untouched(out)
    # only the volume diagonals: the positioning of Y is not seen
    data = copy(raw, tmp_path / "s2")
    _keep_poses(data, {f"S2x{i}d{k}" for i in (1, 2) for k in (1, 2, 3, 4)})
    refused(["calibrate", f"data.path={data}", f"out={out}", "track=false"], capsys,
            "E_YY1 (positioning)", "S2x1d1")
    _untouched(out)
    # accepted on request: what they cannot see is then named in calibration.json
    report = calibrate(data, out, "calibrate.require_seen=[]")
    assert "E_YY1" in report["unidentifiable"] and "E_YY1" not in report["parameters"]


def test_poses_that_see_a_kind_only_faintly_are_refused(tmp_path, capsys):
    """Two bars along X and Y with offset balls (an outside probe's set-up): Z's
    straightness and squareness are seen through the offsets alone, to hundreds of µm a cycle.
    A rank test passed it (exit 0, a 'compensated' VCE of 617 µm); the uncertainty does not."""
    gen = LargeMillVolumetric(train_hours=1.0, test_hours=1.0, misalignment_deg=10.0,
                              sets=("S1",), seed=1)
    data = simulated(gen, tmp_path / "raw")
    out = tmp_path / "out"
    calibrate(data, tmp_path / "all")               # the three axes are fine
    _keep_poses(data, {"S1x1d1", "S1x1d2"})        # along X and Y
    line = refused(["calibrate", f"data.path={data}", f"out={out}", "track=false"], capsys,
                   "the poses S1x1d1, S1x1d2 see", "only faintly", "(straightness, ±", SETUP_FILE,
                   "calibrate.require_seen=[]")
    assert "E_ZZ1" in line or "E_ZX" in line or "E_XZ" in line or "E_YZ" in line
    assert not out.exists()
    report = calibrate(data, out, "calibrate.require_seen=[]")     # on request, as it is
    assert max(p["uncertainty"] for p in report["parameters"].values()) > 100 * np.hypot(0.5, 0.5)


@pytest.fixture(scope="module")
def offset_balls(tmp_path_factory):
    """Two hours and two of balls offset from the bar (misalignment 10°): simulated once for the
    tests that read it (each edits a copy)."""
    gen = LargeMillVolumetric(train_hours=2.0, test_hours=2.0, misalignment_deg=10.0, seed=2)
    return simulated(gen, tmp_path_factory.mktemp("offset_balls") / "raw")


def test_a_pose_off_in_many_cycles_is_named_as_suspect(offset_balls, tmp_path, capsys):
    """Offset balls declared on the wrong side (θ -10° for 10°): no outlier on the right
    description, outliers in several cycles of some poses on the wrong one, named with a
    warning (an outside probe's had 191 outliers, 144 in one pose, and no word)."""
    data = copy(offset_balls, tmp_path)
    assert calibrate(data, tmp_path / "ok")["suspect_poses"] == []
    assert "suspect" not in capsys.readouterr().err
    setup = json.loads((data / SETUP_FILE).read_text())
    setup["artefact"]["misalignment_deg"] = -10.0
    (data / SETUP_FILE).write_text(json.dumps(setup))
    report = calibrate(data, tmp_path / "bad")
    suspect = report["suspect_poses"]
    assert suspect and all(e["cycles"] >= 3 and e["share"] > 0.05 for e in suspect)
    assert [e["cycles"] for e in suspect] == sorted((e["cycles"] for e in suspect), reverse=True)
    pose = suspect[0]["pose"]
    assert sum(o["pose"] == pose for o in report["outliers"]) >= suspect[0]["cycles"]
    err = capsys.readouterr().err
    assert f"pose {pose} has outliers in {suspect[0]['cycles']} of 14 cycles" in err
    assert "misalignment_deg declared right" in err


def test_a_dataset_without_setup_is_refused(raw, tmp_path, capsys):
    data = copy(raw, tmp_path)
    (data / SETUP_FILE).unlink()
    refused(["calibrate", f"data.path={data}", f"out={tmp_path / 'out'}", "track=false"], capsys,
            "not a volumetric dataset", SETUP_FILE)
    _untouched(tmp_path / "out")


def _set(path, value):
    def edit(d):
        *parents, last = path
        for key in parents:
            d = d[key]
        d[last] = value
    return edit


# volumetric.json from outside: each field against its domain (these were tracebacks, exit 1, or
# read as given: a negative length, a pose declared twice, a negative probing uncertainty)
SETUP_FAULTS = [
    (_set(("machine", "order"), 0), "machine.order=0"),
    (_set(("machine", "tool"), [0, 0]), "machine.tool=[0, 0]: must be 3 finite numbers"),
    (_set(("machine", "tool"), None), "machine.tool=None: must be 3 finite numbers"),
    # no default travel or probe offset could be right for a measured machine (a travel of
    # 0..4000 mm instead of 0..8000 halved every identified X parameter, silently)
    (lambda d: d["machine"].pop("ranges"), "machine.ranges: missing"),
    (lambda d: d["machine"]["ranges"].pop("Z"), "machine.ranges.Z: missing"),
    (lambda d: d["machine"].pop("tool"), "machine.tool: missing"),
    (_set(("machine", "ranges", "Y"), [1600, 0]), "machine.ranges.Y=[1600, 0]: must be a travel"),
    (_set(("uncertainty_um",), {"probing": 0.5, "ball": 1e6}), "uncertainty_um.ball=1000000.0"),
    # a typed centre: the balls would be "measured" where no probe goes
    (_set(("poses", 0, "centre"), [90000, 800, 800]), "pose S1x1d1: ball 1 at X=89250 mm puts "
                                                      "the X axis at 89250 mm"),
    (_set(("artefact", "n_balls"), "11"), "artefact.n_balls='11': must be an integer in [2, 100]"),
    # a typo that exhausted the memory (exit 137) instead of being refused
    (_set(("artefact", "n_balls"), 10 ** 9), "artefact.n_balls=1000000000: must be an integer in [2, 100]"),
    (_set(("artefact", "length_mm"), -1500), "artefact.length_mm=-1500"),
    (_set(("artefact", "misalignment_deg"), 90), "artefact.misalignment_deg=90"),
    (_set(("poses", 0, "direction"), [0, 0, 0]), "poses[0] (S1x1d1).direction=[0, 0, 0]: must not be zero"),
    (_set(("poses", 1, "centre"), [float("nan"), 0, 0]), "poses[1].centre=[nan, 0, 0]"),
    (_set(("poses", 2, "name"), "S1x1d1"), "poses[2].name='S1x1d1': declared twice"),
    (_set(("uncertainty_um",), {"probing": -1, "ball": 0.5}), "uncertainty_um.probing=-1"),
    (_set(("poses",), []), "poses: must be a non-empty list"),
    # a misspelt key was read as its default (or was a TypeError of BallArray, exit 2 with
    # Python's words)
    (lambda d: d.__setitem__("uncertainty", d.pop("uncertainty_um")),
     "uncertainty: unknown key; did you mean 'uncertainty_um'? valid keys: machine, artefact, poses, "
     "uncertainty_um"),
    (_set(("machine", "crossterms"), True), "machine.crossterms: unknown key; did you mean 'cross_terms'? "
                                            "valid keys: ranges, chain, tool, order, cross_terms"),
    (_set(("artefact", "misalignment"), 5.0), "artefact.misalignment: unknown key; did you mean "
                                              "'misalignment_deg'?"),
    (_set(("uncertainty_um", "probe"), 0.1), "uncertainty_um.probe: unknown key; did you mean 'probing'?"),
    (_set(("poses", 3, "centr"), [0, 0, 0]), "poses[3].centr: unknown key; did you mean 'centre'?"),
    (_set(("machine", "ranges", "W"), [0, 1]), "machine.ranges.W: unknown key; valid keys: X, Y, Z"),
]


@pytest.mark.parametrize("fault, says", SETUP_FAULTS, ids=[s.split(":")[0] for _, s in SETUP_FAULTS])
def test_a_setup_field_outside_its_domain_is_refused_naming_it(raw, tmp_path, capsys, fault, says):
    data = copy(raw, tmp_path, truth=False)
    d = json.loads((data / SETUP_FILE).read_text())
    fault(d)
    (data / SETUP_FILE).write_text(json.dumps(d))
    refused(["calibrate", f"data.path={data}", f"out={tmp_path / 'out'}", "track=false"], capsys,
            f"{data / SETUP_FILE}", "not a valid set-up", says)
    _untouched(tmp_path / "out")


def test_bad_calibrate_config_is_refused(raw, tmp_path, capsys):
    for bad, says in (("calibrate.outlier_z=0", "calibrate.outlier_z"),
                      ("calibrate.outlier_z=nan", "calibrate.outlier_z"),
                      ("calibrate.column_share=inf", "calibrate.column_share"),
                      ("calibrate.column_share=2", "calibrate.column_share"),
                      ("calibrate.format=xlsx", "calibrate.format"),
                      ("calibrate.require_seen=[squareness]", "calibrate.require_seen"),
                      ("calibrate.prior=3", "calibrate.prior"),
                      ("calibrate.prior={positioning:10}", "calibrate.prior needs a range"),
                      ("calibrate.prior={positioning:10,angular:-1}", "calibrate.prior.angular"),
                      # a prior of a perfect machine: no distance can be fitted
                      ("calibrate.prior={positioning:0,straightness:0,squareness:0,angular:0}",
                       "calibrate.prior (ranges narrower than the machine?)")):
        refused(["calibrate", f"data.path={raw}", f"out={tmp_path / 'out'}", "track=false", bad],
                capsys, says)
    _untouched(tmp_path / "out")


def test_every_calibrate_key_is_documented(raw, clean, tmp_path):
    from test_docs import CLI, DATA_FORMAT, _documented

    keys = yaml.safe_load((ROOT / "conf" / "calibrate" / "default.yaml").read_text())
    assert not [k for k in keys if f"| `calibrate.{k}` |" not in CLI]
    data = copy(raw, tmp_path)          # an outlier and an excluded column: every key shows

    def outlier_and_excluded(df):       # one rewrite of the 1430-column file, not two
        df["E_S1x2d1_B01_B11"] += 1e3
        df["E_S2x1d3_B04_B09"] += np.r_[1e3, np.zeros(len(df) - 1)]
    edit(data, "train_week", outlier_and_excluded)
    report = calibrate(data, tmp_path / "out")
    assert report["outliers"] and report["excluded"]
    found = (set(report) | set(report["roundtrip"]) | set(next(iter(report["parameters"].values())))
             | set(report["fit"])
             | set(report["outliers"][0]) | set(report["excluded"][0]))
    assert not sorted(k for k in found if not _documented(k, CLI))
    setup = json.loads((raw / SETUP_FILE).read_text())
    fields = set(setup) | set(setup["machine"]) | set(setup["artefact"]) | set(setup["poses"][0]) \
        | set(setup["uncertainty_um"])
    assert not sorted(k for k in fields if not _documented(k, DATA_FORMAT))


def test_the_parameter_dataset_never_replaces_data_or_a_folder_of_something_else(
        raw, clean, tmp_path, capsys, default_dataset):
    # calibrate.dataset is replaced whole: pointed at data.path it once deleted the distances,
    # at another dataset its campaigns
    data = copy(raw, tmp_path)
    other = tmp_path / "other"
    shutil.copytree(default_dataset, other)
    before = sorted(p.name for p in other.iterdir())
    for target, says in ((data, f"calibrate.dataset={data} is data.path"),
                         (data / "sub", f"calibrate.dataset={data / 'sub'} lies inside data.path"),
                         (tmp_path, f"calibrate.dataset={tmp_path} holds data.path"),
                         (other, "does not hold this dataset's parameter series")):
        refused(["calibrate", f"data.path={data}", f"out={tmp_path / 'out'}", "track=false",
                 f"calibrate.dataset={target}"], capsys, says)
    assert sorted(p.name for p in other.iterdir()) == before
    assert (data / SETUP_FILE).is_file()
    # its own earlier series (same campaigns) is replaced, as before.  The earlier series is the
    # clean fixture's (the same calibration of the same distances, written to <out>/parameters),
    # not a calibration of its own; a stray file in it shows the folder is replaced whole.
    series = tmp_path / "series"
    shutil.copytree(clean[1] / "parameters", series)
    (series / "stray.txt").write_text("from before")
    calibrate(data, tmp_path / "out", f"calibrate.dataset={series}")
    assert (series / "campaigns.csv").is_file() and not (series / "stray.txt").exists()


PRIOR_STAGES = ["calibrate", "run", "ingest"]
PRIOR_FAULTS = {"{positioning:10}": "missing ['straightness', 'squareness', 'angular']",
                "{positioning:10,straightness:8,squareness:8,angular:6,bogus:1}": "unknown ['bogus']"}


# stage x prior fault: make test keeps the covering set (tests/covering.py); ids name the message
@pytest.mark.parametrize("stage, prior", covering(
    "the same prior check under another stage", join=lambda ids: "-".join((*ids, PRIOR_FAULTS[ids[1]])),
    stage=PRIOR_STAGES, prior=list(PRIOR_FAULTS)))
def test_a_prior_without_every_kind_is_one_line_before_any_reading(raw, tmp_path, capsys, stage,
                                                                   prior):
    # it was found after the data had been read (a progress line first, then the error)
    out = tmp_path / "out"
    code = main([stage, "experiment=volumetric_large_mill", f"data.path={raw}", f"out={out}",
                 f"data.interim={tmp_path / 'interim'}", "track=false", f"calibrate.prior={prior}"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    says = PRIOR_FAULTS[prior]
    assert err[0].startswith("thermocomp: error: calibrate.prior needs a range") and says in err[0]
    assert not out.exists() and not (tmp_path / "interim").exists()


def test_a_cycle_that_measured_one_pose_only_is_refused_naming_its_row(offset_balls, tmp_path,
                                                                      capsys):
    """One pose's distances left in a cycle, offset balls (an outside probe's): the cycle's GLS
    inverted a nearly singular matrix, E_XX1 came out 2.6e16 µm and run 'compensated' to a VCE
    of 7e14 µm, exit 0.  Now the cycle is refused, as an empty one is; a cycle missing one pose
    is fine."""
    data = copy(offset_balls, tmp_path)

    def keep_one_pose(df):
        gone = [c for c in df.columns if c.startswith("E_") and not c.startswith("E_S1x1d1_")]
        df.loc[2, gone] = np.nan

    edit(data, "validation_week", keep_one_pose)
    out = tmp_path / "out"
    line = refused(["calibrate", f"data.path={data}", f"out={out}", "track=false"], capsys,
                   "validation_week.parquet", "row 3", "cannot identify the parameters",
                   "the distances left measured know", "times a full cycle's")
    assert not out.exists(), line
    data = copy(offset_balls, tmp_path / "one_missing")

    def drop_one_pose(df):
        df.loc[2, [c for c in df.columns if c.startswith("E_S2x1d1_")]] = np.nan

    edit(data, "validation_week", drop_one_pose)
    report = calibrate(data, tmp_path / "fine")
    assert report["n_cycles"] == sum(report["campaigns"].values())
