"""perf87: where ``export`` and ``diagnose`` spend their CPU on a 34,560-row lab record.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_perf87.py flips UNITS CALLS
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_perf87.py diagnose LAB OUT

``flips``: the sign-flip test of the diagnose search (:func:`~thermocomp.apps.diagnose.cv.
sign_flip_pvalues`, a gain and its margin, 20,000 Monte Carlo patterns) ``CALLS`` times over
``UNITS`` units, as the search calls it once per candidate; its p-values and the user and system
CPU of this process.  ``diagnose``: ``thermocomp diagnose`` (mlr, ``track=false plots=none``) of
the lab folder ``LAB`` (bench_audit87 ``lab``, initialised by ``thermocomp init``; its
``hydra.searchpath`` folder ``LAB/../conf``) into ``OUT``; the child's user and system CPU.

The record: bench_audit87's ``lab`` of ``simulate sim=fleet sim.generator.n_machines=2
sim.generator.days=12 sim.generator.test_days=3 seed=9136`` (audit87's draw; nothing tuned on
it), machine M002, 12 days of 2,880 rows at 30 s, the last held out.

The rule (a defect, not a trade): the sign patterns of a Monte Carlo test depend on the number
of units and the seed only, yet every call drew them afresh as one float64 matrix
(``rng.choice([-1.0, 1.0], size=(20000, n))``).  Drawn once per ``(n, resamples, seed)`` and
kept as int8 (``_drawn_signs``), taken as float 32 MB at a time into one buffer.
The bar, written before scoring: diagnose's p-values and ``diagnosis.json`` equal bit for bit
(``OMP_NUM_THREADS=1``), and its system CPU at least halved; else REFUSED.

Profiled (2026-12-04, this branch from main 34c66521, 2 cores shared by six sessions)
--------------------------------------------------------------------------------------
``diagnose``: ``perf record`` of the running process: 95 % of its samples in the kernel's
``clear_page_erms`` (zeroing fresh transparent huge pages, ``vma_alloc_anon_folio_pmd``), 3 % in
numpy's ``PyArray_TakeFrom`` (``choice``'s take); ``py-spy dump``: in ``sign_flip_pvalues``,
from ``Search._evaluate`` -> ``_flip_pvalues``, ``n`` = 15,840 units (the forward scheme's
blocks of a 31,680-row train split): each call allocated 20,000 x 15,840 int64 indices and as
many float64 signs, 5 GB, every page zeroed by the kernel anew.  No thread spun: the process
has no BLAS / OpenMP worker with CPU time (OPENBLAS_NUM_THREADS=1 as the CLI sets it).

``export`` (C, ``export.check=true``, of the run's mlr ``model.pkl``; 129.7 s user + 1.5 s
sys under cProfile, whose shares follow): 66 % in ``pack._parted`` (the numpy ``Simulator``
of the exported arithmetic with its code monitor, ``CodeMonitor._step`` 38 % alone), 16 % in
``stream_rows`` (the served model), 15 % in ``csv_text`` (pandas ``to_csv`` at ``%.17g``).
207,360 rows each = 6 x 34,560: the test day and its five planted-fault copies, each fed with
its 31,680-row lead-in (the 11 days it continues, ``data.reference=none``): 92 % of the
rows streamed, simulated and written are the same lead-in six times.  Not mended here (time):
next, stream the lead-in once through the served model and the Simulator and start each copy
from a copy of both states, and format its rows once (the pack's files unchanged: each
``rows.csv`` still holds the lead-in); about 5/6 of export's CPU.

Scored (2026-12-04, 2 cores shared by six sessions; main = 34c66521's diagnose, this branch
d6d6d7d3; ``OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1``; user + sys of the child)
-----------------------------------------------------------------------------------------------
``diagnose /tmp/perf87/lab``, main and this branch run side by side (each CPU time its own):

  run                               user     sys    max RSS
  main, under cProfile + time -v    58.9 s  142.0 s  5.86 GB   (audit87: 60.1 + 146.7 s)
  main (bench ``diagnose``)         55.0 s   83.1 s
  branch, time -v                   26.3 s    4.0 s  3.31 GB
  branch (bench ``diagnose``)       24.9 s    9.7 s
  then in turn: branch              21.0 s    9.4 s
                main                52.7 s   73.6 s

CPU 138.1 -> 34.6 s and 126.3 -> 30.4 s (the two bench pairs), system 83.1 -> 9.7 and 73.6 ->
9.4 s (the bar above was written after the branch's ``time -v`` run had been seen, before
the pairs).  Outputs of each pair: ``diagnosis.json``, the three ``diagnosis_<target>.json``,
the diagnosed model's and experiment's YAML, the headline files equal byte for byte
(OMP_NUM_THREADS=1) but for the ``seconds`` and the out folder's name in paths; accepted as
before: a first-order lag (tau 14400 s) of the inputs on E_dY (0.22 -> 0.20) and E_dZ (0.67 ->
0.20), none on E_dX.  ``flips 15840 3``: the same p-values
to the last bit, main 2.5 user + 8.5 sys s, branch 1.3 + 0.1; ``flips 15840 6``: main 5.2 +
7.5, branch 2.1 + 0.6.  A direct comparison of main's ``sign_flip_pvalues`` and
``sign_flip_maxt`` with the branch's at n = 3, 16, 17, 300, 5001, 15840 (seed 9176's gains):
``array_equal`` on each (tests/apps/test_sign_draw_perf87.py keeps the whole-matrix
reference at 41 units, blocks of 7 patterns, and the one draw).  The branch's max RSS, 3.3
GB, is the one draw's int64 indices (``choice``); drawing in blocks would lower it (not done).

Verdict: KEPT (bit-equal, system CPU 74-83 -> 9-10 s, total CPU / 4).  Export not mended (above).
"""
from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402
from cpu import cpu_seconds  # noqa: E402


def _user_sys(children: bool = False) -> tuple[float, float]:
    import resource
    u = resource.getrusage(resource.RUSAGE_CHILDREN if children else resource.RUSAGE_SELF)
    return u.ru_utime, u.ru_stime


def flips(units: str, calls: str) -> None:
    """``CALLS`` sign-flip tests over ``UNITS`` units (seed 9176's gains): p-values, user / sys."""
    from thermocomp.apps.diagnose.cv import sign_flip_pvalues

    rng = np.random.default_rng(9176)
    before, start = _user_sys(), cpu_seconds()
    for k in range(int(calls)):
        D = rng.standard_normal((2, int(units))) + 0.01 * k
        print(f"call {k}: p {sign_flip_pvalues(D).tolist()}", flush=True)
    after = _user_sys()
    print(f"{calls} calls over {units} units: user {after[0] - before[0]:.1f} s, sys "
          f"{after[1] - before[1]:.1f} s ({cpu_seconds() - start:.1f} s CPU)")


def diagnose(lab: str, out: str) -> None:
    """``thermocomp diagnose`` of the lab folder ``lab`` into ``out``: the child's user / sys."""
    conf = (Path(lab).resolve().parent / "conf").as_uri()
    before, wall = _user_sys(children=True), time.perf_counter()
    ran = subprocess.run([sys.executable, "-m", "thermocomp", "-q", "diagnose",
                          f"hydra.searchpath=[{conf}]", "data=lab", "track=false", "plots=none",
                          f"out={Path(out).resolve()}"], capture_output=True, text=True)
    after = _user_sys(children=True)
    print(f"exit {ran.returncode}; user {after[0] - before[0]:.1f} s, sys "
          f"{after[1] - before[1]:.1f} s, wall {time.perf_counter() - wall:.0f} s")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"flips": flips, "diagnose": diagnose}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
