"""What a calibration of a volumetric folder computes once, or not at all when the data are clean
(counted, not timed: each was a tenth of a second or more of every `calibrate` and `run`)."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import simulated
from thermocomp.apps.sim.volumetric import LargeMillVolumetric
from thermocomp.apps.volumetric import calibration, identify
from thermocomp.core.io import steps


@pytest.fixture(scope="module")
def clean(tmp_path_factory):
    """Two campaigns (9 and 6 cycles) of 1430 distances, without a gross error."""
    gen = LargeMillVolumetric(train_hours=3.0, test_hours=2.0, seed=0)
    return simulated(gen, tmp_path_factory.mktemp("vol") / "raw")


def counted(monkeypatch, owner, name):
    calls = []
    real = getattr(owner, name)
    monkeypatch.setattr(owner, name, lambda *a, **k: calls.append(a) or real(*a, **k))
    return calls


def test_a_campaigns_distances_are_taken_from_its_frame_once(clean, monkeypatch):
    """The screen, the identification and the report share one matrix per campaign (each
    took the 1430 columns again, 45-60 ms a time from the reader's block per column)."""
    taken = counted(monkeypatch, calibration, "distance_matrix")
    params, cal, report, raw = calibration.calibrate_folder(clean, None)
    assert len(taken) == len(raw.campaigns) == 2
    assert report["outliers"] == [] and report["fit"]["consistent"]
    for cid, df in raw.campaigns.items():        # the matrix is the campaign's, column by column
        np.testing.assert_array_equal(calibration.distance_matrix(df, cal),
                                      np.column_stack([df[c].to_numpy(float) for c in cal.design_.columns]))


def test_clean_cycles_are_screened_without_inverting_the_noise_covariance(clean, monkeypatch):
    """The search's whitener (the inverse factor of 1430 x 1430) is built for a cycle with a
    distance beyond outlier_z only: the screened cycles of clean data stop at their first fit."""
    built = counted(monkeypatch, identify.ArtefactCalibration, "_whitener")
    _, cal, report, raw = calibration.calibrate_folder(clean, None)
    assert built == [] and report["outliers"] == []
    gaps = calibration.distance_matrix(raw.campaigns["train_week"], cal)[2]
    gaps[[3, 700]] = np.nan                         # two distances not measured in the cycle
    assert cal.screen(gaps) == ([], False) and built == []
    # a cycle with a gross error is searched, and found as before
    d = calibration.distance_matrix(raw.campaigns["train_week"], cal)[4]
    d[17] += 1000.0
    out, capped = cal.screen(d)
    assert len(built) == 1 and not capped and [o["column"] for o in out] == [cal.design_.columns[17]]


def test_only_columns_with_a_step_that_fits_a_unit_are_judged_one_by_one(clean, monkeypatch):
    """The unit-change check screens the columns side by side; a column is judged against its
    history (unit_change) only where a step fits a conversion, and a real change is still found."""
    from thermocomp.core import io

    judged = counted(monkeypatch, steps, "unit_change")
    ds, _ = io.read_dataset(clean, None, missing="keep_errors")
    n_columns = sum(c.startswith(("E_", "T_")) for c in ds.campaigns["train_week"].columns)
    assert len(judged) < n_columns / 10
    # the same screen as judging every column: a change to mm in one distance column
    x = ds.campaigns["train_week"]["E_S1x1d1_B01_B02"].to_numpy() + 40.0
    x[5:] /= 1000.0
    columns = {name: ds.campaigns["train_week"][name].to_numpy() for name in ds.campaigns["train_week"]
               if name.startswith("E_")}
    columns["E_S1x1d1_B01_B02"] = x
    values = {name: (np.arange(v.size), v) for name, v in columns.items()}
    suspects = steps._suspects(values, steps.UNITS["E"])
    every = [name for name, (_, v) in values.items() if steps.unit_change(v, 5.0, steps.UNITS["E"])[0] >= 0]
    assert every == ["E_S1x1d1_B01_B02"] and set(every) <= set(suspects)


def test_a_set_up_is_fitted_once_per_process(clean, monkeypatch, tmp_path):
    """`run` fits the set-up's calibration to identify the cycles, and again to evaluate against
    the distances; calibrating one set-up again gives the same fit without fitting it, another
    set-up or outlier_z is fitted anew."""
    import json
    import shutil

    monkeypatch.setattr(calibration, "_FITTED", {}, raising=False)
    fits = counted(monkeypatch, identify.ArtefactCalibration, "fit")
    first, cal, _, _ = calibration.calibrate_folder(clean, None)
    again, cal2, _, _ = calibration.calibrate_folder(clean, None)
    assert len(fits) == 1 and cal2 is not cal and cal2._whiteners is not cal._whiteners
    for cid in first.campaigns:
        np.testing.assert_array_equal(first.campaigns[cid][cal.names_], again.campaigns[cid][cal.names_])
    calibration.calibrate_folder(clean, None, outlier_z=5.0)
    assert len(fits) == 2
    other = shutil.copytree(clean, tmp_path / "raw")
    setup = json.loads((other / "volumetric.json").read_text())
    setup["uncertainty_um"]["ball"] = 1.0
    (other / "volumetric.json").write_text(json.dumps(setup))
    _, wider, _, _ = calibration.calibrate_folder(other, None)
    assert len(fits) == 3         # the artefact known worse: no parameter known better, some worse
    assert np.all(wider.uncertainty_ >= cal.uncertainty_ * (1 - 1e-9))
    assert np.any(wider.uncertainty_ > 1.05 * cal.uncertainty_)
