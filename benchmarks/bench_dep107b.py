"""What dep107 left at the deployed seams (stop 107, dep107b; issue 34).

Three seams dep107 (bench_dep107.py) named and left:
1. ``stream.c --state`` with a time-of-day clock (TC_DAY_SECONDS): the days added so far
   (``day_added``) are not in the state file.  A stream cut after midnight and restarted from its
   state against the uninterrupted stream and the served session.
2. a stray blank line within a run: stream.c restarts a campaign there (said), served's stdin
   (``monitor.input=-``) and replay's file read ignore it (dep107: 28.6 / 32.6 um off after it).
   One rule for the three readers, from the data contract (docs/data-format.md,
   docs/to-the-machine.md's rows).
3. connect's offset rate limiter on a plain model, where served and the C apply none (dep107:
   10131 rows 998-1000, 0.316 um): on how many rows it binds on the lab records.

BAR (committed before anything new is run; not to move after):
  B1. item 1: on day-clock records (tests/shell/test_export_day_seconds91's: seconds of day, runs
      across a pause over midnight; h:mm:ss, one run over midnight) the C cut by ``--state`` at
      every data row after midnight against the C uninterrupted: max |difference| (um) over the
      rows after the cut; and against the served session.  A difference > 1e-9 um is a break:
      mended (a failing cheap test, the mend; old state files refused or read as today).
  B2. item 2: one rule for the three readers, decided from the data contract; after it the C and
      served's stdin agree on the 10118 / 10131 cases (a stray blank line at data row 450, and
      ``thermocomp rows``' two campaigns) to <= 1e-9 um, and replay reads the file as they do (or
      the part that cannot agree named with the reason and a measured number).
  B3. item 3: the rows on which connect's limiter binds (plain model) on lab 10118, 10131, 10132,
      counted; the decision (a named machine-side safety in the docs, or removed) from the docs'
      account of the limiter.
  B4. neighbours (dep107's 73 modules: stdin, monitor.input=-, connect) pass; ruff clean.
  Seeds: none new (10118, 10131, 10132 seen: dep107's roots in /tmp/dep107/roots reused).
  Verdict: KEPT where B1-B4 hold with a src change; TRACED where nothing breaks.

SCORED (bar 7a664d42, not moved; 2026-12-07 12:20-12:45 UTC, 2 cores shared with the neighbours'
run; no new seed: dep107's lab roots copied to /tmp/dep107b/roots, the day records made here).
  1. day (``day ROOT mlr|lagbank``): on f7b4121a (p1 probe, same records) the C cut after every
     line (359 / 119 cuts; as written, a stray blank line at data row 90, at row 120) = the C
     uninterrupted to 0 um, mlr and lag bank: the days came back from the last time read (the
     restore's ``day_last = t_read``).  With item 2's rule a pending blank line at the cut past
     midnight read the days as the clock going back: lag bank hms1 4.55 um after the cut (line
     90).  Mended: the state (mark tcstat2) carries day_last / day_added; now 0 um at every cut,
     both models, both records, three variants.  C vs served (one session): hms1 1.3e-14 (mlr) /
     5.9e-14 um (lagbank); seconds3 2.16 / 2.15 um -- the served session fed a numeric Seconds of
     day in one block does not read the pause across midnight (22:00 -> 01:00) as a pause (run 2
     on run 1's state; C = served per run from a reset to 8.9e-16 um): named, the served's.
  2. blank (``blank ROOT 10118|10131``): one rule (stream.c, stdin, the file read): a blank line
     is nothing where the next row's time goes on, a campaign where it is not after the last (or
     none; a time of day gone back); ``thermocomp rows`` writes each block from time 0.  A stray
     blank line at data row 450: |C - served| after it 4.97e-14 / 3.55e-14 um (f7b4121a: 35.7 /
     28.6 um, dep107's); stdin reads the file as ['stdin_1', 'stdin_2'] (900, 361 rows) as
     without it; rows: 2 campaigns each, |C - served| 4.97e-14 / 3.55e-14 um.  (bench_dep107's
     seam-4 line still says "the C restarts": its words, not this tree's.)
  3. limiter (``limiter ROOT SEED``): binds on 0 (10118), 3 (10131: rows 998-1000, 0.316 um),
     0 (10132) of 1261 rows; = dep107's connect offsets to 4.0e-5 / 6.1e-5 um (float32 nodes).
     Decision: kept, a machine-side safety (the docs' account: "what may reach the machine"),
     named in docs/to-the-machine.md with the counts.
  CPU (user + sys, /usr/bin/time): day mlr 22.6+21.7 s, lagbank 21.0+20.9 s (2 x 1800 C
  processes); blank 9.7+1.1 / 9.2+1.0 s; limiter 4.2+0.5 s (10131).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep107b.py day ROOT MODEL        # 1: the day clock cut by --state
    python benchmarks/bench_dep107b.py blank ROOT SEED       # 2: rows' blocks, a stray blank line
    python benchmarks/bench_dep107b.py limiter ROOT SEED     # 3: where connect's limiter binds

``day``: tests/shell/test_export_day_seconds91's records (``seconds3``: three runs of Seconds of
day, 20:00, 01:00 the next day, 10:30, data.runs_at_pauses; ``hms1``: one h:mm:ss run from
23:00, data.time=of_day), MODEL (mlr, lagbank) run and exported as C; each as written, with a
stray blank line at data row 90 and at the run's end (row 120); the C cut after every line,
``--state`` carrying it to a fresh process, against the C uninterrupted, and the C against the
served session (the plain model, one session).  ``blank`` and ``limiter``: lab SEED's export as
bench_dep107's ``lab`` makes it (its ROOT reused where it is on disk), the adaptive model's C of
this tree; ``blank``: bench_dep107's seam 4 (``thermocomp rows`` to the C and to stdin's reader;
a stray blank line at data row 450, C against served) and the campaigns stdin's reader finds in
the stray file; ``limiter``: connect's OffsetLimiter (``offset_limiter`` of the plain model and
its guard, as connect builds them) fed the plain served corrections row by row, a new campaign
after a pause longer than the model's ``pause_s_``: the rows where what it writes differs from
the correction (> 1e-9 um), against the offsets dep107's connect wrote where they are on disk.
"""

from __future__ import annotations

import io
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests"), str(REPO / "tests" / "shell")]
from _cli import run_commands  # noqa: E402

BLANK_AT = (90, 120)            # day: data rows a stray blank line goes above (in a run; a run's end)


def _day_records(root: Path) -> dict:
    import test_export_day_seconds91 as day

    record = day._runs(root / "week.csv", [20, 25, 34.5])
    (root / "hms").mkdir(exist_ok=True)
    frame = pd.read_csv(day._runs(root / "hms" / "week.csv", [23]))
    seconds = frame.pop("Seconds of day").astype(int)
    frame.insert(0, "t", [f"{v // 3600}:{v // 60 % 60:02d}:{v % 60:02d}" for v in seconds])
    frame.to_csv(root / "hms" / "week.csv", index=False)
    return {"seconds3": ([f"data.path={record}", "data.runs_at_pauses=true", "data.test_fraction=0.34"],
                         record),
            "hms1": ([f"data.path={root / 'hms' / 'week.csv'}", "data.time=of_day",
                      "data.test_fraction=0.34"], root / "hms" / "week.csv")}


def _fed(stream: Path, header: str, rows: list[str], *args: str):
    done = subprocess.run([str(stream), *args], input="\n".join([header, *rows]) + "\n",
                          capture_output=True, text=True)
    out = pd.read_csv(io.StringIO(done.stdout)).to_numpy(float) if done.stdout.strip() else np.zeros((0, 1))
    return done.returncode, out, done.stderr


def _served_csv(deployed, header: str, rows: list[str]) -> np.ndarray:
    """The plain served session's corrections of a CSV's ``rows`` (one session from a reset)."""
    from thermocomp.apps.deploy.pyfunc import CompensatorModel

    frame = pd.read_csv(io.StringIO("\n".join([header, *rows]) + "\n"), dtype={"t": str})
    out = CompensatorModel(deployed).predict(None, frame.drop(columns=["E_X"]),
                                             {"session": "s", "reset": True})
    return out.filter(like="C_").to_numpy(float)


def day(root: str, model: str) -> None:
    """Cell day (module doc)."""
    import bench_dep107

    import cbuild
    import test_export_day_seconds91 as d
    from thermocomp.shell.cli import main

    base = Path(root).resolve() / f"day-{model}"
    base.mkdir(parents=True, exist_ok=True)
    for name, (data, path) in _day_records(base).items():
        folder = base / name
        light = [f"model={model}", *d.LIGHT[1:]]
        if not (folder / "run" / "model.pkl").exists():
            assert main(["run", *data, *light, f"out={folder / 'run'}"]) == 0
        code = folder / "c"
        if not (code / "stream").exists():
            assert main(["export", *data, f"export.model={folder / 'run' / 'model.pkl'}",
                         "export.format=c", "export.check=false", f"out={code}"]) == 0
            cbuild.compiled(code)
        served_model = bench_dep107._deployed(data, folder / "run" / "model.pkl", "monitor.adaptive=false")
        lines = path.read_text().splitlines()
        header, plain = lines[0], lines[1:]
        for k in (None, *BLANK_AT):
            body = plain if k is None else [*plain[:k], "", *plain[k:]]
            code_, whole, said = _fed(code / "stream", header, body)
            worst, where, cuts = 0.0, None, 0
            for cut in range(len(body) - 1):
                if body[cut + 1] == "":
                    continue
                state = folder / "cut.state"
                state.unlink(missing_ok=True)
                _fed(code / "stream", header, body[:cut + 1], "--state", str(state))
                exit_, rest, _ = _fed(code / "stream", header, body[cut + 1:], "--state", str(state))
                done = sum(1 for ln in body[:cut + 1] if ln)
                gap = np.abs(rest - whole[done:]).max() if exit_ == 0 and len(rest) else math.inf
                cuts += 1
                if gap > worst:
                    worst, where = gap, cut
            served = _served_csv(served_model, header, [ln for ln in body if ln])
            blank = [ln[:90] for ln in said.splitlines() if "blank" in ln]
            print(f"1. {model} {name} blank {k}: {len(whole)} rows, C exit {code_}; cut at {cuts} lines: "
                  f"max|cut - whole| {worst:.3g} um{'' if where is None else f' (after line {where})'}; "
                  f"|C - served (one session)| {np.abs(whole - served).max():.3g} um; said {blank}",
                  flush=True)


def _lab(root: str, seed: str):
    """bench_dep107's lab (its ROOT reused): ``(base, search, pkl, adaptive C's stream, tsv)``."""
    import bench_audit91
    import bench_audit106
    import bench_dep107

    import cbuild

    base = bench_audit91.lab_root(root, seed)
    bench_audit106.write_export(base, int(seed))
    tsv = base / "once.tsv"
    init = base / "once-init"
    if not init.exists():
        assert bench_dep107._cli("init", str(tsv), f"out={init}").returncode == 0
    conf = next((init / "conf" / "data").glob("*.yaml"))
    search = [f"hydra.searchpath=[file://{init / 'conf'}]", f"data={conf.stem}"]
    pkl = base / "run" / "model.pkl"
    if not pkl.exists():
        assert bench_dep107._cli("run", *search, "model=mlr", f"out={pkl.parent}", "track=false",
                                 "plots=none").returncode == 0
    adaptive = bench_dep107._deployed(search, pkl)
    code = base / "code-adaptive-dep107b"
    if not (code / "stream").exists():
        from thermocomp.apps.deploy.pyfunc import save_compensator

        folder = base / "registered-adaptive"
        if not folder.exists():
            save_compensator(adaptive, folder)
        done = bench_dep107._cli("export", f"export.model={folder}", "export.format=c",
                                 "export.check=false", "track=false", f"out={code}")
        assert done.returncode == 0, done.stderr[-400:]
        cbuild.compiled(code)
    return base, search, pkl, adaptive, code / "stream", tsv


def blank(root: str, seed: str) -> None:
    """Cell blank (module doc)."""
    import bench_dep107
    from omegaconf import OmegaConf

    from thermocomp.core.io import ReadOptions
    from thermocomp.core.io.stdin import stream_campaigns
    from thermocomp.shell.cli import _compose

    base, search, _, adaptive, stream, tsv = _lab(root, seed)
    data = OmegaConf.to_container(_compose([*search, "track=false"], "connect").data, resolve=True)
    lines = tsv.read_text(encoding="utf-8").splitlines()
    header, body = lines[0], lines[1:]
    errors = [c for c in header.split("\t") if c.split(" [")[0] in ("dX", "dY")]
    print(f"lab{seed}: {len(body)} rows, errors {errors}", flush=True)
    bench_dep107._seam4(base, search, adaptive, stream, tsv, header, body, errors)
    k = bench_dep107.ROWS_AT[0]
    text = "\n".join([header, *body[:k], "", *body[k:]]) + "\n"
    parts, _ = stream_campaigns(text, list(adaptive.columns_), ReadOptions.from_cfg(data))
    print(f"2. the stray blank line's file on stdin: {list(parts)} ({[len(p) for p in parts.values()]} "
          f"rows), as without it", flush=True)


def limiter(root: str, seed: str) -> None:
    """Cell limiter (module doc)."""
    import bench_audit106
    import bench_dep107

    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.cli import _compose
    from thermocomp.shell.source import read_streamed
    from thermocomp.shell.stages.connect import _guard, offset_limiter

    base, search, pkl, _, _, tsv = _lab(root, seed)
    cfg = _compose([*search, f"connect.model={pkl}", "track=false", "monitor.adaptive=false"], "connect")
    ds, train_ids = read_streamed(cfg, test=False)[:2]
    plain = deployable_model(cfg, ds, train_ids, str(pkl), "connect.model")[0]
    guard = _guard(cfg, plain, ds, train_ids)
    limit = offset_limiter(plain, guard, float(cfg.connect.hold_s), float(cfg.connect.decay_s))
    lines = tsv.read_text(encoding="utf-8").splitlines()
    header, body = lines[0], lines[1:]
    read = [bench_audit106._export_name(c).split(" [")[0] for c in plain.columns_]
    left = [c for c in header.split("\t")[1:] if c.split(" [")[0] not in read]
    corrections = bench_dep107._served(plain, header, [body], left)[0]
    stamps = pd.to_datetime(pd.read_csv(tsv, sep="\t", dtype=str)["Timestamp"], utc=True, format="ISO8601")
    step = np.r_[math.nan, np.diff((stamps - stamps.iloc[0]).dt.total_seconds().to_numpy())]
    pause = float(getattr(plain, "pause_s_", 0.0) or 0.0)
    written = np.zeros_like(corrections)
    limit.new_campaign()
    for i, c in enumerate(corrections):
        s = step[i]
        if pause and s > pause:
            limit.new_campaign()
            s = math.nan
        written[i] = -limit.fresh(-c, float(i), s)
    gap = np.abs(written - corrections).max(axis=1)
    binds = np.flatnonzero(gap > 1e-9)
    print(f"3. lab{seed}: {len(body)} rows, guard rate {np.round(guard.max_rate_per_s, 4)} um/s per "
          f"{guard.period_s:g} s; the limiter binds on {len(binds)} rows {binds[:10].tolist()}: max "
          f"|written - correction| {gap.max():.3g} um; largest step of the correction "
          f"{np.abs(np.diff(corrections, axis=0)).max():.3g} um", flush=True)
    done = base / "connect-offsets.npy"
    if done.exists():
        wrote = np.load(done)[:bench_dep107.ROWS_AT[-1]]
        print(f"3. lab{seed}: against dep107's connect (rows before its Bad one): max |this - connect| "
              f"{np.abs(-written[:len(wrote)] - wrote).max():.3g} um", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"day": day, "blank": blank, "limiter": limiter}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
