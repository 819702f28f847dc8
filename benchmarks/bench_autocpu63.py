"""``model=auto``'s CPU on the probe grinder's joined train weeks, before and after autocpu63.

    .venv/bin/python benchmarks/bench_probe61.py write DIR     # the probe grinder (seed 6131)
    .venv/bin/python benchmarks/bench_probe61.py init DIR
    .venv/bin/python benchmarks/bench_autocpu63.py DIR [--before REV ...] [--records ...]

Each record is run once per code (``thermocomp run model=auto``, its own process, the CPU user +
sys of that process): the code of each ``--before`` revision (``git archive REV src conf``,
put first on ``PYTHONPATH``) and this checkout's.  ``swiss_lathe_door`` (``thermocomp simulate
sim=swiss_lathe_door``, its default seed, under ``DIR``) has no train files that continue one
another: the control.  Every ``metrics.json`` is compared with the first code's, timings
(``fit_time_s``, ``validation_s``) left out: the largest numeric difference and the keys whose
text differs.  Writes ``DIR/autocpu63.json``.

Where the grinder's CPU went (cProfile of 7b75b1f, main when autocpu63 began: 200 s profiled):
37 lstm fits, 146 s -- 15 by auto's own 5 forward folds x 3 targets (the joined record is one
record: 5 folds, where the two weeks apart gave one), 3 by its refit of each blend on all rows,
15 by the run's validation refitting those very folds (auto's stored out-of-fold predictions were
refused: their scored rows are a probe target's measured rows, the refit's every row of the
fold, NaN where not measured), 4 by the ATI baselines (coldest, warmest week) and mutual
prediction, whose models of the two train weeks were those baselines fitted again (dX, dY: a
blend with an lstm member, nothing chosen of its own); the ATI report also predicted the test
week's joined record again (score had).  After: 23 lstm fits, 15 of them auto's folds (54 of
122 s profiled).

Measured 2026-12-01 (2 shared cores; CPU s of one run, each run once; swiss_lathe_door three
times; ``--records grinder_b`` after ``bench_probe61.py join``)::

    code                           grinder (6131)   grinder_b (6132)   swiss_lathe_door
    acaa1da (before lagbank62)          35.0                               12.7
    7b75b1f (main)                     125.8             143.6             11.3 / 10.8 / 12.0
    autocpu63                           80.6              98.4             12.1 / 11.2 / 11.8

metrics.json against 7b75b1f's: swiss_lathe_door identical; each grinder identical but for its
run's validation block: ``method`` ends "model=auto: its members' out-of-fold predictions,
weights fixed, not refitted", and its figures are auto's own fold fits', a refit's within
1.9e-14 µm (grinder_b 1.3e-14): a refit predicts from Fortran-ordered matrices, auto's folds from
C-ordered copies, and BLAS rounds the two products apart (1.7e-13 µm on an MLR fold's rows).
Test RMSE (µm) E_Probe_dX / dY / dZ unchanged: grinder 0.5187 / 0.5151 / 0.6701.

Not changed (a result change, measured, not committed): the 15 lstm fold fits are the joined
record's forward folds themselves.  Without lstm among the candidates
(``model.candidates=[mlr,pcr,arx,lagbank,hammerstein]``) the grinder's run costs 6.3 s CPU and
tests 0.5183 / 0.5152 / 0.6701 (lstm's weights 0.08 on dX, 0.60 on dY bought nothing on test);
before lagbank62 (the weeks apart, one fold) auto tested 0.5210 / 0.5148 / 1.633.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tarfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from bench_probe61 import data_args  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
TIMINGS = {"fit_time_s", "validation_s"}


def code_of(root: Path, rev: str) -> Path:
    """The ``src`` and ``conf`` of ``rev``, unpacked under ``root`` (once; ``datasets`` linked:
    fl_thermal's path is relative to the project root)."""
    dest = root / f"code-{rev}"
    if not (dest / "src").exists():
        dest.mkdir(parents=True, exist_ok=True)
        archive = dest / "code.tar"
        with archive.open("wb") as out:
            subprocess.run(["git", "archive", rev, "src", "conf"], cwd=REPO, stdout=out, check=True)
        with tarfile.open(archive) as tar:
            tar.extractall(dest, filter="data")
        archive.unlink()
        (dest / "datasets").symlink_to(REPO / "datasets")
    return dest / "src"


def swiss(root: Path, src: Path) -> Path:
    path = root / "swiss_lathe_door"
    if not path.exists():
        subprocess.run([sys.executable, "-m", "thermocomp", "simulate", "sim=swiss_lathe_door",
                        f"data.path={path}", "track=false"], env=_env(src), cwd=root, check=True,
                       capture_output=True)
    return path


def _env(src: Path) -> dict:
    return dict(os.environ, PYTHONPATH=str(src))


def run_auto(root: Path, record: str, src: Path, label: str) -> dict:
    """``thermocomp run model=auto`` of ``record`` with the code at ``src``: CPU s, metrics."""
    data = (data_args(root, record) if record != "swiss_lathe_door"
            else [f"data.path={swiss(root, src)}"])
    out = root / "out" / f"autocpu63-{record}-{label}"
    before = os.times()
    run = subprocess.run([sys.executable, "-m", "thermocomp", "run", *data, "model=auto",
                          "track=false", "plots=none", f"out={out}"], env=_env(src), cwd=root,
                         capture_output=True, text=True)
    after = os.times()
    cpu = (after.children_user - before.children_user
           + after.children_system - before.children_system)
    row = {"record": record, "code": label, "status": run.returncode, "cpu_s": round(cpu, 1)}
    if run.returncode:
        row["error"] = run.stderr.strip().splitlines()[-1]
        return row
    row["metrics"] = json.loads((out / "metrics.json").read_text())
    return row


def differences(a, b, path: str = "") -> list[tuple[str, object]]:
    """``(key path, |a - b| or the two texts)`` where two metrics.json differ, timings left out."""
    if isinstance(a, dict) and isinstance(b, dict):
        return [d for k in sorted(set(a) | set(b), key=str) if k not in TIMINGS
                for d in (differences(a[k], b[k], f"{path}/{k}") if k in a and k in b
                          else [(f"{path}/{k}", "missing")])]
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, f"{path}[{i}]")]
    if isinstance(a, float) and isinstance(b, float):
        return [] if a == b else [(path, abs(a - b))]
    return [] if a == b else [(path, f"{a!r} -> {b!r}"[:160])]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("root")
    parser.add_argument("--before", nargs="*", default=["7b75b1f"])
    parser.add_argument("--records", nargs="+", default=["grinder", "swiss_lathe_door"])
    args = parser.parse_args(argv)
    root = Path(args.root).resolve()
    codes = {rev: code_of(root, rev) for rev in args.before}
    codes["autocpu63"] = REPO / "src"
    rows = []
    for record in args.records:
        first = None
        for label, src in codes.items():
            row = run_auto(root, record, src, label)
            metrics = row.pop("metrics", None)
            if metrics is not None and first is None:
                first = (label, metrics)
            elif metrics is not None:
                diff = differences(first[1], metrics)
                numeric = [d for _, d in diff if isinstance(d, float)]
                row["against"] = first[0]
                row["max_abs_difference"] = max(numeric, default=0.0)
                row["texts_differing"] = [p for p, d in diff if not isinstance(d, float)]
                row["numbers_differing"] = sorted({"/".join(p.split("/")[:4])
                                                   for p, d in diff if isinstance(d, float)})
            rows.append(row)
            print(json.dumps(row), flush=True)
    (root / "autocpu63.json").write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
