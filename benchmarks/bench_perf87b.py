"""perf87b: ``export``'s check pack streams a lead-in shared by campaigns once.

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_perf87b.py export LAB MODEL OUT
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_perf87b.py packs OUT

``export``: ``thermocomp export`` (C, ``export.check=true``, ``track=false``) of ``MODEL`` on the
lab folder ``LAB`` (bench_audit87's ``lab``, its ``hydra.searchpath`` folder ``LAB/../conf``)
into ``OUT``; the child's user and system CPU (``OMP_NUM_THREADS=1``).  ``packs``: the
conformance pack (:func:`~thermocomp.apps.deploy.export.pack.conformance_pack`) of the adaptive
MLR of test_export's record (tests/shell/test_export.py ``adaptive_mlr``, its monitor in the code:
planted copies) on three records, written under ``OUT/<record>/`` to be compared between trees
(``diff -r``): ``back40`` (its 40-row record, the first test campaign continuing its own rows
backwards: the shortcut taken), ``back200`` (the same record drawn with 200 rows a campaign) and
``joined40`` (the 40-row record's test campaign continuing the train campaigns joined: the
monitor acts in the lead-in, the whole streams taken).

The record: bench_audit87's ``lab`` (``simulate sim=fleet sim.generator.n_machines=2
sim.generator.days=12 sim.generator.test_days=3 seed=9136``, machine M002, 12 days of 2,880 rows
at 30 s, the last held out) and bench_perf87's mlr ``model.pkl`` of it.

The rule (a defect, not a trade): the pack streamed each campaign from its start, so the test
day (34,560 rows with its 31,680-row lead-in, ``data.reference=none``) and its five planted-fault
copies handled the same 11 lead-in days six times, through the served model, the numpy model of
the code (``_parted``) and ``to_csv``.  Now (``pack._Lead``) a lead-in shared by campaigns is
streamed once through both and each campaign goes on from a deep copy of their states; its rows'
CSV text is formatted once (float columns only).  Where the lead-in cannot be shared (the code's
monitor parts from the served one in it, a refusal, a row cut within it) each campaign is
streamed whole as before.
The bar, written before scoring: the ``check/`` folder byte-identical to main's on the lab record
and on the three ``packs`` records, and export's CPU (user + sys) on the lab record at least
halved; else REFUSED.  (Written while the branch's first lab export ran, after main's first,
75.5 s, had been seen; before the pairs below.)

Scored (2026-12-04, 2 cores shared by six sessions; main = b9c94b3b, this branch af64cd9d;
``OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1``; user + sys of the child)
-----------------------------------------------------------------------------------------------
``export`` of the lab record's mlr model, C with its pack (207,360 rows: the test day and five
planted copies, each 34,560 rows with its 31,680-row lead-in, none cut), in turn:

  run                                         user     sys    user + sys
  main   (``/usr/bin/time``, first)           73.1 s   2.4 s    75.5 s
  branch (``/usr/bin/time``)                  18.2 s   1.8 s    19.9 s
  main   (bench ``export``)                   66.8 s   1.7 s    68.5 s
  branch (bench ``export``)                   18.3 s   1.3 s    19.6 s
  main   (bench ``export``)                   66.5 s   1.1 s    67.6 s
  branch (bench ``export``)                   17.2 s   1.4 s    18.6 s

Export CPU 75.5 / 68.5 / 67.6 -> 19.9 / 19.6 / 18.6 s (/ 3.5 to 3.8).  ``check/`` (133 MB, six
campaigns) byte-identical between every main and branch run (``diff -r``), and to bench_perf87's
main export of it; the code files differ by their ``exported`` time stamp only.  ``packs``: the
three records' ``check/`` (six campaigns each; back40 80 rows with its 40-row lead-in, back200
400 with 200, joined40 40 rows with 160, its entries cut in the lead-in where the monitor acts at
a junction) byte-identical main vs branch.  cProfile of the branch's export (31.2 s under the
profiler): ``conformance_pack`` 26.3 s, of which the lead-in streamed once (``_Lead``) 13.2 s,
the numpy model (``_parted``, the lead-in's once included) 16.3 s, CSV text 5.0 s (the lead-in's
once included), the six copies' served streams 1.8 s, deep copies 0.7 s.

Verdict: KEPT (the pack byte-identical, export CPU / 3.5).  What remains: the one pass over the
lead-in, row by row through the served model and the numpy model with its code monitor.
"""
from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import made_folder, run_commands  # noqa: E402


def _user_sys() -> tuple[float, float]:
    import resource
    u = resource.getrusage(resource.RUSAGE_CHILDREN)
    return u.ru_utime, u.ru_stime


def export(lab: str, model: str, out: str) -> None:
    """``thermocomp export`` (C, with its check pack) of ``model`` on ``lab``: the child's CPU."""
    conf = (Path(lab).resolve().parent / "conf").as_uri()
    before, wall = _user_sys(), time.perf_counter()
    ran = subprocess.run([sys.executable, "-m", "thermocomp", "-q", "export",
                          f"hydra.searchpath=[{conf}]", "data=lab",
                          f"export.model={Path(model).resolve()}", "export.format=c",
                          "export.check=true", "track=false", f"out={Path(out).resolve()}"],
                         capture_output=True, text=True)
    after = _user_sys()
    print(f"exit {ran.returncode}; user {after[0] - before[0]:.1f} s, sys "
          f"{after[1] - before[1]:.1f} s, wall {time.perf_counter() - wall:.0f} s")


def _backwards(campaign):
    """``campaign``'s rows backwards, ending one sample period before its first row."""
    campaign = campaign.reset_index(drop=True)
    t = campaign["time"].to_numpy(float)
    lead = campaign.iloc[::-1].reset_index(drop=True)
    lead["time"] = t[0] - (t[-1] - t[::-1]) - (t[1] - t[0])
    lead.attrs = dict(campaign.attrs)
    return lead


def packs(out: str) -> None:
    """The pack of test_export's adaptive MLR on three records under ``out`` (module doc)."""
    tests = Path(__file__).resolve().parents[1] / "tests"
    sys.path[:0] = [str(tests / "shell"), str(tests)]
    import test_export
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack
    from thermocomp.core.continuation import preceding

    root = made_folder(out)
    for name, rows in (("back40", 40), ("back200", 200), ("joined40", 40)):
        made = test_export._make_dataset
        test_export._make_dataset = lambda folder, rows=rows: made(folder, rows)
        try:
            deployed, ds, test_ids = test_export.adaptive_mlr(root / "records" / name)
        finally:
            test_export._make_dataset = made
        cid = test_ids[0]
        lead = (_backwards(ds.campaigns[cid]) if name.startswith("back") else
                preceding(ds, [c for c in ds.campaigns if c not in test_ids],
                          float(ds.campaigns[cid]["time"].iloc[0])))
        files, _ = conformance_pack(deployed, state_space(deployed, monitor=True),
                                    {cid: ds.campaigns[cid]}, {cid: lead})
        for path, text in files.items():
            (root / name / path).parent.mkdir(parents=True, exist_ok=True)
            (root / name / path).write_text(text)
        print(f"{name}: {len(files)} files")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"export": export, "packs": packs}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
