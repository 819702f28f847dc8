"""Deployed = scored at the seams no bench checked yet (stop 107, dep107; issue 34).

Four seams (the brief's):
1. ``stream.c --state``: the state saved after a refused row (a bad value / a row written again /
   a time set back) read back by a fresh process goes on as the uninterrupted stream does, and as
   the served session does after the same row;
2. ``connect`` (OPC UA) with a plain model (``monitor.adaptive=false``) fed a missing value (a
   bad-status node, NaN): what it answers against served and the C;
3. a chained file's first row read as a jump (pt10044: W3 fed after W2, ``data.reference`` none):
   the jump or a new campaign, decided from the data contract (docs/data-format.md);
4. a blank line mid-file: ``stream.c`` restarts a campaign there; do served (``monitor.input=-``)
   and ``replay`` read the same file the same way?

BAR (written and committed BEFORE any seed of 10130-10132 is built; not to move after):
  B1. every seam answered with a measured number: |C - served| (and |C cut by --state - C
      uninterrupted|) in um for 1, 2, 4; |replay - run| (the test RMSE, um) and |C - served| for 3.
  B2. every break found is mended (a failing cheap test in the module of the code it concerns,
      the mend, the test passing; a refusal with file / column / row and exit 2 where refusing
      is the right mend) or named as left, with the reason.
  B3. the seeds, kinds chosen now: 10130 a portal mill's weekly files (bench_audit98's PORTAL,
      ``seed=10130``, as pt10044; seam 3), 10131 and 10132 a lab's export as bench_audit106's
      cell L writes it (``write_export``, as dep106b's 10118; seams 1, 2, 4).  Scored once.
  Verdict: KEPT where B1 and B2 hold with a src change; TRACED where nothing breaks.

SCORED once (bar 6c130b8e, committed before any seed was built; not moved; 2026-12-07 11:42-11:52
UTC, 2 cores shared, load 6-8; the harness first run on seen lab 10118 and pt10044).  Seeds drawn:
10130-10132 only.
  1. lab10131 / lab10132, adaptive and plain, rows 450 and 1100, nan / dup / back (24 cases): the
     C cut by ``--state`` = the C uninterrupted (or, at a plain model's missing value, exit 2 at
     the row, = the C without it) to 0 um in every case; = the served session (the row refused by
     the plain model, taken by the adaptive) <= 6.4e-14 um.  Holds on 570d5a78 (no src change).
  2. connect, plain, an input Bad at row 1100 -- on 570d5a78 it ends there (MissingValueError's
     traceback, exit 1: tests/shell/test_opcua67.py).  Now 1261/1261 rows answered, one
     ``refused`` / ``taken``; after the row |connect - served| 2.2e-16 / 4.4e-16 um, |connect - C
     cut| 4.4e-15 / 3.6e-15 um; at it the C's last correction; before it 10131 parts on rows
     998-1000 by 0.316 um: connect's limiter (the guard's rate, what may reach the machine),
     which the plain served model and C do not apply (named in the docs); 10132 4.4e-16 um.
  3. pt10044 (seen): W3 continues W2 (``data.reference=auto``: none; restart98's rule finds W2 a
     restart after W1, not W3 after W2), no pause: by the contract one record; served re-references
     the 4 jumpers (T_bed, T_col_L, T_col_R, T_rail) at W3's first row, the C does the same:
     |C - served| 8.5e-13 um over 20160 rows.  |replay - run|: the plain stream = run to 5.1e-13
     um per row (RMSE 7.468 / 7.112 / 27.961 um); the adaptive replay (the monitor's jump rule)
     8.609 / 4.377 / 29.868 um (+1.14 / -2.73 / +1.91).  pt10130 (fresh): W3 read as a restart
     (every error starts at 0, 2.95e279:1), first_sample, no jump: |C - served| 2.6e-13 um, replay
     = run to 1.7e-13 um per row, RMSE equal.  Decision: no new rule; the contract already starts
     a campaign where the errors restart (restart98), and a lab that knows its files restart says
     ``data.reference=first_sample`` (the reader's warning names it).
  4. ``thermocomp rows`` (2 campaigns, a blank line between): on 570d5a78 ``monitor.input=-``
     reads one campaign (the fixture's 4 runs: 23 events, 3 exclusions); now ``stdin_1``,
     ``stdin_2``, |C - served| 3.6e-14 / 6.4e-14 um.  A stray blank line at row 450: the C
     restarts there (said), served and replay read it as nothing: |C - served| 28.6 / 32.6 um
     after it (10118: 35.7): named, not mended (no time tells it from the blank line between
     blocks of a one-clock run column's file; a stream.c rule was tried and reverted, 62d797b1).
  CPU (user + sys, /usr/bin/time, connect's child included): lab 24.6+3.2 s / 24.3+3.3 s; chain
  pt10130 14.2+0.9 s (with simulation) and 7.0+0.3 s (printing again), pt10044 11.6+0.3 s.
  Verdict: KEPT (two breaks mended with tests, the rest measured or named).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep107.py lab ROOT SEED          # seams 1, 2, 4 on a lab export
    python benchmarks/bench_dep107.py chain ROOT RECORD      # seam 3: pt10044 (seen), pt10130

``lab``: the lab's export as bench_audit106's cell L writes it (``once.tsv``: 1261 rows of two
runs, the 3 h gap between them, local ISO-8601 stamps), ``init`` with no key, ``run model=mlr``
(as dep106b); the model made deployable adaptive (as promote registers it) and plain
(``monitor.adaptive=false``), each exported as C from its registered folder and built.
  1. at data rows ROWS_AT (chosen with the bar), each of: the first input's cell emptied (``nan``),
     the row written again (``dup``), its time set back to the one 3 rows before (``back``): the
     C uninterrupted (or, where it exits 2 there, the C of the file without that row) against
     the C cut after that row, ``--state`` carrying it to a fresh process; and the served
     session fed the rows before it, the row alone (refused or not), the rows after, against
     the cut C.  Largest |difference| over the rows after it (um).
  2. ``connect`` (a process, the plain model) against tests' vendor server, the first input's
     node BadSensorFailure at row ROWS_AT[-1]: |connect - served| (the served session without
     that row) and the C (cut there by ``--state``) over the rows after it, and what connect
     wrote at it against the C's last correction.
  4. ``thermocomp rows`` of the record (each campaign from its time 0, a blank line between)
     fed to the C and read as ``monitor.input=-`` reads stdin (the campaigns it finds, each
     through the served model from a reset): |C - served|; and a stray blank line at data row
     ROWS_AT[0] of the lab's file: the C restarts there (documented), served and replay read it
     as nothing: |C - served| after it, the difference named.
``chain``: RECORD simulated (bench_audit98's PORTAL) and ``run model=mlr`` (bench_cmon92's
``made``), ``replay`` of its model: |replay - run| (replay.json's max_abs_stream_minus_batch and
its RMSE against metrics.json's); W3's first row's steps against the training's largest
one-sample step (the reader's jump warning); the C against served over the test campaign's
healthy frame (bench_dep105c's ``healthy``).
"""

from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests"), str(REPO / "tests" / "shell")]
from _cli import run_commands  # noqa: E402

ROWS_AT = (450, 1100)          # data rows of once.tsv (0-based): in run 1, in run 2 (after the gap)
BACK = 3                       # a time set back to the one this many rows before


def _cli(*args: str) -> subprocess.CompletedProcess:
    import bench_audit97

    return bench_audit97._cli(*args)


def _deployed(search: list[str], pkl: Path, *more: str):
    """The model made deployable as ``connect`` makes it (adaptive, or with ``more``)."""
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.cli import _compose
    from thermocomp.shell.source import read_streamed

    cfg = _compose([*search, f"connect.model={pkl}", "track=false", *more], "connect")
    ds, train_ids = read_streamed(cfg, test=False)[:2]
    return deployable_model(cfg, ds, train_ids, str(pkl), "connect.model")[0]


def _built(base: Path, name: str, deployed) -> Path:
    """The C exported from ``deployed``'s registered folder, built: its ``stream``."""
    import cbuild
    from thermocomp.apps.deploy.pyfunc import save_compensator

    folder, code = base / f"registered-{name}", base / f"code-{name}"
    if not folder.exists():
        save_compensator(deployed, folder)
    if not (code / "stream").exists():
        done = _cli("export", f"export.model={folder}", "export.format=c", "export.check=false",
                    "track=false", f"out={code}")
        assert done.returncode == 0, done.stderr[-400:]
        cbuild.compiled(code)
    return code / "stream"


def _c(stream: Path, lines: list[str], *args: str) -> tuple[int, np.ndarray, str]:
    """``(exit, corrections (rows x targets), stderr)`` of ``stream`` fed ``lines``."""
    done = subprocess.run([str(stream), *args], input=("\n".join(lines) + "\n").encode("utf-8"),
                          capture_output=True)
    out = pd.read_csv(io.BytesIO(done.stdout)) if done.stdout.strip() else pd.DataFrame()
    return done.returncode, out.to_numpy(float), done.stderr.decode()


def _frame(header: str, lines: list[str], errors: list[str]) -> pd.DataFrame:
    """The lab's TSV lines as the served model is sent them (its error columns left out)."""
    df = pd.read_csv(io.StringIO("\n".join([header, *lines]) + "\n"), sep="\t", dtype={"Timestamp": str})
    return df.drop(columns=[c for c in df.columns if c in errors])


def _served(deployed, header: str, blocks: list[list[str]], errors: list[str]) -> list:
    """Each block's corrections in one session (the first from a reset); a refused one: its words."""
    from thermocomp.apps.deploy.pyfunc import CompensatorModel

    model, got = CompensatorModel(deployed), []
    for k, block in enumerate(blocks):
        try:
            out = model.predict(None, _frame(header, block, errors), {"session": "s", "reset": k == 0})
            got.append(out[[c for c in out.columns if c.startswith("C_")]].to_numpy(float))
        except Exception as exc:        # (MlflowException: the served model refuses the block)
            got.append(" ".join(str(exc).split())[:90])
    return got


def _defect(lines: list[str], k: int, kind: str, first: int) -> tuple[list[str], int]:
    """``lines`` (data rows) with ``kind`` at row ``k``; the defective row's index."""
    rows = list(lines)
    if kind == "dup":
        return rows[:k + 1] + [rows[k]] + rows[k + 1:], k + 1
    cells = rows[k].split("\t")
    if kind == "nan":
        cells[first] = ""
    else:
        cells[0] = rows[k - BACK].split("\t")[0]
    rows[k] = "\t".join(cells)
    return rows, k


def _state_cut(base: Path, name: str, stream: Path, header: str, rows: list[str], d: int):
    """The C fed rows[:d + 1] and, from the state file, rows[d + 1:] in a fresh process."""
    state = base / f"{name}.state"
    state.unlink(missing_ok=True)
    first = _c(stream, [header, *rows[:d + 1]], "--state", str(state))
    second = _c(stream, [header, *rows[d + 1:]], "--state", str(state))
    return first, second


def _seam1(base: Path, models: dict, streams: dict, header: str, body: list[str], errors) -> None:
    first = header.split("\t").index(next(c for c in header.split("\t")[1:] if c not in errors))
    for name, deployed in models.items():
        for k in ROWS_AT:
            for kind in ("nan", "dup", "back"):
                rows, d = _defect(body, k, kind, first)
                whole = _c(streams[name], [header, *rows])
                one, two = _state_cut(base, f"{name}-{kind}-{k}", streams[name], header, rows, d)
                ref = whole[1][d + 1:] if whole[0] == 0 else \
                    _c(streams[name], [header, *rows[:d], *rows[d + 1:]])[1][d:]
                served = _served(deployed, header, [rows[:d], [rows[d]], rows[d + 1:]], errors)
                said = one[2].strip().splitlines()[-1][:70] if one[2].strip() else ""
                mid = served[1] if isinstance(served[1], str) else "taken"
                print(f"1. {name:8s} {kind:4s} row {d}: C whole exit {whole[0]}, cut exit {one[0]}/"
                      f"{two[0]} ({said!r}); |cut - {'whole' if whole[0] == 0 else 'C without it'}| "
                      f"{np.abs(two[1] - ref).max():.3g} um; served: row {mid!r}, |cut - served| "
                      f"{np.abs(two[1] - served[2]).max():.3g} um over {len(two[1])} rows", flush=True)


def _connect(base: Path, search: list[str], pkl: Path, program: pd.DataFrame, columns, targets,
             bad: dict) -> tuple[np.ndarray, dict]:
    """``connect`` (a process, the plain model) against tests' vendor server fed ``program``."""
    from asyncua import ua

    from conftest import free_port
    from vendor_machine import VendorMachine, connect_nodes, served_in_thread

    sensors = {c: f"s=Lab.{c}" for c in columns}
    offsets = {t: (f"s=Lab.Offset_{t}", ua.VariantType.Double, 1.0) for t in targets}
    machine = VendorMachine({"LAB.MPF": program}, free_port(), sensors=sensors, offsets=offsets,
                            bad=bad, wait_s=120.0)
    machine.stop_pid = -1
    thread = served_in_thread(machine)
    out = base / "connect-plain"
    proc = subprocess.Popen([sys.executable, "-m", "thermocomp", "connect", *search, f"out={out}",
                             f"connect.model={pkl}", "monitor.adaptive=false",
                             f"connect.endpoint=opc.tcp://127.0.0.1:{machine.port}",
                             "connect.retry_s=0.4", "connect.give_up_s=120", "connect.hold_s=600",
                             "track=false", *connect_nodes(sensors, offsets)],
                            stdout=subprocess.DEVNULL, stderr=open(base / "connect.err", "w"))
    machine.stop_pid = proc.pid
    try:
        code = proc.wait(timeout=1800)
    finally:
        machine.closing.set()
        thread.join(timeout=60)
    link = json.loads((out / "connect.json").read_text()) if (out / "connect.json").is_file() else {}
    print(f"2. connect exit {code}, answered {int(np.sum(machine.served.answered))}/"
          f"{len(machine.served.answered)} rows, samples_refused {link.get('samples_refused')}", flush=True)
    return np.vstack(machine.served.offsets), link


def _seam2(base: Path, search, pkl: Path, plain, stream: Path, rows: pd.DataFrame, tsv: Path,
           errors) -> None:
    from asyncua import ua

    from vendor_machine import as_published

    k = ROWS_AT[-1]
    program = rows[["time", *plain.columns_]].reset_index(drop=True)
    sensor = plain.columns_[0]
    bad = {sensor: (k, k, ua.StatusCodes.BadSensorFailure)}
    seen = as_published({"LAB.MPF": program}, sensors={c: "" for c in plain.columns_}, bad=bad)["LAB.MPF"]
    import bench_audit106

    lab_rows = pd.read_csv(tsv, sep="\t", dtype={"Timestamp": str})
    for c in plain.columns_:
        lab_rows[bench_audit106._export_name(c)] = seen[c].to_numpy(float)
    text = lab_rows.to_csv(sep="\t", index=False, float_format="%.17g", lineterminator="\n")
    lines = text.splitlines()
    header, body = lines[0], lines[1:]
    served = _served(plain, header, [body[:k], [body[k]], body[k + 1:]], errors)
    one, two = _state_cut(base, "connect-c", stream, header, body, k)
    offsets, link = _connect(base, search, pkl, program, plain.columns_, plain.targets_, bad)
    said = [(e["event"], e["sample"]) for e in link.get("events", []) if e["event"] in ("refused", "taken")]
    np.save(base / "connect-offsets.npy", offsets)
    after = -offsets[k + 1:]
    gap = np.abs(-offsets[:k] - served[0]).max(axis=1)
    said_kinds = ("refused", "taken", "connected", "stopped")
    print(f"2. before row {k}: |connect - served| past 1e-9 um at rows {np.flatnonzero(gap > 1e-9)[:8]} "
          f"({int((gap > 1e-9).sum())} rows); events there "
          f"{[(e['event'], e['sample']) for e in link.get('events', []) if e['event'] not in said_kinds]}",
          flush=True)
    print(f"2. row {k} ({sensor} Bad): served {served[1]!r}; C exit {one[0]} ({one[2].strip()[-60:]!r}); "
          f"connect events {said}; |connect - served| after {np.abs(after - served[2]).max():.3g} um, "
          f"|connect - C cut| after {np.abs(after - two[1]).max():.3g} um; before "
          f"{np.abs(-offsets[:k] - served[0]).max():.3g} um; at the row connect wrote "
          f"{-offsets[k]} (the C's last {one[1][-1]})", flush=True)


def _seam4(base: Path, search, deployed, stream: Path, tsv: Path, header: str, body: list[str],
           errors) -> None:
    from thermocomp.core.io import ReadOptions
    from thermocomp.core.io.stdin import stream_campaigns

    done = _cli("rows", str(tsv), *search)
    text = done.stdout
    blanks = sum(1 for ln in text.splitlines()[1:-1] if not ln.strip())
    code, c_rows, _ = _c(stream, text.rstrip("\n").split("\n"))
    parts, _ = stream_campaigns(text, list(deployed.columns_),
                                ReadOptions.from_cfg({"runs_at_pauses": True}))
    from thermocomp.apps.deploy.pyfunc import CompensatorModel

    model = CompensatorModel(deployed)
    served = np.vstack([model.predict(None, part[["time", *deployed.columns_]], {"session": cid,
                                                                                  "reset": True})
                        .filter(like="C_").to_numpy(float) for cid, part in parts.items()])
    print(f"4. thermocomp rows: exit {done.returncode}, {len(c_rows)} rows, {blanks} blank line(s); "
          f"stdin read as {list(parts)}; C exit {code}; |C - served| "
          f"{np.abs(c_rows - served).max():.3g} um", flush=True)
    k = ROWS_AT[0]
    code, blank, said = _c(stream, [header, *body[:k], "", *body[k:]])
    _, plain_c, _ = _c(stream, [header, *body])
    served = _served(deployed, header, [body], errors)[0]
    print(f"4. a stray blank line before data row {k}: C exit {code} "
          f"({[ln[:60] for ln in said.splitlines() if 'blank' in ln]}); |C - served| after it "
          f"{np.abs(blank[k:] - served[k:]).max():.3g} um (the C restarts; served and replay read "
          f"it as nothing); without it |C - served| {np.abs(plain_c - served).max():.3g} um", flush=True)


def lab(root: str, seed: str) -> None:
    """Cell lab (module doc)."""
    import bench_audit91
    import bench_audit106

    base = bench_audit91.lab_root(root, seed)
    rows = bench_audit106.write_export(base, int(seed))
    tsv = base / "once.tsv"
    init = base / "once-init"
    if not init.exists():
        done = _cli("init", str(tsv), f"out={init}")
        print(f"init exit {done.returncode}", flush=True)
    conf = next((init / "conf" / "data").glob("*.yaml"))
    search = [f"hydra.searchpath=[file://{init / 'conf'}]", f"data={conf.stem}"]
    pkl = base / "run" / "model.pkl"
    if not pkl.exists():
        done = _cli("run", *search, "model=mlr", f"out={pkl.parent}", "track=false", "plots=none")
        print(f"run exit {done.returncode}", flush=True)
    models = {"adaptive": _deployed(search, pkl), "plain": _deployed(search, pkl, "monitor.adaptive=false")}
    streams = {name: _built(base, name, d) for name, d in models.items()}
    lines = tsv.read_text(encoding="utf-8").splitlines()
    header, body = lines[0], lines[1:]
    errors = [c for c in header.split("\t") if c.split(" [")[0] in
              [bench_audit106._export_name(t).split(" [")[0] for t in rows.columns if t.startswith("E_")]]
    print(f"lab{seed}: {len(body)} rows; inputs {models['plain'].columns_}; pause_s_ "
          f"{models['plain'].pause_s_:g} s; errors {errors}", flush=True)
    _seam1(base, models, streams, header, body, errors)
    _seam2(base, search, pkl, models["plain"], streams["plain"], rows, tsv, errors)
    _seam4(base, search, models["adaptive"], streams["adaptive"], tsv, header, body, errors)


def chain(root: str, record: str) -> None:
    """Cell chain (module doc)."""
    import bench_audit98
    import bench_dep105b
    from bench_cmon92 import faulted_cell, made
    from bench_dup99 import _targets_env

    from thermocomp.shell.source import read_streamed  # noqa: F401  (the stages' reader)

    base = Path(root).resolve()
    words = {**bench_dep105b.FRESH, "pt10130": [*bench_audit98.PORTAL, "seed=10130"]}
    _targets_env(record)
    made(base, record, "mlr", words)
    out = base / "reports" / record / "mlr-none"
    replayed = base / "replay" / record
    if not (replayed / "replay.json").exists():
        done = _cli("replay", f"data.path={base / 'data' / record}", f"replay.model={out / 'model.pkl'}",
                    f"out={replayed}", "track=false")
        print(f"replay exit {done.returncode} {done.stderr[-300:]!r}", flush=True)
    said = [ln for ln in (out / "thermocomp.log").read_text().splitlines()
            if "restart" in ln or "reference=auto" in ln] if (out / "thermocomp.log").exists() else []
    metrics = json.loads((out / "metrics.json").read_text())
    rep = json.loads((replayed / "replay.json").read_text())
    for t, fig in rep["targets"].items():
        run_rmse = metrics["targets"][t]["test"]["rmse"]
        print(f"3. {record} {t}: test RMSE run {run_rmse:.6g} um, replay's plain stream "
              f"{fig['rmse_batch']:.6g} (max|stream - batch| per row "
              f"{fig['max_abs_stream_minus_batch']:.3g} um), replay adaptive (the monitor's) "
              f"{fig['rmse']:.6g} um: replay - run {fig['rmse'] - run_rmse:+.4g} um", flush=True)
    events = [(e.get("sensor"), e.get("campaign"), e.get("time"), e.get("reason", "")[:40])
              for e in rep.get("events", [])]
    print(f"3. {record}: replay's events {events[:8]}", flush=True)
    print(f"3. {record}: the run's words: {[s[-200:] for s in said][:4]}", flush=True)
    deployed, ss, frame, lead, start, cid = faulted_cell(base, record, "mlr-none")
    from bench_cmon92 import Stepped
    from bench_dep101 import _stream

    stepped = Stepped(deployed, ss)
    c, served = map(np.array, zip(*[(ci, want) for ci, want, *_ in stepped.rows(frame)]))
    compiled, stopped = _stream(base / "c" / record, deployed, ss, frame)
    print(f"3. {record} {cid}: {len(frame)} rows ({lead} lead-in, the chained file's first at "
          f"{lead}); max|mirror - served| {np.abs(c - served).max():.3g} um, max|compiled - served| "
          f"{np.abs(compiled - served[:len(compiled)]).max():.3g} um{stopped}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"lab": lab, "chain": chain}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
