"""A range reading of a sensor no other predicts in the exported C (cmon89b, issue 34): the code's
monitor holds it out as the served monitor does (read as missing, held at its last reading) and
re-admits it by the served test, the sensor's leak onto the others with it and without it within
``readmit`` of their warning bands on every sample of the window (``Readmission._leak_passes``),
behind the compensator.json key ``blind_range`` (an export without it flags ``BLIND`` as before).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's, so
"before" is the same command with main's src first)::

    python benchmarks/bench_cmon89b.py seen AUDIT_ROOT OUT
    python benchmarks/bench_cmon89b.py fresh ROOT SEEDS
    python benchmarks/bench_cmon89b.py compare [ROOT] [SPEC]

``seen``: bench_audit89's six range-faulted copies whose sensor no other predicts, as its
``faults`` left them in ``AUDIT_ROOT`` (``/tmp/audit89/fresh``: ``data/<record>-range`` and the
healthy run's ``reports/<record>/run/model.pkl``): ``export export.format=c export.check=true``
into ``OUT``, compiled as a control's build would (gcc -std=c99 -Wall -Wextra -Werror -O2), the
pack's check run (C = served on every row of the pack: check.sh exit 0, the faulted campaign not
cut); to ``OUT/seen.json``.  ``fresh``: per seed (bench_audit89's generators: seed ``s`` draws
``KINDS[(s - 9316) % 6]``) ``simulate`` -> ``run model=mlr`` -> ``monitor`` (for the costliest
sensor, bench_audit89's rule) -> the range fault (bench_audit89's ``range``: the healthy maximum +
25 degC for a tenth of the rows from the middle) planted on it -> export + pack as ``seen``; to
``ROOT/fresh.json`` with whether the exported ``blind_range`` is set and the sensor predicted.
``compare``: bench_cmon87's ``compared`` (bench_cmon85's 50 campaigns and bench_cmon86's 50) with
"before" the export without ``blind_range``.

Bar (written before any fresh seed 9361-9365 was drawn and before ``seen`` was run on the rule;
the rule was written against test_export_cmon89b's column 8841, where the mirror = served on every
row for a range fault on either of its two unpredicted sensors, ``T_front3`` and ``T_amb``):
B1. seen: the six copies (col9316, col9322, swiss9317, swiss9323, yr9318, yr9324) pack whole and
    check.sh exit 0 on every one (before: cut at the fault's row).
B2. fresh 9361-9365: the range-faulted test campaign not cut and check.sh exit 0 on every record
    whose export sets the key (a record whose costliest sensor the others predict is held by the
    code already: reported, counted too).
B3. compare: bench_cmon85/86's 100 campaigns identical before -> now (C = served rows, largest gap).
B4. every build -Werror clean (a warning fails the build, so B1/B2 show it).
Refused if B1 or B2 fails on any record; B3 not run by the deadline is said so.

Scored (2026-12-05, fix/cmon89b; "before" = main f4543acc's src, the same commands; 2 shared
cores).  B1 ``seen /tmp/audit89/fresh`` (28.4 s CPU now, 22.1 s main): main -> now, the faulted
campaign's pack and check.sh (exit 0 both: a cut pack checks only the rows before its cut):

| record | sensor (none predicts it) | main | now | planted copies cut main -> now |
|---|---|---|---|---|
| col9316 | T_front3 | cut at 721 | whole | 5 -> 2 |
| col9322 | T_front3 | cut at 721 | whole | 5 -> 2 |
| swiss9317 | T_nc_spindle_motor | cut at 721 | whole | 5 -> 2 |
| swiss9323 | T_nc_spindle_motor | cut at 721 | whole | 5 -> 2 |
| yr9318 | T_amb | K09/K12/K15/K18 cut at 29/41/26/48 | whole | 3 -> 3 |
| yr9324 | T_amb | K09/K12/K15/K18 cut at 27/46/39/48 | whole | 3 -> 3 |

B1 MET (6 of 6 whole, exit 0).  B2 ``fresh 9361-9365`` (105.1 s CPU now, 94.8 s main; the key
set on 5 of 5): lmw9361 ``T_col_10``, fleet9362 ``T_s27``, lmv9363 ``T_col_04``, swiss9365
``T_guidebush`` (each predicted by others): whole on main and now (copies cut 2, 2, 2, 3 both);
column9364 ``T_front3`` (none predicts it): cut at 721 on main -> whole now (copies cut 5 -> 4).
B2 MET (5 of 5 whole, exit 0; the rule's own evidence is column9364).  B3 ``compare`` run on the
first half of bench_cmon86's SPEC only (column 8841-8844, trunnion 8845-8846, lathe 8847-8848,
jig 8849-8850: 50 campaigns) by the deadline: 50 of 50 identical (C = served on every row before
and now, largest gap, first flag, pack rows unchanged); summed ``tc_step`` time 334.49 -> 334.76
ms (x1.001; per campaign x0.986-1.014; worst sample x0.83-1.25, the timer's noise).  The second
half (8996-9005) NOT run.  B4 MET: every build above -Werror.  Not scored: bench_cmon88's fresh
rows (``bench_cmon88.py spikes``), not run by the deadline.
Verdict: KEPT (B1, B2, B4 met; B3 met on the 50 campaigns run, half of the bar's 100).
"""

from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from _cli import run_commands, seed_list  # noqa: E402
from bench_audit89 import (  # noqa: E402
    KINDS,
    QUIET,
    _costliest,
    _pack,
    _root,
    data_args,
    label_of,
    plant,
)
from bench_deploy87 import stage  # noqa: E402

SEEN = ("9316", "9322", "9317", "9323", "9318", "9324")


def _exported(model: Path, args: list, out: Path, sensor: str | None = None) -> dict:
    """The C export of ``model`` with the pack of ``args``'s test campaigns in ``out``, built and
    checked (bench_audit89's ``_pack``), with the exported ``blind_range`` key (and whether the
    others predict ``sensor``)."""
    if out.exists():
        shutil.rmtree(out)
    rc, said = stage("export", f"export.model={model}", "export.format=c", "export.check=true",
                     f"out={out}", *args, "track=false")
    if rc:
        return {"note": f"export exit {rc}: {said[:200]}"}
    comp = json.loads((out / "compensator.json").read_text())
    monitor = comp.get("monitor") or {}
    pack = _pack(out)
    names = [comp["inputs"][i] for i in monitor.get("inputs", [])] if "inputs" in comp else []
    predicted = (bool(monitor["predictable"][names.index(sensor)]) if sensor in names else None)
    return {"predicted": predicted, "blind_range": int(monitor.get("blind_range", 0)),
            "check_rc": pack["check_rc"],
            "cut": {c: k for c, k in pack["cuts"].items() if "." not in c},
            "copies_cut": len([c for c in pack["cuts"] if "." in c])}


def _print(row: dict) -> None:
    print(f"{row['record']:<14}{row.get('sensor', ''):<22}{row.get('predicted', '-')!s:>6}"
          f"{row.get('blind_range', '-')!s:>4}{row.get('check_rc', '-')!s:>4}  "
          f"{row.get('cut') or 'whole'}  copies cut {row.get('copies_cut', '-')} {row.get('note', '')}",
          flush=True)


def seen(audit_root: str, out: str) -> None:
    """bench_audit89's six range-faulted copies exported and checked (module doc)."""
    src, folder = Path(audit_root).resolve(), _root(out)
    rows = []
    for record in SEEN:
        label = label_of(record)
        model = src / "reports" / label / "run" / "model.pkl"
        row = {"record": label, **_exported(model, data_args(src, label, src / "data" / f"{label}-range"),
                                            folder / label)}
        _print(row)
        rows.append(row)
    (folder / "seen.json").write_text(json.dumps(rows, indent=1))


def _fresh_record(root: Path, record: str) -> dict:
    label = label_of(record)
    data, out = root / "data" / label, root / "reports" / label
    rc, said = stage("-q", "simulate", f"seed={record}", f"data.path={data}", "track=false",
                     *KINDS[label.rstrip("0123456789")])
    if rc:
        return {"record": label, "note": f"simulate exit {rc}: {said[:200]}"}
    args = data_args(root, label)
    model = out / "run" / "model.pkl"
    for name, more in (("run", ["model=mlr"]), ("monitor", [f"monitor.model={model}"])):
        rc, said = stage(name, *args, f"out={out / name}", *QUIET, *more)
        if rc:
            return {"record": label, "note": f"{name} exit {rc}: {said[:200]}"}
    mon = json.loads((out / "monitor" / "monitor.json").read_text())
    sensor = _costliest(mon)
    copy, _ = plant(root, label, sensor, "range")
    return {"record": label, "sensor": sensor,
            **_exported(model, data_args(root, label, copy), out / "c-range", sensor)}


def fresh(root: str, seeds: str) -> None:
    """Fresh records with the range fault on their costliest sensor (module doc)."""
    folder = _root(root)
    rows = []
    for record in seed_list(seeds):
        row = _fresh_record(folder, str(record))
        _print(row)
        rows.append(row)
    (folder / "fresh.json").write_text(json.dumps(rows, indent=1))


def compare(root: str = "/tmp/cmon89b-bench", spec: str | None = None) -> None:
    """bench_cmon86's campaigns (bench_cmon87's ``compared``), before: without ``blind_range``."""
    from bench_cmon87 import compared
    from bench_cmon88 import _stripped

    compared(root, spec, lambda ss: _stripped(ss, "blind_range"))


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"seen": seen, "fresh": fresh, "compare": compare},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
