"""The C 11.5 um off replay where the air sensor is beyond range from a campaign's first sample
(dep108, issue 34 "deployed as scored").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep108.py score ROOT DATA COLUMN PUSH MODE BASESRC
    python benchmarks/bench_dep108.py healthy ROOT BASESRC RECORD [RECORD ...]

``score``: ROOT a bench_diag107b ``chain`` root (or bench_st107b ``plain``), DATA its record; the
test campaigns with COLUMN changed (bench_st107b's MODEs ``all`` / ``step`` / ``ramp``, and
``back``: +PUSH on the first third of each campaign, read as recorded after it); ``replay`` of the
model deployed as ``export`` deploys it, against the C (``stream --flags``, cc -O2) exported by the
tree (in this process) and by BASESRC (a ``git archive`` of BASE's src, in a child), and the
tree's JSON reference (``Simulator``, the mirror).  Printed per C: max |C - replay|, the rows
flagged ``mon_not_in_code``, the rows before a campaign's first flag with |C - replay| > 1e-9 um,
and the rows where the tree's C is further from replay than BASE's by > 1e-9 um.  ``healthy``:
records as bench_cmon92's ``made`` makes them (bench_st105's :data:`MADE_BY`), each one's first
test campaign with its lead-in (``faulted_cell``'s frame, no fault) streamed through BASE's and the
tree's C: stdout (``--flags``) byte-identical or not, and whether any monitored reading is beyond
its range at the stream's first sample (where the rule acts).

TRACE (BASE = 0dd05741, before any rule; ``bench_st107b.py room`` + ``bench_diag107b.py chain``
in /tmp/dep108/droot: ``ambient_scaled`` on E_X; T_amb +30 on every row): the C 11.5 um off replay,
flagged ``TC_MON_NOT_IN_CODE`` (RANGE) on each campaign's first row.  Why: the lean law's factor
is ``A0 - 20``.  Replay (served, adaptive.py ``_inputs``): the monitor takes no reference of a
reading beyond its range (``_ref`` NaN); the model reads ``_base + clean`` with ``_base`` the
monitor's ``first_c`` (the mean first reading of that sensor in training) and ``clean`` its rebuild
from the others (0 at the first sample, all at their reference), so the stream's ``ambient_c0`` is
``first_c`` = 23.134 degC on every campaign (traced: C03 C06 C09 C12).  The C: ``mon_sample``
references the reading as read and passes it on at the first sample, so its A0 is the
out-of-range reading itself, 49.4 / 54.7 / 53.9 / 51.3 degC; after it both rebuild T_amb from the
others on the same deviations (the plain MLR, no A0 law: C = replay to 7.1e-15).  Not the
manifest's ``ambient_c``, not the next valid sample: the served model's stand-in.  Replay's choice
is kept: an air reading 30 degC beyond its range is no room's ambient (the C's law read 26-31 degC
of A0 that no campaign had); the training's first reading is the served prior.

RULE (src: watch_c.py, watch.py, the mirror in step; the served model unchanged).  At a campaign's
first sample a monitored reading beyond its range is the served stand-in: the model reads
``MON_FIRST_C`` (exported as the monitor's ``first_c``) plus the rebuild, so the campaign's A0 and
the model's reference are replay's; no flag there.  Where that sensor reads within its range again
the served monitor references it late (not in the code): ``TC_MON_NOT_IN_CODE`` (RANGE) on that
row, as before at the first.  An export before it (no ``late`` key) as before.

BAR (committed before the rule is measured and before fresh 10186-10188 are simulated; not moved
after).  BASE = 0dd05741's src (``git archive``), RULE = this branch's src.

* B1 seen (diag107's room, the chain's ``ambient_scaled`` model), MODE ``all`` T_amb +30: RULE's
  |C - replay| <= 1e-9 um on every one of the 480 test rows (BASE 11.5 um), no row flagged
  ``mon_not_in_code`` by RULE's C; the JSON reference = RULE's C to 1e-9 um.  MODE ``back`` T_amb
  +30: RULE's C flags ``mon_not_in_code`` first at the row the air returns (not before), and
  |C - replay| <= 1e-9 um on every row before it.
* B2 fresh 10186, 10187, 10188 (each ``bench_st107b.py simulate DATA SEED room`` once, then
  ``bench_diag107b.py chain``), each scored in all three of bench_st107b's kinds, named now: T_amb
  ``all`` +30 (out from row 0), ``step`` +30, ``ramp`` +10.  ``all``: as B1 (<= 1e-9 um on every
  row, no ``mon_not_in_code`` row; whether diagnose took a lean law or not, said).  ``step`` /
  ``ramp``: no row where RULE's |C - replay| > BASE's + 1e-9 um.
* B3 no other case worse: bench_st107b's seen root (chain, ``ambient_scaled``): ``step`` +30,
  ``ramp`` +10, ``step`` +5 of T_amb, no row where RULE's |C - replay| > BASE's + 1e-9 um; the
  healthy records lr/dl 9964-9967 (bench_st105 ``healthy``'s) and bench_st107's seen records
  (dl9975 lr9985 dl9964 lr9964 lr9966 lr9967 dl9966 dl10007 lr10007 lr10008): C stdout
  (``--flags``) byte-identical to BASE's.
* B4 a test (<= ~3 s CPU, an export test's fixture, the C via tests/cbuild.py) that fails on BASE;
  the neighbours of watch.py / watch_c.py pass.  A clause not measured by 15:35 UTC is not met.
* KEPT where B1-B4 hold; else REFUSED (src back at BASE, the rule in benchmarks/dep108_rule.patch).

SCORED (2026-12-07, the bar 3f1fdd72 unchanged; BASE /tmp/dep108/basesrc = ``git archive 0dd05741
src``; CPU user + sys of the bench with its children, ``/usr/bin/time``; load 10-12 on 2 cores):

* B1 met.  ``all`` +30: BASE 11.5 um, 4 flag rows (each campaign's row 0); RULE 7.1e-15 um on all
  480 rows, 0 flag rows; |JSON - C| 7.1e-15.  ``back`` +30 (rows 0-39): RULE flags first at row 40
  in each campaign (the return), 0 rows > 1e-9 um before it (max after 0.064 um; BASE 11.5).
* B2 met.  Fresh 10186 / 10187 / 10188 simulated once (room) and chained: diagnose took a lean law
  on E_X and E_Z / E_Z only (E_X nothing) / E_X and E_Z.  ``all`` +30: BASE 33.2 / 29.3 / 33.4 um,
  RULE 2.1e-14 / 1.8e-14 / 1.4e-14 um on 2161 / 2212 / 2204 rows, 0 flag rows.  ``step`` +30 and
  ``ramp`` +10: stdout identical to BASE, 0 rows worse.  ~12.5 s CPU a score.
* B3 met.  Seen room ``step`` +30, ``ramp`` +10, ``step`` +5: stdout identical, 0 rows worse.
  ``healthy`` lr/dl 9964-9967, dl9975 lr9985 dl10007 lr10007 lr10008 (13 records, 113 + 7 s CPU):
  no monitored reading beyond range at the first sample, C stdout byte-identical on each.
* The ST on this case (not this task): the block flags ``RANGE`` on T_amb and refuses every row
  (holds ``c``), now 21.5 um from the C (= replay) at most; before, 11.4 um from BASE's C.
"""

from __future__ import annotations

import io
import json
import os
import pickle
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
from _cli import project_root, run_commands  # noqa: E402

TOL = 1e-9     # um
BUILD = ["cc", "-std=c99", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"]


def _files(deployed, basesrc: str | None) -> dict:
    """The C files of ``deployed`` as the tree exports them (``basesrc``: as that src does, in a child)."""
    from thermocomp.apps.deploy.export import exported_files

    if basesrc is None:
        return exported_files(deployed, "c")
    with tempfile.NamedTemporaryFile(suffix=".pkl") as f:
        pickle.dump(deployed, f)
        f.flush()
        code = ("import pickle, sys, json; from thermocomp.apps.deploy.export import exported_files; "
                "sys.stdout.write(json.dumps(exported_files(pickle.load(open(sys.argv[1], 'rb')), 'c')))")
        env = {**os.environ, "PYTHONPATH": str(Path(basesrc).resolve() / "src")}
        return json.loads(subprocess.run([sys.executable, "-c", code, f.name], env=env, check=True,
                                         capture_output=True, text=True).stdout)


def _stream(files: dict, folder: Path, text: str) -> str:
    """``stream --flags`` of the C ``files`` (built in ``folder``) on the CSV ``text``: its stdout."""
    folder.mkdir(parents=True, exist_ok=True)
    for name, body in files.items():
        if name.endswith((".c", ".h")):
            (folder / name).write_text(body)
    subprocess.run(BUILD, cwd=folder, check=True)
    return subprocess.run([str(folder / "stream"), "--flags"], input=text, check=True,
                          capture_output=True, text=True).stdout


def _feed(tests: list[pd.DataFrame], inputs: list[str]) -> str:
    parts = [df[["time", *inputs]].to_csv(index=False, float_format="%.17g") for df in tests]
    return parts[0] + "".join("\n" + p.split("\n", 1)[1] for p in parts[1:])


def _changed(df: pd.DataFrame, column: str, push: float, mode: str) -> pd.DataFrame:
    from bench_st107b import _changed as changed

    if mode != "back":
        return changed(df, column, push, mode)
    df = df.reset_index(drop=True).copy()
    df.loc[:len(df) // 3 - 1, column] += push
    return df


def score(root: str, data: str, column: str, push: str, mode: str, basesrc: str) -> None:
    """|C - replay| of BASE's and the tree's C, their NOT_IN_CODE rows (module doc)."""
    from hydra import compose, initialize_config_dir

    from thermocomp.apps.deploy.export import Simulator, state_space
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    base, data = project_root(root), str(Path(data).resolve())
    os.chdir(base)
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={data}", "track=false"])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    tests = [_changed(ds.campaigns[c], column, float(push), mode) for c in test_ids]
    deployed = deployable_model(cfg, ds, train_ids, str(base / "run" / "model.pkl"), "export.model")[0]
    rep = [replay(deployed, df) for df in tests]
    targets = [t for t in rep[0].columns if t.startswith("E_")]
    expected = np.vstack([-r[targets].to_numpy(float) for r in rep])
    edges = np.cumsum([0] + [len(df) for df in tests])
    tag = f"{column}_{mode}_{float(push):g}"
    got, outs = {}, {}
    for who, src in (("BASE", basesrc), ("RULE", None)):
        files = _files(deployed, src)
        inputs = json.loads(files["compensator.json"])["inputs"]
        outs[who] = _stream(files, base / "dep108" / f"{who}_{tag}", _feed(tests, inputs))
        got[who] = pd.read_csv(io.StringIO(outs[who]))
    ss = state_space(deployed, monitor=True)
    sim = []
    for df in tests:
        s = Simulator(ss)
        s.reset()
        sim += [s.step(u, t) for u, t in zip(df[ss.inputs].to_numpy(float), df["time"].to_numpy(float))]
    print(f"{column} {mode} {float(push):+g}: {len(expected)} rows, {len(tests)} test campaigns, targets "
          f"{targets}; stdout identical {outs['BASE'] == outs['RULE']}")
    gaps = {}
    for who, out in got.items():
        c = out[[f"C_{t[2:]}" for t in targets]].to_numpy(float)
        gap = gaps[who] = np.abs(c - expected).max(axis=1)
        flag = out["mon_not_in_code"].to_numpy() > 0
        before = []
        for k in range(len(tests)):
            rows = np.arange(edges[k], edges[k + 1])
            first = rows[flag[rows]][0] if flag[rows].any() else edges[k + 1]
            before += [r for r in rows if r < first and gap[r] > TOL]
        firsts = [int(np.flatnonzero(flag[edges[k]:edges[k + 1]])[0]) if flag[edges[k]:edges[k + 1]].any()
                  else None for k in range(len(tests))]
        print(f"  {who}: max |C - replay| {gap.max():.3g} um; mon_not_in_code rows {int(flag.sum())} "
              f"(first per campaign {firsts}); rows before a campaign's first flag > {TOL:g} um: "
              f"{len(before)}")
        if who == "RULE":
            js = np.abs(np.array(sim)[:, :len(targets)] - c).max()
            print(f"  RULE: max |JSON (Simulator) - C| {js:.3g} um")
    worse = np.flatnonzero(gaps["RULE"] > gaps["BASE"] + TOL)
    print(f"  rows RULE further from replay than BASE by > {TOL:g} um: {len(worse)}"
          + (f" (max {np.max(gaps['RULE'][worse] - gaps['BASE'][worse]):.3g} um)" if len(worse) else ""))


def healthy(root: str, basesrc: str, *records: str) -> None:
    """BASE's and the tree's C on each record's healthy stream: stdout identical (module doc)."""
    from bench_cmon92 import faulted_cell, made
    from bench_st105 import MADE_BY

    base = Path(root).resolve()
    for record in records:
        made(base, record, "mlr", MADE_BY)
        deployed, ss, frame, _, _, cid = faulted_cell(base, record, "mlr-none")
        m = ss.monitor
        first = frame[[ss.inputs[i] for i in m["inputs"]]].iloc[0].to_numpy(float)
        beyond = bool(((first < np.asarray(m["lo_lim"])) | (first > np.asarray(m["hi_lim"]))).any())
        outs = []
        for who, src in (("BASE", basesrc), ("RULE", None)):
            files = _files(deployed, src)
            inputs = json.loads(files["compensator.json"])["inputs"]
            outs.append(_stream(files, base / "dep108" / record / who, _feed([frame], inputs)))
        print(f"{record} {cid}: {len(frame)} rows; a monitored reading beyond range at the first sample "
              f"{beyond}; C stdout identical {outs[0] == outs[1]} ({len(outs[0].splitlines())} lines)",
              flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score, "healthy": healthy}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
