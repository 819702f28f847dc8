"""diag82f's per-target blocks on records nothing was tuned on: edm81, lathe82, trunnion82b
(verify82; issue 34: "diagnose ... never leaves a record's test error more than 2 % worse", the
control never accepted).  A measurement: no rule, no src change.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_verify82.py diagnose ROOT RECORD LABEL   # -> ROOT/diag_RECORD_LABEL
    python benchmarks/bench_verify82.py table ROOT A B               # per target, label A -> B

ROOT holds each record as its stranger bench's ``write`` made it (``bench_stranger81.py write
ROOT 8111`` -> ``ROOT/edm8111``, ``bench_stranger82.py write ROOT 8211`` -> ``ROOT/lathe8211``,
``bench_stranger82b.py write ROOT 8341`` -> ``ROOT/trunnion8341``) and ``thermocomp init
ROOT/RECORD out=ROOT/init_RECORD`` 's data config.  ``diagnose``: ``thermocomp diagnose`` on that
config as the stranger benches ran it (MLR, defaults, ``plots=none``, ``track=false``).
``table``: every target's (its own ``diagnosis/diagnosis_<target>.json``) test RMSE as
deployed before -> after, starting design (``cv.designs``: test blocks x samples, smallest
reachable p), each round's blocks, whether the control ever cleared the bar, the accepted effects
and the top candidate (CV gain, family-wise p), the two labels one line each.

The two trees (the diagnose package is all diag82f changed: ``git diff 10a06ad4^1 10a06ad4``
touches ``src/thermocomp/apps/diagnose`` only): old = 481c34c6's src with ``apps/diagnose`` from
7b8e171a (its readers: 7b8e171a reads neither the GL840 nor the GX20 files), new = 481c34c6.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from _cli import run_commands  # noqa: E402

RECORDS = ("edm8111", "lathe8211", "trunnion8341", "jig8011", "vtl7846")


def diagnose(root: str, record: str, label: str) -> None:
    """``thermocomp diagnose`` (MLR, defaults) on ``ROOT/init_RECORD``'s config."""
    root_p = Path(root).resolve()
    conf = root_p / f"init_{record}" / "conf"
    out = root_p / f"diag_{record}_{label}"
    ran = subprocess.run([sys.executable, "-m", "thermocomp", "diagnose", f"hydra.searchpath=[file://{conf}]",
                          f"data={record}", "track=false", "plots=none", f"out={out}"],
                         capture_output=True, text=True)
    print(f"{out.name}: exit {ran.returncode}" + (f": {ran.stderr[-600:]}" if ran.returncode else ""))


def targets(out: Path) -> dict[str, dict]:
    """Each target's figures from its own ``diagnosis/diagnosis_<target>.json`` under ``out``."""
    rows = {}
    for path in sorted((out / "diagnosis").glob("diagnosis_*.json")):
        r = json.loads(path.read_text())
        t, cv = r["target"], r["cv"]
        shared = {k: cv[k] for k in ("test_blocks", "block_samples", "min_p")}
        rounds = [f"{d.get('test_blocks', '-')} x {d.get('block_samples', '-')}" for d in r["rounds"]]
        rows[t] = {"before": r["before"]["test_rmse"], "after": r["after"]["test_rmse"],
                   "design": (cv.get("designs") or {}).get(t) or shared, "rounds": rounds,
                   "accepted": [_effect(e) for e in r["effects"] if e.get("accepted")],
                   "top": sorted(r["effects"], key=lambda e: -e["evidence"]["cv_rmse_gain_pct"])[:2],
                   "control": r["control_ever_clears_bar"], "excluded": r.get("excluded_inputs") or []}
    return rows


def _effect(e: dict) -> str:
    return f"{e['column']} x {e['transform']}" if e.get("column") else e["transform"]


def _line(t: str, label: str, r: dict) -> str:
    d = r["design"]
    top = "; ".join(f"{_effect(e)} {e['evidence']['cv_rmse_gain_pct']:.1f} % family p "
                    f"{e['evidence'].get('p_value_family') or float('nan'):.3g}" for e in r["top"])
    return (f"  {t:12s} {label:5s} {r['before']:7.3f} -> {r['after']:7.3f} "
            f"({100 * (r['after'] / r['before'] - 1):+5.1f} %)  {d['test_blocks']} x {d['block_samples']} "
            f"(min p {d['min_p']:.2g}) rounds {', '.join(r['rounds'])}  control clears {r['control']}"
            f"  excluded {r['excluded']}\n      accepted: {'; '.join(r['accepted']) or 'nothing'}"
            f"\n      top candidates: {top or 'none'}")


def table(root: str, a: str, b: str) -> None:
    """Per record and target: label ``a`` then label ``b``."""
    for record in RECORDS:
        outs = {label: Path(root) / f"diag_{record}_{label}" for label in (a, b)}
        missing = [label for label, out in outs.items() if not (out / "diagnosis").is_dir()]
        if missing:
            print(f"{record}: no diagnosis for {missing}")
            continue
        rows = {label: targets(out) for label, out in outs.items()}
        print(record)
        for t in rows[a]:
            for label in (a, b):
                print(_line(t, label, rows[label][t]))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"diagnose": diagnose, "table": table}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
