"""The envelope's pattern tolerance priced on held-out training blocks (clamp75, pure core).

The clamp assumed that a sample off the training pattern is better read at the envelope's edge.
On a machine that runs beyond its training the way its own training record kept doing (tcm74's
night: beds hotter, hall colder than any train row) that cost 15-281 % of the deployed error.
The training record can say which it is: forward blocks of it leave the envelope built on the
rows before them as a test part leaves the whole one, and the model refitted on those rows can
be streamed over each block with and without the excursion read.  The gate's ``tol`` becomes
``c * tol``, ``c`` the candidate of least held-out squared error among 1 and, per fold, the
largest residual of its clamped scored rows over the fold's ``tol``; 1 (the gate as trained) on
a tie, where nothing held out is clamped, or where the model cannot be refitted as chosen
(``benchmarks/bench_clamp75.py`` has the rule, its bar and the figures).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import numpy as np
import pandas as pd
from sklearn.base import clone

from ...core.compensator import refit_as_chosen
from ...core.model_selection.splitters import BlockedForward


def priced_envelope(compensator, campaigns: Mapping[str, pd.DataFrame], envelope, margin: float):
    """``envelope`` with its pattern tolerance priced on ``campaigns`` (module doc); unchanged
    without a pattern or where the price cannot be taken."""
    if envelope is None or envelope.basis is None:
        return envelope
    template = refit_as_chosen(compensator)
    if template is None:
        return envelope
    try:
        held = [_streamed_fold(template, fit, parts, margin) for fit, parts in _folds(campaigns)]
    except ValueError:                  # a fold too short to fit or stream: the gate as trained
        return envelope
    held = [part for fold in held if fold is not None for part in fold]
    ratios = sorted({float(part[4][part[5]].max()) for part in held if part[5].any()})
    if not ratios:
        return envelope
    cost = {1.0: _cost(held, 1.0), **{c: _cost(held, c) for c in ratios if c > 1.0}}
    best = min(cost, key=lambda c: (cost[c], c))
    lines = tuple(f"x{c:.3g}: held-out squared error {e:.4g}" for c, e in cost.items())
    return dataclasses.replace(envelope, tol=envelope.tol * best, tol_factor=best, priced=lines)


def _folds(campaigns: Mapping[str, pd.DataFrame]):
    """``(fit campaigns, [(held-out frame, scored rows)])`` of ``BlockedForward()``'s folds: one
    record's rows, or the campaigns in their order."""
    ids = list(campaigns)
    if len(ids) == 1:
        df = campaigns[ids[0]]
        for fit, pred, score in BlockedForward().folds(None, len(df)):
            yield ({ids[0]: df[fit].reset_index(drop=True)},
                   [(df[pred].reset_index(drop=True), score[pred])])
        return
    for fit, _, score in BlockedForward().folds(np.array(ids)):
        yield ({c: campaigns[c] for c, f in zip(ids, fit) if f},
               [(campaigns[c], np.ones(len(campaigns[c]), bool)) for c, s in zip(ids, score) if s])


def _streamed_fold(template, fit: dict, parts: list, margin: float):
    """``[(stream, frame, scored rows, their measured targets, their residual off the pattern /
    tol, the clamped ones), ...]`` of one fold; None where its envelope has no pattern."""
    from .streaming import StreamingCompensator, replay

    fitted = clone(template).fit(fit)
    stream = StreamingCompensator.from_training(fitted, fit, margin, "clamp", True)
    env = stream.envelope
    if env is None or env.basis is None:
        return None
    out = []
    for frame, scored in parts:
        m = fitted.stacked({"held": frame}, targets=fitted.targets_)
        y = m.Y.to_numpy(float)[scored]
        z = (m.X.to_numpy(float)[scored] - env.mean) / env.scale
        residual = np.linalg.norm(z - z @ env.basis @ env.basis.T, axis=1) / env.tol
        on = replay(stream, frame)
        stream.reset()
        clamped = on["n_clamped"].to_numpy()[scored] > 0
        out.append((stream, frame, scored, y, residual, clamped))
    return out


def _cost(held: list, factor: float) -> float:
    """Squared error of every held-out part's clamped stream over its scored rows, its fold's
    gate at ``factor`` x the fold's ``tol``."""
    from .streaming import replay

    total = 0.0
    for stream, frame, scored, y, _, _ in held:
        trained = stream.envelope
        stream.envelope = dataclasses.replace(trained, tol=trained.tol * factor)
        try:
            got = replay(stream, frame)[stream.targets_].to_numpy(float)[scored]
        finally:
            stream.envelope = trained
            stream.reset()
        total += float(np.nansum((got - y) ** 2))
    return total
