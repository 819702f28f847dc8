"""diagnose's acceptance test per target: each target's own test blocks against one design (the
slowest diagnosed target's) for every target (task diagblocks59, session 59).

Usage::

    python benchmarks/bench_diagnose_targets59.py write ROOT        # bench_diagnose_lag57's records
    python benchmarks/bench_diagnose_targets59.py [shared,own] [CASE ...] [--root ROOT]
    # CASE: bench_diagnose_lag57's 53 (planted:SEED, clean:SEED, scenario, record, machine:NAME),
    # bench_diagnose_few's cases not among them, lab5801 (the position effect alone) and
    # lab5801door (door and position); none: every one, the multi-target ones first

The problem (docs/diagnose.md before this session): the sign-flip test's blocks were as long as
the *slowest* diagnosed target's CV residual takes to decorrelate, one design for every target.
A lab file of 22 train runs (``lab5801``: the default scenario, seed 5801, a planted axis
position effect on E_Y, the last 2 of its 24 campaigns the test, as ``init`` splits a lab's file
of runs) gave E_Y 22 blocks of ~93 samples (E_Z's memory), family-wise p 0.073, nothing accepted;
diagnosed alone, E_Y had 195 blocks of ~8 and took the effect (test 3.79 -> 1.14 µm): a target's
result depended on which other targets were diagnosed with it.

Design (``own``, written before any scoring)
--------------------------------------------
* Each target's candidates are tested on blocks as long as *its own* starting CV residual takes to
  decorrelate (:func:`~thermocomp.core.model_selection.blocks.decorrelation_length`, unchanged).
  Why that is valid: the family-wise correction was always per target and per round (max-T over
  one target's candidates), never across targets; the gain a block carries, ``e0² - e1²``, is made
  of that target's residuals only, so another target's slower memory says nothing about whether
  this target's neighbouring blocks are near-independent.  The shared design was conservative for
  the fast targets, and made their outcome depend on ``diagnose.targets``.
* Sensor health stays joint (a sensor is broken for every target), and its design does not
  matter: a removal's bar is its self-prediction jump and its CV RMSE change over all held-out
  rows and over the in-range rows (:meth:`Search._evaluate`), none of which read the test blocks;
  the p-values it records are not asked.  So it is kept as it is.
* ``diagnosis_<target>.json``: ``cv.test_blocks``, ``cv.block_samples``, ``cv.min_p`` and
  ``bar.min_p`` keep their meaning -- the design *this target's* candidates were tested on (for a
  one-target diagnosis, the same numbers as before); extension ``cv.designs``: every diagnosed
  target's ``{test_blocks, block_samples, min_p}``.  The stage prints one ``acceptance test:``
  line when every target has the same design (as before), else one per target
  (``acceptance test (E_Y): ...``); the warning that ``alpha`` cannot be reached names the targets.
* ``shared``: the code before this session, as a variant (every target set to the longest length).

Adoption rule (written before the scoring run)
----------------------------------------------
``own`` is adopted only if, over every case scored, against ``shared``:

1. on clean data nothing more is accepted (0 false effects added: no ``clean:*``/``scenario``
   target accepts an effect it did not accept before);
2. the random-walk control never clears the bar (any target, any case);
3. no target's test RMSE after diagnosis is more than 2 % worse than under ``shared``, on any case;
4. planted effects are accepted at least as often (the planted column accepted first, counted
   over ``planted:*`` and ``lab5801*``'s E_Y).

Subset chosen before running: with one target (``planted:*``, ``clean:*``, ``scenario``, and every
``bench_diagnose_few`` case: ``targets=["E_Y"]`` or ``["E_Z"]``) the longest length over the
diagnosed targets *is* that target's, so ``own`` and ``shared`` run the same arithmetic; they are
scored (both variants) only as time allows after the multi-target cases (``record``: 5 targets,
the 12 ``machine:*``, ``lab5801``, ``lab5801door``), which are run first.
"""

from __future__ import annotations

import argparse
import json
import resource
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_diagnose_few as few_bench  # noqa: E402
import bench_diagnose_lag57 as lag57  # noqa: E402
import bench_diagnose_memory as memory  # noqa: E402

import thermocomp.apps.diagnose.diagnosis as diagnosis_module  # noqa: E402
from thermocomp.apps.diagnose import SearchOptions, diagnose  # noqa: E402

VARIANTS = ["shared", "own"]
LAB = ["lab5801", "lab5801door"]
MULTI = ["record"] + [c for c in lag57.CASES if c.startswith("machine:")] + LAB
SINGLE = ([c for c in lag57.CASES if c not in MULTI]
          + [c for c in few_bench.TUNING + few_bench.FRESH if c not in lag57.CASES])
CASES = MULTI + SINGLE
OWN_LENGTHS = diagnosis_module.test_block_lengths


def shared_lengths(*args, **kwargs) -> dict:
    """The code before session 59: every target on the slowest target's blocks."""
    own = OWN_LENGTHS(*args, **kwargs)
    return dict.fromkeys(own, max(own.values()))


def variant(name: str) -> None:
    diagnosis_module.test_block_lengths = shared_lengths if name == "shared" else OWN_LENGTHS


def lab5801(effects: str):
    """The default scenario, seed 5801, ``effects`` planted; the last 2 of its 24 campaigns the
    test (as ``init`` splits a lab's file of runs: its last tenth)."""
    import thermocomp.shell.cli  # noqa: F401  (the config resolvers)
    from hydra.utils import instantiate

    from thermocomp.core.io.contract import Dataset
    from thermocomp.shell.builders import build_compensator
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.stages.diagnose import search_options

    cfg = compose(["seed=5801", f"sim.generator.effects=[{effects}]"], "diagnose")
    ds, truth = instantiate(cfg.sim.generator).generate()
    manifest = ds.manifest.copy()
    manifest["split"] = ["train"] * (len(manifest) - 2) + ["test"] * 2
    planted = [e["column"] for e in truth["undeclared_effects"]]
    return (Dataset(manifest, ds.campaigns, ds.name), build_compensator(cfg),
            search_options(cfg.diagnose), planted)


def case_data(case: str, root: Path):
    """(dataset, compensator, targets, options, planted columns) of ``case``, as its bench runs it."""
    if case in LAB:
        ds, comp, options, planted = lab5801("axis_position" if case == "lab5801" else "door,axis_position")
        return ds, comp, None, options, planted
    if case.startswith("machine:"):
        ds, comp, options = lag57.machine_data(root, case.split(":", 1)[1])
        return ds, comp, None, options, []
    ds, comp, targets, planted = memory.dataset(case)
    return ds, comp, targets, SearchOptions(max_effects=2), [planted] if planted else []


def row(case: str, name: str, root: Path) -> dict:
    ds, comp, targets, options, planted = case_data(case, root)
    variant(name)
    cpu = resource.getrusage(resource.RUSAGE_SELF)
    try:
        d = diagnose(ds, comp, targets, "simulation", options)
    finally:
        variant("own")
    after = resource.getrusage(resource.RUSAGE_SELF)
    out = {}
    for t in d.targets:
        j = d.to_json(t)
        accepted = [e for e in j["effects"] if e["accepted"]]
        out[t] = {"accepted": [f'{e["kind"]} {e["column"]} {e["transform"]}' for e in accepted],
                  "planted_first": bool(planted) and bool(accepted) and accepted[0]["column"] in planted,
                  "control_clears": j["control_ever_clears_bar"],
                  "blocks": f'{j["cv"]["test_blocks"]}x{j["cv"]["block_samples"]}',
                  "test_rmse": [round(j["before"]["test_rmse"], 4), round(j["after"]["test_rmse"], 4)]}
    return {"case": case, "variant": name, "planted": planted, "targets": out,
            "cpu_s": round(after.ru_utime + after.ru_stime - cpu.ru_utime - cpu.ru_stime, 1)}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", nargs="*")
    parser.add_argument("--root", type=Path, default=Path("/tmp/bench_diagnose_targets59"))
    args = parser.parse_intermixed_args(argv)
    if args.what[:1] == ["write"]:
        lag57.write(Path(args.what[1] if len(args.what) > 1 else args.root).resolve())
        return 0
    memory.print_rows(args.what, VARIANTS, CASES, lambda c, v: row(c, v, args.root.resolve()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
