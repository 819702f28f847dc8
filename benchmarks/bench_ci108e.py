"""CI time (issue 34; stop 108, ci108e): conformance_pack's and the mirror's CPU, same output.

The py-spy profile of the whole suite (1983 s CPU) puts 4.5 % in ``conformance_pack``: 52 % of it
the mirror (``_parted``: ``Simulator.step``, ``CodeMonitor.step``), 31 % the served model's
streams (``ServedStreams.y``), 6.5 % CSV text.  Prefix sharing (ci101) is in; per-row trims of
the served and mirror loops were refused at -2.6 % mirror (ci101b).

Fixtures (``build``): cmon87's record (lr9032, R1b after its last 864 lead-in rows: 4 planted
copies from row 433 and a cold copy; 4320 mirror steps a pack) and cmon85's column machine (seed
8841) with and without the dropout fault (no lead-in; 5 and 4 copies from row 721), each packed as
its module packs it (``deployed, ss, {campaign: frame}, lead-ins``). ``run`` packs each fixture
three times on one ``ServedStreams``: call 0 fresh (a user's ``export``), calls 1-2 with its
served streams cached (the tests: a module fixture's streams); and steps the ``Simulator`` over
the fixture's fed frame from a reset.

BAR (written and committed before any measurement of a change; no seeds, the rule is exact):
(1) every pack file (md5 of the sorted ``path + text`` of the returned files, check.json in it)
    the same as base's (a1addf5a) on the 3 fixtures, every call;
(2) the mirror the same to the last bit: md5 over rows of the corrections' bytes, ``flag_row``
    and ``refused`` equal to base's on the 3 fixtures;
(3) ``conformance_pack`` CPU (``time.process_time``, calls 0 + 1 summed over the 3 fixtures) down
    >= 30 % from base, base and change run one after the other, in each of 2 repetitions;
(4) the export / cmon / mon / st modules that reach the changed code pass.
Any clause not met: REFUSED (src reverted, the rule kept as benchmarks/ci108e_rule.patch).

Usage (``PYTHONPATH=<tree>/src``, from anywhere; ``TREE`` the checkout whose tests/ build the
fixtures)::

    python benchmarks/bench_ci108e.py build PICKLE      # the 3 fixtures, pickled
    python benchmarks/bench_ci108e.py run PICKLE        # pack CPU + md5s, mirror md5

Measured (2026-12-07 15:21-15:27, base a1addf5a = the ``src`` of ``git archive``, load 1.6-3;
``run`` once, CPU s by ``time.process_time``; splits by process_time wrappers on pack's module
attributes and on ``CodeMonitor.step``/``refuses``/``serving``, scripts in the report)::

  fixture           call 0  call 1  (call 2)  mirror of the fed frame from a reset
  lr9032             2.62    1.64    1.72     1728 rows 0.63 s   404 us/row, monitor 69 %
  col8841            4.55    2.24    2.21     1441 rows 0.52 s   431 us/row, monitor 67 %
  col8841_dropout    4.19    2.13    2.20     1441 rows 0.56 s   487 us/row, monitor 70 %
  calls 0 + 1, the 3 fixtures: 17.38 s
  split, a second run (its totals 3.02/1.90, 5.43/2.71, 4.54/2.15), call 0 / call 1: mirror
  (``_parted``, the ``_Lead``'s too) 1.67/1.72, 2.41/2.42, 2.15/1.93; served from a prefix 0.63/0,
  2.54/0, 1.97/0; served prefix 0.32, 0.17, 0.16 / 0; whole served stream 0.22, 0, 0; csv_text
  0.10/0.09, 0.20/0.19, 0.17/0.14; deepcopy <= 0.03.

No change was made (TRACED): no work is done twice inside a pack any more (ci101 shares the
copies' prefix and the lead-in; the cold copy starts from a reset), the mirror is 62 % of calls
0 + 1 and its monitor 67-70 % of each mirror row, spread over some thirty methods (cProfile of lr9032's
call 1: ``CodeMonitor._step``'s own lines 15 % of ``Simulator.step``, no other method above 8 %;
32 numpy reductions a row).  The bar's -30 % needs the mirror's row ~48 % cheaper (the linear part alone,
~130 us of ~430, cannot give it), i.e. the monitor's row about half its cost, to the last bit:
per-row trims gave -2.6 % (ci101b).  Not attempted in this stop's time.
"""
from __future__ import annotations

import hashlib
import os
import pickle
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402

TREE = Path(os.environ.get("TREE", Path(__file__).resolve().parents[1]))


class _Temp:
    """A ``tmp_path_factory`` for the tests' fixture builders."""

    def __init__(self, root: Path):
        self.root, self.k = root, 0

    def mktemp(self, name: str) -> Path:
        self.k += 1
        path = self.root / f"{name}{self.k}"
        path.mkdir(parents=True, exist_ok=True)
        return path


def build(out: str) -> None:
    """The fixtures (module doc) pickled to ``out`` (their data beside it)."""
    sys.path[:0] = [str(TREE / "tests"), str(TREE / "tests" / "shell")]
    import test_export_cmon85 as m85
    import test_export_cmon87 as m87

    temp = _Temp(Path(out).resolve().parent / "ci108e_data")
    records = {"lr9032": m87.long_record(temp, 9032, m87.LEAD_ROWS)}
    deployed, ss, frame = m85.column_system(temp)
    records["col8841"] = (deployed, ss, frame, 0, {"test": frame}, {})
    deployed, ss, frame = m85.column_record(temp, "dropout")
    records["col8841_dropout"] = (deployed, ss, frame, 0, {"test": frame}, {})
    Path(out).write_bytes(pickle.dumps(records))


def run(pickled: str) -> None:
    """Each fixture packed 3 times (CPU, md5) and mirrored from a reset (md5 of every row)."""
    from thermocomp.apps.deploy.export.pack import conformance_pack
    from thermocomp.apps.deploy.export.served import ServedStreams
    from thermocomp.apps.deploy.export.statespace import Simulator
    from thermocomp.apps.deploy.export.watch import flag_row
    from thermocomp.core.io.contract import manifest_ambient

    total = 0.0
    for name, (deployed, ss, frame, _, tests, leads) in pickle.loads(Path(pickled).read_bytes()).items():
        streams = ServedStreams(deployed)
        for call in range(3):
            start = time.process_time()
            files, _ = conformance_pack(deployed, ss, tests, leads, served=streams)
            spent = time.process_time() - start
            total += spent if call < 2 else 0.0
            digest = hashlib.md5("".join(f"{k}\n{files[k]}" for k in sorted(files)).encode())
            print(f"{name} pack call {call} cpu {spent:.3f} files {len(files)} md5 {digest.hexdigest()}")
        sim = Simulator(ss)
        sim.reset(manifest_ambient(frame))
        U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
        names = [ss.inputs[k] for k in ss.monitor.get("inputs", [])]
        digest, start = hashlib.md5(), time.process_time()
        for i in range(len(frame)):
            digest.update(sim.step(U[i], t[i]).tobytes())
            digest.update(f"{flag_row(sim.watch, names)} {sim.refused}".encode())
        print(f"{name} mirror rows {len(frame)} cpu {time.process_time() - start:.3f} "
              f"md5 {digest.hexdigest()}")
    print(f"pack cpu calls 0+1, 3 fixtures: {total:.3f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"build": build, "run": run}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
