"""CI time (issue 34; stop 100, ci100c): Hydra's per-command work in thermocomp's own entry.

ci100b traced test_hostile's 184 in-process commands: Hydra's ``run_job`` deep-copies the composed
config twice (the task's, the Hydra config's) and calls ``HydraConfig.set_config`` twice a run.

Rule (src/thermocomp/shell/job.py, called by cli._run_job; no key, always on for a run; a sweep
``-m`` and Hydra's flags go through ``hydra.main`` as before): Hydra 1.3's ``run_job`` for a run,
the task on the composed config itself (its ``hydra`` node out for the task's time), the Hydra
config not copied for ``JobReturn.hydra_cfg``, one ``set_config`` (the run folder set on the Hydra
config in place of the second).  Not built: a compose cache in src keyed on (conf content,
overrides): the suite already caches the composition per (conf, root, group overrides)
(tests/hydra_cache.py) and an in-process test rarely repeats a command's whole overrides (its
paths are its own), so a whole-result cache would hit in no test.

BAR (the brief's; written and committed here before any after-measurement of the modules):
(1) test_hostile + test_hostile_numeric + test_hostile_units + the 19 test_stranger*.py modules +
    test_calibrate (tests/shell/): summed CPU (user + sys incl. children; each module alone,
    ``-n 0``, ``nice``, base 063630e6 and after paired back to back, same load, 2 repetitions)
    down >= 15 %;
(2) tests/shell/test_cli*.py, test_sweep*.py, test_tracking.py, test_config*.py pass on the rule;
(3) outputs identical (but time stamps) on the command set (``same``): run, run refused, sweep -m,
    compare, promote, replay, monitor, export, init: stdout, stderr, exit status, every file
    written under the run's folders.
KEPT below 15 % only if >= 8 % and (2) + (3) exact.  No seeds: the rule changes no number.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci100c.py cpu TREE TAG OUT SPEC...   # bench_ci100b's: each spec alone
    python benchmarks/bench_ci100c.py table OUT [BEFORE AFTER BAR] # per spec, the sum, the bar
    python benchmarks/bench_ci100c.py same TREE OUT              # the command set in TREE: OUT/
    python benchmarks/bench_ci100c.py command [REPEAT]           # bench_ci100b's small commands

``same`` runs the command set as processes (``python -m thermocomp``) in a fresh folder OUT/work
(the project root: TREE's conf/ copied there, its data simulated there), and writes OUT/outputs.txt: each
command's exit status, stdout, stderr and every file under OUT/work (path, size, sha256 of text
with the time stamps and OUT's own path replaced); ``diff`` two of them.

Measured: see the end of this docstring (filled in after the measurement).
"""
from __future__ import annotations

import hashlib
import os
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import made_folder, run_commands  # noqa: E402
from bench_ci100b import THREADS, command, cpu, table  # noqa: E402

STAMP = re.compile(rb"\d{4}-\d\d-\d\d[ T_]\d\d[:-]\d\d[:-]\d\d(?:[.,]\d+)?|\b\d{10}(?:\.\d+)?\b"
                   rb"|\b\d+\.\d+ ?s\b|[0-9a-f]{32}")

SHORT = ["sim.generator.n_campaigns=9", "sim.generator.duration_h=[2.0,3.0]"]
LIGHT = ["plots=none", "eval.mutual_prediction=false", "eval.ati_baselines=false",
         "eval.iso10791_a3=false"]
DATA = "data.path=data/raw/s"
COMMANDS = [
    ["simulate", DATA, *SHORT],
    ["run", DATA, "out=reports/r", "model_path=models/r.pkl", *LIGHT],
    ["run", DATA, "out=reports/bad", "data.resample_s=-1", *LIGHT],
    ["run", "-m", DATA, "model=mlr,pcr", "hydra.sweep.dir=sweeps/a", *LIGHT],
    ["compare", "compare.sweep=sweeps/a"],
    ["promote", DATA, "out=reports/p"],
    ["replay", DATA, "model_path=models/r.pkl", "out=reports/rp"],
    ["monitor", DATA, "model_path=models/r.pkl", "out=reports/mo"],
    ["export", "export.model=models/r.pkl", "out=exports/c"],
    ["init", "data/raw/s"],
]


def _text(data: bytes, work: Path) -> bytes:
    return STAMP.sub(b"<t>", data.replace(str(work).encode(), b"<work>"))


def same(tree: str, out: str) -> None:
    """The command set run in ``tree`` (processes), in OUT/work: OUT/outputs.txt."""
    folder, tree = made_folder(out), Path(tree).resolve()
    work = folder / "work"
    subprocess.run(["rm", "-rf", str(work)], check=True)
    work.mkdir()
    subprocess.run(["cp", "-r", str(tree / "conf"), str(work / "conf")], check=True)
    env = {**os.environ, **THREADS, "PYTHONPATH": str(tree / "src"), "THERMOCOMP_ROOT": str(work)}
    lines = []
    for args in COMMANDS:
        run = subprocess.run([sys.executable, "-m", "thermocomp", *args], cwd=work, env=env,
                             capture_output=True)
        lines += [f"$ thermocomp {' '.join(args)}: exit {run.returncode}",
                  "stdout: " + _text(run.stdout, work).decode(errors="replace"),
                  "stderr: " + _text(run.stderr, work).decode(errors="replace")]
    for file in sorted(p for p in work.rglob("*") if p.is_file() and "conf" != p.relative_to(work).parts[0]):
        data = file.read_bytes()
        lines.append(f"{file.relative_to(work)} {hashlib.sha256(_text(data, work)).hexdigest()[:16]}")
    (folder / "outputs.txt").write_text("\n".join(lines) + "\n")
    print(f"{len(COMMANDS)} commands, {len(lines) - 3 * len(COMMANDS)} files: {folder / 'outputs.txt'}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cpu": cpu, "table": table, "same": same, "command": command},
                        argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
