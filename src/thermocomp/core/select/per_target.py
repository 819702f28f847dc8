"""A selector fitted per target: the ``targets`` block of ``selection.json`` (pure core)."""

from __future__ import annotations

import numpy as np
from sklearn.base import clone

from ...base.jsonsafe import json_safe
from ..frame import stack
from .pearson import abs_correlation

CORRELATION_LABEL = "|r| with the error"


def _series(s) -> dict:
    return json_safe({str(k): float(v) for k, v in s.items()})


def measured(X, y):
    """The rows of ``X`` where ``y`` was measured (a target measured now and then,
    ``data.sparse_targets``: a static selector scores the inputs there), ``X`` itself where
    every row is."""
    rows = np.isfinite(np.asarray(y, float))
    return X if rows.all() else X.loc[rows].reset_index(drop=True)


def select_per_target(selector, X, Y, name: str) -> tuple[dict, dict, dict]:
    """(entry per target, scores per target for the figure, their label per target).

    ``selector`` is cloned and fitted on ``X`` against each column of ``Y``; an entry
    holds the selected inputs and what the selector shows of its choice (scores,
    information criterion by size, clusters).  A selector without scores is shown by
    each input's |correlation| with the target.
    """
    result, scores, labels = {}, {}, {}
    full = X
    for t in Y.columns:
        y = Y[t].to_numpy()
        X = measured(full, y)
        y = y[np.isfinite(y)] if len(X) < len(y) else y
        sel = clone(selector).fit(X, y)
        entry = {"selected": list(sel.selected_)}
        if hasattr(sel, "scores_"):
            entry["scores"] = _series(sel.scores_)
            labels[t] = getattr(sel, "score_label", f"{name} score")
        if getattr(sel, "ic_", None) is not None:
            entry["criterion"] = {"name": sel.ic_.name, "by_k": _series(sel.ic_)}
        if hasattr(sel, "clusters_"):
            entry["clusters"] = sel.clusters_
        result[t] = entry
        scores[t] = entry.get("scores") or dict(zip(X.columns, abs_correlation(X.to_numpy(), y)))
        labels.setdefault(t, CORRELATION_LABEL)
    return result, scores, labels


def select_on_campaigns(selector, campaigns: dict, inputs: list, targets: list, reference: str,
                        name: str) -> tuple[dict, dict, dict]:
    """:func:`select_per_target` on ``campaigns`` stacked in the ``reference`` frame, as the
    :class:`~thermocomp.core.compensator.Compensator` stacks what it selects on."""
    m = stack(campaigns, inputs, targets, reference)
    return select_per_target(selector, m.X[inputs], m.Y[targets], name)
