"""A deployed linear compensator as one discrete linear state-space system plus static limits.

:func:`state_space` reads a :class:`~thermocomp.apps.deploy.StreamingCompensator` whose models are
linear (MLR, PCR, ARX with or without its AR term, lag bank) and writes down, as plain arrays,
everything its :meth:`~thermocomp.apps.deploy.StreamingCompensator.step` does to one sample ``u``
(the raw inputs, in ``inputs`` order), in this order:

1. causal FIR denoiser: ``buf <- [u, buf[:-1]]``, ``v = sum_k fir[k] * buf[k]`` (no denoiser:
   one tap of 1);
2. reference: ``ref = referenced * v`` at a campaign's first sample, ``x = v - ref``;
3. envelope (static limit), when ``clamp``: the excess over the bounds ``ex = x - min(max(x, lo), hi)``
   (else 0); with ``pattern``, ``ex = 0`` for a sample on the training pattern: ``z = (x -
   pattern_mean) / pattern_scale``, ``|z - B B' z|² <= pattern_tol²`` with ``B =
   pattern_basis`` (the stream's gate, :class:`~thermocomp.apps.deploy.streaming.Envelope`);
3b. a diagnosed model's derived inputs after the powers (``derived``: ``r_a r_b``, ``r_j = v_j
   - v_j(0)`` in the effect's frame, ``v(0)`` the first value; a signal only they read is
   ``held`` when missing, as the model holds its context): :func:`.derived.derived_inputs`; where
   ``derived_clamped`` (a state times the inputs' rises, export62) ``r_b`` is the model's input's
   rise ``x_b - x_b(0)``, and in the excess channel ``r_a (ex_b - ex_b(0))``; where
   ``derived_over`` names an input ``c`` (a temperature's rise over the air's, overexport72)
   ``r_b - r_c``, ``r_c`` in ``r_b``'s frame;
   then a diagnosed lag's initial-state transient (``initial``: ``w . (c(0) - A0) (1 - exp(-(t
   - t0)/tau))``, ``c(0)`` its sensors at the first sample that has one of them, a missing one
   0, ``A0`` the campaign's initial ambient, ``t0`` its first sample's time; exportrest60);
4. per law ``r``: ``y_r = c_r + b0_r . x + sum_d bd_r[d] . x(t-d) + sum_k g_r[k] (z_k - x[lag_input_k])
   + a_r y_r(t-1)``, and per target ``t`` the sum of its laws ``y_t = sum_{law_target[r] = t} y_r``
   times the law's factor for the campaign (one law per target, factor 1; a ``model=auto``
   blend is its members' laws weighted and summed, each member feeding back its own output, an
   AR term, a law of its own; an ATI model's laws count in the interval of the campaign's
   initial ambient ``A0``, the mean of ``ambient_inputs`` at its first sample (``ambient_given``:
   given at the campaign's start instead, the manifest's ``ambient_c``, exportrest62), its ambient
   interaction's times ``A0 - ambient_centre``, a diagnosed ambient law's under it times its
   square: ``(A0 - ambient_centre) ** law_ambient``, exportati60: :mod:`.laws`), with the input history
   ``x(t-d)`` (``d = 1..depth``) and the first-order lags ``z_k <- e_k z_k + (1 - e_k)
   x[lag_input_k]`` (``z[lag_of_k]``, that lag's new value, for a cascade: a lag bank's lag of a
   diagnosed effect's lag; its term ``g (z_k - z[lag_of_k])``), ``e_k = exp(-dt / tau_k)``,
   ``dt`` the time since the previous sample (``time_period`` without one, timerule.py); the
   same system, without intercept and powers, runs on ``ex`` (its own history, lags and
   feedback) to ``r_t``, the response to the excess; the output is ``y_t - clip(r_t, -b_t,
   b_t)`` (``y_t - r_t`` where
   ``clamp_outright_t``: the stream's clamp of a model without a step gain; an ``arx_rf``'s forest,
   :mod:`.forest`, adds to ``y_t`` times its weight, an ``lstm``'s residual too, its cell stepped
   on the clamped features, ``[x, lags]`` minus their excess channel: :mod:`.recurrent`),
   ``b_t = |clamp_gain_t . ex|`` the response to the excess held for the envelope's horizon
   (0 for a target of ``clamp_spread`` at a sample with two inputs or more out: a white target,
   ``promote.envelope.per_target``)
   (as the stream does; the gain plus ``sum_s r_s clamp_state_gain[s]``, ``r_s`` a state's
   value at the sample before the campaign's first excess, held: an ``inputs_product``'s,
   export62; ``y_t - r_t`` in a campaign out at its first sample where ``clamp_state_first_t``,
   the stream then having no value); at a
   sample within the envelope (``ex = 0``) after an excess, ``b_t`` is the last excess's (0
   before the campaign's first): an excess that fades out ends with a bound near 0 (the model's
   own correction, as scored), one that ends at once (a one-row spike, a sensor's offset gone)
   keeps its bound, so that what it left in the lags and the feedback is taken out as it decays
   (with the sample's own bound, 0 in range, a one-row +50 °C spike stayed in a lag bank's
   correction to the campaign's end);
5. the correction guard, when the model was deployed with one (:mod:`.output`): ``y_t`` held
   within ``guard_rate_t * dt`` of its previous value, then within ``[guard_lo_t - a_t, guard_hi_t
   + a_t]``; ``a_t = guard_gain_t . d`` with ``guard_inputs`` at a sample on the training pattern,
   ``d`` the distance of ``x`` beyond ``[guard_in_lo, guard_in_hi]`` (else 0);
6. the correction sent to the CNC is ``C_t = -y_t`` (with ``adapt``: ``-(gain_t * y_t + bias_t)``,
   updated by each reference measurement).

A sample with an input that is not finite (a sensor dropout) is refused before any of this: the
state is untouched and the last correction given is repeated (0 before a campaign's first
sample), as the plain stream refuses such a row and ``monitor``'s fixed stream holds its
correction; one NaN stepped would stay in the lags, the feedback and the guard to the campaign's end.
A value beyond its input's ``input_limit`` (a temperature beyond ``MAX_ABS_T_C``, 10000 °C: a
logger's overload mark, +9.9E+37 for an open thermocouple) is such a missing value too (a held
signal's held), where the streams refuse it: a PLC cannot refuse a row (code71; the code clamped
it into the model before).

At a campaign's first sample every memory starts in steady state on it (FIR buffer and input
history full of it, lags on it, previous outputs 0), as the stream starts.  Between the
reference and the limit the system is linear: the state is ``[buf, ref, history, z, y_prev]``, the
last three for each channel (``y_prev`` per law), and the limit keeps one number per target, ``b_t``.
"""

from __future__ import annotations

import copy
from dataclasses import asdict, dataclass, field

import numpy as np

from ....core.frame import ambient_c0
from ....core.gains import GainTerm, gain_at, gain_terms
from ....core.io.values import reading_limit
from ....core.timerule import SampleClock, on_grid, repeats
from ..adaptive import AdaptiveCompensator
from ..streaming import Envelope
from .derived import CLAMPED, DERIVED, INITIAL, OVER
from .errors import NotExportable
from .fallbacks import with_fallbacks
from .forest import ForestArrays, Forests, Switches
from .laws import AMBIENT_CENTRE_C, LINEAR_FAMILIES, PLAIN, UNBOUNDED, Powers, target_laws, with_gains
from .output import Output, adapt_fields, guard_fields, time_fields
from .recurrent import Cells, NetArrays, Nets, is_lstm
from .watch import CodeMonitor, MonitorArrays, monitor_fields

FORMATS = ("json", "c", "st", "onnx")


@dataclass
class _System:
    """The linear system and what follows it, :class:`StateSpace`'s first fields."""

    inputs: list                 # raw input columns, in the order of ``u`` (the model's inputs,
                                 # then the machine states its powers read, unfiltered)
    targets: list                # error columns; the code outputs ``C_<axis>`` = -y
    fir: list                    # (taps, n_inputs)
    referenced: list             # (n_inputs,) 1: taken relative to the first sample
    clamp: bool
    lo: list | None              # (n_inputs,) envelope, in the referenced frame (clamp only)
    hi: list | None
    depth: int                   # input history kept (largest ARX delay)
    taus: list                   # (n_lags,) s
    lag_input: list              # (n_lags,) index of each lag's input in ``[x, powers, derived]``
    lag_decay: list              # (n_lags,) exp(-period / tau): the step without a time
    period: float                # s
    intercept: list              # (n_laws,): one law per target, or more (law_target)
    b0: list                     # (n_laws, n_inputs + n_powers + n_derived)
    bd: list                     # (n_laws, depth, n_inputs)
    g: list                      # (n_laws, n_lags)
    ar: list                     # (n_laws,)
    uses_time: bool              # the lags read ``time`` when it is given
    # static powers (Hammerstein): [input index, scale, exponent], sign(w) |w|^e of w = v / scale
    powers: list = field(default_factory=list)
    lag_rest: list = field(default_factory=list)   # (n_lags,) 1: starts at 0, not at its input
                                                   # (a Hammerstein state at rest); [] none
    # (n_lags,) the lag whose output is this lag's input (-1: x[lag_input]): a lag bank's lag of
    # a diagnosed effect's lag, a cascade after its source (exportrest60); [] none
    lag_of: list = field(default_factory=list)
    # a diagnosed model's derived inputs, after the powers: [a, b, ra, rb], r_a r_b (b = -1: r_a)
    # of r_j = v_j - rj v_j(0), v(0) the campaign's first sample (:func:`.derived.derived_inputs`)
    derived: list = field(default_factory=list)
    # (n_inputs,) 1: a signal only derived inputs read (no declared input): a missing value does
    # not refuse the sample, it is held at the campaign's last one (0 before any: its derived
    # inputs 0, its first value their reference), as the diagnosed model holds its context
    held: list = field(default_factory=list)
    # (n_inputs,) the largest |value| a sensor of each input reads (a temperature's MAX_ABS_T_C,
    # UNBOUNDED for any other): beyond it (a logger's overload mark, +9.9E+37) the value is
    # missing, as NaN, in every form of the code (:meth:`StateSpace.measured`; code71); empty (an
    # older export): any finite value
    input_limit: list = field(default_factory=list)
    # (n_derived,) 1: r_b is the model's input's rise x_b - x_b(0), the clamped one in the excess
    # channel (e_b - e_b(0), e(0) the excess at the campaign's first sample): a state times the
    # inputs' rises (inputs_product, export62); [] none
    derived_clamped: list = field(default_factory=list)
    # (n_derived,) the input c whose r_c the second factor is taken over, r_a (r_b - r_c): a
    # temperature's rise over the air's (Effect.over, overexport72); -1 none; [] none at all
    derived_over: list = field(default_factory=list)
    # a diagnosed lag's initial-state transient, after the derived inputs, one per direction:
    # [tau, [sensor input indices], [weights]]: w . (v(0) - A0) (1 - exp(-(t - t0) / tau)),
    # v(0) the sensors at the campaign's first sample that has one of them (a missing one: 0)
    initial: list = field(default_factory=list)
    # (n_laws, n_inputs) step gain at the horizon (clamp only): the model's gain terms, each on a
    # law of its factor (:func:`.laws.with_gains`)
    clamp_gain: list | None = None
    # (n_targets,) 1: the response to the excess is taken out whole (b_t infinite): the stream
    # clamps a model without a step gain outright; empty: none
    clamp_outright: list = field(default_factory=list)
    # (n_targets,) 1: a white target (``promote.envelope.per_target``): unclamped (b_t = 0) at a
    # sample whose excess at least two inputs share (the stream's spread_excess); empty: none
    clamp_spread: list = field(default_factory=list)
    # a diagnosed state times the inputs' rises (inputs_product, export62): the gain grows by each
    # state's value r_a (``[input, referenced]``: v_a - referenced v_a(0), as a derived input's)
    # at the sample before the campaign's first excess, times ``clamp_state_gain`` (n_laws,
    # n_states, n_inputs); ``clamp_state_first`` (n_targets,) 1: a target whose gain reads them,
    # clamped outright in a campaign whose first sample is out (the stream has no value yet)
    clamp_states: list = field(default_factory=list)
    clamp_state_gain: list = field(default_factory=list)
    clamp_state_first: list = field(default_factory=list)
    # the training pattern (clamp only; a machine state: scale UNBOUNDED, basis 0, never off it)
    pattern: bool = False            # clamp only a sample off the pattern (else every excursion)
    pattern_mean: list | None = None     # (n_inputs,)
    pattern_scale: list | None = None    # (n_inputs,)
    pattern_basis: list | None = None    # (n_inputs, rank)
    pattern_tol: float = 0.0
    # what follows the system: the correction guard and the reference update (:mod:`.output`)
    substitute_time: bool = False    # a non-increasing time too is substituted (timerule.py)
    skip_repeats: bool = False       # (dup99) a row written again is skipped (timerule.repeats)
    time_period: float = 0.0         # s: a sample without time is this after the previous
    # s: the training period a model with a memory steps on (cadence72): a sample less than it
    # after the last one stepped (timerule.on_grid) is answered by the model's step from that
    # one's state, not kept (between73); 0: none
    grid_period: float = 0.0
    guard: bool = False
    guard_lo: list | None = None     # (n_targets,) µm of predicted error
    guard_hi: list | None = None
    guard_rate: list | None = None   # (n_targets,) µm/s; null: no rate limit
    guard_period: float = 0.0        # s: the shortest ``dt`` of the rate limit (training's period)
    guard_lo_new: list | None = None  # (cmon82b) the bound in a new thermal state (None: lo, hi)
    guard_hi_new: list | None = None
    # the bound following the inputs on the training pattern (pattern only; :mod:`.output`)
    guard_inputs: bool = False
    guard_gain: list | None = None   # (n_targets, n_inputs) |step gain| (a state's: 0)
    guard_in_lo: list | None = None  # (n_inputs,) the training range (a state's: unbounded)
    guard_in_hi: list | None = None
    adapt: str = "none"              # none | bias | rls
    adapt_gain: list | None = None   # (n_targets,) as served (learned so far)
    adapt_bias: list | None = None   # (n_targets,) µm, as served
    adapt_var: list | None = None    # (n_targets,) µm², the bias's variance (bias)
    adapt_cov: list | None = None    # (n_targets, 2, 2) covariance of (gain, bias) (rls)
    adapt_forgetting: float = 1.0
    adapt_max_bias: float = 0.0      # µm
    adapt_max_gain_change: float = 0.0
    adapt_var_cap: float = 0.0       # µm², the prior variance (the variance never exceeds it)
    provenance: dict = field(default_factory=dict)
    # the target each law adds to (a blend's member with its own feedback: a law of its own);
    # empty (an older export): law i is target i's
    law_target: list = field(default_factory=list)
    # (cmon83) whose law each is: 0 the model's, s a fallback model's (the monitor's
    # fallback_set: the correction fitted without a sensor, served while it is out); every law
    # steps, the output sums the served set's (:mod:`.fallbacks`); empty: every law the model's
    law_set: list = field(default_factory=list)
    # when each law counts (an ATI model's, ati=cmeans): A0, the mean of the ambient inputs at a
    # campaign's first sample, in (law_lo, law_hi]; times A0 - ambient_centre where law_ambient
    law_lo: list = field(default_factory=list)       # (n_laws,) °C; empty: every law always
    law_hi: list = field(default_factory=list)
    law_ambient: list = field(default_factory=list)  # (n_laws,) the power of A0 - centre: 0, 1, 2
    ambient_inputs: list = field(default_factory=list)   # indices of the ambient inputs (A0)
    ambient_centre: float = 20.0                     # °C
    # A0 is given at a campaign's start, not read from an input: the model reads no ambient
    # sensor, each campaign's ambient is its manifest's ``ambient_c`` (campaigns.csv), as the
    # stream takes it at reset (C: tc_set_ambient; ST: the input ambient_c; exportrest62)
    ambient_given: bool = False
    # ... and a campaign given none still starts (no ambient law: a diagnosed lag's initial state
    # alone reads A0, and without it the mean of its sensors' first values, as the model does;
    # stranger66)
    ambient_optional: bool = False


def within_limits(u, limits: np.ndarray) -> np.ndarray:
    """Per input, whether the raw value ``u`` is one a sensor reads: ``|u| <= limits`` (NaN, an
    infinity, a temperature's overload mark: missing); one rule for the state space and its
    sample-by-sample :class:`Simulator` (which makes ``limits`` once)."""
    with np.errstate(invalid="ignore"):
        return np.abs(np.asarray(u, float)) <= limits


@dataclass
class StateSpace(MonitorArrays, NetArrays, ForestArrays, _System):
    """Arrays of the exported system (module doc); lists, so that it is its own JSON.  After the
    linear system's (:class:`_System`), an arx_rf model's forests on a machine state's
    switching (:class:`~.forest.ForestArrays`, exportrest62) and an lstm model's networks
    (:class:`~.recurrent.NetArrays`, lstmexport62), each declared once, in its module."""

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> "StateSpace":
        return cls(**d)

    def measured(self, u) -> np.ndarray:
        """Per input, whether the raw value ``u`` is one a sensor reads: within its
        ``input_limit`` (NaN, an infinity, a temperature's overload mark: missing)."""
        return within_limits(u, np.asarray(self.limits, float))

    @property
    def limits(self) -> list:
        """``input_limit``, or (an older export) UNBOUNDED for every input."""
        return list(self.input_limit) or [UNBOUNDED] * len(self.inputs)

    @property
    def laws(self) -> list:
        """The target index of each law."""
        return list(self.law_target) or list(range(len(self.targets)))

    def factors(self, a0: float) -> np.ndarray:
        """Each law's factor in a campaign of initial ambient ``a0`` (°C; 0 without ambient
        inputs): 1, or 0 outside its interval, times ``(a0 - ambient_centre) ** law_ambient``
        (a product, as the C and the ST compute it)."""
        laws = len(self.laws)
        lo = np.asarray(self.law_lo or [-UNBOUNDED] * laws, float)
        hi = np.asarray(self.law_hi or [UNBOUNDED] * laws, float)
        power = np.asarray(self.law_ambient or [0] * laws, int)
        factor = np.ones(laws)
        for p in range(int(power.max(initial=0))):
            factor = np.where(power > p, factor * (a0 - self.ambient_centre), factor)
        return np.where((a0 > lo) & (a0 <= hi), factor, 0.0)

    @property
    def n_states(self) -> int:
        n = len(self.inputs)
        return ((len(self.fir) - 1) * n + n + 2 * (self.depth * n + len(self.taus) + len(self.laws))
                + 2 * len(self.lstm_target) * self.lstm_layers * self.lstm_hidden)   # an lstm's h, c


def state_space(deployed, provenance: dict | None = None, known_ambient: bool = True,
                monitor: bool = False) -> StateSpace:
    """The :class:`StateSpace` of a deployed stream or adaptive compensator (module doc; of the
    latter its plain stream, guard and reference update); :class:`NotExportable` names what
    keeps it from being one.  ``known_ambient``: false for a stream made without its training
    data (which ambient sensors an ATI model reads is not known yet: not refused for it).
    ``monitor``: with the adaptive compensator's sensor monitor (:mod:`.watch`, the C's)."""
    stream = deployed.streaming if isinstance(deployed, AdaptiveCompensator) else deployed
    comp = stream.compensator
    declared = list(comp.inputs_)
    states = [c for c in stream.columns_ if c not in declared]   # read raw by Hammerstein powers
    inputs, n = declared + states, len(declared)
    if stream.envelope is not None and stream.policy == "refuse":
        raise NotExportable("envelope policy 'refuse' stops the stream; the code clamps or passes "
                            "the inputs (promote.envelope.policy=clamp|off)")
    den = stream.denoiser
    if den is None:
        fir = np.ones((1, n))
    elif getattr(den, "causal", None) == "fir" and hasattr(den, "fir_"):
        fir = np.asarray(den.fir_, float).reshape(-1, n)
    else:
        raise NotExportable(f"denoiser {type(den).__name__} (causal={getattr(den, 'causal', None)!r}) "
                            "is not a linear filter; the causal FIR one exports "
                            "(denoise.denoiser.causal=fir)")
    unfiltered = np.zeros((len(fir), len(states)))     # a state's value as read (one tap of 1)
    unfiltered[0] = 1.0
    fir = np.hstack([fir, unfiltered])
    N = len(inputs)
    env, clamp = stream.envelope, stream.envelope is not None and stream.policy == "clamp"
    laws, period, powers, chosen = [], None, Powers(), {}      # laws: (target index, Law)
    outright, spread, by_state, forests, nets = [], [], [], Forests(), Nets()
    for i, (t, est, idx) in enumerate(stream._plan):
        cols = np.arange(n) if idx is None else np.asarray(idx)
        beside: list = []        # an arx_rf's forest, an lstm's network (laws.Beside)
        own, period, kept = target_laws(t, est, cols, inputs, powers, period, beside)
        for b in beside:         # each takes the factor of its linear part's law
            r = len(laws) + _law_of(own, b.key, t)
            if is_lstm(b.model):     # a network's inputs each the factor of its law too
                nets.add(i, b.weight, b.model, r, [(p, tau, len(laws) + _law_of(own, key, t))
                                                   for p, tau, key in b.reads])
            else:
                forests.add(i, b.weight, b.model, inputs, r)
        # the clamp's gain: the deployed model's own, split as its laws count (gain61: the one
        # computation the stream's step_gain sums at the campaign's A0); none: clamped outright
        # a target the stream leaves unclamped (white_targets) has its gain too: it is clamped
        # at a sample whose excess one input alone carries (clamp_spread)
        terms, by = _clamp_terms(t, est, env.horizon_s, inputs) if clamp else (None, {})
        outright.append(int(clamp and terms is None))
        spread.append(int(clamp and t in stream.unclamped_))
        by_state.append(int(bool(by) and terms is not None))
        if terms is not None:
            with_gains(own, terms, cols, N, t, by)
        laws += [(i, law) for law in own]
        if kept is not None:
            chosen[t] = kept
    place = _in_code_order(laws, powers, N)
    ati = any(law.key != (-UNBOUNDED, UNBOUNDED, False) for _, law in laws)
    initial = [k for k in sorted(powers, key=powers.get) if k[0] == INITIAL]
    ambient, given = _ambient_inputs(stream, inputs, ati or bool(initial), known_ambient)
    switches = [j for j in forests.switch_input if j >= 0]     # a forest's state columns
    # a forest's state ramps over the time the model is given: the stream's clock, or (a plain
    # stream without one: no lag's period) the time as read
    forests.switch_raw_time = bool(switches) and not isinstance(
        deployed, AdaptiveCompensator) and stream._clock is None
    read = {inputs[j] for j in _read(powers) | set(switches)} | {inputs[j] for j in ambient}
    if any(c not in read for c in states):
        raise NotExportable(f"the model reads columns beyond its inputs ({stream.columns_}): "
                            f"only the families {', '.join(LINEAR_FAMILIES)} export to C/ST")
    width = N + len(powers)
    depth = max((d for _, law in laws for d in law.delayed), default=0)
    # (tau, input, source): the plain lags first, then the cascades on them (a lag's lag)
    keys = sorted({(tau, j, src) for _, law in laws for tau, j, _, src in law.lags}
                  | {(tau, j, PLAIN) for tau, j in nets.lags(place)},     # (a network's own)
                  key=lambda k: (k[2] != PLAIN, *k))
    where = {k: i for i, k in enumerate(keys)}
    targets = list(stream.targets_)
    b0 = np.zeros((len(laws), width))
    g = np.zeros((len(laws), len(keys)))
    bd = np.zeros((len(laws), depth, N))
    for r, (_, law) in enumerate(laws):
        for cols, row in law.terms:     # one place twice (two effects on one derived input,
            np.add.at(b0[r], cols, row)   # a lag and the signal as read): both coefficients
        for tau, j, gain, src in law.lags:
            g[r, where[(tau, j, src)]] += gain
        for d, row in law.delayed.items():
            bd[r, d - 1] = row
    period = float(period) if period is not None else 0.0
    grid = float(getattr(comp, "grid_period_s_", None) or 0.0)
    states_by = sorted({key for _, law in laws for key in law.gain_by})
    state_gain = np.zeros((len(laws), len(states_by), N))
    for r, (_, law) in enumerate(laws):
        for s, key in enumerate(states_by):
            state_gain[r, s] = law.gain_by.get(key, 0.0)
    derived = [k for k in sorted(powers, key=powers.get) if k[0] == DERIVED]
    ss = StateSpace(
        inputs=inputs, targets=targets, fir=fir.tolist(),
        referenced=[int(r) for r in stream._is_ref] + [0] * len(states), clamp=bool(clamp),
        lo=env.lo.tolist() + [-UNBOUNDED] * len(states) if clamp else None,
        hi=env.hi.tolist() + [UNBOUNDED] * len(states) if clamp else None,
        depth=int(depth), taus=[k[0] for k in keys], lag_input=[k[1] for k in keys],
        lag_rest=[int(j - N in powers.rest) for _, j, _ in keys] if powers.rest else [],
        lag_of=[-1 if src == PLAIN else where[(src, j, PLAIN)] for _, j, src in keys]
        if any(k[2] != PLAIN for k in keys) else [],
        lag_decay=[float(np.exp(-period / k[0])) for k in keys], period=period,
        intercept=[float(law.c) for _, law in laws], b0=b0.tolist(),
        bd=bd.tolist(), g=g.tolist(), ar=[float(law.a) for _, law in laws],
        law_target=[i for i, _ in laws], law_lo=[law.lo for _, law in laws],
        law_hi=[law.hi for _, law in laws], law_ambient=[int(law.ambient) for _, law in laws],
        ambient_inputs=ambient, ambient_centre=AMBIENT_CENTRE_C, ambient_given=given,
        ambient_optional=bool(given and not ati and stream.ambient_optional_),
        uses_time=bool(keys) or bool(initial) or bool(switches) or bool(grid),
        powers=[list(k) for k in sorted(powers, key=powers.get) if k[0] not in (DERIVED, INITIAL)],
        derived=[list(k[1:5]) for k in derived],
        derived_clamped=[int(k[5:] == (CLAMPED,)) for k in derived]
        if any(k[5:] == (CLAMPED,) for k in derived) else [],
        derived_over=[k[6] if k[5:6] == (OVER,) else -1 for k in derived]
        if any(k[5:6] == (OVER,) for k in derived) else [],
        initial=[[k[3], list(k[1]), list(k[2])] for k in initial],
        held=_held(inputs, n, powers, ambient, switches),
        input_limit=[min(reading_limit(c), UNBOUNDED) for c in inputs],
        **forests.fields(), **nets.fields(place, {(tau, j): at for (tau, j, src), at in where.items()
                                                   if src == PLAIN}, width),
        clamp_gain=[(law.gain if law.gain is not None else np.zeros(N)).tolist()
                    for _, law in laws] if clamp else None,
        clamp_outright=outright if any(outright) else [],
        clamp_spread=spread if any(spread) else [],
        clamp_states=[list(k) for k in states_by], clamp_state_gain=state_gain.tolist()
        if states_by else [], clamp_state_first=by_state if states_by else [],
        **_pattern_fields(env if clamp else None, len(states)),
        # a sample without time: one period later (timerule.py); a plain stream's: the lags'
        **time_fields(deployed, period or grid),
        grid_period=grid,
        **guard_fields(deployed, len(states), clamp and env.basis is not None),
        **adapt_fields(deployed),
        **(monitor_fields(deployed, inputs) if monitor else {}),
        provenance={**(provenance or {}), **({"laws": chosen} if chosen else {})})
    if ss.monitor:      # (cmon83) the served fallback models, beside the model's laws
        with_fallbacks(ss, deployed, lambda fb: state_space(fb, known_ambient=known_ambient))
    return ss


def _law_of(own: list, key: tuple, target: str) -> int:
    """The index among a target's laws ``own`` of the one whose factor is ``key``'s."""
    found = next((k for k, law in enumerate(own) if law.key == key), None)
    if found is None:
        raise NotExportable(f"a network of {target} reads a feature counting where no law of the "
                            f"code does ({key[0]:.4g} < A0 <= {key[1]:.4g}, power {key[2]})")
    return found


def _clamp_terms(target: str, est, horizon_s: float, inputs: list) -> tuple[list | None, dict]:
    """``(terms, by)``: the gain terms of ``target``'s model at the clamp's horizon
    (:mod:`thermocomp.core.gains`), ``None`` where it has no gain in any campaign (the stream
    clamps it outright, the code too); ``by``: ``{(state input, referenced): terms}`` the value of
    a state held at the campaign's first excess multiplies, of a diagnosed ``inputs_product``
    (:meth:`~thermocomp.apps.diagnose.AugmentedRegressor.held_gain_terms`; ``terms`` then with
    the states at 0).  A model with a gain for some campaigns' initial ambient only is refused:
    the code's outright clamp is per target, the stream's per campaign."""
    terms, by = _held_terms(est, horizon_s, inputs)
    if terms is None:
        terms = gain_terms(est, horizon_s)
    # each interval of A0 the terms' edges make (an edge belongs to the interval below it)
    edges = np.array(sorted({e for t in terms for e in (t.lo, t.hi) if np.isfinite(e)}))
    probes = np.r_[edges, (edges[1:] + edges[:-1]) / 2, edges.min(initial=0.0) - 1.0,
                   edges.max(initial=0.0) + 1.0]
    none = [gain_at(terms, a0) is None for a0 in probes]
    if all(none):
        return None, {}
    if any(none):
        raise NotExportable(f"the model of {target} has a step gain for some campaigns' initial "
                            "ambient only (an ATI interval's AR term without a steady state): the "
                            "stream clamps the others outright, the code clamps per target; "
                            "export it with promote.envelope.policy=off")
    return terms, by


def _held_terms(est, horizon_s: float, inputs: list) -> tuple[list | None, dict]:
    """A diagnosed model's gain terms with an ``inputs_product`` (the stream's gain depends on
    its state's value, held from the sample before the campaign's first excess): ``(terms at the
    states' value 0, {(state input, referenced): the terms its value multiplies})``; ``(None,
    {})`` for any other model."""
    from ...diagnose.features import frames  # a diagnosed model's: loaded with it
    held = getattr(est, "held_gain_terms", None)
    effects = getattr(est, "effects_", ())
    if not callable(held) or not any(e.transform == "inputs_product" for e in effects):
        return None, {}
    terms, per_effect = held(horizon_s)
    by: dict = {}
    for i, part in per_effect.items():
        e = effects[i]
        key = (inputs.index(e.column), int(frames(e, est.reference)[0] == "first_sample"))
        by[key] = by.get(key, []) + [GainTerm(*t) for t in part]
    return terms, by


def _held(inputs: list, n: int, powers: dict, ambient: list, switches: list) -> list[int]:
    """Per input, 1 for a signal only powers, derived inputs or forests (``switches``) read (a
    machine state: not one of the ``n`` declared inputs, no ambient sensor): the stream checks
    the declared inputs and the ambient sensors only, and a Hammerstein model, the diagnosed model
    and arx_rf hold a missing value of their context (0 before a campaign's first); the code
    refused the sample (lead59)."""
    read = _read(powers) | set(switches)
    held = [int(j >= n and j in read and j not in ambient) for j in range(len(inputs))]
    return held if any(held) else []


def _read(powers: dict) -> set:
    """The inputs the registered features read (a power's, a derived input's, a transient's
    sensors)."""
    out = set()
    for k in powers:
        if k[0] == DERIVED:
            out |= {j for j in (*k[1:3], *k[6:7]) if j >= 0}     # an air's too (OVER)
        elif k[0] == INITIAL:
            out |= set(k[1])
        else:
            out.add(k[0])
    return out


def _in_code_order(laws: list, powers: Powers, n: int):
    """The registered features (``powers``, in the order the targets registered them) put in
    the code's order, the powers first, then the derived inputs, then the transients: the laws'
    places (after the ``n`` inputs), ``powers``' values and its powers at rest renumbered in
    place; returns the renumbering of a place (a network's inputs', :class:`.recurrent.Nets`)."""
    rank = {DERIVED: 1, INITIAL: 2}       # powers, then derived inputs, then transients
    order = sorted(powers, key=lambda k: (rank.get(k[0], 0), powers[k]))
    new = {powers[k]: i for i, k in enumerate(order)}
    move = np.array([new[i] for i in range(len(powers))] or [0], int)

    def place(j):
        j = np.asarray(j, int)
        return np.where(j >= n, n + move[np.clip(j - n, 0, None)], j)

    for _, law in laws:
        law.terms = [(place(cols), row) for cols, row in law.terms]
        law.lags = [(tau, int(place(j)), g, src) for tau, j, g, src in law.lags]
    for k in order:
        powers[k] = new[powers[k]]
    powers.rest, powers.steady = {new[i] for i in powers.rest}, {new[i] for i in powers.steady}
    return place


def _ambient_inputs(stream, inputs: list, ati: bool, known: bool) -> tuple[list[int], bool]:
    """``(the code's inputs whose first sample's mean is a campaign's initial ambient A0, A0
    given instead)``: the stream's ambient sensors, read as it reads them (a declared one
    filtered, not referenced); none without an ATI law.  Where the stream reads no ambient sensor
    it takes A0 at reset, the campaign's manifest ``ambient_c`` (``ambient_given_``): so does the
    code (exportrest62; ``known`` false: a stream made without its training data, not yet
    knowing its sensors, reads none)."""
    if not ati:
        return [], False
    if not stream.ambient_columns:
        return [], bool(known and stream.ambient_given_)
    return [inputs.index(c) for c in stream.ambient_columns], False


def _pattern_fields(env, n_states: int) -> dict:
    """The training pattern of the envelope ``env`` (None: no clamp) over the code's inputs: a
    machine state read by a power is scaled away (never off the pattern)."""
    if env is None or env.basis is None:
        return {}
    pad = np.zeros((n_states, env.basis.shape[1]))
    return {"pattern": True, "pattern_mean": env.mean.tolist() + [0.0] * n_states,
            "pattern_scale": env.scale.tolist() + [UNBOUNDED] * n_states,
            "pattern_basis": np.vstack([env.basis, pad]).tolist(), "pattern_tol": float(env.tol)}


class Simulator:
    """The exported arithmetic in numpy (the reference the generated code is read against)."""

    def __init__(self, ss: StateSpace):
        self.ss = ss
        self.fir = np.asarray(ss.fir, float)
        lo, hi = (np.asarray(getattr(ss, k) or [], float) for k in ("lo", "hi"))
        m, n = len(ss.targets), len(ss.inputs)
        laws = len(ss.laws)
        self.clamp_gain = np.asarray(ss.clamp_gain or np.zeros((laws, n)), float).reshape(laws, n)
        self.state_gain = np.asarray(ss.clamp_state_gain or np.zeros((laws, 0, n)), float).reshape(
            laws, len(ss.clamp_states), n)
        self.envelope = Envelope(tuple(ss.inputs), lo, hi) if not ss.pattern else Envelope(
            tuple(ss.inputs), lo, hi, mean=np.asarray(ss.pattern_mean, float),
            scale=np.asarray(ss.pattern_scale, float), tol=ss.pattern_tol,
            basis=np.asarray(ss.pattern_basis, float).reshape(n, -1))
        self.b0 = np.asarray(ss.b0, float).reshape(
            laws, n + len(ss.powers) + len(ss.derived) + len(ss.initial))
        self.bd = np.asarray(ss.bd, float).reshape(laws, ss.depth, n)
        self.g = np.asarray(ss.g, float).reshape(laws, len(ss.taus))
        self.sum = np.zeros((laws, m))            # law -> the target it adds to
        self.sum[np.arange(laws), ss.laws] = 1.0
        self.law_set = np.asarray(ss.law_set or [0] * laws, int)     # (cmon83) whose law
        self.sets = int(self.law_set.max(initial=0)) + 1
        self.serving = 0           # the set the output sums: the model's, or a fallback's
        self.taus = np.asarray(ss.taus, float)
        self.lag_input = np.asarray(ss.lag_input, int)
        self.lag_rest = np.asarray(ss.lag_rest or [0] * len(ss.taus), bool)
        self.lag_of = np.asarray(ss.lag_of or [-1] * len(ss.taus), int)
        self.cascade = np.flatnonzero(self.lag_of >= 0)
        # (ci98) the intercept in the measured channel, the autoregressive gains: made once
        self.intercept = np.outer([1.0, 0.0], ss.intercept)
        self.ar = np.asarray(ss.ar)
        self.outright = np.asarray(ss.clamp_outright or [0] * m, bool)
        self.output = Output(ss)       # guard and reference update: what is learned stays
        self.clock = SampleClock(ss.time_period, judge=ss.substitute_time)
        self.switches = Switches(ss) if ss.forest_target else None
        self.cells = Cells(ss) if ss.lstm_target else None
        self.watch = CodeMonitor(ss.monitor) if ss.monitor else None   # the code's sensor monitor
        # (ci98) the per-input masks and limits each sample reads, made once
        self.held = np.asarray(ss.held or [0] * n, bool)
        self.limits = np.asarray(ss.limits, float)
        self.watched = np.zeros(n, bool)
        if self.watch is not None:
            self.watched[self.watch.idx] = True
        self.reset()

    def reset(self, ambient_c: float = float("nan")) -> None:
        """A new campaign: the next sample is its first.  ``ambient_c``: its initial ambient A0
        (°C) where it is given (``ambient_given``: the manifest's, no ambient input)."""
        self.first = True
        self.ambient_c = float(ambient_c)
        self.c = np.zeros(len(self.ss.targets))      # the last corrections given
        self.refused = self.repeated = False
        self.u_last = None        # (dup99) the inputs of the last sample stepped on, as read
        self.n_repeated = 0       # rows written again in this campaign, skipped (skip_repeats)

    def reference(self, measured) -> None:
        """A reference measurement of the error per target (NaN: none) at the last sample (none
        taken at a refused one)."""
        if not self.refused:
            self.output.reference(measured)

    def step(self, u, time: float = float("nan")) -> np.ndarray:
        """Correction ``C`` (µm, = -predicted error) per target for one sample.  A sample with
        an input not measured (not finite, or beyond its ``input_limit``) is refused (``refused``
        true): nothing remembered changes and the last corrections given are returned (0 before a
        campaign's first sample).  A row written again (``skip_repeats``, :func:`~thermocomp.core.
        timerule.repeats`) is skipped (``repeated`` true): the same, counted in ``n_repeated``."""
        u = np.asarray(u, float)
        ss, held, watched = self.ss, self.held, self.watched
        self.repeated = bool(ss.skip_repeats and not self.first
                             and repeats(self.clock.snapshot(), float(time), u, self.u_last))
        if self.repeated:
            self.n_repeated += 1
            self.refused = False
            return self.c.copy()
        read = u
        measured = self._measured(u)
        if self.watch is not None:       # a monitored reading missing: the monitor's (cdrop77)
            u = np.where(watched & ~measured, np.nan, u)
        # A0 not given where the code has no input for it: no campaign starts (the stream's refusal)
        self.refused = not measured[~held & ~watched].all() or (
            self.first and ss.ambient_given and not ss.ambient_optional
            and not np.isfinite(self.ambient_c))
        if self.watch is not None:     # (its flags say why it refuses, or none)
            self.refused = bool(self.watch.refuses(u, self.first)) or self.refused
        if self.refused:
            return self.c.copy()
        self.u_last = read
        if self.first:
            self.clock.reset()
            self.seen, self.last = np.zeros(len(u), bool), np.zeros(len(u))
        now, dt, _ = self.clock.step(float(time))
        if self.watch is not None:      # the monitored inputs as the model reads them
            u = self.watch.step(u, self.first, dt, now)
            measured = self._measured(u)
            self.serving = self.watch.serving()
        self.last = np.where(measured, u, self.last)
        u = np.where(measured, u, np.where(self.seen, self.last, 0.0))     # a held signal
        if self.first:
            self.buf = np.tile(u, (len(self.fir), 1))
        else:
            self.buf = np.concatenate((u[None, :], self.buf[:-1]))
        v = (self.buf * self.fir).sum(axis=0)
        first, model, lag_dt = self.first, self, dt
        if not first and ss.grid_period:      # the training grid (cadence72): lags by the time
            lag_dt = now - self.t_grid         # since the last grid row
            if not on_grid(lag_dt, dt, ss.grid_period):
                # a row between (between73): the model's step from the committed state, on a copy
                model = copy.deepcopy(self, {id(ss): ss, id(self.output): self.output,
                                             id(self.clock): self.clock})
        y, allow = model._model(u, v, measured, now, lag_dt, time)
        self.c = self.output.step(y, first, dt, allow,
                                  self.watch is not None and self.watch.novel)
        return self.c.copy()

    def _measured(self, u: np.ndarray) -> np.ndarray:
        """:meth:`StateSpace.measured` of the sample ``u``, on the limits made once."""
        return within_limits(u, self.limits)

    def _model(self, u, v, measured, now: float, lag_dt: float, time: float
               ) -> tuple[np.ndarray, np.ndarray]:
        """The model's step on the denoised sample ``v``: ``(y before the guard, its widening)``."""
        ss = self.ss
        self.t_grid = now
        if self.first:
            self.ref = np.where(np.asarray(ss.referenced, bool), v, 0.0)
            a0 = ambient_c0(v[ss.ambient_inputs]) if ss.ambient_inputs else (
                self.ambient_c if ss.ambient_given else 0.0)
            # the campaign's laws (ATI), fixed over it (A0 optional and not given: no law reads it)
            self.factor = ss.factors(a0 if np.isfinite(a0) else 0.0)
            self.a0, self.t0 = a0, now
            self.start = np.zeros(len(ss.initial))        # a transient's w . (v(0) - A0)
            self.started = np.zeros(len(ss.initial), bool)
        x = v - self.ref
        excess = self.envelope.excess(x) if ss.clamp else np.zeros_like(x)
        if self.first:          # the model's inputs at its first sample (an inputs_product's)
            self.x0, self.e0 = x.copy(), excess.copy()
            self.excessed, self.by_held = False, np.zeros(len(ss.clamp_states))
            self.by_prev = np.zeros(len(ss.clamp_states))
            self.by_outright = np.zeros(len(ss.targets), bool)
        xe = x                      # [x, static powers of machine states (Hammerstein basis)]
        if ss.powers:
            src, scale, e = (np.array(c) for c in zip(*ss.powers))
            w = v[src.astype(int)] / scale
            xe = np.r_[x, np.abs(w) ** e * np.sign(w)]
        if self.first:
            self.v0 = v.copy()
        self.v0 = np.where(measured & ~self.seen, v, self.v0)   # a signal's first value
        self.seen |= measured
        of_excess = np.zeros(len(ss.derived))    # the derived inputs' excess channel
        if ss.derived:      # a diagnosed model's derived inputs, from v as the model reads it
            a, b, ra, rb = (np.array(c, int) for c in zip(*ss.derived))
            ta = np.where(self.seen[a], v[a] - ra * self.v0[a], 0.0)
            tb = np.where(b < 0, 1.0, np.where(self.seen[b], v[b] - rb * self.v0[b], 0.0))
            if ss.derived_over:     # a rise over the air's: r_b - r_c, r_c in r_b's frame
                c = np.asarray(ss.derived_over, int)
                tb = tb - np.where((c >= 0) & self.seen[c], v[c] - rb * self.v0[c], 0.0)
            # an inputs_product's: the model's input's rise, the clamped one's in channel 1
            clamped = np.asarray(ss.derived_clamped or [0] * len(a), bool)
            tb = np.where(clamped, x[b] - self.x0[b], tb)
            of_excess = np.where(clamped, ta * (excess[b] - self.e0[b]), 0.0)
            xe = np.r_[xe, ta * tb]
        if ss.initial:      # a diagnosed lag's initial-state transient, as the model computes it
            xe = np.r_[xe, self._transient(v, measured, now)]
        self._held_states(v, excess)
        # two channels of one system: the measured inputs, and their excess (no powers, no intercept)
        xs = np.concatenate([xe, excess, np.zeros(len(ss.powers)), of_excess,
                             np.zeros(len(ss.initial))]).reshape(2, -1)
        xl = xs[:, self.lag_input]
        first = self.first
        e = None if self.first else np.exp(-lag_dt / self.taus)
        if self.first:
            self.hist = np.repeat(xs[:, None, :len(x)], ss.depth, axis=1)
            z, self.y = np.where(self.lag_rest, 0.0, xl), np.zeros((2, len(ss.laws)))
            self.bound = np.zeros((self.sets, len(ss.targets)))     # each set's own
        else:
            z = e * self.z + (1.0 - e) * xl
        for k in self.cascade:     # a cascade: on its source's new value
            xl[:, k] = z[:, self.lag_of[k]]
            z[:, k] = xl[:, k] if e is None else e[k] * self.z[:, k] + (1.0 - e[k]) * xl[:, k]
        self.z = z
        y = (self.intercept + xs @ self.b0.T
             + np.einsum("tdi,sdi->st", self.bd, self.hist) + (self.z - xl) @ self.g.T
             + self.ar * self.y)
        if ss.depth:
            self.hist = np.concatenate([xs[:, None, :len(x)], self.hist[:, :-1]], axis=1)
        self.y, self.first = y, False
        y = self._summed(y)
        if ss.forest_target:        # an arx_rf's forest, in the measured channel (its weight)
            value = self.switches.step(v, float(time) if ss.switch_raw_time else now, first)
            self._beside(y[0], ss.forest_target, ss.forest_weight, ss.forest_law, value)
        if ss.lstm_target:          # an lstm's residual, of the clamped inputs (no step gain)
            value = self.cells.step(xs, self.z, self.factor, first)
            self._beside(y[0], ss.lstm_target, ss.lstm_weight, ss.lstm_law, value)
        if excess.any():            # back in range, the bound of the excess's last sample holds
            gain = self.clamp_gain + np.einsum("s,rsi->ri", self.by_held, self.state_gain)
            self.bound = np.abs([self._summed(gain @ excess, k) for k in range(self.sets)])
        outright = self.outright | self.by_outright
        bound = np.where(outright, np.inf, self.bound[self.serving])
        if ss.clamp_spread and np.count_nonzero(excess) >= 2:     # a heat source's: carried on
            bound = np.where(np.asarray(ss.clamp_spread, bool), 0.0, bound)
        return y[0] - np.clip(y[1], -bound, bound), self.output.allowance(x, self.envelope)

    def _beside(self, y: np.ndarray, targets: list, weights: list, laws: list,
                value: np.ndarray) -> None:
        """A forest's or network's ``value`` added to its target's ``y`` times its weight and
        its law's factor (empty ``laws``, an older export: 1)."""
        factor = self.factor[np.asarray(laws, int)] if laws else np.ones(len(value))
        if laws:        # (cmon83) a fallback model's network adds only while it is served
            factor = np.where(self.law_set[np.asarray(laws, int)] == self.serving, factor, 0.0)
        added = np.where(factor != 0.0, np.asarray(weights) * factor * value, 0.0)
        np.add.at(y, np.asarray(targets, int), added)

    def _held_states(self, v: np.ndarray, excess: np.ndarray) -> None:
        """The states an inputs_product's gain reads, held at the campaign's first excess at
        their value of the sample before (a first sample out: its targets clamped outright)."""
        ss = self.ss
        if not ss.clamp_states:
            return
        if excess.any() and not self.excessed:
            self.excessed = True
            if self.first:
                self.by_outright = np.asarray(ss.clamp_state_first, bool)
            else:
                self.by_held = self.by_prev.copy()
        a, ra = (np.array(c, int) for c in zip(*ss.clamp_states))
        self.by_prev = np.where(self.seen[a], v[a] - ra * self.v0[a], 0.0)

    def _transient(self, v: np.ndarray, measured: np.ndarray, now: float) -> np.ndarray:
        """Each direction's ``w . (v(0) - A0) (1 - exp(-(t - t0) / tau))``: ``v(0)`` its sensors at
        the campaign's first sample that has one of them (a missing one: 0), 0 before it."""
        for i, (_, sensors, w) in enumerate(self.ss.initial):
            if not self.started[i] and measured[sensors].any():
                # A0 not given (ambient_optional): the mean of its sensors' first values
                a0 = self.a0 if np.isfinite(self.a0) else float(
                    np.mean(np.asarray(v)[sensors][measured[sensors]]))
                self.start[i] = np.asarray(w, float) @ np.where(measured[sensors], v[sensors] - a0, 0.0)
                self.started[i] = True
        taus = np.array([tau for tau, _, _ in self.ss.initial], float)
        return self.start * (1.0 - np.exp(-(now - self.t0) / taus))

    def _summed(self, per_law: np.ndarray, of: int | None = None) -> np.ndarray:
        """Per target: its laws' values (last axis) times their factors, summed (a law out of
        the campaign's interval adds nothing, whatever its state), of the set ``of`` (None: the
        one served)."""
        keep = (self.factor != 0.0) & (self.law_set == (self.serving if of is None else of))
        return np.where(keep, per_law * self.factor, 0.0) @ self.sum
