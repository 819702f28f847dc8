"""What the targets of one diagnosis share, traced (stop 68, blocks68): the test blocks' length
and the sensor check.

Usage (``PYTHONPATH=<checkout>/src`` chooses the code measured)::

    python benchmarks/bench_blocks68.py write ROOT          # bench_iso67's iso_a (seed 6701), init
    python benchmarks/bench_blocks68.py trace ROOT          # iso_a's cells (below), ROOT/trace.jsonl
    python benchmarks/bench_remeasure62.py write ROOT62
    python benchmarks/bench_blocks68.py rows ROOT62 joint|single|own [GROUP ...]   # the 139 rows
    python benchmarks/bench_blocks68.py compare ROOT62      # single against joint, row by row

``trace`` is run on speedsq68's rule (906279d5's src: a state's square as a candidate, applied to a
copy of this checkout for the trace only; not adopted); ``rows`` on this checkout's (main's) code.

What the targets share (``diagnosis._diagnose``)
------------------------------------------------
1. The test blocks: every target's candidates are tested on blocks as long as the *slowest*
   target's starting CV residual takes to decorrelate (``decorrelation_length``, the max).
2. The sensor check (``search.sensor_health``): a nominated sensor is excluded only if its removal
   clears the bar on *every* target; the exclusions then hold for every target.
A target's starting CV residual does not depend on the others, so its own length is the same
integer diagnosed alone or with others; the cells force one of the two shared things at a time:

* ``length=E_Z``: every target's blocks as long as E_Z's own length (measured in the E_Z-alone
  cell), the sensor check as shipped;
* ``sensors=E_Z``: a removal is decided by E_Z's evaluation alone (the other targets do not veto;
  they take the exclusion), the blocks as shipped;
* and E_Z alone with the five targets' length forced, or with its own sensor exclusion refused.

``rows``: bench_remeasure62's diagnose rows, ``joint`` as shipped, ``single``: every diagnosis of
more than one target run one target at a time (each its own ``diagnose``; a one-target diagnosis
is the same computation either way, so only the 44 multi-target cases, 91 of the 139 rows, can
differ); ``own``: one joint diagnosis, each target tested on its own blocks (the sensor check
joint), which tells the blocks' share of single's differences from the sensor check's.

Measured 2026-12-01 (2 shared cores, load 5-10)
-----------------------------------------------
``trace`` (speedsq68's rule applied to this checkout's src, MLR, forward chaining, 16 CV units;
own lengths in target order 553 / 536 / 225 (E_Z) / 329 / 317 samples; CPU 71.6 s user + sys)::

  cell                          blocks  excluded        square on E_Z: gain  p fam.  clears  E_Z test
  five (as shipped)             13x553  -               41.8 %  0.13     no      0.903 -> 0.903
  E_Z alone                     34x225  T7 X screw      74.7 %  1e-4     yes     0.903 -> 0.336
  five, length=E_Z              34x225  -               41.8 %  6.5e-4   no (margin p 0.043)  0.903
  five, sensors=E_Z             13x553  T7 X screw      74.7 %  0.0043   yes     0.903 -> 0.318
  five, length=E_Z sensors=E_Z  34x225  T7 X screw      74.7 %  1e-4     yes     0.903 -> 0.336
  E_Z alone, length=five        13x553  T7 X screw      74.7 %  0.0043   yes     0.903 -> 0.318
  E_Z alone, no exclusion       34x225  -               41.8 %  6.5e-4   no (margin)  0.903

The sensor check decides, not the blocks.  ``T7 X screw`` (``T_xdrive``, the X drive's only
sensor: 20.2-21.7 °C in every campaign but AXIS-X, up to 29.8 there) is nominated by its
self-prediction (5.6 °C in AXIS-X, jump ratio 4.0 >= 3), costs E_Z nothing (CV 1.1523 ->
1.1522 µm), and is vetoed by E_X1 and E_Tilt_B (removal CV -1085 % / -436 %; excluded for all
five, ``sensors=E_Z``: test E_X1 0.307 -> 3.770, E_Tilt_B 0.364 -> 2.522 µm): a healthy sensor.
E_Z alone, max_effects 1, 13 blocks: the square's blocks at VS1's end and AXIS-X's start go
0.141 -> 2.564 and 0.460 -> 0.793 µm² with it (penalty 0.1), 0.110 -> 0.134 and 0.119 -> 0.146
without it (penalty 3e-4).

``rows`` (main's code, no square; CPU user + sys of each whole process: joint 298 s, single
491 s, own 433 s).  joint reproduces the shipped counts (clean + null accepting 0 of 44, planted
found 19 of 23, > 2 % worse than before diagnose 2 of 139: 5682, the jig's E_DISP_Y).  Rows
that differ from joint (test after, µm)::

  single  record E_ch3           4.343 -> 3.848  (-11.4 %)  T_16 removed (E_ch1, E_ch2 veto it jointly)
  single  record E_ch4           4.324 -> 3.807  (-12.0 %)  T_16 removed
  single  record E_ch5           3.041 -> 3.406  (+12.0 %)  T_16 removed
  single  gantry E_Z_error       0.3203 -> 0.3425 (+6.9 %)  the same 4 h lag, its own 5040 blocks'
  single  gantry-noY E_Z_error   0.3203 -> 0.3425 (+6.9 %)  penalty (one standard error smaller)
  own     gantry, gantry-noY E_Z_error: the same two rows; no other row differs

single's counts: 0 of 44, 19 of 23, > 2 % worse than before diagnose 3 of 139 (record E_ch5
added); own's: 0 of 44, 19 of 23, 2 of 139.  So on main the blocks account for the gantry's two
rows and the sensor check for the record's three.  diagblocks59's other two differences
(vendor5 E_X's 900 s lag, record E_ch1's 1 h lag) do not appear on today's code.  No rule was
written: the blocks' part is diagblocks59's refused one; the sensor check's is a sensor kept
out of some targets' models only (a per-target input set, which the compensator does not have),
2 rows better and 1 worse by 12 % here -- left open.
"""

from __future__ import annotations

import contextlib
import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from _cli import made_folder, run_commands  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

ISO = {"iso_a": 6701}
FIVE: list[str] = []            # every target (diagnose.targets unset)
CELLS = {   # name -> (targets, forced length: "E_Z" / "five" / None, sensors decided by, veto)
    "five": (FIVE, None, None, False),
    "E_Z": (["E_Z"], None, None, False),
    "five length=E_Z": (FIVE, "E_Z", None, False),
    "five sensors=E_Z": (FIVE, None, ["E_Z"], False),
    "five length=E_Z sensors=E_Z": (FIVE, "E_Z", ["E_Z"], False),
    "E_Z length=five": (["E_Z"], "five", None, False),
    "E_Z no exclusion": (["E_Z"], None, None, True),
}


@contextlib.contextmanager
def forced(length: int | None = None, decide: list[str] | None = None, veto: bool = False):
    """The shipped diagnosis with one shared thing forced; yields what it recorded: every
    target's own decorrelation length (in the order diagnosed) and the length used.

    ``length``: every target's test blocks this long; ``decide``: a sensor's removal is decided
    by these targets' evaluations only (the others take it); ``veto``: no removal is accepted."""
    import thermocomp.apps.diagnose.diagnosis as diagnosis
    from thermocomp.apps.diagnose.search import Search

    shipped_length, shipped_evaluate = diagnosis.decorrelation_length, Search._evaluate
    seen: dict = {"own": [], "used": None}

    def measured(residual, campaigns, scored, *rest):
        own = shipped_length(residual, campaigns, scored, *rest)
        seen["own"].append(int(own))
        seen["used"] = int(length) if length else max(seen["own"])
        return int(length) if length else own

    def evaluate(self, effect, *a, **k):
        ev = shipped_evaluate(self, effect, *a, **k)
        if effect.transform == "remove":
            if veto:
                ev.clears_bar = False
            elif decide is not None and self.problem.target not in decide:
                ev.clears_bar = True
        return ev

    diagnosis.decorrelation_length, Search._evaluate = measured, evaluate
    try:
        yield seen
    finally:
        diagnosis.decorrelation_length, Search._evaluate = shipped_length, shipped_evaluate


def write(root: Path) -> None:
    import bench_iso67 as iso67
    iso67.write(root, ISO)
    for name in ISO:
        if not (root / f"init-{name}").exists():
            iso67.initialised(root, name, ["data.test_fraction=0.1"])


def _square_p(report: dict, target: str = "E_Z") -> dict:
    """E_Z's evaluations of the spindle speed's square (first round that tried it)."""
    for rnd in report["rounds"]:
        for e in rnd["evaluated"]:
            if "Spindle" in str(e["column"]) and "square" in str(e["transform"]):
                ev = e["evidence"]
                return {"step": rnd["step"], "gain_pct": round(ev["cv_rmse_gain_pct"], 1),
                        "p": ev["p_value"], "p_family": ev.get("p_value_family"),
                        "clears": ev["clears_bar"]}
    return {}


def trace(root: Path) -> None:
    import lab_matrix
    lab_matrix.project(root)
    lengths: dict = {}
    for cell, (targets, force, decide, veto) in CELLS.items():
        length = lengths.get(force)
        out = root / "diag" / cell.replace(" ", "_").replace("=", "-")
        extra = [f"diagnose.targets=[{','.join(targets)}]"] if targets else []
        before = cpu_seconds()
        with forced(length, decide, veto) as seen:
            rc, said, _ = lab_matrix.stage("diagnose", *lab_matrix.data_args(root, "iso_a"),
                                           "model=mlr", "plots=none", "track=false", *extra,
                                           f"out={out}")
        row = {"cell": cell, "rc": rc, "own_lengths": seen["own"], "length": seen["used"],
               "cpu_s": round(cpu_seconds() - before, 1)}
        if cell == "five":
            lengths["five"] = seen["used"]
        if cell == "E_Z":
            lengths["E_Z"] = seen["used"]
        if rc:
            row["said"] = said
        else:
            report = json.loads((out / "diagnosis" / "diagnosis_E_Z.json").read_text())
            row |= {"target": report["target"], "blocks": report["cv"]["test_blocks"],
                    "block_samples": report["cv"]["block_samples"],
                    "excluded": report["excluded_inputs"],
                    "E_Z_test": [report["before"]["test_rmse"], report["after"]["test_rmse"]],
                    "E_Z_accepted": [s["effect"] for s in report["steps"] if s["effect"]],
                    "square": _square_p(report)}
        _append(root / "trace.jsonl", row)


def _append(path: Path, row: dict) -> None:
    with path.open("a") as f:
        f.write(json.dumps(row, ensure_ascii=False, default=float) + "\n")
    print(json.dumps(row, ensure_ascii=False, default=float), flush=True)


@contextlib.contextmanager
def one_at_a_time():
    """Every diagnosis of several targets run as one ``diagnose`` per target; the result answers
    ``targets`` and ``to_json(target)`` from that target's own diagnosis."""
    from sklearn.base import clone

    import thermocomp.apps.diagnose.diagnosis as diagnosis
    from thermocomp.core.continuation import fit_joined
    from thermocomp.core.scoring.evaluation import require_split

    shipped = diagnosis._diagnose

    def single(ds, compensator, targets, *rest):
        if targets is None:
            fitted = fit_joined(clone(compensator), ds, require_split(ds, "train"))
            targets = list(fitted.targets_)
        targets = [targets] if isinstance(targets, str) else list(targets)
        if len(targets) < 2:
            return shipped(ds, compensator, targets, *rest)
        return Separate({t: shipped(ds, compensator, [t], *rest) for t in targets})

    diagnosis._diagnose = single
    try:
        yield
    finally:
        diagnosis._diagnose = shipped


class Separate:
    """Per target its own :class:`~thermocomp.apps.diagnose.diagnosis.Diagnosis`."""

    def __init__(self, by_target: dict):
        self.by_target = by_target
        self.targets = {t: d.targets[t] for t, d in by_target.items()}

    def to_json(self, target: str) -> dict:
        return self.by_target[target].to_json(target)


@contextlib.contextmanager
def own_blocks():
    """The joint diagnosis (one sensor check) with each target tested on its own residual's
    blocks (diagblocks59's ``own``, on today's signatures)."""
    import thermocomp.apps.diagnose.diagnosis as diagnosis
    from thermocomp.apps.diagnose.cv import Problem

    shipped_length, shipped_set = diagnosis.decorrelation_length, Problem.set_test_blocks
    own: dict = {}

    def measured(residual, campaigns, scored, *rest):
        own[id(scored)] = length = shipped_length(residual, campaigns, scored, *rest)
        return length

    def setting(self, length):
        shipped_set(self, own.get(id(self.validated), length))

    diagnosis.decorrelation_length, Problem.set_test_blocks = measured, setting
    try:
        yield
    finally:
        diagnosis.decorrelation_length, Problem.set_test_blocks = shipped_length, shipped_set


def rows(root: Path, how: str, groups: list[str]) -> None:
    import bench_remeasure62 as rm
    with {"single": one_at_a_time, "own": own_blocks}.get(how, contextlib.nullcontext)():
        rm.measure(root / f"{how}68.jsonl", rm.diagnose_rows(root, groups or
                                                             ["cases", "few", "fresh", "null", "jig"]))


def compare(root: Path) -> None:
    import bench_remeasure62 as rm
    joint = rm._read(root / "joint68.jsonl")
    print(rm._wrapped(rm.diagnose_table(joint)))
    for how in ("single", "own"):
        other = rm._read(root / f"{how}68.jsonl")
        print(rm._wrapped([f"joint -> {how}"] + ["  " + line for line in rm.compare(joint, other)]))
        print(rm._wrapped(rm.diagnose_table(other)[-6:]))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "rows": lambda root, kind, *groups: rows(made_folder(root), kind, list(groups)),
        "write": lambda root, *_: write(made_folder(root)),
        "trace": lambda root, *_: trace(made_folder(root)),
        "compare": lambda root, *_: compare(made_folder(root)),
    }, argv)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
