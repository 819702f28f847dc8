"""Where ``connect`` says a real gap, and stdin's blank line at midnight's step back (stop 109,
con109; issue 34 "deployed as scored").  Stop 108 left: (1) once the campaign's
``rates.StepWatch`` has a period, connect says a stretch without rows (its ``time`` event and,
on the server's clock, its ``clock_gap``) one sample after it, where the file reader names the
row after the stretch; (2) a stream on stdin (``monitor.input=-``) read a blank line before a time
of day's step back past midnight (23:59 then 00:00) as nothing, where ``stream.c`` starts a
campaign there, as the data contract says (docs/data-format.md, dep108d: "... or starts where a
blank line stands before the row").

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_con109.py gap                  # cells G1-G3 (offline, no server)
    python benchmarks/bench_con109.py blank OUT            # cells B1-B3 (a model run, its C built)

``gap``: the time steps of bench_dep108b/e's feeds (100 s rows; ``gap``: data rows 301-305 left
out, a step of 6 periods into data row 301; ``period10``: 1000 s from data row 202; ``healthy``)
and a fresh feed (37 s rows; a step of 4 periods into data row 53; 111 s from data row 140) fed
to an offline ``Connection`` (tests/conftest.py's ``offline_connection``: the client's own
``_sample``/``_step``, no server) on the server's clock (``connect.clock=server``, a vendor's)
and on a ``time`` node (the twin's); per feed what the file reader says of the same rows and,
per event connect says, its kind, the data row it names and the data row being read when it is
said.  The at-once variant (a subclass here, not in src: ``clock_gap`` and the watch's gap said
at the long step itself, once the watch has a period) is measured beside it.

``blank``: one run of 120 rows at 60 s from 23:00 (test_export_day_seconds91's ``_runs``, seed 91),
its time as ``Seconds of day`` (numbers) and as ``h:mm:ss`` (``data.time=of_day``), mlr run on it
and exported as C (this tree's export, built); fed with a blank line before data row 61
(00:00:00, midnight's step back), before data row 30 (within the run), before data row 60 (a
minute before midnight) and without one: the campaigns (rows) stdin's reader
(``stream_campaigns``) finds against the C's (its ``a new campaign starts at line`` words), and
the corrections of stdin's campaigns, each streamed from a reset (``stream_rows``, as ``monitor``
streams them), against the C's stdout; stdin's frames saved as OUT/<feed>.pkl (``same`` compares
two trees').

    python benchmarks/bench_con109.py same OUT_BASE OUT_THIS   # B3: stdin's frames, both trees

BAR (written and committed BEFORE any figure of the change below was measured; not to move after):
G1. gap feeds (seen and fresh, both routes): connect names the file reader's row (``time`` event
    ``row``; on the server's clock ``clock_gap`` ``row``) AND says it while that row is read (the
    sample it happens), its samples counted missed as BASE.
G2. period-change feeds (seen and fresh, both routes): no ``clock_gap``, 0 missed, ``time`` events
    exactly [(period changed, the reader's row)], as BASE.
G3. healthy feeds: nothing said, 0 missed.
(1) is KEPT only with a src rule meeting G1, G2 and G3 together; the at-once variant is measured
against G1 and G2 (a rule reading one row at a time sees the step, not the steps after it).
B1. blank before midnight's step back (numbers and h:mm:ss): stdin's campaigns = the C's (row
    counts; BASE: stdin [120], one); the corrections of stdin's campaigns = the C's to 1e-9 um.
B2. no blank, blank within the run, blank a minute before midnight: stdin's campaigns = the C's,
    = BASE's.
B3. stdin's frames on the B2 feeds identical to BASE's (``same``); no C source changed (the C's
    stdout is this tree's build of BASE's driver).
The test added fails on 348af997, passes here, <= 0.5 s CPU, no server, no C build.
(2) KEPT where B1-B3 hold; else REFUSED (src reverted, the rule kept as con109_rule.patch).

Harness after the bar (no rule, no figure chosen): B1's corrections compared as the C prints them
(minus what ``stream_rows`` predicts); B1 on the lag bank beside the bar's mlr (mlr reads no
state: a campaign's start changes none of its corrections, 1.33e-14 um on both trees).

SCORED (2026-12-07 ~17:50-18:02 UTC, 2 cores shared, ``nice``; BASE = 348af997's src extracted to
/tmp, this tree 32fb8c0d's; OUT apart; ``gap`` printed identically by both trees)::

  G1 gap feeds: the row named = the file reader's on every feed and route (seen 301, fresh 53),
     missed 5 / 3 as BASE; said while the row AFTER it is read (rows late 1), by BASE and here.
     The at-once variant says ``clock_gap`` at the row (late 0), the watch's ``rows missing`` still
     1 late: not met by any tree or variant.
  G2 period feeds: connect (both trees) no clock_gap, 0 missed, [(period changed, 202 / 140)] =
     the reader's, said 5 rows on: holds.  The at-once variant: 6 clock_gaps, 54 / 12 missed; its
     first-long-step form: 1 clock_gap at the change's first step, 9 / 2 missed: fails G2.
  G3 healthy: nothing, 0 missed (all): holds.
  (1): TRACED -- the sample after is the soonest a rule reading one sample at a time can tell a
     stretch from a new period's first step (G1 and G2 cannot both hold); no src change.
  B1 blank before 00:00 (numbers, h:mm:ss): the C a new campaign at line 63; stdin BASE [120],
     here [60, 60]; |stdin's corrections - C| mlr 1.33e-14 both trees; lag bank BASE 2.91 um,
     here 4e-14 um: holds.
  B2 none / within / minute_before: stdin [120] = the C's one campaign = BASE's: holds.
  B3 ``same``: the 12 B2 frames identical to BASE's (the 4 midnight ones differ: B1's mend); no C
     source changed: holds.  Test: test_stdin_of_day92 (2 cases, 0.19 s CPU) fails on 348af997
     ([48] != [30, 18]).  (2): KEPT.
CPU (user + sys, /usr/bin/time): blank 13.2 s BASE, 11.8 s here; gap 2.4 / 1.9 s (process).
"""

from __future__ import annotations

import io
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), *(str(REPO / "tests" / p) for p in ("", "base", "core", "apps", "shell"))]
from _cli import made_folder, run_commands  # noqa: E402

BLANKS = {"none": None, "midnight": 61, "within": 30, "minute_before": 60}   # before data row
CLOCKS = {"numbers": "Seconds of day", "h:mm:ss": "t"}
# (harness, after the bar: the bar's mlr reads no state, a campaign's start changes none of its
# corrections; the lag bank's state does)
MODELS = ("mlr", "lagbank")


def _feeds() -> dict[str, np.ndarray]:
    """The feeds' times (s): bench_dep108b/e's steps (100 s) and the fresh ones (37 s)."""
    def gap(period, rows, at, periods):
        t = np.arange(rows) * period
        t[at - 1:] += (periods - 1) * period
        return t

    def change(period, rows, at, to):
        t = np.arange(rows) * period
        t[at - 1:] = t[at - 2] + to * np.arange(1, rows - at + 2)
        return t

    return {"seen healthy": np.arange(325) * 100.0, "seen gap": gap(100.0, 325, 301, 6),
            "seen period10": change(100.0, 325, 202, 1000.0),
            "fresh healthy": np.arange(200) * 37.0, "fresh gap": gap(37.0, 200, 53, 4),
            "fresh period": change(37.0, 200, 140, 111.0)}


def _file_said(times: np.ndarray) -> list:
    from test_opcua67 import file_said

    return file_said(pd.DataFrame({"time": times}))


def _at_once(first: bool = False):
    """The at-once variant (module doc): a Connection whose ``clock_gap``, once the watch has a
    period, is said at the long step itself (``first``: a long step after a long one not said,
    its one sample taken: the least it could say at a period change)."""
    from thermocomp.apps.machine.client import Connection

    class AtOnce(Connection):
        long_before = False

        def _clock_gap(self, gap, steps):
            period = self._clock_period()
            long = gap >= 1.5 * period
            again, self.long_before = first and long and self.long_before, long
            if not long or again:
                return steps if not long else 1
            paused = gap > 100 * period
            self._said_gap(gap, steps, period, paused, self._last, self._rows + 1)
            return 1 if paused else steps

    return AtOnce


def _connected(times: np.ndarray, period: float, route: str, kind=None) -> tuple[list, int]:
    """``([(event, row named, row being read)], missed)`` of ``times`` fed to an offline
    connection on ``route`` (``server``: its clock; ``node``: a time node)."""
    from datetime import datetime, timedelta, timezone

    from asyncua import ua

    from conftest import NoLimiter, ZeroStream
    from thermocomp.apps.machine.client import Connection, _Plan

    epoch = datetime(2026, 3, 2, 6, 0, tzinfo=timezone.utc)
    plan = _Plan(inputs=[object(), None], labels=["T_a", "time"], status={}, clock=object(),
                 offsets=[], types=[], answered=None, watched=[], registers=np.zeros(0))
    conn = (kind or Connection)(ZeroStream(), None, "opc.tcp://127.0.0.1:1", NoLimiter(),
                                clock="server" if route == "server" else "node", period_s=period)
    said = []
    for r, s in enumerate(times):
        n = len(conn.events)
        if route == "server":
            got = conn._sample(plan, [ua.DataValue(ua.Variant(20.0, ua.VariantType.Float)),
                                      ua.DataValue(ua.Variant(epoch + timedelta(seconds=float(s))))])
        else:
            got = ("P1.MPF", [20.0, float(s)], r, r)
        if got is not None:
            conn._step(*got)
        said += [(e.get("to") or e["event"], e.get("row"), r + 1) for e in conn.events[n:]
                 if e["event"] in ("time", "clock_gap")]
    return said, conn.missed


def gap() -> None:
    """Cells G1-G3 (module doc)."""
    for name, times in _feeds().items():
        period = float(np.median(np.diff(times[:11])))
        print(f"{name}: file reader {_file_said(times)}", flush=True)
        for route in ("server", "node"):
            for label, kind in (("connect", None), ("at-once variant", _at_once()),
                                ("at-once, first long step only", _at_once(first=True))):
                if label != "connect" and route == "node":
                    continue
                said, missed = _connected(times, period, route, kind)
                late = [r - row for _, row, r in said if row is not None]
                print(f"    {route} {label}: said (kind, row named, row read) {said}; missed "
                      f"{missed}; rows late {late}", flush=True)


def _record(folder: Path, clock: str) -> tuple[list[str], Path]:
    """One run from 23:00, its time under ``clock`` (numbers or h:mm:ss): its data words."""
    import test_export_day_seconds91 as d

    folder.mkdir(parents=True, exist_ok=True)
    path = d._runs(folder / "night.csv", [23])
    if clock == "h:mm:ss":
        frame = pd.read_csv(path)
        s = frame.pop("Seconds of day").astype(int)
        frame.insert(0, "t", [f"{v // 3600}:{v // 60 % 60:02d}:{v % 60:02d}" for v in s])
        frame.to_csv(path, index=False)
    return [f"data.path={path}", "data.time=of_day", "data.test_fraction=0.34"], path


def _built(folder: Path, data: list[str], model: str) -> Path:
    """test_export_day_seconds91's ``_built`` of ``model`` (its light run's words): the C's folder."""
    import test_export_day_seconds91 as d
    from cbuild import compiled
    from thermocomp.shell.cli import main

    assert main(["run", *data, f"model={model}", *d.LIGHT[1:], f"out={folder / 'run'}"]) == 0
    code = folder / "c"
    assert main(["export", *data, f"export.model={folder / 'run' / 'model.pkl'}",
                 "export.format=c", "export.check=false", f"out={code}"]) == 0
    compiled(code)
    return code


def blank(out: str) -> None:
    """Cells B1, B2 (module doc); stdin's frames saved for B3."""
    from omegaconf import OmegaConf

    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.core.io import ReadOptions
    from thermocomp.core.io.stdin import stream_campaigns
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.cli import _compose
    from thermocomp.shell.source import read_streamed

    scratch = made_folder(out)
    for model, clock in ((m, c) for m in MODELS for c in CLOCKS):
        folder = scratch / model / clock.replace(":", "")
        data, path = _record(folder, clock)
        code = _built(folder, data, model)
        pkl = folder / "run" / "model.pkl"
        cfg = _compose([*data, f"connect.model={pkl}", "track=false", "monitor.adaptive=false"],
                       "connect")
        ds, train = read_streamed(cfg, test=False)[:2]
        deployed = deployable_model(cfg, ds, train, str(pkl), "connect.model")[0]
        opts = ReadOptions.from_cfg(OmegaConf.to_container(cfg.data, resolve=True))
        lines = path.read_text().splitlines()
        for feed, k in BLANKS.items():
            body = lines if k is None else [*lines[:k], "", *lines[k:]]
            text = "\n".join(body) + "\n"
            fed = subprocess.run(["./stream"], cwd=code, input=text, capture_output=True, text=True)
            c = pd.read_csv(io.StringIO(fed.stdout)).filter(like="C_").to_numpy(float)
            starts = [ln.split("starts at line ")[1].split()[0] for ln in fed.stderr.splitlines()
                      if "a new campaign starts at line" in ln]
            parts, _ = stream_campaigns(text, list(deployed.columns_), opts)
            (scratch / f"{model}-{clock.replace(':', '')}-{feed}.pkl").write_bytes(pickle.dumps(parts))
            # (the C prints corrections: minus the errors stream_rows predicts)
            ys = -np.vstack([stream_rows(deployed, p.reset_index(drop=True)).y for p in parts.values()])
            gap_um = float(np.abs(ys - c).max()) if ys.shape == c.shape else float("nan")
            print(f"{model} {clock} [{feed}]: C exit {fed.returncode}, {len(c)} rows, new campaign "
                  f"at line(s) {starts}; stdin's campaigns {[len(p) for p in parts.values()]}; max |stdin's "
                  f"corrections - C| {gap_um:.3g} um", flush=True)


def same(base: str, this: str) -> None:
    """Cell B3: stdin's frames of each feed, this tree's against BASE's."""
    for path in sorted(Path(this).glob("*.pkl")):
        b, t = (pickle.loads(p.read_bytes()) for p in (Path(base) / path.name, path))
        equal = list(b) == list(t) and all(b[k].equals(t[k]) for k in b)
        print(f"{path.stem}: campaigns base {[len(p) for p in b.values()]}, this "
              f"{[len(p) for p in t.values()]}; frames identical {equal}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"gap": gap, "blank": blank, "same": same}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
