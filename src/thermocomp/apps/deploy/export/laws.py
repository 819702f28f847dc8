"""The linear laws of one target of the exported system (:mod:`.statespace`).

A target's output is the sum of its laws, each ``c + b0 . x + sum_d bd[d] . x(t-d) + sum_k g[k]
(z_k - x[j_k]) + a y(t-1)`` on its own previous output, times a factor the campaign's first
sample fixes: 1 for a plain model; for an ATI model (``ati=cmeans``) 1 within the interval of
the campaign's initial ambient ``A0`` and 0 outside it, and for its ambient interaction ``x (A0
- 20 °C)`` the law of those coefficients times ``A0 - 20`` (``A0`` is fixed over the campaign,
so ``b . x (A0 - 20) = (A0 - 20) b . x``, and a feedback is linear: the law with the interaction
is the sum of the two laws, each with the model's feedback); a diagnosed model's ambient step
``x [A0 > A_thr]`` is a law on ``x`` counting where ``A0 > A_thr`` (exportrest60), within its
ATI interval when the effects are around an ATI model.  A ``model=auto`` blend is its
members' laws weighted: members without feedback summed into one law per factor, a member with
an AR term a law of its own (its feedback is on its own output, not on the blend's).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ....core.models import ARX, MLR, PCR, Hammerstein, LagBank
from ....core.models.ati import AMBIENT_CENTRE_C, ATIRegressor
from .derived import (
    EXPORTED_EFFECTS,
    Derived,
    ambient_blocks,
    canonical_order,
    derived_inputs,
    exports,
    features,
    is_derived,
)
from .errors import NotExportable
from .forest import is_forest
from .members import described, is_diagnosed, members
from .recurrent import is_lstm, net_reads, skip_law

LINEAR_FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein")   # what exports to C / ST
# what exports, as every refusal names it: the linear families, what wraps them, and the two
# nonlinear ones as arrays (an onnx refusal named the linear five only: deploy88)
EXPORTED_FAMILIES = (f"{', '.join(LINEAR_FAMILIES)}; their ATI models and model=auto's blends of "
                     "them too; arx_rf, its forest as arrays; lstm, its network as arrays")
# and arx_rf: its ARX a law, its forest walked as arrays (:mod:`.forest`, exportrest62); lstm:
# its skip path a law, its cell stepped over arrays (:mod:`.recurrent`, lstmexport62); both within
# an ATI model too, each interval's forest or network counting in its interval (exportati63);
# a diagnosed lstm with any effect set the linear families export, its network reading the
# features the code computes for them (exportlstm64)
UNBOUNDED = sys.float_info.max      # an open interval edge (finite for JSON and ST)
PLAIN = 0.0                         # a lag's source: its input itself (a tau is > 0)


@dataclass
class Law:
    """One law over the code's ``[x, powers]`` (module doc), and when it counts: ``lo < A0 <=
    hi``, times ``(A0 - AMBIENT_CENTRE_C) ** ambient`` (``ambient`` 0, 1 or 2: a diagnosed
    ambient law's ``x (A0 - 20)`` around an ATI model's interaction, exportati60)."""

    c: float = 0.0
    terms: list = field(default_factory=list)      # [(indices into [x, powers], b0 there)]
    delayed: dict = field(default_factory=dict)    # {delay: row over x}
    # [(tau, index into [x, powers], gain, source)]: a lag of that input (source PLAIN), or of
    # its lag of tau ``source`` (a cascade: a lag bank's lag of a diagnosed effect's lag)
    lags: list = field(default_factory=list)
    a: float = 0.0
    gain: np.ndarray | None = None                 # step gain over x at the clamp's horizon
    lo: float = -UNBOUNDED
    hi: float = UNBOUNDED
    ambient: int = 0          # the power of A0 - 20 the law counts times
    # {(state input, its frame): gain over x} the gain adds times that state's value the sample
    # before the campaign's first excess (an ``inputs_product``'s, export62)
    gain_by: dict = field(default_factory=dict)

    @property
    def key(self) -> tuple:
        return self.lo, self.hi, self.ambient

    def add(self, other: "Law") -> "Law":
        """This law plus ``other`` (both without feedback, the same factor)."""
        delayed = dict(self.delayed)
        for d, row in other.delayed.items():
            delayed[d] = delayed.get(d, 0.0) + row
        return Law(self.c + other.c, self.terms + other.terms, delayed, self.lags + other.lags,
                   0.0, None, *self.key)


class Beside(NamedTuple):
    """An ``arx_rf``'s forest or an ``lstm``'s network the code runs beside the laws: its blend
    ``weight``, the fitted ``model``, and the interval ``lo < A0 <= hi`` of the campaign's
    initial ambient where it counts (an ATI model's; else unbounded); a network's ``reads``, per
    column of its inputs, the feature of the code it is (:func:`.recurrent.net_reads`)."""

    weight: float
    model: object
    lo: float = -UNBOUNDED
    hi: float = UNBOUNDED
    reads: tuple = ()

    @property
    def key(self) -> tuple:
        """The key of the law whose factor it takes (:attr:`Law.key`): its own linear part's."""
        return self.lo, self.hi, 0


def target_laws(target: str, est, cols: np.ndarray, inputs: list, powers: dict,
                period, beside: list) -> tuple[list[Law], object, str | None]:
    """``(laws, lag period, what model=auto or an ATI model kept)`` of ``target``'s estimator ``est`` reading
    the inputs ``cols`` of the code's ``inputs``; ``powers`` registers the features the code
    computes from its inputs (Hammerstein powers, a diagnosed model's derived inputs: :data:`DERIVED`
    keys), shared by the targets.  The clamp's gains: :func:`with_gains`.  An ``arx_rf`` (a
    member, an ATI interval's model) is its ARX's laws, its forest appended to ``beside``
    (:class:`Beside`, :mod:`.forest`); an ``lstm`` its skip path's law, its network likewise
    (:mod:`.recurrent`)."""
    parts, own = members(est), []
    for name, w, member in parts:
        try:
            for lo, hi, base, interacts, derived in _intervals(member):
                if is_forest(base) or is_lstm(base):
                    # the linear part a law, the forest or the network beside it, counting where
                    # that law does (an ATI interval's: exportati63)
                    reads = net_reads(base, cols, inputs, powers, interacts, derived, lo,
                                      hi) if is_lstm(base) else ()
                    beside.append(Beside(w, base, lo, hi, tuple(reads)))
                    base = base.arx_ if is_forest(base) else skip_law(base)
                laws, period = _member_laws(base, interacts, w, cols, inputs, powers, period,
                                            target, derived)
                for law in laws:     # an ambient step's law counts within the interval too
                    law.lo, law.hi = max(law.lo, lo), min(law.hi, hi)
                own += laws
        except NotExportable as exc:
            raise NotExportable(_member_refused(target, name, w, parts, exc)) from None
    return _summed(own), period, _named(described(parts), parts)


def with_gains(laws: list[Law], terms: list, cols: np.ndarray, n: int, target: str,
               by: dict | None = None) -> None:
    """The clamp's gain of a target's model, its ``terms`` (:func:`~thermocomp.core.gains.gain_terms`
    over the model's inputs ``cols`` of the code's ``n``), each added to the gain of the first
    law that counts as it does (the same interval of ``A0`` and power of ``A0 - 20``): the code's bound,
    ``|sum_r factor_r gain_r . ex|``, is then the model's own gain at the campaign's ``A0``, the
    one the stream takes (gain61: no second computation of it here).  ``by``: ``{(state input,
    frame): terms}`` that count times a state's value (an ``inputs_product``'s, the stream's
    ``AugmentedRegressor.held_gain_terms``), on ``gain_by`` the same way."""
    for law, gain in zip(laws, _on_laws(laws, terms, cols, n, target)):
        law.gain = gain
    for key, part in (by or {}).items():
        for law, gain in zip(laws, _on_laws(laws, part, cols, n, target)):
            law.gain_by[key] = gain


def _on_laws(laws: list[Law], terms: list, cols: np.ndarray, n: int, target: str) -> list:
    """Per law the sum of the ``terms`` that count as it does (:func:`with_gains`), over the
    code's ``n`` inputs."""
    out = [np.zeros(n) for _ in laws]
    for t in terms:
        if t.gain is None:      # an empty interval of A0 (a step above its ATI interval)
            continue
        key = (max(t.lo, -UNBOUNDED), min(t.hi, UNBOUNDED), t.power)
        r = next((r for r, law in enumerate(laws) if law.key == key), None)
        if r is None:
            if np.any(t.gain != 0.0):
                raise NotExportable(f"the clamp's gain of {target} counts where no law of the code "
                                    f"does ({key[0]:.4g} < A0 <= {key[1]:.4g}, power {key[2]})")
            continue
        out[r] = out[r] + _spread(t.gain, cols, n)
    return out


def _named(kept: str | None, parts: list) -> str | None:
    """What ``provenance.laws`` (and so the banner) says of a target: what ``model=auto`` or an
    ATI model kept, and the diagnosed effects the code computes as derived inputs, by title."""
    effects = [e for _, _, m in parts if is_diagnosed(m) for e in m.effects_]
    titles = [e.title for e in effects if is_derived(e)]
    # the ambient law, a low-pass of the inputs, a sensor's removal: laws of the code too, which
    # the banner left unnamed (which target carries the ambient law was nowhere in the code)
    others = [e.title for e in effects if not is_derived(e)]
    said = ([f"the derived inputs of {'; '.join(titles)}"] if titles else []) + \
        ([f"the diagnosed {'; '.join(others)}"] if others else [])
    if not said:
        return kept
    return f"{kept + ' ' if kept else ''}with {' and '.join(said)}"


def _intervals(est) -> list:
    """``[(lo, hi, model, takes the ambient interaction, derived inputs)]``: an ATI model's per
    interval of the initial ambient (``lo < A0 <= hi``, as ``interval_of`` assigns one), a
    diagnosed model's (:func:`_diagnosed`), else the model itself."""
    if is_diagnosed(est):
        return _diagnosed(est)
    if not isinstance(est, ATIRegressor):
        return [(-UNBOUNDED, UNBOUNDED, est, False, Derived())]
    edges = [-UNBOUNDED, *map(float, est.boundaries_), UNBOUNDED]
    return [(edges[m], edges[m + 1], e, bool(est.interactions_[m]), Derived())
            for m, e in enumerate(est.estimators_)]


def _diagnosed(est) -> list:
    """A diagnosed model's intervals: its base model's, when every effect it accepted is a
    sensor's removal (no feature: the base fitted on the inputs kept); else the base's law on
    ``[x, derived inputs]``, when each effect is one the code computes from its inputs as the
    stream does (:data:`DERIVED_TRANSFORMS`, a lag's initial-state transient:
    :func:`derived_inputs`), with a law on ``x`` per ambient law ``x (A0 - 20)`` or ambient step
    ``x [A0 > A_thr]`` (exportrest60: the step's law counts where ``A0 > A_thr``, what an ATI
    interval is); a lean level law ``(A0 - 20) x . w`` (diag107b) the ambient law's, its
    coefficients the base's one times ``w`` (:meth:`Derived.columns`).  Around an ATI model
    (``diagnose ati=cmeans``), the same per interval of the initial ambient, each interval's
    model fitted on the features (and, with the ambient interaction, on the features times ``A0
    - 20``: :func:`_member_laws`); a state times the inputs' rises (``inputs_product``) there too
    (exportprod65), its clamp's gain per interval a law's (:func:`with_gains`' ``by``: the ATI
    model's gain terms, each times the state's held value, on the law of their interval and power
    of ``A0 - 20``).  Any other effect is refused, naming it."""
    effects = list(est.effects_)
    if not effects:
        return _intervals(est.estimator_)
    if all(exports(e) for e in effects):
        feats, initial = features(est)
        order, factor = canonical_order(effects, int(est.n_features_in_), initial, est.initial_weights_)
        derived = Derived(
            feats, est.reference, float(getattr(est, "sample_period_s_", 1.0) or 1.0), order,
            [e.tau_s for e in effects if e.transform == "lowpass_inputs"], ambient_blocks(effects),
            factor)
        base = est.estimator_
        if not isinstance(base, ATIRegressor):
            return [(-UNBOUNDED, UNBOUNDED, base, False, derived)]
        edges = [-UNBOUNDED, *map(float, base.boundaries_), UNBOUNDED]
        return [(edges[m], edges[m + 1], e, bool(base.interactions_[m]), derived)
                for m, e in enumerate(base.estimators_)]
    others = [e.title for e in effects if not exports(e)]
    several = len(others) > 1
    raise NotExportable(f"the diagnosed effect{'s' if several else ''} {'; '.join(others)} "
                        f"{'do' if several else 'does'} not export (the code holds of diagnose's "
                        f"effects: {EXPORTED_EFFECTS}); the served model runs "
                        f"{'them' if several else 'it'} (thermocomp serve, connect)")


def _member_laws(est, interacts: bool, w: float, cols, inputs, powers, period, target,
                 derived: Derived) -> tuple[list[Law], object]:
    """The laws of one member (weight ``w``): its own, and per block of ``x`` the campaign's
    initial ambient switches (the ATI interaction's, a diagnosed model's ambient laws and steps:
    ``derived.blocks``) the law of its coefficients on that block (its inputs ``[x, blocks,
    powers]``); a diagnosed model's on ``[x, blocks, derived inputs, powers]``.  An ATI interval
    around a diagnosed model that takes the ambient interaction is fitted on ``[Z, Z (A0 -
    20)]``, ``Z`` those features: its laws on ``Z`` and, times ``A0 - 20``, its laws on the
    second half (each with the model's feedback: ``A0`` is fixed over the campaign)."""
    extra = derived_inputs(derived, inputs, powers, cols)
    linear, feats = _powered(est, inputs, powers)
    whole = interacts and derived.blocks is not None      # [Z, Z (A0 - 20)] (exportrest60)
    blocks = derived.blocks if derived.blocks is not None else [("ambient", None)] * interacts
    k = len(cols)
    own_x = k * (1 + len(blocks))               # the inputs' (and the ambient blocks') columns
    end = own_x + len(extra)                    # then the derived inputs', the low-pass blocks'
    # the model's own columns: a lean level law's one column is its block's k (canonical) places
    width = end + k * len(derived.lowpass) - derived.widened
    c, b0, delayed, lags, a, period = _target_law(linear, width * (1 + whole) + len(feats), period)
    if derived.lowpass or any(tau is not None for _, tau in extra) or any(
            f.initial is not None for f in derived.features):     # a transient's time too
        period = _one_period(period, derived.period)
    out = []
    for half in range(1 + whole):
        own = (lambda row: _half(row, half, width, len(feats))) if whole else (lambda row: row)
        laws = _laws(0.0 if half else c, own(b0), {d: own(r) for d, r in delayed.items()},
                     [(tau, _half_index(j, half, width) if whole else j, g) for tau, j, g in lags
                      if not whole or _half_index(j, half, width) is not None],
                     a, w, cols, len(inputs), target, derived, blocks, extra, feats)
        for law in laws if half else ():
            # the interaction's: times A0 - 20 (a step's too); the diagnosed ambient law's block
            # ``x (A0 - 20)`` times it is ``x (A0 - 20)^2`` (exportati60)
            law.ambient += 1
        out += laws
    return out, period


def _half(row: np.ndarray, half: int, width: int, n_feats: int) -> np.ndarray:
    """One half of an ATI interval's coefficients over ``[Z, Z (A0 - 20), powers]`` as a row
    over ``[Z, powers]``: a Hammerstein model's powers follow the interaction (its states from
    the context, not multiplied by ``A0 - 20``), so they belong to the first half's law."""
    out = np.zeros(width + n_feats)
    out[:width] = row[half * width:(half + 1) * width]
    if half == 0:
        out[width:] = row[2 * width:2 * width + n_feats]
    return out


def _half_index(j: int, half: int, width: int) -> int | None:
    """Where column ``j`` of ``[Z, Z (A0 - 20), powers]`` is in ``half``'s ``[Z, powers]``."""
    if half * width <= j < (half + 1) * width:
        return j - half * width
    return j - width if half == 0 and j >= 2 * width else None


def _laws(c, b0, delayed, lags, a, w, cols, n, target, derived, blocks, extra, feats):
    """:func:`_member_laws`' laws of one estimator's coefficients over ``[x, blocks, derived
    inputs, low-pass blocks, powers]`` (in the effects' order: :meth:`Derived.canonical`)."""
    k = len(cols)
    own_x = k * (1 + len(blocks))
    end = own_x + len(extra)
    width = end + k * len(derived.lowpass)
    b0, delayed, lags = derived.canonical(b0, delayed, lags)
    if any(np.any(r[own_x:width] != 0.0) for r in delayed.values()):
        raise NotExportable(f"the ARX law of {target} delays a diagnosed effect's feature: the "
                            "code's input history holds the inputs only")
    pw = n + np.asarray(feats, int)                     # the powers' places in [x, powers]
    dx = n + np.asarray([f for f, _ in extra], int)     # the derived inputs' places
    out = []
    for b, block in enumerate([None, *blocks]):
        x = slice(b * k, (b + 1) * k)
        terms = [(cols, w * b0[x])]
        own = [(tau, int(cols[j - x.start]), w * g, PLAIN) for tau, j, g in lags
               if x.start <= j < x.stop]
        if block is None:
            terms += [(dx, w * b0[own_x:end]), (pw, w * b0[width:])]
            # the base's lag of a derived input: of an effect's lag L1[r], a lag of that lag's
            # channel (a cascade, its source tau; exportrest60: the lag bank's second order)
            own += [(tau, int(dx[j - own_x]), w * g, extra[j - own_x][1] or PLAIN)
                    for tau, j, g in lags if own_x <= j < end]
            own += [(tau, int(pw[j - width]), w * g, PLAIN) for tau, j, g in lags if j >= width]
            # an effect's lag L[r] = r + (L[r] - r): its coefficient on r and on the lag channel
            own += [(tau, int(dx[i]), w * b0[own_x + i], PLAIN) for i, (_, tau) in enumerate(extra)
                    if tau is not None]
            for m, tau in enumerate(derived.lowpass):     # L[x] = x + (L[x] - x), per input
                lowpass = w * b0[end + m * k:end + (m + 1) * k]
                terms.append((cols, lowpass))
                own += [(tau, int(cols[j]), g, PLAIN) for j, g in enumerate(lowpass)]
            # the base's lag of a low-pass copy L1[x_j]: a cascade on x_j's channel
            own += [(tau, int(cols[(j - end) % k]), w * g, derived.lowpass[(j - end) // k])
                    for tau, j, g in lags if end <= j < width]
        # x [A0 > A_thr] (a step) counts where A0 > A_thr: the law of its block there
        lo = block[1] if block is not None and block[0] == "step" else -UNBOUNDED
        out.append(Law(0.0 if block else w * c, terms,
                       {d: w * _spread(r[x], cols, n) for d, r in delayed.items()}, own, a, lo=lo,
                       ambient=int(block is not None and block[0] == "ambient")))
    return out


def _one_period(period: float | None, own: float) -> float:
    if period is not None and own != period:
        raise NotExportable(f"the lags of the targets assume sample periods {period} and {own} s; "
                            "one exported step has one period")
    return own


def _summed(own: list[Law]) -> list[Law]:
    """One target's laws from its members' ``own``: those without feedback summed per factor,
    each with feedback a law of its own (``w a y_i(t-1)`` of the member's weighted output)."""
    plain: dict = {}
    for law in own:
        if law.a == 0.0:
            plain[law.key] = plain[law.key].add(law) if law.key in plain else law
    return [*plain.values(), *(law for law in own if law.a != 0.0)]


def _target_law(est, n: int, period: float | None):
    """``(c, b0, {delay: row}, [(tau, input, gain)], a, period)`` of one fitted estimator."""
    if type(est) not in (MLR, PCR, ARX, LagBank):     # exactly: a subclass may stream otherwise
        raise NotExportable(f"model {type(est).__name__} is not one of the linear families that "
                            f"export to C/ST ({EXPORTED_FAMILIES}); the served model runs it "
                            "(thermocomp serve, connect)")
    c = float(est.intercept_)
    if isinstance(est, (MLR, PCR)):
        return c, np.asarray(est.coef_, float), {}, [], 0.0, period
    if isinstance(est, ARX):
        b0, delayed = np.zeros(n), {}
        for (j, d), b in zip(est.terms_, est.coef_):
            row = b0 if d == 0 else delayed.setdefault(int(d), np.zeros(n))
            row[j] += float(b)
        return c, b0, delayed, [], float(est.ar_coef_), period
    coef = np.asarray(est.coef_, float)      # the lag bank
    lags = [(float(tau), j, float(coef[n * (i + 1) + j]))
            for i, tau in enumerate(est.taus_) for j in range(n)]
    return (c, coef[:n].copy(), {}, lags, float(est.ar_coef_),
            _one_period(period, float(est.sample_period_s_)))


def _powered(est, inputs: list, powers: dict) -> tuple[object, list[int]]:
    """``(linear estimator, its power features' indices)``: a Hammerstein model is its lag bank
    on the inputs and the powers of its states (registered in ``powers``, shared by targets).  A
    power one model starts at rest and another steady (audit106: one ATI interval's model and
    another's, ``rest_states_`` decided per fit) is two features, each with its start: the export
    was refused, "one exported power has one start"."""
    if type(est) is not Hammerstein:
        return est, []
    rest = getattr(est, "rest_states_", ())
    feats = []
    for e in est.exponents_:
        for s, col in enumerate(est.state_columns_):
            at_rest = col in rest
            key = (inputs.index(col), float(est.state_scale_[s]), float(e))
            if key in powers and (powers[key] in powers.rest) != at_rest:
                key = (*key, "rest" if at_rest else "steady")     # (its own start: a feature of its own)
            f = powers.setdefault(key, len(powers))
            (powers.rest if at_rest else powers.steady).add(f)
            feats.append(f)
    return est.lagbank_, feats


class Powers(dict):
    """The Hammerstein powers of the exported code, ``(input, scale, exponent) -> index`` in
    ``[x, powers]``, and which of them start their lags at rest (``rest_states_``)."""

    def __init__(self):
        super().__init__()
        self.rest, self.steady = set(), set()


def _member_refused(target: str, name, weight: float, parts: list, exc: NotExportable) -> str:
    """Why ``target``'s law does not export, naming what ``model=auto`` chose (``name``, of
    ``parts``) when it chose."""
    if name is None:
        return str(exc)
    if len(parts) == 1:
        return f"model=auto chose {name} for {target}: {exc}"
    return (f"model=auto's {described(parts)} for {target}: the member {name} (weight "
            f"{weight:.4g}) does not export: {exc}")


def _spread(row: np.ndarray, cols: np.ndarray, n: int) -> np.ndarray:
    out = np.zeros(n)
    out[cols] = row
    return out


__all__ = ["AMBIENT_CENTRE_C", "EXPORTED_FAMILIES", "LINEAR_FAMILIES", "UNBOUNDED", "Law", "target_laws",
           "with_gains"]
