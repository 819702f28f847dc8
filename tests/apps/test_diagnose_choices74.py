"""diag74: the search's CV fits at the choices the deployed base made on all train rows.

A family with its own CV (the lag bank's penalty, the hammerstein's powers) chose again in every
fold of the search, so a candidate's CV gain could be a change of the base's own choice: on
``fl_thermal`` (60/20/20, hammerstein) a product moved the lag bank's penalty 316 -> 0.03 in the
deployed model and raised E_ch5's test error (``benchmarks/bench_diag73.py``, ``bench_diag74.py``).
Now every fold fits at ``chosen_params`` of the base fitted on all train rows.
"""

from __future__ import annotations

from test_diagnose_positions61 import gantry
from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import LagBank


def test_every_fold_of_the_search_fits_the_lag_bank_at_the_base_models_penalty(monkeypatch):
    """The gantry's 4 train campaigns under a lag bank: the model as it is, every candidate and
    the sensor-health bar are cross-validated with the penalty the base chose on all of them
    (before, each fold's own CV chose it: 0.01 .. 1e4 on this record, the base 10)."""
    fits, shipped = [], LagBank.fit

    def spy(self, X, y, context=None):
        out = shipped(self, X, y, context=context)
        fits.append((len(y), self.alpha_))
        return out

    monkeypatch.setattr(LagBank, "fit", spy)
    ds = gantry()
    d = diagnose(ds, Compensator(LagBank(n_taus=2)), options=SearchOptions(max_effects=1))
    rows = sum(len(ds.campaigns[c]) for c in ds.ids("train"))
    chosen = d.before_model.estimators_["E_Y"].alpha_
    folds = [alpha for n, alpha in fits if n < rows]
    assert len(folds) >= 8
    assert set(folds) == {chosen}, sorted(set(folds))
