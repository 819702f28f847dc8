r"""Calibration design study (paper 001): which artefact and which poses calibrate a machine best.

Two digital twins (paper 001, Eq. 1): the *machine* M, a family of kinematic models whose
error parameters are drawn at random, and the *compensation model* C identified from
artefact distances measured on M.  M is richer than C (a higher Legendre order and the
column-ram cross terms, paper 001 § 3.4), so what C cannot represent, and what a pose set
cannot see, both show in the result.  For one machine and one strategy (number of balls
over the same bar length, misalignment angle θ, position set):

1. the ball array is measured in every pose through M's full homogeneous transformation
   matrices, with the probing noise of every probed centre and the calibration error of
   every ball (the same in every pose);
2. C is identified from the distance deviations by
   :class:`~thermocomp.apps.volumetric.identify.ArtefactCalibration` as ``calibrate`` would: by GLS
   (parameters the poses cannot see stay at 0, those they see faintly take the noise), or with
   a prior (``prior_sd``) as the posterior mean of every parameter;
3. the volumetric compensation error is the RMS over a 3D grid of the workspace of
   :math:`\|C(X) - M(X)\|` (paper 001, Eq. 7), the volumetric error VE that of
   :math:`\|M(X)\|` (Eq. 4).

A Monte Carlo over machines (the same machines for every strategy, so strategies are
compared on equal terms) gives each strategy's VCE distribution.  Every machine and every
measurement has its own seed, so the result does not depend on ``n_jobs`` (joblib workers
over draws for the machines' truth, then over strategies: each fits its calibration once).

The family: each parameter uniform in :math:`[-a, a]`, with :math:`a` set per kind
(positioning, straightness, squareness, angular, cross) for the kind's lowest order and
multiplied by ``decay`` per order above it (a list gives the amplitudes per order instead).
"""

from __future__ import annotations

import itertools
import time
from contextlib import nullcontext
from dataclasses import dataclass, field

import numpy as np
from joblib import delayed
from threadpoolctl import threadpool_limits

from ...base.lifetime import parallel
from ...base.progress import bar
from ...core.metrics import reduction_pct
from .artefact import BallArray, Setup, check_reach, position_set
from .identify import ArtefactCalibration
from .kinematics import KINDS, KinematicModel, Parameter, workspace_grid
from .measure import artefact_distances

DEFAULT_AMPLITUDES = {"positioning": 10.0, "straightness": 8.0, "squareness": 8.0, "angular": 6.0,
                      "cross": 8.0}
DEFAULT_STUDIES = {
    "balls": {"n_balls": [3, 4, 5, 7, 9, 11], "misalignment_deg": [15.0],
              "position_sets": ["S1+S2+S3"]},                               # paper 001, Fig. 6
    "misalignment": {"n_balls": [11], "misalignment_deg": [0.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0],
                     "position_sets": ["S2", "S2+S3"]},                     # Fig. 8
    "position_sets": {"n_balls": [11], "misalignment_deg": [0.0],
                      "position_sets": ["S1", "S2", "S3", "S1+S2", "S1+S3", "S2+S3", "S1+S2+S3"]},
}                                                                           # Fig. 9


def kind(p: Parameter) -> str:
    """The family kind of a parameter (squareness: the order-1 straightness the model keeps)."""
    if p.kind == "straightness" and p.order == 1:
        return "squareness"
    return p.kind


@dataclass
class MachineFamily:
    """Machines M: a kinematic model whose parameters are uniform in ``[-a, a]``.

    Parameters
    ----------
    model : KinematicModel
        The machine's structure (order, cross terms, ranges, chain, tool).
    amplitudes : dict
        Kind -> ``a`` of the kind's lowest order (µm; angular µm/m), or a list of ``a`` per
        order from the lowest.
    decay : float
        Factor per order above the lowest (when the amplitude is one number).
    """

    model: KinematicModel
    amplitudes: dict = field(default_factory=lambda: dict(DEFAULT_AMPLITUDES))
    decay: float = 0.3

    def __post_init__(self):
        unknown = sorted(set(self.amplitudes) - set(KINDS))
        if unknown:
            raise ValueError(f"unknown parameter kind(s) {unknown}: use {list(KINDS)}")
        if not 0 <= self.decay:
            raise ValueError(f"decay must be >= 0, got {self.decay}")

    def bounds(self) -> np.ndarray:
        """``a`` of every parameter of the model."""
        lowest = {}
        for p in self.model.parameters:
            lowest[kind(p)] = min(lowest.get(kind(p), p.order), p.order)
        out = []
        for p in self.model.parameters:
            a = self.amplitudes.get(kind(p), 0.0)
            k = p.order - lowest[kind(p)]
            if isinstance(a, (list, tuple)):
                out.append(float(a[k]) if k < len(a) else 0.0)
            else:
                out.append(float(a) * self.decay ** k)
        bounds = np.array(out)
        if np.any(bounds < 0) or not np.all(np.isfinite(bounds)):
            raise ValueError("parameter ranges must be finite and >= 0")
        return bounds

    def sd(self) -> np.ndarray:
        """Standard deviation ``a / sqrt(3)`` of every parameter (uniform in ``[-a, a]``), as a
        calibration's prior; a parameter held at 0 gets a tiny one (known exactly, without 1/0)."""
        sd = self.bounds() / np.sqrt(3.0)
        return np.maximum(sd, 1e-6 * max(sd.max(), 1e-12))

    def draw(self, seeds) -> np.ndarray:
        """One parameter row per seed (``(n, p)``)."""
        a = self.bounds()
        return np.array([np.random.default_rng(s).uniform(-1.0, 1.0, a.size) * a for s in seeds])


@dataclass(frozen=True)
class Strategy:
    """One calibration strategy: artefact and position set."""

    n_balls: int
    misalignment_deg: float
    position_set: str                 # "S2+S3"

    @property
    def sets(self) -> list[str]:
        return self.position_set.split("+")


def strategies(studies: dict) -> tuple[list[Strategy], dict]:
    """The strategies of the studies (each a product of ``n_balls`` × ``misalignment_deg`` ×
    ``position_sets``), each once, and which studies each belongs to."""
    out, member = [], {}
    for name, spec in studies.items():
        missing = [k for k in ("n_balls", "misalignment_deg", "position_sets") if k not in spec]
        if missing:
            raise ValueError(f"study {name!r} lacks {missing}")
        for nb, th, s in itertools.product(spec["n_balls"], spec["misalignment_deg"],
                                           spec["position_sets"]):
            st = Strategy(int(nb), float(th), "+".join(str(s).replace(" ", "").split("+")))
            if st not in member:
                out.append(st)
                member[st] = []
            member[st].append(name)
    return out, member


def _rms(e: np.ndarray) -> np.ndarray:
    """RMS over the grid of the error vectors' length: ``(k, n, 3)`` -> ``(k,)``."""
    return np.sqrt(np.mean(np.sum(e ** 2, axis=-1), axis=-1))


def measure(machine: KinematicModel, params: np.ndarray, setup: Setup, rngs) -> np.ndarray:
    """Distance deviations ``(k, m)`` (µm, the calibration's column order) of machines ``params``
    (k, p) measuring ``setup``'s artefact in every pose: each machine its own ball errors (the
    same in every pose) and probing noise, from its own generator (``rngs=None``: without
    either, what a perfect probe reads on a perfect artefact)."""
    nb = setup.array.n_balls
    if rngs is None:
        return artefact_distances(machine, setup, params, np.zeros((nb, 3)),
                                  np.zeros((len(params), len(setup.poses), nb, 3)))
    ball = np.stack([r.normal(0.0, setup.ball_um, (nb, 3)) for r in rngs])
    probe = np.stack([r.normal(0.0, setup.probing_um, (len(setup.poses), nb, 3)) for r in rngs])
    return artefact_distances(machine, setup, params, ball, probe)


def _truth(study: CalibrationDesignStudy, machines: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Parameters ``(k, p)`` and TCP errors on the grid ``(k, n, 3)`` of machine indices."""
    params = study.family.draw([(study.seed, int(i)) for i in machines])
    return params, study.family.model.error(params, study.grid_points(), form="htm")


def _strategy(study: CalibrationDesignStudy, s: int, strategy: Strategy, params: np.ndarray,
              truth: np.ndarray) -> tuple[np.ndarray, dict]:
    """VCE ``(k,)`` of every machine calibrated with one strategy, and the strategy's row facts."""
    setup = study.setup(strategy)
    cal = ArtefactCalibration(setup, outlier_z=np.inf,             # no gross error is simulated
                              prior_sd=study.prior_sd).fit()
    rngs = [np.random.default_rng((study.seed, i, s + 1)) for i in range(len(params))]
    measured = measure(study.family.model, params, setup, rngs)
    exact = measure(study.family.model, params, setup, None)
    basis = study.compensation.basis(study.grid_points())

    def tcp(distances):
        return np.einsum("nip,kp->kni", basis, cal.full(cal.identify(distances)[0]))

    # the estimate is linear in the distances (no outlier rule here; GLS or a posterior mean),
    # so the identified error splits exactly into that of the noise-free distances (what the
    # poses cannot see and C cannot represent) and that of the measurement noise alone
    blind, noise = tcp(exact) - truth, tcp(measured - exact)
    n_poses = len(setup.poses)
    facts = {"n_poses": n_poses, "n_distances": len(cal.design_.rows),
             "n_probings": n_poses * strategy.n_balls, "n_identified": len(cal.seen_),
             "unidentifiable": sorted(cal.unidentifiable_), "reachable": _reachable(setup),
             "noise_free_median": float(np.median(_rms(blind))),
             "noise_only_median": float(np.median(_rms(noise)))}
    return _rms(blind + noise), facts


def _reachable(setup: Setup) -> bool:
    """Every ball of every pose within the machine's travel (else a what-if, not a measurement)."""
    try:
        check_reach(setup.model, setup.array, setup.poses)
    except ValueError:
        return False
    return True


class CalibrationDesignStudy:
    """Monte Carlo study of artefact calibration strategies (paper 001).

    Parameters
    ----------
    compensation : KinematicModel
        C, the model the calibration identifies (its parameters must all be M's).
    family : MachineFamily
        The machines M.
    length_mm : float
        Bar length of every artefact (balls evenly spread over it).
    x_centres : sequence of float
        Where along X each position set is repeated (fractions of the X travel).
    probing_um, ball_um : float
        Standard uncertainty per coordinate of a probed centre and of a calibrated ball.
    grid : (int, int, int)
        Points per axis of the evaluation grid over the workspace (paper 001: 60 × 20 × 20).
    n_machines : int
        Monte Carlo draws.
    n_jobs : int
        joblib workers over chunks of machines (-1: every core).
    seed : int
    prior_sd : array-like or None
        The calibration's prior standard deviation of each parameter of C (None: GLS);
        :meth:`MachineFamily.sd` of the family is the prior that knows the machines exactly.

    Attributes
    ----------
    result_ : dict
        After :meth:`run`: ``ve``, ``strategies`` (one row each), ``findings``, ``time_s``.
    """

    def __init__(self, compensation: KinematicModel, family: MachineFamily, length_mm=1500.0,
                 x_centres=(1 / 6, 0.5, 5 / 6), probing_um=0.5, ball_um=0.5,
                 grid=(30, 12, 12), n_machines=100, n_jobs=1, seed=0, prior_sd=None):
        self.compensation = compensation
        self.family = family
        self.length_mm = float(length_mm)
        self.x_centres = tuple(float(x) for x in x_centres)
        self.probing_um = float(probing_um)
        self.ball_um = float(ball_um)
        self.grid = tuple(int(g) for g in grid)
        self.n_machines = int(n_machines)
        self.n_jobs = n_jobs
        self.seed = int(seed)
        self.prior_sd = None if prior_sd is None else np.asarray(prior_sd, float)
        missing = [n for n in compensation.names if n not in family.model.names]
        if missing:
            raise ValueError(f"the machine family lacks parameters of the compensation model: "
                             f"{missing[:5]} (give the machine an order >= {compensation.order}"
                             f"{' and cross terms' if compensation.cross_terms else ''})")
        if len(self.grid) != 3 or min(self.grid) < 2:
            raise ValueError(f"grid must be 3 numbers of points >= 2, got {list(grid)}")
        if self.n_machines < 1:
            raise ValueError(f"n_machines must be >= 1, got {n_machines}")

    def grid_points(self) -> np.ndarray:
        """``(n, 3)`` commanded positions (mm) spanning the workspace."""
        return workspace_grid(self.family.model, self.grid)

    def setup(self, strategy: Strategy) -> Setup:
        """The measurement set-up of a strategy (C as the model)."""
        array = BallArray(strategy.n_balls, self.length_mm, strategy.misalignment_deg)
        poses = position_set(strategy.sets, self.compensation.ranges, self.x_centres,
                             self.compensation.tool)
        return Setup(self.compensation, array, poses, self.probing_um, self.ball_um)

    def run(self, studies: dict | None = None) -> dict:
        """Every strategy of ``studies`` (default: paper 001's three) over the Monte Carlo."""
        t0 = time.perf_counter()
        studies = DEFAULT_STUDIES if studies is None else studies
        todo, member = strategies(studies)
        # run in this process, one BLAS thread: the products are small (a pose's centres), and a
        # BLAS pool per core costs more than it gains (n_machines=20 on 2 cores: 16.5 -> 8.9 s
        # CPU, 12.0 -> 10.1 s wall); joblib's workers limit their own pools the same way
        with threadpool_limits(limits=1, user_api="blas") if _workers(self.n_jobs) == 1 else nullcontext():
            return self._run(todo, member, t0)

    def _run(self, todo, member, t0) -> dict:
        # draws in parallel for the machines' truth, then strategies in parallel (each fits its
        # calibration once and measures every machine; seeds are per machine and strategy)
        jobs = parallel(self.n_jobs)
        chunks = [c for c in np.array_split(np.arange(self.n_machines), _workers(self.n_jobs)) if c.size]
        parts = jobs(delayed(_truth)(self, c) for c in chunks)
        params = np.vstack([p[0] for p in parts])
        truth = np.concatenate([p[1] for p in parts])
        ve = _rms(truth)
        # as they finish, in order: a bar on a terminal (or at -v) over the long part
        done = list(bar(parallel(self.n_jobs, return_as="generator")(
            delayed(_strategy)(self, s, st, params, truth) for s, st in enumerate(todo)),
            desc="design strategies", total=len(todo), unit="strategy"))
        vce = np.column_stack([d[0] for d in done])
        rows = [_row(st, vce[:, s], ve, member[st], done[s][1]) for s, st in enumerate(todo)]
        self.ve_, self.vce_, self.strategies_ = ve, vce, todo
        self.result_ = {"ve": _distribution(ve), "strategies": rows,
                        "findings": findings(rows, float(np.median(ve))),
                        "time_s": time.perf_counter() - t0}
        return self.result_


def _workers(n_jobs) -> int:
    import os

    if n_jobs is None or n_jobs == 0:
        return 1
    if n_jobs < 0:
        return max(1, (os.cpu_count() or 1) + 1 + n_jobs)
    return int(n_jobs)


def _distribution(v: np.ndarray) -> dict:
    return {"median": float(np.median(v)), "p95": float(np.percentile(v, 95)),
            "mean": float(np.mean(v)), "p5": float(np.percentile(v, 5))}


def _row(st: Strategy, vce: np.ndarray, ve: np.ndarray, studies: list[str], facts: dict) -> dict:
    return {"n_balls": st.n_balls, "misalignment_deg": st.misalignment_deg,
            "position_set": st.position_set, "studies": studies, **_distribution(vce),
            "improvement_pct": reduction_pct(float(np.median(ve)), float(np.median(vce))), **facts}


def findings(rows: list[dict], ve_median: float) -> dict:
    """Paper 001's questions answered from the rows.

    ``balls_for_95pct``: the fewest balls giving 95 % of the largest improvement VE - VCE
    (medians) of the ``balls`` study; ``misalignment``: per position set of the
    ``misalignment`` study, VCE at the smallest angle and at the best one, and at both the VCE
    of the noise-free distances (``noise_free``) and of the noise alone (``noise_only``);
    ``best_position_set``: the lowest median VCE of the ``position_sets`` study.
    """
    out: dict = {}
    balls = sorted((r for r in rows if "balls" in r["studies"]), key=lambda r: r["n_balls"])
    if balls:
        gain = np.array([ve_median - r["median"] for r in balls])
        best = gain.max()
        # no improvement at all (noise far above the machine's errors): no number of balls
        out["balls_for_95pct"] = (int(next(r["n_balls"] for r, g in zip(balls, gain)
                                           if g >= 0.95 * best)) if best > 0 else None)
        out["balls_improvement_um"] = {str(r["n_balls"]): float(g) for r, g in zip(balls, gain)}
    mis = [r for r in rows if "misalignment" in r["studies"]]
    if mis:
        out["misalignment"] = {}
        for s in dict.fromkeys(r["position_set"] for r in mis):
            rs = sorted((r for r in mis if r["position_set"] == s), key=lambda r: r["misalignment_deg"])
            best = min(rs, key=lambda r: r["median"])
            out["misalignment"][s] = {
                "vce_aligned": rs[0]["median"], "aligned_deg": rs[0]["misalignment_deg"],
                "vce_best": best["median"], "best_deg": best["misalignment_deg"],
                "reduction_pct": reduction_pct(rs[0]["median"], best["median"]),
                # why: what the poses cannot see (noise-free) and the noise they amplify
                "noise_free": [rs[0]["noise_free_median"], best["noise_free_median"]],
                "noise_only": [rs[0]["noise_only_median"], best["noise_only_median"]]}
    sets = [r for r in rows if "position_sets" in r["studies"]]
    if sets:
        best = min(sets, key=lambda r: r["median"])
        out["best_position_set"] = {"position_set": best["position_set"], "median": best["median"],
                                    "n_probings": best["n_probings"],
                                    "reachable": best.get("reachable", True)}   # else a what-if
    return out
