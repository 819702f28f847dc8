"""Thermocomp run as a stranger would after stop 99's merges (stop 100, audit100; issue 34): what
audit97-99 did not touch: stop 99's new ``model.diagnosed=true`` through every route to the
machine, a lab's Excel-like export (``sep=;`` first line, local stamps over a daylight saving
change, names with spaces / umlauts / parentheses, an all-empty column, µm written ``um`` / ``mu
m``), a machine kind no bench tuned on through ``auto`` with ``ati``, ``diagnose``, ``promote`` and
the HTTP API fed bad requests, a healthy record of another kind through ``monitor``, the C and the
ST, and the docs site's build and links.  The bar was written first; scored once (see "Scored").

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_audit100.py diagnosed CLONE ROOT KIND SEED    # cell A (mtc68 9888, gpg69 9922)
    python benchmarks/bench_audit100.py lab ROOT SEED [FAMILIES]          # cell L (fresh 9921)
    python benchmarks/bench_audit100.py machine CLONE ROOT SEED PORT      # cell N (fresh 9922)
    python benchmarks/bench_audit100.py healthy ROOT SEED                 # cell H (fresh 9923)
    python benchmarks/bench_audit100.py docs CLONE                        # cell K

``diagnosed``: KIND ``mtc68`` (conf68; seed 9888 seen: audit99's and autodiag99b's record) or
``gpg69`` (conf69, stranger69's gear grinder; seed 9922 fresh), simulated under ROOT, the last run
held out (``data.test_fraction=0.1``); in CLONE (bench_audit97's clone and shims: its own MLflow
registry) ``run -m model=auto model.diagnosed=false,true`` (joblib), ``compare``, ``promote``,
``replay`` of @champion, ``export`` C of @champion with its check pack (``export.check=true``) and
``export`` ST, ``monitor`` of @champion on the test run; then each job's printed table and
``metrics.json`` searched for what the ``diagnosed`` candidate accepted.
``lab``: seed SEED's swiss production campaign (bench_audit91's ``contract.csv``, 1441 rows at
60 s) written as ``excel.csv`` (:func:`write_excel`): UTF-8 with a BOM, CRLF, ``sep=;`` on line 1,
then a header of the lab's names (``Zeitstempel (Ortszeit)``, ``KW``, the sensors as
``Spindelkasten vorn (°C)``, ``Führungsbuchse``, ``Motor Spindel (Gehäuse)``..., ``Weg X (um)``,
``Weg Y [mu m]``, ``Drehzahl Spindel (1/min)``, ``Tür``, ``Reserve (leer)``), the stamps
``2026-10-25 02:30:00`` on
Europe/Berlin's local clock without an offset (the record starts 2026-10-24 14:00 local, so the
hour 02:00-03:00 of 25 Oct repeats inside it), ``KW`` the ISO week date ``2026-W43-6`` (text),
``Reserve (leer)`` empty in every row, decimal commas.  ``init`` with NO key first; where it
refuses naming a key, init again with the key it names (each try said); then per family (mlr,
lagbank) run ``data.test_fraction=0.25`` -> replay (adaptive, plain) -> export C + check pack ->
the compiled ``stream`` fed the raw bytes, and ``thermocomp rows`` of the file into the ``stream``
(the README's route), against contract.csv through the same stages.
``machine``: gpg69 seed SEED (8 runs of 24 h, the last held out), in CLONE: ``run -m
model=auto,mlr 'model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati]'`` (the ATI wrapper a
candidate, as audit99's refusal says to name it), ``promote``; ``diagnose model=mlr``; ``serve``
of @champion on PORT, sent: one valid block of the test run (its corrections against replay's
first rows), a body that is not JSON, a JSON body that is no ``dataframe_split``, a block missing
one sensor column, a block with one sensor NaN in one row, a block with a text cell.
``healthy``: tsc66 (conf66, stranger66's twin-spindle turning centre, 6 runs of 40 h), seed SEED,
the last run held out; ``run model=mlr``; ``monitor`` on the test run; export C with its check
pack; the compiled ``stream`` fed the test run's file (a cold start) and its numpy mirror flags
counted (bench_audit99's ``h_flags``); bench_st93's ``trace`` (the ST block stepped with the served
model over the test run after its lead-in; healthy, then its planted faults).
``docs``: in CLONE ``make docs`` (``mkdocs build --strict``) and every Markdown link of README.md and
docs/*.md: a relative file that exists, an anchor that is a heading of the target page
(:func:`slug`, MkDocs' ``toc`` slugs) or an explicit ``{#id}`` / ``<a id>``.

Records (fresh seeds of this brief, chosen before any was simulated)::

  lab 9921   the lab's Excel-like file (contract: swiss_lathe_door's test campaign): cell L
  gp9922     gpg69, 8 runs: cells A (second record), N
  ts9923     tsc66, 6 runs: cell H
  mt9888     mtc68, seen (audit99, autodiag99b): cell A's first record (a trace, not scored fresh)

BAR (written and committed BEFORE seeds 9921-9923 were simulated; what counts as a BREAK: a
traceback or exit 1, exit 0 on bad input, a figure that differs between run and replay / the
deployed code, a false alarm, an unclear message (no file, column or row where one is at fault),
a docs command that fails as written)
-----------------------------------------------------------------------------------------------
A1. (mt9888, gp9922) the sweep's 2 jobs, compare, promote, replay, export C (+ pack) and ST, monitor
    exit 0; promote says it ranked by simulation and registers the job of lower mean
    simulation-mode validation; its "as deployed" test figure = replay of @champion to 1e-6
    relative; the check pack exits 0 (C = the deployed model to its tolerance); monitor: 0 events
    on the healthy test run.
A2. What the ``diagnosed`` candidate accepted (the effect, per target) is said where the user reads
    the run: the printed table or ``metrics.json`` (cli.md: "``<t> diagnosed: ...``" one line per
    target); where it accepted something on mt9888 (autodiag99b: E_X / E_Z ``S_B_deg`` products) the
    line names the effect.  Missing: a finding (an unclear message), mended if small.
L1. excel.csv goes in: ``init`` with no key reads it, or refuses in one line naming the key to set
    (``data.timezone``, the column and row of the repeated hour); with at most the keys its
    refusals name, init exits 0: the stamps read on Europe/Berlin's clock (60 s throughout, the
    repeated hour told apart by row order, not a gap nor a step), ``Reserve (leer)`` and ``KW``
    not taken as sensors (dropped, said), the errors from ``um`` / ``mu m`` read as µm, the
    names with spaces / umlauts / parentheses carried to the contract names and back (replay and
    the C take the lab's file as written).  Never a traceback; never a silent wrong time.
L2. Per family every figure (run, plain, replay, C by ``rows``; RMSE per target) = contract.csv's
    to 1e-6 µm, C = replay to 1e-9 µm; the C fed the raw bytes either = replay to 1e-9 µm or exits
    non-zero in one line naming the row and the fix (the stream reads no ``data.timezone``: a
    documented refusal, not a break).
N1. (gp9922) the sweep (2 jobs) exits 0 or refuses before fitting in one line; ``auto`` with the
    ``ati`` candidate fits or says per target why ``ati`` did not apply; promote exit 0 and ranks by
    simulation; ``diagnose`` exit 0 with its table.
N2. ``serve`` of @champion: the valid block answered (200) with C_* = replay's first rows to 1e-6
    µm; each bad request answered 4xx (never 5xx, never a Python traceback in the body or on the
    server's stderr) with a message naming what is wrong (the column for a missing / text one,
    the column and row for NaN, "JSON" for the body); a NaN may instead be served as the
    fault-tolerant compensator's dropout (200, the sensor named in ``events``).
H1. (ts9923, mlr, healthy) ``monitor``: 0 sensor events on the test run; export C + pack exit 0;
    the C fed the raw test file exits 0 with 0 flagged rows (its mirror); the ST block: 0 false
    flags, ST = the C's mirror to 1e-6 µm before the mirror's first event.  (Planted faults:
    reported, not scored.)
K1. ``make docs`` exits 0 with no WARNING; every relative link of README.md and docs/*.md points
    to a file that exists and an anchor its page has.
A cell breaking one of these is a finding, named with command, file, row and numbers; mended only
where small and clear, with a test failing on 9bbbb214 (< 5 s), KEPT; else listed for the lead.

Status: bar committed before any of 9921-9923 was simulated.
"""

from __future__ import annotations

import io
import json
import os
import re
import signal
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests")]
import bench_audit97  # noqa: E402
import bench_audit99  # noqa: E402
from _cli import run_commands  # noqa: E402

KINDS = {"mtc68": ("conf68", "mt"), "gpg69": ("conf69", "gp"), "tsc66": ("conf66", "ts")}
HOLD = "data.test_fraction=0.1"
SAID = "rank|error|diagnos|event"          # the lines of a stage's output cell A prints
ZONE = "Europe/Berlin"
START_LOCAL = pd.Timestamp("2026-10-24 14:00:00")          # 12.5 h before the clock goes back
LAB_FAMILIES = ("mlr", "lagbank")
# the lab's names for the contract's columns (swiss_lathe_door's, then any other T_ by its name)
LAB_NAMES = {"E_X": "Weg X (um)", "E_Y": "Weg Y [mu m]", "S_door": "Tür", "S_spindle_rpm":
             "Drehzahl Spindel (1/min)", "S_tool_rpm": "Drehzahl Werkzeug (1/min)",
             "T_headstock": "Spindelkasten vorn (°C)", "T_guidebush": "Führungsbuchse",
             "T_nc_spindle_motor": "Motor Spindel (Gehäuse)", "T_amb": "Umgebung Luft (°C)"}


def simulated(root: str, kind: str, seed: str) -> Path:
    """KIND's record of seed SEED under ROOT/data (made once)."""
    from bench_audit86b import stage

    conf, tag = KINDS[kind]
    bench_audit99._targets(f"{kind}.")
    data = Path(root).resolve() / "data" / f"{tag}{seed}"
    if not data.exists():
        rc, said = stage("simulate", f"hydra.searchpath=[file://{HERE / conf}]", f"sim={kind}",
                         f"seed={seed}", f"data.path={data}")
        assert rc == 0, said
    return data


def _said(done) -> str:
    return " | ".join(x.strip() for x in (done.stdout + done.stderr).strip().splitlines()[-3:])[:400]


def diagnosed(word: str, root: str, kind: str, seed: str) -> None:
    """Cell A (module doc)."""
    from bench_audit96b import sh

    data = simulated(root, kind, seed)
    clone = bench_audit97.clone_of(word)
    tag = f"audit100-{kind}{seed}"
    multirun = f"{tag}/multirun"
    done = sh(clone, f".venv/bin/thermocomp run -m model=auto model.diagnosed=false,true "
                     f"hydra/launcher=joblib plots=none data.path={data} {HOLD} "
                     f"hydra.sweep.dir={multirun}")
    print(f"  run -m exit {done.returncode}: {done.stderr.strip()[-300:]}", flush=True)
    for job in sorted((clone / multirun).glob("*/metrics.json")):
        said = [ln for ln in (job.parent / "thermocomp.log").read_text().splitlines()
                if "diagnosed" in ln][-6:] if (job.parent / "thermocomp.log").exists() else []
        metrics = json.loads(job.read_text())["targets"]
        auto = {t: {k: v for k, v in (m.get("auto") or {}).items() if "diagnos" in str(k) or
                    "diagnos" in json.dumps(v)[:2000]} for t, m in metrics.items()}
        test = {t: round(m['test']['rmse'], 4) for t, m in metrics.items()}
        print(f"  job {job.parent.name}: test {test}"
              f"\n    log lines naming 'diagnosed': {said}\n    metrics.json auto (diagnosed keys): "
              f"{json.dumps(auto)[:900]}", flush=True)
    champion = "models:/thermocomp-compensator@champion"
    lines = [f"compare compare.sweep={multirun}",
             f"promote data.path={data} {HOLD} out={tag}/promote",
             f"replay data.path={data} {HOLD} replay.model={champion} out={tag}/replay",
             f"export data.path={data} {HOLD} export.model={champion} export.format=c "
             f"export.check=true out={tag}/c",
             f"export export.model={champion} export.format=st out={tag}/st",
             f"monitor data.path={data} {HOLD} monitor.model={champion} track=false out={tag}/monitor"]
    for line in lines:
        done = sh(clone, f".venv/bin/thermocomp {line}")
        print(f"  {line.split()[0]} exit {done.returncode}: "
              f"{[x for x in (done.stdout + done.stderr).splitlines() if re.search(SAID, x)][:4]}",
              flush=True)
    if (clone / tag / "c" / "compensator.c").exists():
        subprocess.run(["gcc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"],
                       cwd=clone / tag / "c", capture_output=True)
        pack = subprocess.run(["sh", "check/check.sh"], cwd=clone / tag / "c", capture_output=True, text=True)
        print(f"  check pack exit {pack.returncode}: {_said(pack)}", flush=True)
    mon = clone / tag / "monitor" / "monitor.json"
    if mon.exists():
        print(f"  monitor events: {json.loads(mon.read_text()).get('events', [])[:5]}", flush=True)
    try:
        bench_audit97.two_mode_figures(clone, multirun, clone / tag)
    except (OSError, KeyError, ValueError) as exc:
        print(f"  two_mode_figures: {exc!r}", flush=True)


def _lab_name(column: str) -> str:
    """The lab's header for a contract column (:data:`LAB_NAMES`, else ``Temp <name> (°C)``)."""
    if column in LAB_NAMES:
        return LAB_NAMES[column]
    if column.startswith("S_"):
        return f"Zustand {column[2:]}"
    if column.startswith("E_"):
        return f"Weg {column[2:]} (um)"
    return f"Temp {column[2:].replace('_', ' ')} (°C)"


def write_excel(base: Path, seed: int) -> pd.DataFrame:
    """``contract.csv`` (bench_audit91's) and ``excel.csv`` (module doc); the contract rows."""
    import bench_audit91

    if not (base / "contract.csv").exists():
        bench_audit91.lab_files(base, seed)
    rows = pd.read_csv(base / "contract.csv")
    cols = [c for c in rows.columns if c != "time"]
    utc0 = START_LOCAL.tz_localize(ZONE).tz_convert("UTC")
    local = [(utc0 + pd.Timedelta(seconds=float(t))).tz_convert(ZONE) for t in rows["time"]]
    head = ["Zeitstempel (Ortszeit)", "KW", *(_lab_name(c) for c in cols), "Reserve (leer)"]
    body = [";".join([f"{w:%Y-%m-%d %H:%M:%S}", f"{w.isocalendar()[0]}-W{w.isocalendar()[1]:02d}-"
                      f"{w.isocalendar()[2]}", *(repr(float(v)).replace(".", ",") for v in r), ""])
            for w, r in zip(local, rows[cols].itertuples(index=False))]
    lines = ["sep=;", ";".join(head), *body]
    (base / "excel.csv").write_bytes(("\ufeff" + "".join(f"{ln}\r\n" for ln in lines)).encode("utf-8"))
    print(f"wrote {base / 'excel.csv'}: {len(rows)} rows; {head!r}; row 1 {body[0]!r}", flush=True)
    return rows


def _init_tries(base: Path, path: Path) -> tuple[Path | None, list[str]]:
    """``init`` with no key, then with each key its refusal names (at most 3 tries)."""
    from bench_data88 import _refusal

    keys: list[str] = []
    for attempt in range(3):
        init = base / f"{path.stem}-init{attempt}"
        done = bench_audit97._cli("init", str(path), f"out={init}", *keys)
        print(f"  init {' '.join(keys) or '(no key)'}: exit {done.returncode}: "
              f"{_refusal(done) if done.returncode else ''}\n    "
              + "\n    ".join(done.stdout.strip().splitlines()[-30:]
                             + done.stderr.strip().splitlines()[-12:]),
              flush=True)
        if not done.returncode:
            return init, keys
        named = re.findall(r"(data\.[\w.]+=[^\s,;)'\"]+)", _refusal(done))
        if not named or named[0] in keys:
            return None, keys
        keys.append(named[0].rstrip("."))
    return None, keys


def _lab_stage(base: Path, path: Path, family: str) -> dict:
    """bench_audit97's ``lab_stage`` with :func:`_init_tries` and the ``rows`` route into the C."""
    from bench_data88 import _refusal
    from bench_data92 import deployed_and_fed

    init, keys = _init_tries(base, path)
    if init is None:
        return {"said": f"init refused with keys {keys}"}
    conf = next((init / "conf" / "data").glob("*.yaml"))
    search = [f"hydra.searchpath=[file://{init / 'conf'}]", f"data={conf.stem}", "track=false",
              "plots=none", "data.test_fraction=0.25"]
    out = base / f"{path.stem}-{family}"
    done = bench_audit97._cli("run", *search, f"model={family}", f"out={out}")
    if done.returncode:
        return {"said": f"run exit {done.returncode}: {_refusal(done)}"}
    run = json.loads((out / "metrics.json").read_text())["targets"]
    row = deployed_and_fed(search, out, path, pack=True)
    if "fed" not in row:
        return row
    fed, rep = row.pop("fed"), row.pop("rep")
    row.update(keys=keys, run={t: v["test"]["rmse"] for t, v in run.items()},
               n_test=next(iter(rep.values()))["n_samples"],
               said=f"pack {row.pop('pack')}, C fed raw exit {fed.returncode} "
                    f"{fed.stderr.decode(errors='replace').strip()[-300:]}")
    if not fed.returncode:
        row["C_raw"] = pd.read_csv(io.BytesIO(fed.stdout))
    done = bench_audit97._cli("rows", str(path), *search[:2])
    if done.returncode:
        row["said"] += f"; rows exit {done.returncode}: {_refusal(done)}"
        return row
    fed = subprocess.run([str(out.parent / f"{out.name}-c" / "stream")], input=done.stdout.encode(),
                         capture_output=True)
    row["said"] += f"; rows -> C exit {fed.returncode}"
    if not fed.returncode:
        row["C"] = pd.read_csv(io.BytesIO(fed.stdout))
    return row


def lab(root: str, seed: str, families: str = ",".join(LAB_FAMILIES)) -> None:
    """Cell L (module doc)."""
    import bench_audit91

    base = bench_audit91.lab_root(root, seed)
    rows = write_excel(base, int(seed))
    for family in families.split(","):
        ref = _lab_stage(base, base / "contract.csv", family)
        got = _lab_stage(base, base / "excel.csv", family)
        print(f"{family}: contract {ref['said']}\n  excel keys {got.get('keys')}: {got['said']}", flush=True)
        for t in (c for c in rows.columns if c.startswith("E_")):
            lab_t = next((k for k in got.get("run", {}) if k.endswith(t[2:])), None)
            figures = {}
            for label, r, name in (("contract", ref, t), ("excel", got, lab_t)):
                if name is None or "run" not in r:
                    continue
                n = r["n_test"]
                f = {"run": r["run"][name], "plain": r["plain"].get(name, np.nan),
                     "replay": r["replay"][name]}
                for c_key in ("C", "C_raw"):
                    if c_key in r:
                        col = next(c for c in r[c_key].columns if c.endswith(t[2:]) and c.startswith("C_"))
                        corr = r[c_key][col].to_numpy(float)[-n:]
                        f[c_key] = float(np.sqrt(np.mean((rows[t].to_numpy(float)[-n:] + corr) ** 2)))
                figures[label] = f
            line = "  ".join(f"{label} " + " ".join(f"{k} {v:.9f}" for k, v in f.items())
                             for label, f in figures.items())
            if len(figures) == 2:
                off = max(abs(v - figures["contract"][k]) for k, v in figures["excel"].items()
                          if k in figures["contract"])
                line += f"  max|excel - contract| {off:.2g} ({t} as {lab_t!r})"
            print(f"  {t}: {line}", flush=True)


def _post(port: int, body: bytes) -> tuple[int, str]:
    req = urllib.request.Request(f"http://127.0.0.1:{port}/invocations", data=body,
                                 headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=120) as got:
            return got.status, got.read().decode(errors="replace")
    except urllib.error.HTTPError as exc:
        return exc.code, exc.read().decode(errors="replace")
    except OSError as exc:
        return -1, repr(exc)


def _served(clone: Path, data: Path, port: int, tag: str) -> None:
    """Cell N2 (module doc): @champion served on ``port``, the requests sent."""
    log = clone / tag / "serve.err"
    log.parent.mkdir(parents=True, exist_ok=True)
    with log.open("w") as err:
        proc = subprocess.Popen(["nice", str(clone / ".venv/bin/thermocomp"), "serve",
                                 "serve.model=models:/thermocomp-compensator@champion",
                                 f"serve.port={port}"], cwd=clone, stdout=err, stderr=err,
                                start_new_session=True)
    try:
        waited = bench_audit99._wait_port(port, proc)
        print(f"  serve up after {waited:.0f} s", flush=True)
        manifest = pd.read_csv(data / "campaigns.csv")
        names = list(manifest["file"])
        test = data / names[-1]
        frame = pd.read_csv(test) if str(test).endswith(".csv") else pd.read_parquet(test)
        inputs = [c for c in frame.columns if not c.startswith("E_")]
        block = frame[inputs].iloc[:5]

        def body(cols, rows, reset=True):
            return json.dumps({"dataframe_split": {"columns": cols, "data": rows},
                               "params": {"session": "m1", "reset": reset}}).encode()

        sensor = next(c for c in inputs if c.startswith("T_"))
        nan_rows = block.to_numpy(float).tolist()
        nan_rows[2][inputs.index(sensor)] = float("nan")
        text_rows = block.astype(object).to_numpy().tolist()
        text_rows[1][inputs.index(sensor)] = "n/a"
        cases = {"valid": body(inputs, block.to_numpy(float).tolist()),
                 "not JSON": b'{"dataframe_split": {"columns": [',
                 "no dataframe_split": json.dumps({"rows": [1, 2]}).encode(),
                 f"missing {sensor}": body([c for c in inputs if c != sensor],
                                           block.drop(columns=sensor).to_numpy(float).tolist()),
                 f"NaN in {sensor} row 3": body(inputs, nan_rows).replace(b"NaN", b"NaN"),
                 f"text in {sensor} row 2": body(inputs, text_rows)}
        for label, payload in cases.items():
            status, said = _post(port, payload)
            print(f"  [{label}] HTTP {status}: {said[:400]}", flush=True)
    finally:
        os.killpg(proc.pid, signal.SIGTERM)
        proc.wait(timeout=60)
    text = log.read_text(errors="replace")
    print(f"  server stderr: {len(text.splitlines())} lines; tracebacks {text.count('Traceback')}; "
          f"last: {text.strip().splitlines()[-3:] if text.strip() else []}", flush=True)


def machine(word: str, root: str, seed: str, port: str) -> None:
    """Cell N (module doc)."""
    from bench_audit96b import sh

    data = simulated(root, "gpg69", seed)
    clone = bench_audit97.clone_of(word)
    tag = f"audit100-n{seed}"
    multirun = f"{tag}/multirun"
    start = time.monotonic()
    done = sh(clone, f".venv/bin/thermocomp run -m model=auto,mlr "
                     f"'model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati]' hydra/launcher=joblib "
                     f"plots=none data.path={data} {HOLD} hydra.sweep.dir={multirun}")
    print(f"  run -m exit {done.returncode} ({time.monotonic() - start:.0f} s): {done.stderr.strip()[-400:]}",
          flush=True)
    for job in sorted((clone / multirun).glob("*/metrics.json")):
        metrics = json.loads(job.read_text())["targets"]
        chosen = {t: (m.get("auto") or {}).get("chosen", (m.get("auto") or {}).get("kept"))
                  for t, m in metrics.items()}
        test = {t: round(m['test']['rmse'], 4) for t, m in metrics.items()}
        print(f"  job {job.parent.name}: test {test}"
              f" chosen {chosen}", flush=True)
        log = job.parent / "thermocomp.log"
        ati = [ln for ln in log.read_text().splitlines() if "ati" in ln.lower()][:6] if log.exists() else []
        print("    " + "\n    ".join(ati), flush=True)
    for line in (f"compare compare.sweep={multirun}", f"promote data.path={data} {HOLD} out={tag}/promote",
                 f"replay data.path={data} {HOLD} replay.model=models:/thermocomp-compensator@champion "
                 f"out={tag}/replay",
                 f"diagnose data.path={data} {HOLD} model=mlr track=false plots=none out={tag}/diagnose"):
        done = sh(clone, f".venv/bin/thermocomp {line}")
        print(f"  {line.split()[0]} exit {done.returncode}:\n    " + "\n    ".join(
            (done.stdout + done.stderr).strip().splitlines()[-14:]), flush=True)
    replayed = clone / tag / "replay" / "replay.json"
    if replayed.exists():
        print(f"  replay: {json.loads(replayed.read_text())['targets']}"[:600], flush=True)
    _served(clone, data, int(port), tag)


def healthy(root: str, seed: str) -> None:
    """Cell H (module doc): bench_audit99's ``healthy`` on tsc66's runs, the last held out."""
    import bench_st93
    from bench_audit86b import stage
    from bench_data88 import _refusal

    data = simulated(root, "tsc66", seed)
    record = data.name
    base = Path(root).resolve()
    model = base / "reports" / record / "mlr-none" / "model.pkl"
    if not model.exists():
        rc, said = stage("run", f"data.path={data}", HOLD, "model=mlr", "plots=none", "track=false",
                         f"out={model.parent}")
        assert rc == 0, said
    bench_audit99.CUT[:] = [HOLD]
    bench_st93.deployed_cell = lambda *_: bench_audit99._deployed_cell(data, model)
    bench_st93.trace(str(base), record)
    out = base / "reports" / record / "monitor"
    done = bench_audit97._cli("monitor", f"data.path={data}", f"monitor.model={model}", "track=false",
                              HOLD, f"out={out}")
    said = json.loads((out / "monitor.json").read_text()) if (out / "monitor.json").exists() else {}
    print(f"monitor exit {done.returncode}: {_refusal(done) if done.returncode else ''}; "
          f"{len(said.get('events', []))} events {said.get('events', [])[:5]}", flush=True)
    c_dir = base / "reports" / record / "c"
    done = bench_audit97._cli("export", f"data.path={data}", f"export.model={model}", "export.format=c",
                              "export.check=true", HOLD, f"out={c_dir}")
    print(f"export c exit {done.returncode}: {_refusal(done) if done.returncode else ''}", flush=True)
    if done.returncode:
        return
    subprocess.run(["gcc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=c_dir,
                   check=True, capture_output=True)
    pack = subprocess.run(["sh", "check/check.sh"], cwd=c_dir, capture_output=True, text=True)
    print(f"check pack exit {pack.returncode}: {(pack.stdout + pack.stderr).strip()[-300:]}", flush=True)
    test = data / pd.read_csv(data / "campaigns.csv")["file"].iloc[-1]
    with test.open("rb") as raw:
        fed = subprocess.run([str(c_dir / "stream")], stdin=raw, capture_output=True)
    got = pd.read_csv(io.BytesIO(fed.stdout)) if not fed.returncode else pd.DataFrame()
    print(f"  C fed {test.name}: exit {fed.returncode}, {len(got)} rows, columns {list(got.columns)} "
          f"{fed.stderr.decode(errors='replace').strip()[-300:]}", flush=True)


def slug(heading: str) -> str:
    """MkDocs' ``toc`` slug of a heading (Python-Markdown's default ``slugify``)."""
    import unicodedata

    text = re.sub(r"`|\*|_(?=\w*_)", "", re.sub(r"\[([^]]*)]\([^)]*\)", r"\1", heading))
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode()
    text = re.sub(r"[^\w\s-]", "", text).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


def _anchors(page: Path) -> set[str]:
    text = page.read_text()
    body = re.sub(r"```.*?```", "", text, flags=re.S)
    found = {slug(h) for h in re.findall(r"^#{1,6}\s+(.*?)\s*(?:\{#[^}]*})?\s*$", body, flags=re.M)}
    explicit = set(re.findall(r"\{#([\w-]+)}", body))
    return found | explicit | set(re.findall(r"<a (?:id|name)=\"([^\"]+)\"", body))


def docs(word: str) -> None:
    """Cell K (module doc)."""
    clone = bench_audit97.clone_of(word)
    for stamp in (".installed-core", ".installed"):
        (clone / ".venv" / stamp).touch()
    mkdocs = Path(sys.executable).parent / "mkdocs"
    (clone / ".venv/bin/mkdocs").write_text(f"#!/bin/sh\nexec {mkdocs} \"$@\"\n")
    (clone / ".venv/bin/mkdocs").chmod(0o755)
    start = time.monotonic()
    done = subprocess.run(["nice", "make", "docs"], cwd=clone, capture_output=True, text=True)
    warns = [ln for ln in (done.stdout + done.stderr).splitlines() if "WARNING" in ln]
    print(f"make docs exit {done.returncode} ({time.monotonic() - start:.0f} s), {len(warns)} WARNING lines "
          f"{warns[:5]}\n  {_said(done)}", flush=True)
    bad = []
    pages = [clone / "README.md", *sorted((clone / "docs").glob("*.md"))]
    for page in pages:
        text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", target):
                continue
            path, _, anchor = target.partition("#")
            dest = (page.parent / path).resolve() if path else page
            if not dest.exists():
                bad.append(f"{page.relative_to(clone)} -> {target}: no file")
            elif anchor and dest.suffix == ".md" and anchor not in _anchors(dest):
                bad.append(f"{page.relative_to(clone)} -> {target}: no anchor")
    print(f"links: {len(pages)} pages, {len(bad)} broken\n  " + "\n  ".join(bad[:40]), flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"diagnosed": diagnosed, "lab": lab, "machine": machine,
                                  "healthy": healthy, "docs": docs}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
