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
