"""A temperature header's note in brackets, and auto's skipped ``ati`` said in the log (notes100,
issue 34; follow-up of ``bench_audit100.py``'s cell L).

RULE (``core/io/units.bracket_reading``, read by ``core/io/roles.naming``; no key): a header read
as a temperature (or an ambient) whose brackets hold no unit -- no known unit, none written as
one (``m/s``, ``W/m^2``, ``unitless``: today's foreign unit), a word of three or more letters
(``T1 (front)``, ``Spindel (Gehäuse)``) -- is named with its bracket (``T_T1_front``), no unit
(°C, the contract's), said once a run at INFO.  A temperature's unit beside a word
(``(K Kühlung)``) or a token of one or two letters that is no unit (``(R)``) is refused naming
file, column and both readings (``data.units`` / ``data.columns``), with a config file's lines
and how to pass it (``base.errors.config_file_form``: the hint for a map's key Hydra's grammar
cannot read said to use the config ``init`` writes, which a refused ``init`` never wrote).
``model=auto``: a candidate that does not apply (``ati``: no T_amb, fewer than 3 ambient levels)
is said in the log, ``auto: ati skipped: <why>``, once a run (``core/models/auto.py``).

BAR (written and committed before the rule's runs below; main's numbers are seen):
B1. ``init /tmp/audit100/hand/b.csv`` exits 0 (main: 2) with ``T1 (front)`` -> ``T_T1_front``,
    ``Spindel (Gehäuse)`` -> ``T_Spindel_Gehäuse`` (temperatures), each said once in stderr.
B2. ``amb.csv`` (b.csv's headers as ``T1 (R)``, ``Spindel (K Kühlung)``): exit 2, one message
    naming the file, both columns, "a unit the reader does not know or as a note", ``data.units``,
    ``data.columns`` and ``hydra.searchpath``.
B3. Every other column reads the same: init's proposal table of ``excel.csv`` (audit100's lab
    9921, seen; and a fresh one written by bench_audit100.write_excel with seed 10001, scored
    once) and of b.csv's other columns identical main -> rule, line for line.
B4. ``run model=auto`` on b.csv's config says ``auto: ati skipped:`` once in stderr (main: 0).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_notes100.py init ROOT FILE...       # -> ROOT/init.json
    python benchmarks/bench_notes100.py compare MAIN_ROOT RULE_ROOT
    python benchmarks/bench_notes100.py auto ROOT CONF_DIR      # data=b from CONF_DIR/data/b.yaml

``init``: ``thermocomp init FILE out=ROOT/<stem>`` per file: exit code, its proposal table (the
lines of two spaces), stderr's lines.  ``compare``: B1-B3 from the two ``init.json``.

MEASURED (2026-12-06, 2 cores shared by up to 8 helpers; main = fb0ed988's src and conf):
B1 b.csv exit 2 -> 0, 'T1 (front)' -> T_T1_front, 'Spindel (Gehäuse)' -> T_Spindel_Gehäuse, each
   said once (2 lines). B2 amb.csv exit 2 -> 2, one message: both columns, both readings, the
   keys and a config file's lines with hydra.searchpath (main: "unit 'R' is not a temperature's").
B3 excel.csv (9921, seen; 10001, fresh, scored once) needs data.timezone=Europe/Berlin (audit100's
   second try) and an empty column left out, data.roles.ignore=[Reserve] (main refused it with the
   bracket, "unit 'leer'"; now as "every cell is empty", after the note is said: a wrong note
   before a right refusal); main also needs 'Motor Spindel' ignored (its bracket, Gehäuse): 19 of
   19 of main's table lines identical in both files, the one new line the bracket's column,
   'Motor Spindel (Gehäuse)' temperature T_Motor_Spindel_Gehäuse (main: ignore).
B4 run model=auto on b.csv: 'auto: ati skipped: no campaign ambient (a T_amb sensor) ...' 0 -> 1
   line in stderr (main run with units {'T1 (front)': °C, ...} in its data config).
Bar met (run details above are the execution, the clauses unchanged): KEPT.  Wall: init ~4 s a
file, auto on b.csv ~12 s.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402


def _thermocomp(*args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    return subprocess.run([sys.executable, "-m", "thermocomp", *args], capture_output=True,
                          text=True, env=env)


def init(root: str, *files: str) -> None:
    """``thermocomp init`` of each file -> ``ROOT/init.json`` (exit code, table, stderr); an
    argument with ``=`` is an override given to every file's (``data.timezone=Europe/Berlin``,
    excel.csv's second try in audit100)."""
    out = {}
    given = [f for f in files if "=" in f]
    for f in (f for f in files if "=" not in f):
        done = _thermocomp("init", f, f"out={Path(root) / Path(f).stem}", *given)
        table = [ln for ln in done.stdout.splitlines() if ln.startswith("  ")]
        out[f] = {"rc": done.returncode, "table": table, "stderr": done.stderr.splitlines()}
        print(f"{f}: exit {done.returncode}, {len(table)} columns; "
              f"{[ln for ln in done.stderr.splitlines() if 'bracket' in ln or 'error' in ln]}")
    Path(root).mkdir(parents=True, exist_ok=True)
    (Path(root) / "init.json").write_text(json.dumps(out, indent=1, ensure_ascii=False))


def compare(main_root: str, rule_root: str) -> None:
    """B1-B3 from MAIN_ROOT's and RULE_ROOT's ``init.json``."""
    main, rule = (json.loads((Path(r) / "init.json").read_text()) for r in (main_root, rule_root))
    for f in rule:
        a, b = main.get(f, {"rc": None, "table": []}), rule[f]
        notes = [ln for ln in b["stderr"] if "bracket read as part of the name" in ln]
        same = [ln for ln in b["table"] if ln in a["table"]]
        differ = [ln for ln in b["table"] if ln not in a["table"]]
        refused = next((ln for ln in b["stderr"] if "error:" in ln), "")
        print(f"{Path(f).name}: exit {a['rc']} -> {b['rc']}; lines same {len(same)}, new "
              f"{differ}; lost {[ln for ln in a['table'] if ln not in b['table']]}; "
              f"notes said {len(notes)}: {notes}")
        if refused:
            print(f"  refused: {refused[:400]}")


def auto(root: str, conf_dir: str) -> None:
    """B4: ``run model=auto`` of ``data=b`` from CONF_DIR; the lines saying ati was skipped."""
    done = _thermocomp("run", f"hydra.searchpath=[file://{Path(conf_dir).resolve()}]", "data=b",
                       f"out={Path(root) / 'auto'}", "model=auto", "track=false")
    said = [ln for ln in done.stderr.splitlines() if "ati skipped" in ln]
    print(f"auto on b: exit {done.returncode}; stderr lines saying ati skipped: {len(said)} {said}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"init": init, "compare": compare, "auto": auto}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
