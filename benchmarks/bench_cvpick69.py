"""diagnose's ``cv=auto`` keeps the campaigns scheme where forward chaining's design cannot reach
alpha and the campaigns' can (issue 34; stop 69, cvpick69).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_cvpick69.py rows ROOT WORK [GROUP ...]   # -> WORK/moretest.jsonl
    python benchmarks/bench_cvpick69.py gpg ROOT                     # gpg69's two records
    python benchmarks/bench_cvpick69.py compare BASE NEW             # the bar, two WORKs

``rows``: ``bench_moretest68.py rows`` (same ROOT, groups, draws) with each row's CV design
(``cv.scheme``, ``cv.why``, ``cv.test_blocks``, ``cv.min_p``) kept.  ``gpg``: ROOT holds
``init-gpg_a`` / ``init-gpg_b`` as ``bench_stranger69.py init`` leaves them; ``diagnose``
``model=mlr`` at the defaults, rerun, replay, C check (``lab_matrix.diagnosed``).

Why (stranger69): ``auto`` switches to forward chaining when the train campaigns are fewer than
``units_needed(alpha)`` (c892e2c6: 5 campaigns held out whole give p >= 1/32).  That predates
the test's time blocks within campaigns (``Problem.set_test_blocks``): on gpg69's 7 train runs
forward chaining gives 5 / 3 test blocks (min p 0.031 / 0.12 > 0.01) and nothing can be
accepted, while the campaigns scheme's blocks within the 7 runs accept the planted effect.

The rule (written and committed before it was scored)
-----------------------------------------------------
Under ``diagnose.cv=auto``, where the switch to forward chaining (too few campaigns) gives a
design whose smallest p cannot reach alpha (``smallest_p(n_blocks_tested) > alpha``) while the
campaigns scheme's design (its test blocks within the campaigns) can, the campaigns scheme is
kept; ``cv.why`` and the log say so.  The choice depends on the design only (the block counts,
from the start model's residual memory as the test blocks always are), never on any
candidate's test statistic.  Everywhere else nothing changes.

The bar
-------
1. gpg69: both records (seeds 6901, 6902) accept the planted ``S_X-Achse`` x a rise on E_dX at
   the defaults (before: nothing accepted on either).
2. moretest68's instrument (``bench_moretest68.py``, its ROOT /tmp/moretest68-root and draws):
   the rows that can switch are those with 2-7 train campaigns (the others never reach the
   rule: listed from moretest68's rows' ``train``): boring_mill, boring_mill-noW (7), rig40 (6),
   vendor5 (4) (groups ``mill``, ``om``) and the jig (6, ``jig``).  Of these ONLY the rows whose
   forward design could not reach alpha before (old tree's ``cv.min_p > alpha`` with
   ``cv.why``) may change; none of the changed rows > 2 % worse on the new campaigns with its
   90 % resampled interval above +2 %; the rows of every other group are untouched by
   construction (fewer than 2 or at least 8 train campaigns), so clean + null accepting stays
   0 of 44 and planted found stays.
3. fresh 6941-6960 (``bench_planted69.py fresh``): clean accepting not more than before.
If any fails: the src change is reverted, this bench kept, REFUSED with the numbers.

Measured (2026-12-01, base 46a13af4 vs this branch; CPU user + sys, 2 shared cores)
-----------------------------------------------------------------------------------
1. gpg69 at the defaults: 6901 forward 5 blocks (min p 0.031) -> campaigns 7 blocks (0.0078),
   E_dX 4.040 -> 4.040 (nothing) before, 4.040 -> 0.376 µm after (S_X-Achse x T_Rundtisch rise
   accepted); 6902 forward 3 (0.12) -> campaigns 7, 4.380 -> 0.677 µm.  Rerun = replay,
   stream - batch <= 1.1e-14, C check passed.  diagnose 10.0 / 5.5 -> 10.5 / 5.2 s CPU; the
   whole ``gpg`` step 31.8 -> 33.1 s (rerun at the committed wording of ``cv.why``: the same
   figures, diagnose 9.6 / 4.0 s, the step 26.8 s).
2. ``rows`` mill, jig, om (14 case x target rows; CPU 105.6 -> 96.3 s): forward reached alpha on
   the mill (66 blocks), the jig (2112) and vendor5 (9); lathe43 / lathe43m are campaigns (39 /
   36 train).  Only rig40 E_X / E_Z could not reach (forward 5 blocks, min p 0.031) and its 6
   campaigns' blocks cannot either: it stays forward (the warning now says so).  All 14 rows
   identical (accepted, own and new-campaign RMSE); none changed, so none worse.  The other
   groups have 1 (twin lathe, gantry) or >= 8 (few, cases, grinder, fresh, null) train
   campaigns: the rule is never reached there (clean + null 0 of 44 and the planted rows as
   they were, by construction).
3. fresh 6941-6960: identical rows; planted found 8 / 10, clean accepting 1 / 10 on both trees
   (CPU 23.4 -> 19.4 s).
All three hold: ADOPTED.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402

ALPHA = 0.01


def _with_design(targets_of):
    """``bench_moretest68.targets_of`` whose rows carry the diagnosis' CV design."""
    def wrapped(d, *args):
        out = targets_of(d, *args)
        cv = {k: d.cv.get(k) for k in ("scheme", "why", "test_blocks", "min_p", "units")}
        for row in out.values():
            row["cv"] = cv
        return out
    return wrapped


def rows(root: Path, work: Path, groups) -> None:
    import bench_moretest68 as mt

    mt.targets_of = _with_design(mt.targets_of)
    mt.rows(root, work, groups)


def gpg(root: Path) -> None:
    import lab_matrix

    for name in ("gpg_a", "gpg_b"):
        print(json.dumps(lab_matrix.diagnosed(root, name, "mlr", accepted=True)[0], default=str),
              flush=True)


def compare(base: Path, new: Path) -> None:
    """Per row: the designs before / after, whether it changed, and for a changed row its new
    campaigns' change and 90 % interval (``bench_moretest68``'s figures)."""
    import numpy as np
    from bench_moretest68 import resampled
    from bench_remeasure62 import _read

    old = {(r["case"], t): o for r in _read(base / "moretest.jsonl") for t, o in r["targets"].items()}
    for r in _read(new / "moretest.jsonl"):
        for t, o in r["targets"].items():
            b = old[(r["case"], t)]
            could_not = bool(b["cv"]["why"]) and b["cv"]["min_p"] > ALPHA
            changed = (b["accepted"] != o["accepted"] or b["own"]["rmse"] != o["own"]["rmse"]
                       or b["new"]["rmse"] != o["new"]["rmse"])
            line = (f"{r['case']} {t}: {b['cv']['scheme']} {b['cv']['test_blocks']} blocks "
                    f"(min p {b['cv']['min_p']:.2g}) -> {o['cv']['scheme']} {o['cv']['test_blocks']} "
                    f"(min p {o['cv']['min_p']:.2g}); forward could not reach: {could_not}; "
                    f"changed: {changed}")
            if changed:
                (nb, na) = o["new"]["rmse"]
                lo, hi = resampled(np.array(o["new"]["per_campaign"], float))
                line += (f"; new campaigns {nb:.4g} -> {na:.4g} ({100 * (na / nb - 1):+.1f} %) "
                         f"[{lo:+.1f}, {hi:+.1f}]; accepted {b['accepted']} -> {o['accepted']}")
            print(line)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "rows": lambda root, work, *groups: rows(Path(root).resolve(), Path(work).resolve(),
                                                 list(groups) or ("mill", "jig", "om")),
        "gpg": lambda root, *_: gpg(Path(root).resolve()),
        "compare": lambda base, new, *_: compare(Path(base).resolve(), Path(new).resolve()),
    }, argv)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
