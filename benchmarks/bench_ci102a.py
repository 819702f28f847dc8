"""CI time (issue 34; stop 102, ci102a): the export MONITOR modules' heaviest tests, and what they
compute beyond what their assertions read.

The group: tests/shell/test_export_{cmon8*,cmon9*,mon*,spike*,st9*,st100,bent93,step99,wires100,
freeze*,cdrop77,dep*,lead_perf87b,served99,quiet94c,monitor76}.py (45 modules, 168 s of CPU in
the fresh-clone CI of d85f1799: /work/notes/prof102/modules_cpu.txt).

Rule (candidates, tests only unless exact): a test computes no more than its assertions read: a
shorter stream where its fault is at row k, no planted copies or cold copy in a pack whose
summary it reads one entry of, a lead-in's state streamed once; a record simulated and fitted
once per process.  No key.

BAR (the brief's, written and committed here before any after-measurement):

1. every test id stays and passes; each assertion stays or is replaced by one at least as
   strong (``asserts``: no fewer ``assert`` statements per changed module; each replaced one
   listed in the report); a test whose subject is shrunk still holds it (the planted fault, the
   effect, the rule's trigger) and its docstring says what the smaller data holds; a ``full``
   mark only where a named CI test covers it end to end (reported apart, seconds moved);
2. the changed modules' summed pytest CPU (user + sys incl. children of ``/usr/bin/time nice
   pytest -q -n 0 -p no:cacheprovider -m "not full"``, each module alone; base tree = ``git
   archive d85f1799`` into /tmp/ci102a/base) down >= 30 %, base and after paired (started
   together); one rep for the whole set, a 2nd rep for the modules changed most if time allows;
3. every changed test fails on a planted break of what it checks (``plant``: one per changed
   test, or per changed fixture for many small ones); src changes only where exact (the same
   outputs to the bit on the module's inputs, shown) and measured.

No seeds: nothing is scored.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci102a.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci102a.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci102a.py asserts BASE SPEC...           # bench_ci101c's asserts
    python benchmarks/bench_ci102a.py plant TREE FILE OLD NEW SPEC   # bench_ci101c's plant
    python benchmarks/bench_ci102a.py parts SEED [FEATURE]           # a long record's parts

Rule built (tests only; REFUSED, saved as benchmarks/ci102a_rule.patch, which applies to d85f1799;
the five modules are back to d85f1799 on the branch): test_export_cmon87's ``long_record`` /
``deployed_mlr`` take ``lead_rows`` (default None: R1a whole, as before), R1b's lead-in cut to its
last rows; cmon87, cmon88, cmon89, cmon92b and cmon93 pass ``LEAD_ROWS = 864`` (R1b's length; R1a
is 3457 of the 4321 fed rows).  Each subject at the same R1b rows with 864 and with 3457 lead-in
rows (lr9032's spike ``T_table`` out 397 / back 408; lr9126's second ``T_bed_left`` 820 / 821;
lr9132 frozen pair: the rule not in the code beside ``T_table``'s exclusion at 443); cmon89's and
cmon93's rows are R1b's (``lead + ...``) and their tests pass.  No assertion touched.

Trace (``parts 9032``, base's lead-in, CPU s in one process, load ~12): record 1.21, served stream
of the fed campaign 0.81, mirror (ss) 1.46, mirror without blind_jump 1.32, pack (ss, its served
copies first) 3.79, pack without blind_jump 2.32, the pack's stepping of R1b alone 1.26: the
pack's planted and cold copies are ~1 s of the "export before" test's pack; the lead-in 80 % of
every per-row stream.

Measured (2026-12-06 21:56-22:17, base = git archive of d85f1799, after = 480f2956; paired: base
and after started together, 2 reps, ``cpu``'s command line; CPU s user + sys incl. children;
load 11-16)::

  module                  rep 1           rep 2           mean
  test_export_cmon87      15.88 -> 11.02  15.04 ->  9.77  15.5 -> 10.4  -32.8 %
  test_export_cmon93      19.12 -> 10.62  15.89 -> 10.41  17.5 -> 10.5  -39.9 %
  test_export_cmon89      19.27 -> 14.19  16.43 -> 11.30  17.9 -> 12.7  -28.6 %
  test_export_cmon88      15.26 -> 13.66  13.81 -> 11.53  14.5 -> 12.6  -13.3 %
  test_export_cmon92b      8.26 ->  6.78   7.85 ->  5.72   8.1 ->  6.2  -22.4 %
  sum                     77.8 -> 56.3    69.0 -> 48.7    73.4 -> 52.5  -28.5 %

Against the bar: (1) kept: ``asserts`` 12/6/7/6/4, tests 2/2/2/2/1 on both sides, no assertion
edited, the same 9 tests pass; docstrings say what the cut lead-in holds.  (2) NOT met: -28.5 % of
the five modules' CPU (-27.7 % rep 1, -29.4 % rep 2) against >= 30 %.  (3) met, 9 plants (one per
changed test, on 480f2956's copy), each failed its test: watch.py ``spikes`` without blind_jump ->
cmon87's held test; pack.py ``_parted``'s cut row + 1 -> each "export before" test (cmon87, 88,
89, 93); watch.py ``seconds`` without JUMP -> cmon88's held test; ``pair_jump`` branch off ->
cmon93's held test; ``instant`` False -> cmon89's held test; watch_c.py ``mon_missed`` never set
-> cmon92b's test.  Bench CPU: 252 s of paired pytest runs, 9 plants (35-99 s wall each),
parts 13.9 s.

Why short: the lead-in's cut removes 60 % of the fed rows, but a module also pays pytest's start
and imports (~2-3 s), the record (simulate + fit, 1.2 s), the C build and the pack's planted and
cold copies of R1b (unchanged); cmon88's cut was -10 % and -17 % in the two reps (the load).

``parts``: in this process, the CPU of each computation a long-record module makes
(test_export_cmon87's ``long_record`` of SEED; FEATURE: the monitor key its "export before" test
drops, default ``blind_jump``): the record (simulate + fit + deploy), the served stream of the
fed test campaign, the numpy mirror over it (``ss``, then without FEATURE), the conformance pack
(``ss``: its served copies first; then without FEATURE), and the pack's own stepping of the
campaign alone (``_parted`` on its fed rows: what a pack without planted or cold copies steps).
"""
from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402
from bench_ci100b import cpu, table  # noqa: E402
from bench_ci101c import asserts, plant  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


class _Folders:
    """``tmp_path_factory``'s ``mktemp`` for the tests' record builders, outside pytest."""

    def __init__(self, root: str):
        self.root = root

    def mktemp(self, name: str) -> Path:
        return Path(tempfile.mkdtemp(prefix=name, dir=self.root))


def parts(seed: str, feature: str = "blind_jump") -> None:
    """CPU s of each part of a long-record module's computations (module doc)."""
    sys.path[:0] = [str(ROOT / "tests"), str(ROOT / "tests" / "shell")]
    from test_export_cmon85 import _mirror, without
    from test_export_cmon87 import long_record
    from thermocomp.apps.deploy.export.pack import _parted, conformance_pack, corrections
    from thermocomp.apps.deploy.export.served import ServedStreams

    def timed(what: str, run):
        start = time.process_time()
        out = run()
        print(f"{what:55s} {time.process_time() - start:6.2f} s", flush=True)
        return out

    with tempfile.TemporaryDirectory(prefix="ci102a-parts-") as root:
        record = timed(f"record lr{seed} (simulate, fit, deploy)",
                       lambda: long_record(_Folders(root), int(seed)))
        deployed, ss, frame, lead, tests, leads = record
        print(f"fed rows {len(frame)}, of them the lead-in {lead}")
        streams = ServedStreams(deployed)
        y = timed("served stream of the fed campaign", lambda: streams.rows(frame, "R1b").y)
        old = without(ss, feature)
        timed("mirror (ss) over the fed campaign", lambda: _mirror(ss, frame))
        timed(f"mirror (without {feature})", lambda: _mirror(old, frame))
        _, summary = timed("pack (ss), its served copies streamed first",
                           lambda: conformance_pack(deployed, ss, tests, leads, served=streams))
        print("pack entries:", [(e["campaign"], e["rows"]) for e in summary["campaigns"]])
        timed(f"pack (without {feature})",
              lambda: conformance_pack(deployed, old, tests, leads, served=streams))
        timed(f"the pack's stepping of the campaign alone (without {feature})",
              lambda: _parted(old, frame, corrections(ss, y)))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cpu": cpu, "table": table, "asserts": asserts, "plant": plant,
                                  "parts": parts}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
