"""The exported C reads a lab's odd rows as replay / the served model read them (cin103, issue 34;
audit103's findings 2-3): a header naming an input's column twice, the copy's values apart, is
refused where the model's reader refuses it and read where the reader reads it; a row whose time
is empty or not after the last one read is named in ``./stream --flags`` as served names it in
its events.

Rule (src/thermocomp/apps/deploy/export: ``TC_TWIN_REFUSED`` in compensator.h, stream.c's
``twin_col``; ``--flags``' column ``time_read``):

* export asks the model's reader (``core/io/twins.copy_refused``: ``roles.naming`` on the header
  written twice, with the export's ``data.roles`` / ``data.columns``) for each header stream.c
  reads an input by (its contract name, the lab's headers) whether a copy holding other values
  is refused; those headers go to ``TC_TWIN_REFUSED``.  stream.c compares such a copy (a later
  column of the same header, no input of the model's) with the input's column row by row, as
  text: at the first row where they differ, exit 2 naming both columns, the header and the
  ``data.columns`` fix in replay's words; a copy the reader reads (a roles-read lab file: the
  copy is ``T_Luft_2``, no input) or equal to the first (left out) is read as before.
* ``--flags`` appends ``time_read`` after ``excluded_inputs``: 0 the row's time read as given;
  1 no time (an empty cell) and 2 a time not after the last read, each taken one period after
  the previous row (served: a ``time`` event ``ok -> substituted`` at the row it sets in,
  ``substituted -> ok`` at the row it ends); 3 a row written again, skipped (served:
  ``repeated``).  Without ``--flags`` nothing printed changes; ``--check-flags`` compares the
  monitor's columns as before.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_cin103.py record ROOT NAME PORT [SEED]   # cell R: large_mill_week
    python benchmarks/bench_cin103.py lab ROOT SEED             # cell L: a role-read lab file

``record``: NAME's mlr model (ROOT/reports/NAME/mlr-none/model.pkl and its data ROOT/data/NAME;
simulated first where SEED is given: large_mill_week, 48 h train + 24 h test at 60 s, as
bench_audit103's lm9980) exported to C by this tree and by BASE's src (``git archive 90800103
src``, /tmp/cin103/base); both streams fed the test file healthy and with one odd row planted at
data row 200 in the first non-ambient T_ column as audit103 planted them: ``twice`` (the column
written again, the copy 5 degC above from row 200), ``same`` (the copy equal), ``notime`` (row
200's time cell empty), ``order`` (row 200's time 30 s before row 199's); ``replay`` of the
``twice`` / ``same`` files (exit, message); served events (bench_audit103's cell F2: the model
served on PORT, rows 0-219 posted as one block from a reset) for ``notime`` / ``order``.
``lab``: test_audit86's german export of seed SEED (roles: error dX/dZ, ambient 'T Luft') with
'T Luft [°C]' written again 5 degC above: run -> export C; replay and the C fed the file with and
without the copy.

BAR (written and committed BEFORE seeds 9996-9997 were simulated; seen: lm0 (audit103's probe)
and lm9980 (audit103's root), test_audit86's german export of seed 9020):

C1. ``twice`` on a contract-named record: the C exits 2 (was 0) naming both columns and the
    header (``columns A and B have the same header 'T_...'``, replay's words) and replay exits 2;
    ``same``: the C exits 0 and prints main's C bytes exactly.  Role-read lab file with the copy
    apart: replay exits 0 and the C exits 0, its corrections = those without the copy (= replay's
    input) to <= 1e-9 um.
C2. ``notime`` / ``order``: the C's ``--flags`` ``time_read`` is non-zero at the row served's
    ``time`` event (``ok -> substituted``) names and 0 again at the row of its ``substituted ->
    ok``; corrections = main's C to <= 1e-12 um on every row (the rule says, changes nothing).
C3. Healthy files: the C's output without ``--flags`` byte-identical to main's; with ``--flags``
    main's columns identical and ``time_read`` 0 on every row; tests/shell/test_export.py,
    test_export_cflags100.py, test_streamraw65.py, test_export_day_seconds91.py pass.
C4. Fresh (scored once): large_mill_week seeds 9996 and 9997 (cell R) and the lab file of seeds
    9996 and 9997 (cell L): C1-C2 hold.
KEPT if C1-C4 hold; else REFUSED (benchmarks/cin103_rule.patch) or TRACED.

Status: the bar committed in 3b5550b5 before seeds 9996-9997 were simulated; unchanged.  After
it, harness only (18b4c8cc, before any fresh run): served events through bench_audit103's cell
F2 over HTTP (the in-process probe named no API the model has), tests/shell on the path.

Scored (2026-12-07, 00:53-01:06 UTC; 2 cores shared, load 6-9, every job ``nice``; rule a43d5194;
main = 90800103's src)::

  record          twice: C / main / replay   same: C   notime: time_read   order: time_read
  lm0 (seen)      2 / 0 / 2, replay's words  = main    1 at row 200         2 at row 200
  lm9980 (seen)   2 / 0 / 2                  = main    1 at row 200         2 at row 200
  lm9996 (fresh)  2 / 0 / 2                  = main    1 at row 200         2 at row 200
  lm9997 (fresh)  2 / 0 / 2                  = main    1 at row 200         2 at row 200

In every record: the C's ``twice`` message ``stream: line 202: columns 2 and 57 have the same
header 'T_table_01', different values ('24.46', '29.46'): name the second,
data.columns={'T_table_01#2': T_<name>} ...`` (values per record), replay's ``columns 2 and 57
have the same header 'T_table_01', different values: name the second, data.columns=
{'T_table_01#2': T_<name>}``; ``same`` replay exit 0; served's time events ``ok -> substituted``
at row 200 and ``substituted -> ok`` at row 201 for ``notime`` and ``order``, the C's
``time_read`` non-zero at row 200 alone; corrections of every healthy / same / notime / order
file byte-identical to main's C without ``--flags``, and with it main's columns identical
(|C - main| 0 µm), ``time_read`` 0 on every healthy row; served |C - healthy| <= 5.3e-15 µm, 0
tracebacks.  Lab files (german export, roles; 'T Luft [°C]' copied 5 °C above):
9020 (seen), 9996, 9997 (fresh): C exit 0, corrections = without the copy to 0 µm; replay exit
0 with and without the copy, replay.json equal in every figure but ``us_per_sample``
(TC_TWIN_REFUSED there: ``T_amb``, ``T_Spindel``, ``T_Lager``, the contract names; the lab's
headers not).  C1-C4 hold: KEPT.  Wall / CPU: ``record`` 49 s wall, 24 s user of its children
(lm9980); ``lab`` 49 s wall, 12 s user.
"""

from __future__ import annotations

import io
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests"), str(REPO / "tests" / "shell")]
from _cli import run_commands  # noqa: E402

BASE_SRC = Path("/tmp/cin103/base/src")           # git archive 90800103 src
FAULT_ROW = 200                                   # the data row an odd row starts at (audit103's)
ODD = ("twice", "same", "notime", "order")
SIM = ["sim=large_mill_week", "sim.generator.train_hours=48", "sim.generator.test_hours=24",
       "sim.generator.sample_period_s=60"]


def _thermocomp(*args: str, src: Path = REPO / "src", cwd: Path | None = None) -> subprocess.CompletedProcess:
    env = {**__import__("os").environ, "PYTHONPATH": str(src)}
    return subprocess.run(["nice", sys.executable, "-m", "thermocomp", *args], capture_output=True,
                          text=True, env=env, cwd=cwd)


def _stream(model: Path, data: Path, out: Path, src: Path, extra: tuple = ()) -> Path:
    """``model`` exported to C in ``out`` by the code of ``src``, built; its stream."""
    if not (out / "stream").exists():
        done = _thermocomp("export", f"export.model={model}", "export.format=c", f"data.path={data}",
                           f"out={out}", "track=false", *extra, src=src)
        assert done.returncode == 0, done.stderr[-2000:]
        cc = subprocess.run(["cc", "-O2", "-std=c99", "-o", str(out / "stream"), str(out / "stream.c"),
                             str(out / "compensator.c"), "-lm"], capture_output=True, text=True)
        assert cc.returncode == 0, cc.stderr[-2000:]
    return out / "stream"


def odd(frame: pd.DataFrame, kind: str, sensor: str) -> pd.DataFrame:
    """``frame`` (text cells) with ``kind`` (module doc) planted at :data:`FAULT_ROW`."""
    out, r = frame.astype(object).copy(), FAULT_ROW
    if kind in ("twice", "same"):
        copy = out[sensor].copy()
        if kind == "twice":
            copy.iloc[r:] = [repr(float(v) + 5.0) for v in copy.iloc[r:]]
        out = pd.concat([out, copy.rename(sensor)], axis=1)
    elif kind == "notime":
        out.loc[r, "time"] = ""
    elif kind == "order":
        out.loc[r, "time"] = repr(float(frame.loc[r - 1, "time"]) - 30.0)
    return out


def _fed(stream: Path, text: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(stream), *args], input=text, capture_output=True, text=True)


def _frame(stdout: str) -> pd.DataFrame:
    return (pd.read_csv(io.StringIO(stdout), keep_default_na=False, dtype=str) if stdout.strip()
            else pd.DataFrame())


def _served(model: Path, data: Path, raw: pd.DataFrame, inputs: list[str], sensor: str,
            healthy_c: np.ndarray, port: str, scratch: Path) -> None:
    """bench_audit103's cell F2 (the model served on ``port``, each odd row's block of rows 0-219
    posted from a reset, the events printed) for ``notime`` and ``order``."""
    import bench_audit103

    bench_audit103.FAULTS, bench_audit103.faulted = ("notime", "order"), odd
    bench_audit103.served(model, data, raw, inputs, sensor, healthy_c, int(port), scratch)


def record(root: str, name: str, port: str, seed: str | None = None) -> None:
    """Cell R (module doc)."""
    base = Path(root).resolve()
    data, cell = base / "data" / name, base / "reports" / name / "mlr-none"
    if seed is not None and not (cell / "model.pkl").exists():
        done = _thermocomp("simulate", *SIM, f"seed={seed}", f"data.path={data}", cwd=base)
        assert done.returncode == 0, done.stderr[-2000:]
        done = _thermocomp("run", "model=mlr", f"data.path={data}", f"out={cell}", "track=false",
                           "plots=none", cwd=base)
        assert done.returncode == 0, done.stderr[-2000:]
    scratch = Path("/tmp/cin103") / name
    scratch.mkdir(parents=True, exist_ok=True)
    new = _stream(cell / "model.pkl", data, scratch / "c-new", REPO / "src")
    old = _stream(cell / "model.pkl", data, scratch / "c-base", BASE_SRC)
    manifest = pd.read_csv(data / "campaigns.csv")
    file = manifest.loc[manifest.split == "test", "file"].iloc[0]
    raw = pd.read_csv(data / file, dtype=str, keep_default_na=False)
    inputs = [c for c in raw.columns if c.startswith(("T_", "S_"))]
    sensor = next(c for c in inputs if c.startswith("T_") and c != "T_amb")
    for kind in ("healthy", *ODD):
        rows = raw if kind == "healthy" else odd(raw, kind, sensor)
        text = rows.to_csv(index=False)
        a, b = _fed(new, text), _fed(old, text)
        fa, fb = _fed(new, text, "--flags"), _fed(old, text, "--flags")
        line = (f"  [{kind}] C exit {a.returncode} (main {b.returncode}); bytes = main "
                f"{a.stdout == b.stdout}; stderr {a.stderr.strip()[:260]!r}")
        got, was = _frame(fa.stdout), _frame(fb.stdout)
        if len(got) and len(got) == len(was):
            corr = [c for c in got.columns if c.startswith("C_")]
            d = np.abs(got[corr].to_numpy(float) - was[corr].to_numpy(float)).max()
            same_cols = all((got[c] == was[c]).all() for c in was.columns)
            codes = got.get("time_read", pd.Series([], dtype=str))
            coded = [(i, v) for i, v in enumerate(codes) if v not in ("0", "")]
            line += (f"; --flags: |C - main| {d:.3g} um, main's columns equal {same_cols}, "
                     f"time_read != 0 at {coded[:6]}")
        print(line, flush=True)
        if kind in ("twice", "same"):
            folder = scratch / f"data-{kind}"
            folder.mkdir(exist_ok=True)
            manifest.to_csv(folder / "campaigns.csv", index=False)
            for f in manifest["file"]:
                src = rows if f == file else pd.read_csv(data / f, dtype=str, keep_default_na=False)
                src.to_csv(folder / f, index=False)
            rep = _thermocomp("replay", f"data.path={folder}", f"replay.model={cell / 'model.pkl'}",
                              f"out={scratch / ('replay-' + kind)}", "track=false")
            tail = [ln for ln in rep.stderr.splitlines() if ln.strip()][-1:] or [""]
            print(f"    replay exit {rep.returncode}: {tail[0][:300]!r}", flush=True)
        if kind == "healthy":
            healthy_c = _frame(a.stdout).to_numpy(float)
    _served(cell / "model.pkl", data, raw, ["time", *inputs], sensor, healthy_c, port, scratch)


def lab(root: str, seed: str) -> None:
    """Cell L (module doc)."""
    from test_audit86 import german_export

    base = Path(root).resolve() / f"lab{seed}"
    base.mkdir(parents=True, exist_ok=True)
    path = german_export(base / "lauf.csv", int(seed), ["6000"])
    lines = path.read_text(encoding="utf-8").splitlines()
    rows = [ln.split(";") for ln in lines]
    luft = rows[0].index("T Luft [°C]")
    copied = [[*rows[0], rows[0][luft]]] + [
        [*r, f"{float(r[luft].replace(',', '.')) + 5.0:.2f}".replace(".", ",")] for r in rows[1:]]
    keys = [f"data.path={path}", "data.delimiter=;", "data.decimal=,", "data.test_fraction=0.2",
            "data.roles.error=[dX, dZ]", "data.roles.ambient=[T Luft]", "track=false"]
    if not (base / "run" / "model.pkl").exists():
        done = _thermocomp("run", *keys, "plots=none", f"out={base / 'run'}")
        assert done.returncode == 0, done.stderr[-2000:]
    stream = _stream(base / "run" / "model.pkl", path, base / "code", REPO / "src", tuple(keys[1:]))
    plain = _fed(stream, path.read_text(encoding="utf-8"))
    twin = base / "twin" / "lauf.csv"
    twin.parent.mkdir(exist_ok=True)
    twin.write_text("\n".join(";".join(r) for r in copied) + "\n", encoding="utf-8")
    fed = _fed(stream, twin.read_text(encoding="utf-8"))
    d = (np.abs(_frame(fed.stdout).to_numpy(float) - _frame(plain.stdout).to_numpy(float)).max()
         if fed.returncode == 0 else np.nan)
    print(f"  lab{seed}: C exit {fed.returncode} (without the copy {plain.returncode}); |C copy - C| "
          f"{d:.3g} um; stderr {fed.stderr.strip()[:200]!r}", flush=True)
    for name, file in (("without", path), ("copy", twin)):
        rep = _thermocomp("replay", f"data.path={file}", *keys[1:],
                          f"replay.model={base / 'run' / 'model.pkl'}", f"out={base / ('replay-' + name)}")
        said = [ln for ln in rep.stdout.splitlines() if "E_" in ln][-3:]
        print(f"    replay {name} exit {rep.returncode}: {said} {rep.stderr.strip()[-200:]!r}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"record": record, "lab": lab}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
