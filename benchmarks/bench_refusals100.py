"""A lab file's independent refusals gathered into one message (refusals100, issue 34; audit100's
finding 2: excel.csv took three tries, its refusals coming one at a time).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_refusals100.py tries ROOT SEED LABEL [fresh]   # -> ROOT/LABEL.json
    python benchmarks/bench_refusals100.py compare MAIN.json RULE.json     # R1 / R3

``tries`` (R1 with SEED 9921, the seen file; R3 with 9946 and ``fresh``): the lab file under
``ROOT/lab<SEED>`` (bench_audit91's ``lab_root``): bench_audit100's
:func:`~bench_audit100.write_excel` (BOM, ``sep=;``, local stamps over 2026-10-25's repeated
hour, umlauts, ``KW`` text, the empty ``Reserve (leer)``), or with ``fresh`` :func:`fresh_file`:
the same and a new mix of faults chosen before it was made (a second empty column ``Reserve
2``, a flux sensor ``Sonne (W/m^2)``, no sensor of the model).  ``init`` with no key; where the
refusal gives one command line with every key, that line run as written (``sh -c``, ``thermocomp``
= this tree's module); else the keys each refusal names, a try each (bench_audit100's
:func:`~bench_audit100._init_tries`, main's way); then ``run`` per family (mlr, lagbank) on the
config written.  Run once with main's src on PYTHONPATH, once with the rule's, into two ROOTs;
``compare``: the tries, the config written and its column table, every test figure.

On main (063630e6, after notes100: ``Motor Spindel (Gehäuse)`` is read as a temperature) excel.csv
takes 3 tries: the clock (``data.timezone``, column 'time', data row 781), then the empty
``Reserve (leer)`` (``data.roles.ignore=['Reserve']``), then exit 0.

BAR (written and committed BEFORE seed 9946 was made or any rule measured; the brief's):
R1. excel.csv 9921 (seen) in ONE try: ``init`` with no key exits 2 with one message that names
    every key main's tries needed (``data.timezone=Europe/Berlin`` with column 'time' and row 781,
    ``data.roles.ignore`` with ``Reserve``), each with file, column (row where one is at fault),
    and ONE suggested command line with all keys together; that line, run as written, exits 0
    and writes the same data config as main's last try (the column table and the yaml equal);
    ``run`` mlr / lagbank on it: every test figure = main's 3-try config's to 1e-9 µm (audit100's
    digits were with ``Motor Spindel`` left out, which notes100 since reads; said, not scored).
R2. Every existing refusal test still passes: the test files under tests/core and tests/shell that
    match 'error:' and touch init / core.io (listed with their counts where run), and
    tests/test_lint.py, tests/test_benchmarks_cli.py.
R3. Fresh lab file seed 9946 (the faults above), scored ONCE: ``init`` with no key exits 2 with
    one message naming all its faults' keys; its suggested line run as written exits 0.
R4. A refusal another makes moot stays alone (no time column at all, a file without rows): said
    as main says it.  A test that fails on 063630e6 (< 3 s).
KEPT only if R1-R4 hold; else REFUSED (benchmarks/refusals100_rule.patch, src reverted).

The rule (``src/thermocomp/shell/stages/gathered.py``, called by ``init`` on a ContractError; no
key): where a refusal names ``key=value`` settings of :data:`~thermocomp.shell.stages.gathered.
FOLLOWED` only (``data.timezone``, ``data.roles.ignore``, ``data.thousands``, ``data.dayfirst``),
one value per key, ``init`` reads again with them set (stdout and warnings held, nothing
written), up to 6 reads; the refusals met come as one ContractError (exit 2), each as the reader
words it, then ``all the keys together, with which it reads the file: thermocomp init ...``.

Scored (2026-12-06 16:37-16:46 UTC, 2 cores shared, load 9-15, ``nice``; main = 063630e6's src
by ``git archive``, the rule = e42bfa86; bar 9bfce9f5 unchanged; harness commits 227ba50d, a245e756
made no rule change)::

  R1 seen 9921 (excel.csv = audit100's, byte for byte): main 3 tries (the clock, data row 781;
     then 'Reserve (leer)' empty; then exit 0); rule 1 refusal "2 refusals of the file at once"
     naming data.timezone=Europe/Berlin (column 'time', line 783, data row 781) and
     data.roles.ignore=['Reserve'] (column 'T_Reserve_leer', header 'Reserve (leer)'), its line
     run as written exit 0; config yaml and column table = main's; test RMSE (µm) main = rule:
     mlr E_Weg_X / E_Weg_Y 1.63843805040023 / 1.0991101012111855,
     lagbank 1.245220296341389 / 0.9257184075440478 (max |d| 0).  audit100's digits are with
     ``Motor Spindel`` left out and data.test_fraction=0.25: by hand with those (and the
     follow-up patch below) mlr 1.693987262 / 1.119769191, lagbank 1.290917637 / 0.952003398 =
     audit100's.  init wall: rule 44.3 s (refusal + line), main 100.2 s (the harness's 4 inits).
  R2 the 83 test functions (94 cases, 42 files) that run ``init`` and assert a refusal (exit 2,
     ``refused(``, returncode) in the 57 files grep names: 94 passed; the 498-case run of those
     57 files whole, stopped for time at 346 of 498 cases: 345 passed, 1 failed
     (test_stranger76::test_the_export_piped_into_monitor_streams_as_the_file_is_read, under
     load 15-17; its file again on the head: 5 passed); lint + benchmarks_cli + docs +
     test_refusals100: 802 passed.
  R3 fresh 9946 (scored once): main 3 tries (the clock; then both empty columns in one
     refusal; then exit 0); rule 1 refusal naming data.timezone=Europe/Berlin and
     data.roles.ignore=['Reserve', 'Reserve 2'], its line exit 0; yaml / table = main's; mlr
     1.4693150687234786 / 0.9982564205805173, lagbank 1.285259242984651 / 0.7927116885488036
     µm, main = rule.  The flux sensor ``Sonne (W/m^2)`` was no refusal on main either (init
     leaves it out, said): the bar's guess that the naming refuses it was wrong; not a fault.
  R4 a file without a time column (``notime.csv``): the same one-line refusal as main
     (``set data.sample_period_s``); a file with no rows: alone (test).  test_refusals100: 2 cases,
     the first fails on 063630e6 (the clock alone); both cases 2.94 s of CPU (collection
     included), the first 5.4-12 s wall under load 9-17: < 3 s met on CPU, not on wall here.

Found after the fresh run (not on the fresh data): a key the user gave (``init excel.csv
'data.roles.ignore=[Motor Spindel]'``) is dropped from the suggested line where a refusal names
the same list key (the line read ``data.roles.ignore=['Reserve']``: Motor Spindel read again).
The reads themselves had it.  Fix + a test failing on the head: benchmarks/refusals100_followup.patch
(the line then ``"data.roles.ignore=['Motor Spindel','Reserve']"``): NOT applied (rule frozen
after the fresh score); the lead's call.

VERDICT: KEPT on the bar as worded (R1, R3, R4 met; R2 met on the refusal tests run), with the
follow-up above; the test's 3 s clause met on CPU (2.94 s), not on wall under load 9-17.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests")]
from _cli import run_commands  # noqa: E402

FAMILIES = ("mlr", "lagbank")
LINE = re.compile(r"all the keys together[^:]*: (thermocomp init .*)$")


def fresh_file(base: Path, seed: int) -> None:
    """``excel.csv`` (bench_audit100's :func:`~bench_audit100.write_excel`) with the fresh mix
    (module doc): a second empty column and a flux sensor in W/m^2 appended."""
    import numpy as np
    from bench_audit100 import write_excel

    write_excel(base, seed)
    lines = (base / "excel.csv").read_bytes().decode("utf-8").split("\r\n")
    flux = np.abs(np.sin(np.arange(len(lines)) / 240.0)) * 610.0
    out = [*lines[:1], lines[1] + ";Reserve 2;Sonne (W/m^2)",
           *(f"{ln};;{flux[i]:.1f}".replace(".", ",") for i, ln in enumerate(lines[2:]) if ln), ""]
    (base / "excel.csv").write_bytes("\r\n".join(out).encode("utf-8"))
    print(f"fresh {base / 'excel.csv'}: header {out[1]!r}", flush=True)


def _shim(root: Path) -> dict:
    """The environment a suggested line runs in: ``thermocomp`` = this interpreter's module
    (the tree on PYTHONPATH)."""
    bin_ = root / "bin"
    bin_.mkdir(parents=True, exist_ok=True)
    (bin_ / "thermocomp").write_text(f'#!/bin/sh\nexec {sys.executable} -m thermocomp "$@"\n')
    (bin_ / "thermocomp").chmod(0o755)
    return {**os.environ, "PATH": f"{bin_}:{os.environ['PATH']}", "OMP_NUM_THREADS": "1",
            "OPENBLAS_NUM_THREADS": "1"}


def tries(root: str, seed: str, label: str, fresh: str = "") -> None:
    """``init`` of the lab file as a user does: no key, then the one suggested line where the
    refusal gives one (run as written), else the keys each refusal names (bench_audit100's
    :func:`~bench_audit100._init_tries`); ``run`` per family on the config; ``ROOT/LABEL.json``."""
    import bench_audit91
    from bench_audit97 import _cli
    from bench_audit100 import _init_tries, write_excel
    from bench_data88 import _refusal

    base = bench_audit91.lab_root(root, seed)
    if not (base / "excel.csv").exists():
        fresh_file(base, int(seed)) if fresh else write_excel(base, int(seed))
    path, init = base / "excel.csv", base / "excel-init"
    out: dict = {"tree": os.environ.get("PYTHONPATH"), "tries": []}
    t0 = time.time()
    done = _cli("init", str(path), f"out={init}")
    out["tries"].append({"keys": [], "exit": done.returncode,
                         "said": _refusal(done) if done.returncode else ""})
    line = next((m.group(1) for m in map(LINE.search, done.stderr.splitlines()) if m), None)
    if done.returncode and line:
        ran = subprocess.run(["sh", "-c", line], capture_output=True, text=True, env=_shim(Path(root)),
                             cwd=base)
        out["tries"].append({"line": line, "exit": ran.returncode, "said": ran.stderr.strip()[-600:]})
        ok = ran.returncode == 0
        out["table"] = [ln for ln in ran.stdout.splitlines() if ln.startswith("  ")]
    elif done.returncode:
        got, keys = _init_tries(base, path)
        out["tries"].append({"keys": keys, "exit": 0 if got else 2})
        ok = got is not None
        rerun = _cli("init", str(path), f"out={init}", *keys) if ok else None
        out["table"] = [ln for ln in rerun.stdout.splitlines() if ln.startswith("  ")] if ok else []
    else:
        ok = True
    out["init_s"] = round(time.time() - t0, 1)
    if ok:
        out["yaml"] = next((init / "conf" / "data").glob("*.yaml")).read_text()
        search = [f"hydra.searchpath=[file://{init / 'conf'}]", "data=excel"]
        for family in FAMILIES:
            run_out = base / f"{label}-{family}"
            done = _cli("run", *search, f"model={family}", f"out={run_out}", "track=false", "plots=none")
            out[family] = ({t: v["test"]["rmse"] for t, v in json.loads(
                (run_out / "metrics.json").read_text())["targets"].items()}
                if not done.returncode else _refusal(done))
    (Path(root) / f"{label}.json").write_text(json.dumps(out, indent=1, ensure_ascii=False))
    print(json.dumps({k: v for k, v in out.items() if k not in ("yaml", "table")}, indent=1,
                     ensure_ascii=False), flush=True)


def compare(main_json: str, rule_json: str) -> None:
    """R1 / R3: main's tries against the rule's: tries, the config and table, every figure."""
    # (each run's paths under its own ROOT: compared with ROOT written as <ROOT>)
    main, rule = (json.loads(Path(p).read_text().replace(str(Path(p).resolve().parent), "<ROOT>"))
                  for p in (main_json, rule_json))
    print(f"tries: main {len(main['tries'])} (the last following the keys each refusal named, "
          f"one init each: {main['tries'][-1].get('keys')}) / rule "
          f"{len(rule['tries'])} (line exit {rule['tries'][-1].get('exit')})")
    print(f"config yaml equal: {main.get('yaml') == rule.get('yaml')}; column table equal: "
          f"{main.get('table') == rule.get('table')}")
    for family in FAMILIES:
        a, b = main.get(family), rule.get(family)
        if isinstance(a, dict) and isinstance(b, dict):
            print(f"{family}: main {a} rule {b} max|d| {max(abs(a[t] - b[t]) for t in a):.3g} µm")
        else:
            print(f"{family}: main {a!r} rule {b!r}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"tries": tries, "compare": compare}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
