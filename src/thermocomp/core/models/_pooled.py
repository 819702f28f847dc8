r"""The lag bank's ridge path over campaign folds from per-campaign moments.

When every fold of the lag bank's CV holds whole campaigns out (leave-campaigns-out) and no
term feeds the output back, everything its fit computes -- the standardisation, each fold's
centred Gram matrix and cross-products, the validation MSE of every penalty, the refit -- is a
sum over campaigns of each campaign's own moments: its row count, feature means
:math:`\bar f_c`, centred Gram :math:`C_c = \sum (f - \bar f_c)(f - \bar f_c)^\top`, and the same
with the target.  A lag bank starts its lags at each campaign's first sample, so a campaign's
features, and its moments, do not depend on which other campaigns are fitted with it: the ATI
wrapper's elbow (one lag bank per held-out campaign and number of intervals, thousands on a
climate-room record) and the validation folds refit the same campaigns in many combinations.
Their moments are computed once per campaign and pooled (Chan, Golub & LeVeque's parallel
formula, :func:`pool`); the folds' products over all their rows are not recomputed.

The numbers are those of :func:`thermocomp.core.models.lagbank.ridge_path_cv` and of its refit up
to rounding (the pooled sums are ordered differently).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

# StandardScaler's own rule for a constant column (private helpers): the pooled path must scale
# exactly as the row-by-row fit's StandardScaler does, or the two paths' penalties differ;
# tests/shell/test_lagbank_pooled.py holds them equal, so an upgrade that moves these fails there
from sklearn.preprocessing._data import _handle_zeros_in_scale, _is_constant_feature

from ._dynamics import first_order_lags
from ._memo import ArrayMemo


class Moments:
    """Pooled moments of a set of campaigns: ``n``, feature ``mean``, centred Gram ``gram``,
    ``y_mean``, centred cross-products ``fy`` and target sum of squares ``yy``."""

    __slots__ = ("n", "mean", "gram", "y_mean", "fy", "yy")

    def __init__(self, n, mean, gram, y_mean, fy, yy):
        self.n, self.mean, self.gram, self.y_mean, self.fy, self.yy = n, mean, gram, y_mean, fy, yy


def pool(counts, means, grams, y_means, fys, yys, which) -> Moments:
    r"""The moments of the campaigns ``which`` together: means weighted by the row counts and

    .. math:: C = \sum_c C_c + \sum_c n_c (\bar f_c - \bar f)(\bar f_c - \bar f)^\top

    (and likewise the cross-products with the target), without the cancellation of
    :math:`\sum f f^\top - n \bar f \bar f^\top`.
    """
    n_c = counts[which]
    n = n_c.sum()
    mean = n_c @ means[which] / n
    y_mean = n_c @ y_means[which] / n
    dm, dy = means[which] - mean, y_means[which] - y_mean
    member = np.zeros(len(counts))
    member[which] = 1.0
    # the sum of the members' Grams as one product over all segments: no copy of the members'
    gram = (member @ grams.reshape(len(counts), -1)).reshape(grams.shape[1:]) + (dm * n_c[:, None]).T @ dm
    fy = member @ fys + dm.T @ (n_c * dy)
    yy = member @ yys + n_c @ dy ** 2
    return Moments(float(n), mean, gram, float(y_mean), fy, float(yy))


def standardisation(total: Moments) -> tuple[np.ndarray, np.ndarray]:
    """``(mean_, scale_)`` of :class:`sklearn.preprocessing.StandardScaler` fitted on the rows of
    ``total`` (a constant column: scale 1, as scikit-learn decides it)."""
    var = np.diag(total.gram) / total.n
    constant = _is_constant_feature(var, total.mean, total.n)
    return total.mean, _handle_zeros_in_scale(np.sqrt(var), copy=False, constant_mask=constant)


def scaled(m: Moments, centre, d) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(mean, centred Gram, cross-products)`` of the design ``(f - centre) * d``."""
    return (m.mean - centre) * d, m.gram * np.outer(d, d), m.fy * d


def validation_mse(W, c, val: Moments, centre, d) -> np.ndarray:
    r"""Mean squared residual :math:`y - c - z^\top w` over the rows of ``val``, per column of ``W``:
    its spread around the means plus the squared mean residual."""
    z_mean, gram, fy = scaled(val, centre, d)
    spread = (val.yy - 2.0 * fy @ W + np.einsum("ij,ij->j", W, gram @ W)) / val.n
    return np.maximum(spread, 0.0) + (val.y_mean - c - z_mean @ W) ** 2


def lag_features(X, time, runs, taus, rest=None) -> np.ndarray:
    """``[x | L_tau1[x] - x | ... ]`` of the lag bank (:meth:`LagBank._features`); ``rest``: the
    columns whose lags start at 0 (:func:`first_order_lags`)."""
    n, p = X.shape
    out = np.empty((n, p * (taus.size + 1)))
    blocks = out.reshape(n, taus.size + 1, p)     # a view: block k holds columns k*p .. k*p+p-1
    # into one array, each lag block less x by broadcasting: no tiled copy of X nor a stacked
    # copy of the lags (a year at 1 min of 34 sensors: 1 GB each, scale58), nor the lags written
    # apart first and copied in (scale60)
    first_order_lags(X, time, runs, taus, rest, out=out[:, p:])
    blocks[:, 1:, :] -= X[:, None, :]
    blocks[:, 0, :] = X
    return out


def _feature_moments(X, time, taus, rest=None) -> tuple[np.ndarray, np.ndarray]:
    """``(mean, centred Gram)`` of one campaign's lag-bank features."""
    F = lag_features(X, time, None, taus, rest)
    mean = F.mean(axis=0)
    F -= mean
    return mean, F.T @ F


def _compute_target_moments(X, time, taus, y, mean, rest=None) -> tuple[float, np.ndarray, float]:
    """``(mean of y, centred cross-products with the features, centred sum of squares of y)``
    of one campaign (the features again: one filter pass over it, cheaper than keeping them)."""
    y_mean = float(y.mean())
    resid = y - y_mean
    return y_mean, (lag_features(X, time, None, taus, rest) - mean).T @ resid, float(resid @ resid)


# a campaign's feature moments by its inputs, times and time constants: about p^2 numbers each
# (0.4 MB for 24 inputs and 8 lags), so a few hundred campaigns' worth
_campaign_moments = ArrayMemo(_feature_moments, size=256, max_bytes=256e6)
# and its target's, by the campaign's digest and the target's values (p numbers each)
_target_moments = ArrayMemo(_compute_target_moments, size=4096)


class CampaignMoments:
    """Each segment's feature moments (remembered: a campaign's rows recur in many fits) and
    target moments (recomputed: a target's are cheap), in the order of the fit's rows."""

    def __init__(self, X, time, bounds, taus, y, rest=None):
        k, p = len(bounds), X.shape[1] * (len(taus) + 1)
        self.counts = np.array([stop - start for start, stop in bounds], dtype=float)
        self.means, self.grams = np.empty((k, p)), np.empty((k, p, p))
        self.y_means, self.fys, self.yys = np.empty(k), np.empty((k, p)), np.empty(k)
        taus, self.keys = np.asarray(taus, dtype=float), []
        for i, (start, stop) in enumerate(bounds):
            x_c, t_c = np.ascontiguousarray(X[start:stop]), np.ascontiguousarray(time[start:stop])
            self.keys.append(_campaign_moments.key(x_c, t_c, taus, rest))
            self.means[i], self.grams[i] = _campaign_moments.lookup(self.keys[-1], x_c, t_c, taus, rest)
            y_c = np.ascontiguousarray(y[start:stop])
            self.y_means[i], self.fys[i], self.yys[i] = _target_moments.lookup(
                ArrayMemo.key(self.keys[-1], y_c), x_c, t_c, taus, y_c, self.means[i], rest)
        self.key = ArrayMemo.key(*self.keys)

    def pool(self, which) -> Moments:
        """:func:`pool` of the segments ``which`` (an index array)."""
        return pool(self.counts, self.means, self.grams, self.y_means, self.fys, self.yys, which)


def _compute_spectra(trains: list[Moments], centre, d, alpha, free) -> tuple:
    """Each training fold's factorisation (:func:`spectra_of_grams`) of the design
    ``(f - centre) * d``."""
    return spectra_of_grams([scaled(train, centre, d)[:2] for train in trains], alpha, free)


# the folds' factorisations depend on the features alone: every target of a compensator shares them,
# and an ATI wrapper fits every target's elbow (some hundred lag banks, 2 MB each with 24 inputs
# and 8 lags) on the same sets of campaigns, one target after the other
_spectra = ArrayMemo(_compute_spectra, size=4096, max_bytes=768e6)


def pooled_path_cv(moments: CampaignMoments, folds, centre, d, alphas, free: int) -> np.ndarray:
    """Validation MSE ``(n_folds, n_alphas)`` of the ridge fits of
    :func:`thermocomp.core.models.lagbank.ridge_path_cv` (no output feedback) on the design
    ``(f - centre) * d``, the first ``free`` columns unpenalised; ``folds``: ``(train, validation)``
    segment indices."""
    alphas = np.asarray(alphas, dtype=float)
    alpha = alphas[0] if alphas.size == 1 else None
    key = ArrayMemo.key(moments.key, *(i for fold in folds for i in fold), centre, d, alpha, int(free))
    trains = [moments.pool(train) for train, _ in folds]
    spectra = _spectra.lookup(key, trains, centre, d, alpha, int(free))
    out = np.empty((len(folds), alphas.size))
    for f, (tr, (_, val)) in enumerate(zip(trains, folds)):
        W, c = weights_of_moments(spectra[f], tr.fy * d, tr.y_mean, alphas)
        out[f] = validation_mse(W, c, moments.pool(val), centre, d)
    return out


def pooled_refit(moments: CampaignMoments, centre, d, alpha: float, free: int):
    """``(W, c)`` of the ridge fit with penalty ``alpha`` on every segment's rows."""
    total = moments.pool(np.arange(len(moments.counts)))
    mean, gram, fy = scaled(total, centre, d)
    spectrum = spectra_of_grams([(mean, gram)], float(alpha), int(free))[0]
    return weights_of_moments(spectrum, fy, total.y_mean, np.array([float(alpha)]))


# The ridge solution from a Gram matrix and cross-products, shared by the lag bank's row-by-row
# fold path (lagbank.fold_spectra / fold_weights) and the pooled one here.

def spectra_of_grams(grams, alpha, free: int) -> tuple:
    """Each fold's factorisation from its ``(mean, centred Gram)`` (the Gram is overwritten), as
    :func:`thermocomp.core.models.lagbank.fold_spectra` remembers them."""
    out = []
    for mean, gram in grams:
        S = B = None
        if free:
            # pinvh: a constant or duplicated sensor leaves G_ss singular; OLS takes the minimum norm
            S = scipy.linalg.pinvh(gram[:free, :free])
            B = S @ gram[:free, free:]
            gram = gram[free:, free:] - gram[free:, :free] @ B
        if alpha is None:
            out.append((mean, *np.linalg.eigh(gram), B, S))
        else:
            gram[np.diag_indices_from(gram)] += alpha
            out.append((mean, None, scipy.linalg.cho_factor(gram), B, S))
    return tuple(out)


def weights_of_moments(spectrum, rhs, y_mean: float, alphas) -> tuple[np.ndarray, np.ndarray]:
    r""":func:`thermocomp.core.models.lagbank.fold_weights` from the training rows' centred
    cross-products ``rhs`` (:math:`Z_c^\top y_c`) and mean target ``y_mean``."""
    mean, lam, V, B, S = spectrum
    free = 0 if S is None else S.shape[0]
    r = rhs[free:] - (B.T @ rhs[:free] if free else 0.0)
    if lam is None:   # one penalty (fixed beforehand): V holds the factor of G + alpha I
        W = scipy.linalg.cho_solve(V, r)[:, None]
    else:
        W = V @ ((V.T @ r)[:, None] / (np.clip(lam, 0.0, None)[:, None] + alphas[None, :]))
    if free:
        W = np.vstack([(S @ rhs[:free])[:, None] - B @ W, W])
    return W, y_mean - mean @ W
