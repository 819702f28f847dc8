"""The served model over midnight fed a time of day as plain seconds (stop 108, dep108d; issue 34
"deployed as scored").  dep107b (bench_dep107b.py ``day``) named, not mended: a served session
fed numeric ``Seconds of day`` does not read the pause across midnight (22:00 -> 01:00) as the
C (``TC_DAY_SECONDS``, stream.c's ``of_day``) and the file reader (``timestamps.seconds_of_day``)
do: 2.16 um off the C (mlr), the C = served per run from a reset to 8.9e-16 um.

BAR (committed before the change is measured; not to move after):
  B1. the named case (bench_dep107b's ``seconds3``: three runs of Seconds of day from 20:00,
      01:00 the next day, 10:30; data.runs_at_pauses), mlr and lagbank, as written and with a
      stray blank line at data row 90 / 120: |served - C| <= 1e-9 um on every row, the served
      session fed as one block and as blocks of 40 rows.
  B2. every other feed unchanged: bench_dep107b's ``hms1`` (h:mm:ss, one run from 23:00) and
      bench_dep107c's feeds (``faults``: healthy, period10, gap, comma; mlr-none, lagbank-none):
      the served corrections identical to BASE (4f56cd99) to 1e-12 um.
  B3. the C's stdout byte-identical to BASE's on every feed here and in bench_dep107c.
  B4. stdin (``monitor.input=-``'s reader, ``stream_campaigns``) and the file reader read the
      named record as the same campaigns (row counts) as the C; said as measured.
  B5. a test of the mend, <= ~2 s CPU, reusing test_export_day_seconds91's fixture, failing on
      4f56cd99.
  Seeds: none (test_export_day_seconds91's records are seeded already, 91).
  Verdict: KEPT where B1-B5 hold with a src change; REFUSED (src reverted, the rule kept as
  benchmarks/dep108d_rule.patch) where not.

SCORED (bar 40f0ac01, not moved; 2026-12-07 15:25-15:40 UTC, 2 cores shared; BASE = 4f56cd99's src
extracted to /tmp, this tree 829e8879; ROOTs apart, each tree running, exporting and building its own):
  B1 seconds3, every variant (plain, blank90, blank120): max |served - C| BASE 2.16 (mlr) / 2.15 um
     (lagbank), 120 rows > 1e-9 (run 2, joined to run 1); now 8.88e-16 / 1.6e-14 um, one block and
     blocks of 40: holds.
  B2 hms1 served = BASE exactly (0 um, 12 arrays); bench_dep107c faults /tmp/a107/root: the 12 served
     arrays (healthy, period10, gap x one block / 50) = BASE exactly (0 um); its words unchanged
     (but the OUT paths): holds.  (seconds3's served differ from BASE by 2.16 / 2.15 um: B1's mend.)
  B3 the C's stdout byte-identical to BASE's: 12 feeds here, 8 in bench_dep107c: holds.
  B4 stdin's campaigns of seconds3: BASE [240, 120] (blank120: [120, 120, 120]); now [120, 120, 120]
     every variant, as the file reader's 3 runs and the C's; hms1 [120] both: holds.
  B5 test_export_day_seconds91's served/stdin test: fails on 4f56cd99 (2.16 um), passes here; +1.5 /
     +1.6 s CPU (paired, the module's fixture test alone vs with it).  Verdict: KEPT.
  CPU (user + sys, /usr/bin/time): day mlr 9.9 + 1.3 s, lagbank 10.0 + 1.3 s (BASE 9.3 + 1.8, 9.8 + 1.8).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep108d.py day ROOT MODEL       # B1-B4 on the day records
    python benchmarks/bench_dep108d.py same BASE_DIR NEW_DIR  # B2/B3: *.npy to 1e-12, *.out bytes

``day``: bench_dep107b's records under ROOT/day-MODEL, the model run and exported as C (this
tree's export), the served (plain) model fed each variant; the served corrections saved as
``served-<name>-<variant>-<block>.npy`` and the C's stdout as ``c-<name>-<variant>.out`` in
ROOT/day-MODEL/out (``same`` compares two such folders, or two bench_dep107c OUTs).
"""

from __future__ import annotations

import hashlib
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

BLANK_AT = (90, 120)       # bench_dep107b's stray blank lines (data rows)
BLOCK = 40                 # rows of a block where the session is fed in blocks


def _served(deployed, header: str, rows: list[str], block: int | None) -> np.ndarray:
    """The plain served session's corrections of a CSV's ``rows``, one session from a reset, as
    one block (``block`` None) or blocks of ``block`` rows."""
    from thermocomp.apps.deploy.pyfunc import CompensatorModel

    frame = pd.read_csv(io.StringIO("\n".join([header, *rows]) + "\n"), dtype={"t": str})
    frame = frame.drop(columns=["E_X"])
    model, step = CompensatorModel(deployed), block or len(frame)
    outs = [model.predict(None, frame.iloc[k:k + step].reset_index(drop=True),
                          {"session": "s", "reset": k == 0}) for k in range(0, len(frame), step)]
    return pd.concat(outs, ignore_index=True).filter(like="C_").to_numpy(float)


def _campaign_rows(text: str, deployed, data: list[str]) -> list[int]:
    """The rows of each campaign stdin's reader (``stream_campaigns``) finds in ``text``."""
    from omegaconf import OmegaConf

    from thermocomp.core.io import ReadOptions
    from thermocomp.core.io.stdin import stream_campaigns
    from thermocomp.shell.cli import _compose

    cfg = OmegaConf.to_container(_compose([*data, "track=false"], "connect").data, resolve=True)
    parts, _ = stream_campaigns(text, list(deployed.columns_), ReadOptions.from_cfg(cfg))
    return [len(p) for p in parts.values()]


def day(root: str, model: str) -> None:
    """Cell day (module doc)."""
    import bench_dep107
    import bench_dep107b

    import cbuild
    import test_export_day_seconds91 as d
    from thermocomp.shell.cli import main

    base = Path(root).resolve() / f"day-{model}"
    out = base / "out"
    out.mkdir(parents=True, exist_ok=True)
    for name, (data, path) in bench_dep107b._day_records(base).items():
        folder = base / name
        if not (folder / "run" / "model.pkl").exists():
            assert main(["run", *data, f"model={model}", *d.LIGHT[1:], f"out={folder / 'run'}"]) == 0
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
            text = "\n".join([header, *body]) + "\n"
            fed = subprocess.run([str(code / "stream")], input=text, capture_output=True, text=True)
            variant = "plain" if k is None else f"blank{k}"
            (out / f"c-{name}-{variant}.out").write_text(fed.stdout)
            whole = pd.read_csv(io.StringIO(fed.stdout)).to_numpy(float)
            rows = [ln for ln in body if ln]
            gaps = []
            for block in (None, BLOCK):
                served = _served(served_model, header, rows, block)
                np.save(out / f"served-{name}-{variant}-{block or 'one'}.npy", served)
                gaps.append(np.abs(whole - served).max(axis=1))
            worst = max(g.max() for g in gaps)
            off = int(np.count_nonzero(gaps[0] > 1e-9))
            stdin = _campaign_rows(text, served_model, data)
            print(f"B1 {model} {name} {variant}: {len(whole)} rows, C exit {fed.returncode} "
                  f"(sha256 {hashlib.sha256(fed.stdout.encode()).hexdigest()[:12]}); max |served - C| "
                  f"one block {gaps[0].max():.3g} um ({off} rows > 1e-9), blocks of {BLOCK} "
                  f"{gaps[1].max():.3g} um: {'holds' if worst <= 1e-9 else 'FAILS'}; stdin's "
                  f"campaigns {stdin}", flush=True)


def same(old: str, new: str) -> None:
    """Cell same (module doc): every ``*.npy`` and ``*.out`` under ``old`` against ``new``'s."""
    old_dir, new_dir = Path(old), Path(new)
    for path in sorted(old_dir.rglob("*")):
        if path.suffix not in (".npy", ".out"):
            continue
        other = new_dir / path.relative_to(old_dir)
        if not other.exists():
            print(f"{path.relative_to(old_dir)}: missing in {new}")
        elif path.suffix == ".out":
            print(f"B3 {path.relative_to(old_dir)}: "
                  f"{'byte-identical' if path.read_bytes() == other.read_bytes() else 'DIFFERS'}")
        else:
            a, b = np.load(path), np.load(other)
            gap = np.abs(a - b).max() if a.shape == b.shape and a.size else (0.0 if a.shape == b.shape
                                                                              else np.inf)
            print(f"B2 {path.relative_to(old_dir)}: max |new - base| {gap:.3g} um "
                  f"{'(<= 1e-12)' if gap <= 1e-12 else 'DIFFERS'}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"day": day, "same": same}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
