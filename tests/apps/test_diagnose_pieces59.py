"""diagnose's closed-form CV from the QR factors of row pieces: the fits on each fold's rows.

Forward chaining's 16 nested folds refitted the record's first half 16 times (35 % of
``diagnose`` on a week at 10 s, stop 59).  When every fold's design is the same, each fold's
ridge path (:class:`thermocomp.apps.diagnose.shrink.PartialRidgePath`) comes from the
factors of the pieces of rows its training holds (``CrossValidator._pieces``); it must give
the path the fold's rows give, in both CV schemes, with collinear inputs too.
"""

from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.diagnose.cv import CrossValidator, Problem
from thermocomp.apps.diagnose.features import Effect, initial_offsets, principal_directions, transient
from thermocomp.apps.diagnose.shrink import ALPHAS, PartialRidgePath
from thermocomp.core.models import MLR
from thermocomp.core.models._campaign_ls import CampaignLeastSquares


def rows_design(kind: str, seed: int = 1, n: int = 600):
    """Four inputs (absolute temperatures) and three effect features; ``collinear``: an input
    the sum of two others plus 1e-6 of noise, a feature another's copy plus 1e-7; ``exact``:
    that input exactly the sum."""
    rng = np.random.default_rng(seed)
    Z = np.cumsum(rng.normal(size=(n, 7)), axis=0) * 0.1 + 20.0
    if kind in ("collinear", "exact"):
        Z[:, 3] = Z[:, 0] + Z[:, 1] + (0.0 if kind == "exact" else 1e-6 * rng.normal(size=n))
        Z[:, 6] = Z[:, 5] + 1e-7 * rng.normal(size=n)
    y = Z @ rng.normal(size=7) + rng.normal(0, 0.1, n)
    return Z, y


@pytest.mark.parametrize("kind", ["random", "collinear", "exact"])
def test_the_path_from_a_union_of_pieces_predicts_as_the_path_on_its_rows(kind):
    Z, y = rows_design(kind)
    pieces = np.array_split(np.arange(len(y)), 6)
    ls = CampaignLeastSquares(Z, y, pieces)
    for members in ([0, 1, 2], [0, 2, 4, 5], list(range(6))):
        rows = np.concatenate([pieces[c] for c in members])
        fast = PartialRidgePath.from_triangle(*ls.union(members), 4)
        # exactly collinear inputs: a singular value of rounding's size, which may lie near
        # lstsq's cut-off (eps * rows): then the rows decide (None); else the same fit
        assert fast is not None or kind == "exact"
        if fast is None:
            continue
        want = PartialRidgePath(Z[rows], y[rows], 4).predict(Z, ALPHAS)
        np.testing.assert_allclose(fast.predict(Z, ALPHAS), want, rtol=0,
                                   atol=1e-9 * np.abs(want).max())


def problem(scheme: str, seed: int = 2):
    """Six campaigns of a heated machine: inputs T_a, T_b, T_c (T_c nearly T_a + T_b), error
    from a lag of the inputs and a square."""
    rng = np.random.default_rng(seed)
    frames = []
    for k in range(6):
        n = 150
        t_a = 20 + np.cumsum(rng.uniform(0, 0.05, n))
        t_b = 20 + np.cumsum(rng.uniform(0, 0.03, n))
        frames.append(pd.DataFrame({"time": np.arange(n) * 60.0, "T_a": t_a, "T_b": t_b,
                                    "T_c": t_a + t_b + 1e-6 * rng.normal(size=n),
                                    "campaign": f"C{k}"}))
    df = pd.concat(frames, ignore_index=True)
    lagged = df.groupby("campaign")["T_a"].transform(lambda s: s.ewm(alpha=0.05).mean())
    y = (2 * (df["T_a"] - 20) + 3 * (lagged - 20) + 0.5 * (df["T_b"] - 20) ** 2
         + rng.normal(0, 0.02, len(df))).to_numpy()
    camp = df["campaign"].to_numpy(object)
    return Problem(df[["T_a", "T_b", "T_c"]], y, df[["time", "T_a", "T_b", "T_c"]], camp, camp,
                   "E_X", scheme=scheme, n_blocks=8, reference="none")


EFFECTS = [Effect(kind="dynamics", transform="lowpass_inputs", tau_s=1200.0),
           Effect(kind="nonlinear", transform="square", column="T_b")]


@pytest.mark.parametrize("scheme", ["forward", "campaigns"])
@pytest.mark.parametrize("effects", [[], EFFECTS])
def test_the_cv_from_row_pieces_equals_the_cv_fitted_on_each_folds_rows(monkeypatch, scheme, effects):
    p = problem(scheme)
    cv = CrossValidator(p, MLR())
    assert cv._pieces(["T_a", "T_b", "T_c"], effects) is not None
    fast = cv.run(["T_a", "T_b", "T_c"], effects)
    monkeypatch.setattr(CrossValidator, "_pieces", lambda self, inputs, effects: None)
    plain = CrossValidator(p, MLR()).run(["T_a", "T_b", "T_c"], effects)
    assert fast.alpha == plain.alpha
    np.testing.assert_array_equal(np.isnan(fast.prediction), np.isnan(plain.prediction))
    ok = ~np.isnan(plain.prediction)
    np.testing.assert_allclose(fast.prediction[ok], plain.prediction[ok], rtol=0,
                               atol=1e-9 * np.abs(plain.prediction[ok]).max())
    np.testing.assert_allclose(fast.rmse, plain.rmse, rtol=1e-9)


def test_the_forward_read_scores_each_later_campaign_by_the_fit_on_the_campaigns_before_it():
    # diag103 (Search._forward_within_gain): campaigns C3, C4, C5 of six, each by the fit on the
    # ones before it, a start lag's initial direction learned on those too; within: less its mean
    p = problem("campaigns")
    cv, names = CrossValidator(p, MLR()), ["T_a", "T_b", "T_c"]
    lag = Effect("dynamics", "first_order_lag", "T_a", tau_s=1200.0, initial_state=("T_a", "T_b", "T_c"),
                 initial_directions=1)
    camps, time = np.asarray(p.campaigns), p.context["time"].to_numpy(float)
    offsets = initial_offsets(p.context, lag.initial_state, camps)
    plain = cv.features(replace(lag, initial_state=None, initial_directions=None), names)
    want, learned_on_all = [], []
    for j in (3, 4, 5):
        train, test = np.isin(camps, [f"C{k}" for k in range(j)]), camps == f"C{j}"
        for out, rows in ((want, train), (learned_on_all, np.ones(len(camps), bool))):
            w = principal_directions(offsets[rows], camps[rows], 1)
            Z = np.hstack([p.X.to_numpy(float), plain, transient(offsets, w, time, camps, 1200.0)])
            r = p.y[test] - PartialRidgePath(Z[train], p.y[train], 3).predict(Z[test], [0.01])[:, 0]
            out.append(np.sum((r - r.mean()) ** 2))
    got = cv.forward_within(names, [lag], 0.01)
    np.testing.assert_allclose(got, want, rtol=1e-9)
    assert not np.allclose(got, learned_on_all, rtol=1e-6)     # the directions are the earlier ones'
    assert cv.forward_within(names[:2], [], None).shape == (3,)
