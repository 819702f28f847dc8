"""perf87: the Monte Carlo sign patterns of the diagnose search's tests are drawn once per
``(units, resamples, seed)`` and taken as float in blocks; the p-values stay those of the whole
float matrix drawn afresh (benchmarks/bench_perf87.py: over a 34,560-row record's 15,840 units
each call drew 2.5 GB, freshly zeroed by the kernel, the bulk of diagnose's system CPU)."""

from __future__ import annotations

import numpy as np
import pytest

from thermocomp.apps.diagnose import cv


def _whole(D, n_resamples, seed, maxt):
    """The p-values from one float matrix of every pattern, drawn afresh (main's way)."""
    D = np.atleast_2d(D)
    n = D.shape[1]
    signs = np.random.default_rng(seed).choice([-1.0, 1.0], size=(n_resamples, n))
    if not maxt:
        hits = [np.sum(signs @ d / n >= d.mean() - 1e-12 * np.abs(d).sum()) for d in D]
        return (1 + np.asarray(hits)) / (n_resamples + 1)

    def t(mean, square):
        return mean / np.sqrt(np.maximum(square - n * mean ** 2, 1e-300) / ((n - 1) * n))

    order = np.argsort(-t(D.mean(axis=1), (D ** 2).sum(axis=1)))
    D = D[order]
    square = (D ** 2).sum(axis=1)
    observed = t(D.mean(axis=1), square)
    tail = np.maximum.accumulate(t(signs @ D.T / n, square)[:, ::-1], axis=1)[:, ::-1]
    hits = (tail >= observed - 1e-9 * np.maximum(np.abs(observed), 1.0)).sum(axis=0)
    out = np.empty(len(D))
    out[order] = np.maximum.accumulate((1 + hits) / (n_resamples + 1))
    return out


@pytest.fixture
def draws(monkeypatch):
    """Count the generators the module makes (each a fresh draw of the patterns)."""
    made = []
    real = np.random.default_rng

    def counted(*args, **kwargs):
        made.append(args)
        return real(*args, **kwargs)

    cv._drawn_signs.cache_clear()
    monkeypatch.setattr(np.random, "default_rng", counted)
    monkeypatch.setattr(cv, "CHUNK_CELLS", 7 * 41)     # 7 patterns a block: 500 = 71 x 7 + 3
    yield made
    cv._drawn_signs.cache_clear()


def test_monte_carlo_signs_are_drawn_once_and_blocks_give_the_whole_matrix_p_values(draws):
    rng = np.random.Generator(np.random.PCG64(9176))
    D = rng.standard_normal((2, 41)) + 0.3
    M = rng.standard_normal((5, 41)) + np.linspace(0, 0.6, 5)[:, None]
    got = [cv.sign_flip_pvalues(D, 500, seed=3), cv.sign_flip_maxt(M, 500, seed=3),
           cv.sign_flip_pvalues(D[:1], 500, seed=3)]
    assert len(draws) == 1          # three tests over the same 41 units: one draw
    cv.sign_flip_pvalues(D, 500, seed=4)
    assert len(draws) == 2          # another seed: its own patterns
    draws.clear()
    want = [_whole(D, 500, 3, False), _whole(M, 500, 3, True), _whole(D[:1], 500, 3, False)]
    for g, w in zip(got, want):
        np.testing.assert_array_equal(g, w)
    assert 0 < got[1].min() < got[1].max() <= 1      # the test can tell the candidates apart


def test_drawn_signs_are_read_only(draws):
    signs = cv._drawn_signs(41, 500, 3)
    assert signs.shape == (500, 41) and set(np.unique(signs)) == {-1, 1}
    with pytest.raises(ValueError):
        signs[0, 0] = 1
