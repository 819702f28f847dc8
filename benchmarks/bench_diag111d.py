"""Where diag111's refit null does not gate: lags of the model inputs and the forward scheme (diag111d).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag111d.py lags FIRST N      # bench_diag108's null rooms, round 1's lags
    python benchmarks/bench_diag111d.py starts FIRST N    # the same rooms, campaigns started unsoaked
    python benchmarks/bench_diag111d.py forward FIRST N   # the same rooms cut to one long record

diag111 gated the candidate a round takes by refitting it with its per-campaign drivers moved among
the train campaigns, but not (a) a lag of the model inputs (kind ``dynamics``: its driver is what the
base reads) nor (b) the ``forward`` scheme (one time line: no campaigns to permute).  Are they lenient
on clean data?  ``lags``: on each null room (families signal + ambient_interval + dynamics), round 1's
best ``dynamics`` candidate's flip p (bench_diag111's statistic: max-T of the held-out campaigns' gain
shares over round 1's family) and the search's own family p; TAKE: the round would take a lag.
``forward``: ``null_room(seed, n_campaigns=3, n=960)`` keeps C01 (80 h, train) and C03 (test), so
``cv=auto`` chains forward over the one record; round 1's best family p (the search's own flips) and
whether the round would take it.  The bar: ``benchmarks/diag111d_bar.md`` (``starts``: its addendum).

Scored (2026-12-07, once; 4a1e2d2b's src and this tree's, identical per room; CPU user + sys per pass)
* ``lags 0 200`` (52.6 / 41.8 s): best lag flip p <= .01 / .05 on 3 / 18 rooms (the search's own
  family p, finer ranked blocks: 7 / 36); taken 1 (room 54, a 14400 s lag of all inputs, 19.0 %).
  No start lag is offered there (campaigns start soaked: ``spanned_directions``).
* ``starts 0 200`` (67.4 / 66.8 s): best lag, always a start lag, flip p <= .01 / .05 on 8 / 24 (family
  p 18 / 38); taken 0: each of the 8 is refused by the start lag's own clauses (within-campaign share,
  forward within: diag98-103) or saturates 8 campaigns.
* ``forward 0 100`` (24.2 / 23.5 s): best family p <= .01 / .05 on 2 / 2 records (92 reach .01), both
  taken (18: S_hyd lag 18.7 %; 31: T_6 lag 7.8 %).  Beyond the bar, ``forward 100 100`` (21.3 / 20.5 s):
  3 / 8, 2 taken (114, 169: lags of T_6, T_amb): over 200 records 5 at .01, 4 taken (about 2x alpha).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag108 as d108  # noqa: E402
from _cli import run_commands  # noqa: E402

ALPHA = 0.01


def _search(dataset, families: tuple):
    """The E_X search of ``dataset`` as diagnose builds it (no round run)."""
    from bench_diag105 import _searches

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.apps.diagnose.candidates import CandidateOptions
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    options = SearchOptions(max_effects=0, candidates=CandidateOptions(families=families))
    store = {}
    with _searches(store):
        diagnose(dataset, Compensator(MLR()), options=options, targets=["E_X"])
    s = store["E_X"]
    s.effects = []
    return s


def _round1(s):
    first = s.cv.run(s.inputs(), [])
    evals, current, eligible, _ = s._round(first, s._read_columns(), 1)
    family = [ev for ev in evals if not ev.control and ev.effect.transform != "remove"]
    return family, current, eligible


def _unit_flips(family, current) -> np.ndarray:
    from thermocomp.apps.diagnose.cv import sign_flip_maxt

    D = [np.clip(1.0 - ev.result.unit_mse / np.maximum(current.unit_mse, 1e-300), -1, 1) for ev in family]
    return np.asarray(sign_flip_maxt(D), float)


def _count(name: str, ps: list) -> None:
    ps = np.asarray(ps, float)
    print(f"  {name} p <= .01 / .05: {int((ps <= .01).sum())} / {int((ps <= .05).sum())} of {len(ps)}")


def unsoaked_room(seed: int):
    """bench_diag108's null room ``seed`` with every input's initial distance spread per campaign
    (U(-3, 3) K, its own stream): the campaigns start in different states, so start lags are offered;
    E_X still reads the rises alone (nothing planted)."""
    ds = d108.null_room(seed)
    rng = np.random.default_rng((seed, 111))
    for df in ds.campaigns.values():
        for c in [c for c in df.columns if c.startswith("T_") and c != "T_amb"]:
            df[c] += rng.uniform(-3.0, 3.0)
    return ds


def starts(first_room: str, count: str) -> None:
    """:func:`lags` on :func:`unsoaked_room`: the start lags' count too."""
    lags(first_room, count, unsoaked_room)


def lags(first_room: str, count: str, room=None) -> None:
    """Round 1's best lag of the model inputs on each null room."""
    warnings.filterwarnings("ignore")
    unit_p, own_p, start_p, taken = [], [], [], 0
    for seed in range(int(first_room), int(first_room) + int(count)):
        s = _search((room or d108.null_room)(seed), ("signal", "ambient_interval", "dynamics"))
        family, current, eligible = _round1(s)
        lag = [i for i, ev in enumerate(family) if ev.effect.kind == "dynamics"]
        flips = _unit_flips(family, current)
        unit_p.append(min((flips[i] for i in lag), default=1.0))
        start_p.append(min((flips[i] for i in lag if family[i].effect.initial_state), default=1.0))
        own_p.append(min((family[i].p_family for i in lag), default=1.0))
        take = bool(eligible) and eligible[0].effect.kind == "dynamics"
        taken += take
        best = min(lag, key=lambda i: flips[i]) if lag else None
        what = family[best].effect.title if best is not None else "-"
        print(f"  room {seed}: {len(lag)} lags refitted; best lag unit p {unit_p[-1]:.4f} family p "
              f"{own_p[-1]:.4f} ({what}, gain {family[best].gain_pct if lag else 0:.1f} %); "
              f"{s.start_lags_screened} start lags screened, best start lag unit p {start_p[-1]:.4f}"
              f"{' TAKE' if take else ''}", flush=True)
    _count("best lag, unit flips", unit_p)
    _count("best lag, search's family p", own_p)
    _count("best start lag, unit flips", start_p)
    print(f"  rooms where round 1 takes a lag: {taken} of {len(unit_p)}")


def null_record(seed: int):
    """bench_diag108's null room as one long record: C01 (960 samples, 80 h) train, C03 test."""
    ds = d108.null_room(seed, n_campaigns=3, n=960)
    keep = ["C01", "C03"]
    return type(ds)(ds.manifest.loc[keep], {c: ds.campaigns[c] for c in keep}, name="null_record")


def forward(first_room: str, count: str) -> None:
    """Round 1's best candidate on each null record (forward chaining, the search's own flips)."""
    warnings.filterwarnings("ignore")
    best_p, taken = [], 0
    for seed in range(int(first_room), int(first_room) + int(count)):
        s = _search(null_record(seed), ("signal", "ambient_interval", "dynamics", "interaction", "nonlinear"))
        assert s.problem.scheme == "forward", s.problem.scheme
        family, current, eligible = _round1(s)
        best = min(family, key=lambda ev: ev.p_family) if family else None
        best_p.append(best.p_family if best else 1.0)
        taken += bool(eligible)
        took = f" TAKE {eligible[0].effect.title}" if eligible else ""
        print(f"  record {seed}: {len(family)} refitted, {s.problem.n_blocks_tested} test blocks; best p "
              f"{best_p[-1]:.4f} ({best.effect.title if best else '-'}, gain "
              f"{best.gain_pct if best else 0:.1f} %){took}", flush=True)
    _count("forward best family p", best_p)
    print(f"  records where round 1 takes an effect: {taken} of {len(best_p)}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"lags": lags, "starts": starts, "forward": forward}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
