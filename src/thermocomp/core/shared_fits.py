"""Fits shared within one report: a family fitted again on the very rows it was fitted on.

A run's report fits small models of its own: the ATI baselines (one on the coldest train
campaign, one on the warmest) and mutual prediction (one on each campaign).  With model=auto
they are each target's chosen family, and where that family chose nothing on all the train data
(no hyper-parameter of its own: MLR, ARX, an LSTM, a blend of them) mutual prediction's model of
the coldest campaign is the ATI baseline's, fitted a second time (the probe grinder: a blend with
an LSTM member, twice per train week and target).  Inside :func:`shared_fits`, a
:class:`~thermocomp.core.compensator.Compensator`'s per-target fit is remembered by what
determines it -- the estimator's class and parameters (what ``clone`` copies), the rows' bytes
and memory layout, the frame -- and a second fit of the same is a copy of the first, to the bit.
Outside, nothing is remembered.
"""

from __future__ import annotations

import copy
import hashlib
from collections.abc import Callable
from contextlib import contextmanager
from contextvars import ContextVar

import numpy as np
import pandas as pd

_MEMO: ContextVar[dict | None] = ContextVar("shared_fits", default=None)


@contextmanager
def shared_fits():
    """Within the block, a per-target fit already made on the same rows is copied, not redone."""
    token = _MEMO.set({})
    try:
        yield
    finally:
        _MEMO.reset(token)


def fitted(fit: Callable[[], tuple], template, X: np.ndarray, y: np.ndarray, groups, context,
           frame: str) -> tuple:
    """``fit()`` (its ``(estimator, label)``), or inside :func:`shared_fits` a deep copy of the
    one a fit of the same ``template`` on the same rows returned (the caller may change its
    copy: an intercept dropped)."""
    memo = _MEMO.get()
    if memo is None:
        return fit()
    key = (_params(template), frame, _digest(X, y, groups, context))
    if key not in memo:
        memo[key] = fit()
    return copy.deepcopy(memo[key])


def _params(estimator) -> str:
    """The class and parameters of an unfitted estimator, nested ones included (what ``clone``
    copies, so all a fit depends on besides its rows), as text."""
    return repr(_plain(estimator))


def _plain(value):
    if hasattr(value, "get_params") and not isinstance(value, type):
        return (type(value).__module__, type(value).__qualname__,
                _plain(value.get_params(deep=False)))
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return (value.dtype.str, value.shape, _plain(value.tolist()))
    return value


def _digest(X, y, groups, context) -> str:
    """The rows' values, dtypes, shapes and memory layout (a BLAS call can round a C- and a
    Fortran-ordered copy of one matrix differently: not the same fit to the bit)."""
    h = hashlib.blake2b(digest_size=20)
    for a in (X, y):
        a = np.asarray(a)
        h.update(repr((a.dtype.str, a.shape, a.flags.c_contiguous, a.flags.f_contiguous)).encode())
        h.update(np.ascontiguousarray(a).tobytes())
    if groups is not None:
        h.update(pd.util.hash_array(np.asarray(groups, dtype=object)).tobytes())
    if context is not None:
        h.update(repr((list(context.columns), list(context.dtypes.astype(str)))).encode())
        h.update(pd.util.hash_pandas_object(context, index=False).to_numpy().tobytes())
    return h.hexdigest()
