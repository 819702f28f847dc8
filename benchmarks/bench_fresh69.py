"""An independent check of clean69's ``withinrest`` (diagnose, campaigns scheme: a candidate must
also gain ``min_gain_pct`` within the campaigns with its best held-out campaign left out) on
records nobody has seen: fresh seeds 7001-7040 only (issue 34; stop 69, fresh69).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_fresh69.py rows ROOT [RECORD ...]   # the records -> ROOT/fresh.jsonl
    python benchmarks/bench_fresh69.py compare BASE NEW         # the table and the verdict

The two trees: shipped before the rule, main e1304acc (a ``git archive`` of it), against main
0ccfb2ac (the rule merged; this branch changes no src).  Each tree's rows written by ``rows``
into its own ROOT.

The records (chosen and written here BEFORE anything was run or scored; seeds 7001-7040, on
none of which anything was tuned)
------------------------------------------------------------------------------------------
* ``planted:7001`` .. ``planted:7010`` and ``clean:7011`` .. ``clean:7020``: bench_planted69's
  ``fresh`` kind (``bench_diagnose_refnoise57.row``, variant ``before``: 8 train / 4 test
  campaigns, E_Y, MLR, ``max_effects=2``; planted: the position effect ``S_pos_Y``).
* ``grind:7021`` .. ``grind:7025``: stable67's grinder as bench_zerofew67 draws it
  (``grind_record``) with 14 runs (11 train, 3 test); 7021-7023 as built (``spindle_um=0``:
  no thermal effect worth a correction), 7024-7025 with the 1.5 µm spindle growth on E_Z.
* ``gpg:7026`` .. ``gpg:7033``: the gear grinder ``benchmarks/gpg69.py`` with 12 runs of 24 h
  (the last fifth held out as grind_record's: 10 train, 2 test); planted: the table's radial
  growth at the head radius on E_X.
* ``tsc:7034`` .. ``tsc:7040``: the twin-spindle turning centre ``benchmarks/tsc66.py`` with 12
  runs (10 train, 2 test), ``run_h=20`` (half its 40 h, for CPU); planted: the bed's lever on
  E_Z2.
* The machines: every target, MLR, ``max_effects=2``.  A record x target not diagnosed in the
  ``campaigns`` scheme is reported and left out of the verdict.

The verdict criteria (written before scoring; the rule PASSES only if all hold)
-------------------------------------------------------------------------------
1. Planted found (``planted:SEED``: ``S_pos_Y`` accepted first) with the rule not fewer than
   shipped.
2. Clean accepting something (``clean:SEED`` and ``grind:7021-7023``) with the rule not more
   than shipped.
3. No record x target whose test RMSE after diagnose is more than 2 % above shipped's after
   (the rule refusing a helpful effect, or taking a worse one in its place).

Reported beside, not in the verdict: the rows that differ, each one's test RMSE before /
shipped after / rule after; the rows > 2 % better with the rule; CPU (user + sys) per tree.

Scored (2026-12-01/02; shipped e1304acc from a ``git archive`` (/tmp/fresh69-old), rows
/tmp/fresh69-base; the rule 0ccfb2ac (this branch's src), rows /tmp/fresh69-rule; ``compare``)
--------------------------------------------------------------------------------------------
Every record x target diagnosed in the ``campaigns`` scheme (the machines' recorded; the
planted / clean rows' not recorded by ``refnoise.row``, the rule firing on two of them shows it).
87 record x target rows; 85 identical (accepted effects and test RMSE after), 2 differ, both
planted (test RMSE µm, own 4 test campaigns; before / shipped after / rule after)::

  planted:7008 E_Y  4.4692 / 0.8278 / 0.8609 (+4.0 %)   second effect: shipped the inputs x
      [ambient_c0 > 21.23 °C] (within 19.8 %, 2.6 % without K01), the rule the inputs x
      (ambient_c0 - 20 °C) (within 25.8 %, 6.5 % without K01)
  planted:7009 E_Y  6.1788 / 2.3571 / 2.6820 (+13.8 %)  second effect refused by the rule:
      S_spindle_rpm 2 h lag (absolute), CV gain 22.7 %, within 7.1 %, -2.0 % without K01
      (K01 114 % of the within gain, 2 of 8 campaigns gain within)

(within figures: ``bench_clean69.py campaigns planted:7009 planted:7008`` on the rule tree.)

1. Planted found: 7 of 10 both (missed 7001, 7002, 7005).  Held.
2. Clean accepting something: 0 of 13 both (clean:7011-7020, grind:7021-7023).  Held.
3. Rows > 2 % above shipped's after: 2 (planted:7008 +4.0 %, planted:7009 +13.8 %).  **FAILED.**
   Rows > 2 % below shipped's: 0.  The machines (grind, gpg, tsc: 67 targets) identical; the
   grinders accept nothing in either tree.

**Verdict: the rule fails criterion 3** (not reverted: no src change in this branch; the lead
decides).  Beside the verdict (seeds already used, not fresh: bench_clean69's ``moretest``, 24
more test campaigns of the record's own law from seeds 6981, 6982): 7009's harm holds, new 24
4.4647 -> 2.0740 shipped, 2.1877 rule (+5.5 %); 7008's reverses, 4.5285 -> 1.5827 shipped,
1.4118 rule (-10.8 %).  So one of the two is a real loss: a helpful spindle lag whose within
gain one campaign carries, the same signature as clean 6953's harmful lag.  CPU (user + sys,
getrusage, the rows' own): shipped 113.7 s, rule 112.6 s (the 87 rows; the records' simulation
included); the moretest pair 6.0 / 6.1 s (/usr/bin/time).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402

PLANTED = [f"planted:{s}" for s in range(7001, 7011)]
CLEAN = [f"clean:{s}" for s in range(7011, 7021)]
MACHINES = ([f"grind:{s}" for s in range(7021, 7026)] + [f"gpg:{s}" for s in range(7026, 7034)]
            + [f"tsc:{s}" for s in range(7034, 7041)])
CLEAN_MACHINES = {"grind:7021", "grind:7022", "grind:7023"}


def _held_out_last(ds, fraction: float = 0.2):
    """``ds`` with its last ``fraction`` of campaigns split ``test`` (grind_record's split)."""
    from thermocomp.core.io.contract import Dataset

    ids = list(ds.campaigns)
    n_test = round(fraction * len(ids))
    manifest = ds.manifest.loc[ids].copy()
    manifest["split"] = ["train"] * (len(ids) - n_test) + ["test"] * n_test
    return Dataset(manifest, ds.campaigns, ds.name)


def machine_dataset(case: str, scratch: Path):
    """The dataset of a ``grind:`` / ``gpg:`` / ``tsc:`` record."""
    from bench_zerofew67 import grind_record

    from thermocomp.core.io.read import read_dataset

    kind, seed = case.split(":")
    seed = int(seed)
    if kind == "grind":
        path = scratch / f"grind{seed}"
        if not path.exists():
            grind_record(path, 14, 1.5 if seed >= 7024 else 0.0, seed)
        return read_dataset(path)[0]
    if kind == "gpg":
        from gpg69 import Gpg69
        return _held_out_last(Gpg69(runs=12, seed=seed).generate()[0])
    from tsc66 import Tsc66
    return _held_out_last(Tsc66(runs=12, run_h=20.0, seed=seed).generate()[0])


def machine_row(case: str, scratch: Path) -> dict:
    import bench_diagnose_refnoise57 as refnoise

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    ds = machine_dataset(case, scratch)
    d = diagnose(ds, Compensator(MLR()), options=SearchOptions(max_effects=2))
    targets = refnoise.targets_of(d)
    for t in targets:
        targets[t]["scheme"] = d.to_json(t)["cv"]["scheme"]
    return {"case": case, "variant": "before", "targets": targets}


def rows(root: Path, cases: list[str]) -> None:
    import bench_diagnose_refnoise57 as refnoise
    import bench_remeasure62 as rm

    root.mkdir(parents=True, exist_ok=True)
    scratch = root / "records"
    scratch.mkdir(exist_ok=True)
    cases = cases or PLANTED + CLEAN + MACHINES
    rm.measure(root / "fresh.jsonl", (("fresh69", machine_row(c, scratch) if c.split(":")[0] in
                                       ("grind", "gpg", "tsc") else refnoise.row(c, "before", root / "lag"))
                                      for c in cases))


def _read(path: Path) -> dict:
    return {r["case"]: r for r in map(json.loads, path.read_text().splitlines())}


def compare(base: Path, new: Path) -> None:
    """The table of the two trees' rows (rows that differ marked), the criteria, the CPU."""
    b, n = _read(base / "fresh.jsonl"), _read(new / "fresh.jsonl")
    print(f"{'record':13s} {'target':8s} {'sch':4s} {'before':>7s} {'shipped':>7s} {'rule':>7s} "
          f"{'rule/sh':>7s}  accepted shipped | rule")
    above, better, left_out, found, accepting = [], [], [], [0, 0], [0, 0]
    for case in b:
        if case not in n:
            print(f"{case}: missing in {new}")
            continue
        kind = case.split(":")[0]
        any_acc = [False, False]
        for t, ob in b[case]["targets"].items():
            on = n[case]["targets"][t]
            before, shipped, rule = ob["test_rmse"][0], ob["test_rmse"][1], on["test_rmse"][1]
            scheme = on.get("scheme", "campaigns")
            differ = ob["accepted"] != on["accepted"] or abs(rule - shipped) > 1e-9
            for k, o in enumerate((ob, on)):
                any_acc[k] |= bool(o["accepted"])
                found[k] += bool(o.get("right_first"))
            if scheme != "campaigns":
                left_out.append(f"{case} {t} ({scheme})")
            elif rule > 1.02 * shipped:
                above.append(f"{case} {t} {100 * (rule / shipped - 1):+.1f} %")
            elif rule < 0.98 * shipped:
                better.append(f"{case} {t} {100 * (rule / shipped - 1):+.1f} %")
            short = [" | ".join(a.split(" ", 2)[1] + " " + a.split(" ", 2)[2][:38] for a in o["accepted"])
                     or "-" for o in (ob, on)]
            print(f"{case:13s} {t[:8]:8s} {scheme[:4]:4s} {before:7.4f} {shipped:7.4f} {rule:7.4f} "
                  f"{rule / shipped:7.3f}{' *' if differ else '  '} {short[0]}  ||  {short[1]}")
        if kind == "clean" or case in CLEAN_MACHINES:
            for k in (0, 1):
                accepting[k] += any_acc[k]
    cpu = [sum(r["cpu_s"] for r in x.values()) for x in (b, n)]
    print(f"(* : the row differs)\n1. planted found: shipped {found[0]}, rule {found[1]} of {len(PLANTED)} "
          f"-> {'held' if found[1] >= found[0] else 'FAILED'}")
    print(f"2. clean accepting something: shipped {accepting[0]}, rule {accepting[1]} of "
          f"{len(CLEAN) + len(CLEAN_MACHINES)} -> {'held' if accepting[1] <= accepting[0] else 'FAILED'}")
    print(f"3. rule > 2 % above shipped: {len(above)} {above} -> {'held' if not above else 'FAILED'}")
    print(f"rule > 2 % below shipped: {len(better)} {better}\nleft out (not campaigns): {left_out}")
    print(f"CPU s (rows' own): shipped {cpu[0]:.1f}, rule {cpu[1]:.1f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "rows": lambda root, *records: rows(Path(root).resolve(), list(records)),
        "compare": lambda base, new: compare(Path(base).resolve(), Path(new).resolve()),
    }, argv)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
