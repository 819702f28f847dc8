r"""Statistics across campaigns (paper 003, Sects. 3.3-3.4): one-way ANOVA, mutual prediction.

Pure core: campaign arrays/DataFrames in, dicts/DataFrames out.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import pandas as pd
from scipy import stats as sps
from sklearn.base import clone

from ...base.errors import FallbackWarning
from ..first_probe import late_starts
from ..frame import resolve_columns, stack
from ..metrics import rsd
from ..model_selection import TrainOnEachCampaign


def anova_oneway(samples: Mapping[str, np.ndarray], alpha: float = 0.001) -> dict:
    r"""One-way ANOVA of a quantity (the thermal error) across campaigns (paper 003, Sect. 3.3).

    With :math:`r` campaigns, :math:`n_i` samples :math:`y_{ij}` each, campaign
    means :math:`\bar y_i` and grand mean :math:`\bar y` (:math:`N = \sum n_i`):

    .. math::

        S_A = \sum_i n_i (\bar y_i - \bar y)^2,\quad
        S_E = \sum_i \sum_j (y_{ij} - \bar y_i)^2,\quad
        F = \frac{S_A / (r-1)}{S_E / (N-r)}

    :math:`p = P(F_{r-1,N-r} \ge F)` and :math:`F_{crit} = F^{-1}_{r-1,N-r}(1-\alpha)`
    (scipy).  ``significant`` is :math:`F \ge F_{crit}`: the campaigns do not share
    one mean, i.e. the error law differs between them (paper 003 read it as the
    ambient level changing the law).

    Returns ``{"F": None, "reason": ...}`` with fewer than two campaigns or
    no within-campaign degrees of freedom.
    """
    groups = {c: np.asarray(v, float)[np.isfinite(np.asarray(v, float))] for c, v in samples.items()}
    groups = {c: v for c, v in groups.items() if v.size}
    r, n = len(groups), sum(v.size for v in groups.values())
    if r < 2 or n - r < 1:
        return {"F": None, "p_value": None, "F_crit": None, "alpha": alpha, "significant": None,
                "campaigns": r, "reason": f"ANOVA needs two campaigns or more with samples to spare "
                                          f"(have {r} campaigns, {n} samples)"}
    values = list(groups.values())
    F, p = sps.f_oneway(*values)
    grand = np.concatenate(values).mean()
    ss_between = float(sum(v.size * (v.mean() - grand) ** 2 for v in values))
    ss_within = float(sum(((v - v.mean()) ** 2).sum() for v in values))
    df_between, df_within = r - 1, n - r
    F_crit = float(sps.f.ppf(1.0 - alpha, df_between, df_within))
    F = float(F) if np.isfinite(F) else None
    return {"F": F, "p_value": float(p) if np.isfinite(p) else None, "F_crit": F_crit,
            "alpha": alpha, "significant": None if F is None else bool(F >= F_crit),
            "df_between": df_between, "df_within": df_within,
            "ss_between": ss_between, "ss_within": ss_within,
            "ms_between": ss_between / df_between, "ms_within": ss_within / df_within,
            "campaigns": r}


def mutual_prediction(campaigns: Mapping[str, pd.DataFrame], make_compensator: Callable,
                      mode: str = "simulation", trained_on: Sequence[str] | None = None
                      ) -> dict[str, pd.DataFrame]:
    r"""Mutual prediction matrix (paper 003, Sect. 3.4, Fig. 6).

    A model trained on campaign :math:`i` alone predicts every campaign
    :math:`j`; entry :math:`(i, j)` is :math:`R_{sd}` of that prediction (paper
    003, Eq. 17, in the target's unit).  The diagonal is the self-fit.

    Each model predicts all campaigns in one call; the measured targets are
    taken once (the reference frame does not depend on the model, but for a first probe after a
    campaign's first row: :mod:`thermocomp.core.first_probe`) and the
    Rsd of every (model, campaign) pair comes from one residual array per target.

    Parameters
    ----------
    campaigns : dict id -> campaign DataFrame (contract columns)
    make_compensator : callable returning a new, unfitted
        :class:`~thermocomp.core.compensator.Compensator` (any model config)
    mode : 'simulation' or 'one_step'
    trained_on : the campaigns that get a model (the rows), in the order of
        ``campaigns``; None: every campaign

    Returns
    -------
    dict target -> DataFrame (index: trained on, columns: predicted), in the
    order of ``campaigns``.
    """
    with warnings.catch_warnings():     # one campaign per model: a fallback is the design here
        warnings.simplefilter("ignore", FallbackWarning)
        return _mutual_prediction(campaigns, make_compensator, mode, trained_on)


def _mutual_prediction(campaigns, make_compensator, mode, trained_on) -> dict[str, pd.DataFrame]:
    ids = list(campaigns)
    rows = _rows(ids, trained_on)
    first = make_compensator()
    if first.denoiser is not None:      # denoised per training campaign: the campaign-level path
        return _mutual_by_campaign(campaigns, make_compensator, mode, rows)
    # no denoiser: stack every campaign once; each model fits on its campaign's rows of the stack
    # and predicts the whole stack (the same numbers as fit/predict on the campaign dicts).  The
    # columns as a fit on the first campaign resolves them, without that fit (a blend with an
    # LSTM member on a record's train part: one more model of the slowest kind)
    inputs, targets = resolve_columns(list(campaigns[ids[0]].columns), first.inputs, first.targets)
    m = stack(campaigns, inputs, targets, first.reference)
    bounds = _bounds(m.groups, ids)
    Y = m.Y.to_numpy()
    residuals = {t: [] for t in targets}
    from ...base.progress import bar

    for i in bar(rows, desc="mutual prediction", total=len(rows), unit="model"):
        comp = clone(first).fit_stacked(m.subset(m.rows_of(i)))
        P = comp.predict_stacked(m, mode)
        r = comp.scored_label(Y, m.groups, P if mode == "simulation"
                              else (lambda comp=comp: comp.predict_stacked(m))) - P
        for k, t in enumerate(comp.targets_):
            residuals[t].append(r[:, k])
    return _rsd_matrices(residuals, rows, ids, bounds)


def _rows(ids: list, trained_on) -> list:
    """The campaigns of ``ids`` that get a model (:class:`TrainOnEachCampaign`'s order)."""
    every = [ids[train[0]] for train, _ in TrainOnEachCampaign().split(ids, groups=ids)]
    if trained_on is None:
        return every
    wanted = set(trained_on)
    unknown = wanted - set(ids)
    if unknown:
        raise ValueError(f"trained_on names campaigns not given: {sorted(unknown)}")
    return [c for c in every if c in wanted]


def _bounds(groups, ids) -> list[tuple[int, int]]:
    """(start, stop) rows of each campaign of a stack, in ``ids`` order."""
    return [(int(np.flatnonzero(groups == c)[0]), int(np.flatnonzero(groups == c)[-1]) + 1) for c in ids]


def _rsd_matrices(residuals: dict, rows, ids, bounds) -> dict[str, pd.DataFrame]:
    index = pd.Index(rows, name="trained_on")
    columns = pd.Index(ids, name="predicted")
    return {t: pd.DataFrame([[rsd(row[a:b]) for a, b in bounds] for row in r],
                            index=index, columns=columns)
            for t, r in residuals.items()}


def _mutual_by_campaign(campaigns, make_compensator, mode, rows) -> dict[str, pd.DataFrame]:
    ids = list(campaigns)
    measured, residuals, bounds, own = None, {}, [], False
    for i in rows:
        # the unit IS the file (a matrix of file-on-file figures): fitted on one alone, and
        # every campaign predicted on its own, from its first sample, as that fit was
        comp = make_compensator().fit({i: campaigns[i]})
        predicted = comp.predict(campaigns, mode=mode)
        if measured is None or own:
            frames = comp.measured(campaigns,
                                   predicted=predicted if mode == "simulation" else None)
            measured = _by_target(frames, ids, comp.targets_)
            ends = np.cumsum([len(frames[c]) for c in ids])
            bounds = list(zip(ends - np.diff(ends, prepend=0), ends))  # rows of each campaign
            # a late first probe (first-sample frame): each model's label is completed by its
            # own y_hat(m) (:mod:`thermocomp.core.first_probe`), so measured once per model
            own = comp.reference == "first_sample" and bool(late_starts(
                np.column_stack([measured[t] for t in comp.targets_]),
                np.concatenate([np.full(b - a, c, dtype=object) for c, (a, b) in zip(ids, bounds)])))
        pred = _by_target(predicted, ids, comp.targets_)
        for t in comp.targets_:
            residuals.setdefault(t, []).append(measured[t] - pred[t])
    return _rsd_matrices(residuals, rows, ids, bounds)


def _by_target(frames: Mapping[str, pd.DataFrame], ids, targets) -> dict[str, np.ndarray]:
    """Per target, the column of every campaign of ``frames`` end to end (in ``ids`` order)."""
    return {t: np.concatenate([frames[c][t].to_numpy(float) for c in ids]) for t in targets}
