"""A lab's data in (stop 88, data88b): ONE run as two loggers' files, and a time of day past
midnight with no date, through ``thermocomp init`` + ``run`` with no key typed (data88 found both
refused; bench_data88's writers, fresh seeds).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_data88b.py write ROOT SEED     # bench_data88's exports + skips
    python benchmarks/bench_data88b.py score ROOT SEED     # init + run (+ replay) of each
    python benchmarks/bench_data88b.py times ROOT SEED     # the skips' times as read

``write``: bench_data88's ``write`` (``thermocomp simulate seed=SEED``, its longest campaign as
a lab's one record from 21:30:00, past midnight: ``contract.csv``, ``midnight.csv`` with
``Time`` as ``hh:mm:ss`` and no date, ``groups/`` the run as two loggers' files
``run01_temp.csv`` + ``run01_disp.csv`` with timestamps, and its other exports), then a logger
that skipped samples: four rows dropped (the first after midnight and three drawn by SEED
among the inner rows), as ``skips_contract.csv`` and ``skips_midnight.csv``.

``score``: per record ``init <path>`` then ``run model=mlr data.test_fraction=0.25`` on the data
config it wrote (bench_data88's ``_run``), the exit codes and the test RMSE per target; the
skips' midnight also with data88's fix (``data.roles.ignore=['Time'] data.sample_period_s=300``,
its rows timed by the period), for contrast; ``groups`` and ``contract`` also ``replay`` with the
same fraction (the stream warmed on the train part it continues), its streamed RMSE.
``times`` (added while the fresh seeds were scored; no bar of its own): MLR reads no time, so
the RMSE cannot see what data88's fix does to the skips' times: read in process, each time from
its first row against ``skips_contract.csv``'s.

BAR (written before the fresh seeds 9236-9240 were scored; dev seed 4242 only before): KEPT
where on 5 of 5 seeds (a) ``groups`` goes in with no key, its test RMSE equal to
``contract``'s to 1e-6 µm on every target and its replay's streamed RMSE equal to
``contract``'s replay's to 1e-6; (b) ``midnight`` goes in with no key, RMSE = ``contract``'s to
1e-6; (c) ``skips_midnight`` goes in with no key, RMSE = ``skips_contract``'s to 1e-6.  Any
export read silently wrong (exit 0, RMSE not the contract's) refuses the rule; a refusal on a
seed leaves it TRACED with the reason.  On main 86f7cf7c (a checkout of it) all three are
expected refused (exit 2).

Scored (2026-12-04, fresh seeds 9236-9240, each ``write`` once by fix/data88b, then ``score`` on
fix/data88b and on a checkout of main 86f7cf7c (a copy of the same files); dev seed 4242 only
before the bar was written; the bar unchanged)
------------------------------------------------------------------------------------------
Test RMSE (µm, E_X / E_Y / E_Z; mlr, the last quarter held out), the same on both trees where
read: contract 9236 0.601667 / 0.430106 / 1.444719; 9237 0.620475 / 1.046665 / 0.683143; 9238
0.582517 / 0.325924 / 1.559920; 9239 0.575786 / 1.144084 / 0.868375; 9240 0.378085 / 0.559337 /
1.287203.  skips_contract (rows dropped: 9236 5, 14, 30, 47 of 52; 9237 9, 11, 30, 40 of 59;
9238 8, 30, 45, 48 of 59; 9239 19, 20, 21, 30 of 57; 9240 30, 37, 43, 47 of 55; row 30 the
first after midnight): 9236 0.635541 / 0.476237 / 1.664238; 9237 0.449789 / 1.103260 /
0.587831; 9238 0.585475 / 0.321548 / 1.655670; 9239 0.554944 / 0.801019 / 0.788718; 9240
0.404954 / 0.677875 / 1.723105.

==============  ==========================================  ===========================================
record          main 86f7cf7c (5 of 5 seeds alike)          fix/data88b (5 of 5 seeds alike)
==============  ==========================================  ===========================================
groups          init exit 2 "a folder whose one run is      init 0, run 0, RMSE = contract (1e-6);
                two loggers' files ... not cut in two"      replay = contract's replay (1e-6; 9236
                                                            0.601667 / 0.430106 / 1.444719 ... 9240
                                                            0.387393 / 0.611189 / 0.835739)
midnight        init exit 2 "a time of day without its      init 0, run 0, RMSE = contract (1e-6)
                date (it would go back at midnight)"
skips_midnight  init exit 2 (the same)                      init 0, run 0, RMSE = skips_contract (1e-6)
  data88's fix  accepted, RMSE = skips_contract (MLR        same; ``times`` (this tree): 1200 s off
                reads no time)                              on 43 / 46 / 47 / 34 / 21 rows
==============  ==========================================  ===========================================

``times`` (fix/data88b): skips_midnight read with no key, its time from the first row, equals
skips_contract's on every row of every seed (max 0 s); data88's fix (rows timed by the period)
puts 21-47 rows of each seed up to 1200 s off (the 4 skipped samples closed up): the loss the
rule mends, which MLR's RMSE does not see (a lag bank or Hammerstein reads the time).

Against the BAR: (a), (b), (c) hold on 5 of 5 seeds on fix/data88b; nothing was read silently
wrong.  KEPT.  On main all three were refused on 5 of 5 seeds.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd
from _cli import run_commands
from bench_data88 import START, _cli, _refusal, _run, _short
from bench_data88 import write as write_exports

DROPPED = 3            # inner rows a logger skipped, beside the first after midnight
FIX = ("data.roles.ignore=['Time']", "data.sample_period_s=300")     # data88's refusal's fix


def write(root: str, seed: str) -> None:
    """bench_data88's exports of ``seed`` and the skips (module docstring)."""
    write_exports(root, seed)
    base = Path(root) / seed
    rows = pd.read_csv(base / "contract.csv")
    clock = START + pd.to_timedelta(rows["time"], unit="s")
    after = int(np.flatnonzero(clock.dt.date.to_numpy() != clock.dt.date.iloc[0])[0])
    inner = [k for k in range(2, len(rows) - 2) if k != after]
    drawn = np.random.default_rng(int(seed)).choice(inner, DROPPED, replace=False)
    kept = rows.drop(index=[after, *drawn.tolist()]).reset_index(drop=True)
    kept.to_csv(base / "skips_contract.csv", index=False)
    text = (base / "midnight.csv").read_text(encoding="utf-8").splitlines()
    dropped = {after, *drawn.tolist()}
    lines = [text[0], *(ln for k, ln in enumerate(text[1:]) if k not in dropped)]
    (base / "skips_midnight.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"skips: rows {sorted(int(k) for k in dropped)} of {len(rows)} dropped "
          f"(row {after} the first after midnight)")


def _replay(base: Path, label: str) -> dict | None:
    """``replay`` of ``label``'s run, the last quarter held out: streamed RMSE per target."""
    import json

    init, out = base / f"{label}-init", base / f"{label}-replay"
    data = next((init / "conf" / "data").glob("*.yaml")).stem
    done = _cli("replay", f"hydra.searchpath=[file://{init / 'conf'}]", f"data={data}",
                "model=mlr", "data.test_fraction=0.25",
                f"replay.model={base / f'{label}-run' / 'model.pkl'}", f"out={out}",
                "track=false", "plots=none")
    if done.returncode:
        print(f"    replay exit {done.returncode}: {_refusal(done)}")
        return None
    said = json.loads((out / "replay.json").read_text())["targets"]
    return {t: float(s["rmse"]) for t, s in said.items()}


def _same(got: dict | None, want: dict | None) -> bool:
    return (got is not None and want is not None and len(got) == len(want)
            and all(abs(a - b) <= 1e-6 for a, b in zip(sorted(got.values()),
                                                        sorted(want.values()))))


def score(root: str, seed: str) -> None:
    """Each record of ``seed`` through init + run (+ replay) against its contract file."""
    base = Path(root) / seed
    wanted = {}
    for label, path, against in (("contract", "contract.csv", None),
                                 ("skips_contract", "skips_contract.csv", None),
                                 ("groups", "groups", "contract"),
                                 ("midnight", "midnight.csv", "contract"),
                                 ("skips_midnight", "skips_midnight.csv", "skips_contract")):
        said, got = _run(base, base / path, label)
        wanted[label] = got
        verdict = ("" if against is None else
                   " = " + against if _same(got, wanted[against]) else
                   f" != {against} {_short(wanted[against] or {})}")
        print(f"seed {seed} {label}: {said}; RMSE {_short(got) if got else '-'}{verdict}")
    said, got = _run(base, base / "skips_midnight.csv", "skips_period", *FIX)
    print(f"seed {seed} skips_midnight with data88's fix {' '.join(FIX)}: {said}; RMSE "
          f"{_short(got) if got else '-'}"
          f"{' = skips_contract' if _same(got, wanted['skips_contract']) else ' != skips_contract'}")
    if wanted["groups"] is not None:
        streamed = {label: _replay(base, label) for label in ("contract", "groups")}
        print(f"seed {seed} replay: contract {_short(streamed['contract'] or {})}; groups "
              f"{_short(streamed['groups'] or {})}"
              f"{' = contract' if _same(streamed['groups'], streamed['contract']) else ' != contract'}")


def times(root: str, seed: str) -> None:
    """The skips' times as read (in this process, by the data configs ``score``'s inits wrote):
    ``skips_midnight.csv`` (no key, and with data88's fix) against ``skips_contract.csv``'s,
    each from its first row (s)."""
    import yaml

    from thermocomp.core.io import ContractError, read_dataset

    base = Path(root) / seed
    want = read_dataset(base / "skips_contract.csv")[0].campaigns["skips_contract"]["time"]
    for label, init in (("no key", "skips_midnight"), ("data88's fix", "skips_period")):
        # the data config `score`'s init wrote (its roles; the fix's keys in it)
        written = next((base / f"{init}-init" / "conf" / "data").glob("*.yaml"), None)
        cfg = {k: v for k, v in yaml.safe_load(written.read_text()).items()
               if k not in ("defaults", "test_fraction", "val_fraction")   # (the whole record)
               } if written else {}
        try:
            got = read_dataset(base / "skips_midnight.csv", cfg)[0].campaigns["skips_midnight"]
        except ContractError as exc:
            print(f"seed {seed} skips_midnight, {label}: refused: {exc}")
            continue
        diff = np.abs((got["time"] - got["time"].iloc[0]).to_numpy() - want.to_numpy())
        print(f"seed {seed} skips_midnight, {label}: max |time - contract's| {diff.max():g} s, "
              f"{int((diff > 0).sum())} of {len(diff)} rows off")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "score": score, "times": times}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
