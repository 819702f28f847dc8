"""An error whose first measurement comes after its campaign's first sample (first-sample frame).

With ``data.reference=first_sample`` the temperatures are referenced at a campaign's first row
(the deployed stream's first sample) but an error measured now and then (a probe cycle,
:mod:`thermocomp.core.io.sparse`) at its first MEASUREMENT, row ``m > 0``: its label is
``E(t) - E(m)`` while a model predicts ``E(t) - E(0)``.  The difference, the constant
``E(m) - E(0)`` per campaign, was never measured.  The one rule, for scoring and fitting alike:
the label is completed by the model's own estimate of that constant.

* Scoring compares ``y_hat(t) - y_hat(m)`` with the label (what a lab can check of the deployed
  correction ``y_hat(t)``): the label completed by ``y_hat(m)`` (:func:`completed`), the same
  residual for every command that scores (run, replay, promote, monitor, diagnose, auto's folds).
* Fitting refits on the label completed by ``y_hat(m) - y_hat(0)`` (``from_start=True``): the
  model's estimate of ``E(m) - E(0)``, free of its intercept (completing by ``y_hat(m)`` alone
  would add the intercept to the labels at every refit: measured, the deployed correction's
  true error 1.5-3 times larger).  Of the fit on the label and its :data:`REFITS` refits, the one
  of the lowest :func:`frame_loss` on the training rows is kept.

A campaign whose error is measured at its first row, a dense column, and the ``none`` frame
(:func:`late_starts` empty) are left as they are, bit for bit.
"""

from __future__ import annotations

import numpy as np

REFITS = 2      # refits on the completed label after the fit on the label (measured: docs)


def late_starts(Y: np.ndarray, groups: np.ndarray) -> list[tuple[int, int, int]]:
    """``[(k, start, m)]``: target column ``k`` of the stacked labels ``Y`` (rows of a campaign
    contiguous, ``groups``) first measured at row ``m`` after its campaign's first row
    ``start``; a campaign never measuring it is not listed (nothing to complete)."""
    Y = np.asarray(Y, float).reshape(len(groups), -1)
    out = []
    if not len(groups):
        return out
    edges = np.flatnonzero(np.r_[True, groups[1:] != groups[:-1], True])
    for start, stop in zip(edges[:-1], edges[1:]):
        measured = np.isfinite(Y[start:stop])
        for k in range(Y.shape[1]):
            if measured[:, k].any() and not measured[0, k]:
                out.append((k, int(start), int(start + measured[:, k].argmax())))
    return out


def completed(Y: np.ndarray, predicted: np.ndarray, groups: np.ndarray,
              from_start: bool = False) -> np.ndarray:
    """The labels ``Y`` (``(n,)`` or ``(n, k)``) completed where a campaign's first measurement
    is late: plus ``predicted`` at that row (minus ``predicted`` at the campaign's first row
    when ``from_start``); ``Y`` itself where none is (no copy: bit for bit)."""
    late = late_starts(Y, groups)
    if not late:
        return Y
    out = np.array(Y, float, copy=True)
    flat = out.reshape(len(groups), -1)
    P = np.asarray(predicted, float).reshape(len(groups), -1)
    edges = np.flatnonzero(np.r_[True, groups[1:] != groups[:-1], True])
    stops = dict(zip(edges[:-1], edges[1:]))
    for k, start, m in late:
        flat[start:stops[start], k] += P[m, k] - (P[start, k] if from_start else 0.0)
    return out


def frame_loss(Y: np.ndarray, predicted: np.ndarray, groups: np.ndarray) -> float:
    """RMS over the measured rows of the labels ``Y`` less ``predicted`` in the frame the model is
    used in: where a campaign's first measurement (row m) is late, ``Y(t) - (y_hat(t) - y_hat(m))
    - y_hat(0)`` (the label checked as scored, and the prediction at the first sample, where the
    frame's error is 0 by definition), else ``Y - y_hat``.  What the refits are kept by."""
    residual = completed(Y, predicted, groups, from_start=True) - np.asarray(predicted, float)
    return float(np.sqrt(np.nanmean(residual ** 2)))


def late_first_note(reference: str, targets, campaigns) -> str | None:
    """One line where, in the first-sample frame, a target's first measurement comes after its
    campaign's first row: how its figures are then read (a stranger sees a model-dependent RMS
    before otherwise and cannot guess why); None where no campaign has one."""
    if reference != "first_sample":
        return None
    targets = list(targets)
    frames = [df.reindex(columns=targets) for df in campaigns.values()]   # (a target not recorded: NaN)
    Y = np.concatenate([df.to_numpy(float) for df in frames]) if frames else np.empty((0, 0))
    groups = np.repeat(np.arange(len(frames)), [len(df) for df in frames])
    rows = {}
    for k, start, m in late_starts(Y, groups):
        rows.setdefault(targets[k], []).append(m - start)
    if not rows:
        return None
    first = ", ".join(f"{t} at row {min(r)}" + (f"-{max(r)}" if max(r) > min(r) else "")
                      + f" of {len(r)} campaign{'s' * (len(r) > 1)}" for t, r in rows.items())
    return (f"first measured after the campaign's first sample ({first}): scored as the change "
            "since that first reading, y_hat(t) - y_hat(m), the model fitted so; RMS before and "
            "persistence read the error completed by the model's estimate of the drift before it")
