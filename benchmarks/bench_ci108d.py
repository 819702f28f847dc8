"""CI time (issue 34; stop 108, ci108d): ``read_dataset``'s CPU, the same output.

The suite's profile (py-spy, stop 107's head) puts 7.7 % of its CPU in
``thermocomp.core.io.read.read_dataset``.  This bench reads three datasets with a tree's
``src`` (a separate process per tree, ``PYTHONPATH``): (a) the default simulated dataset
(``thermocomp simulate``, as tests/conftest.py's ``default_dataset``), (b) the vendored record
``datasets/fl_thermal`` (``conf/data/fl_thermal.yaml``'s keys), (c) (a) written as a German lab
exports it (``;``, decimal commas, ``Zeit [s]``), and compares what a read gives on more.

BAR (written and committed before any after-measurement):

1. CPU (``time.process_time`` of the reading process around ROUNDS rounds of (a)+(b)+(c), one
   warm-up round first, *_NUM_THREADS=1): the change's is at most 0.70 x the base tree's
   (base = ``git archive a1addf5a``), base and change run one after the other, paired, two pairs
   at least (more when the difference is under 10 %); the ratio is the mean of the pairs';
2. the same output: on every dataset of ``same`` (10+: the three above and the tests' makers
   reached from here), each campaign's frame equal (``DataFrame.equals`` and dtypes, index,
   column order, ``attrs``), the manifest equal, ``meta`` and the report equal, and for a
   refused read the message word for word;
3. the reader's test modules pass (tests/core/test_io_read.py, test_io_errors.py,
   test_raw_exports*.py, and every module that imports the changed functions), ruff clean.

Measured (2026-12-07 15:29-15:32 UTC, load 3.7-4.6 on 2 cores, a pytest run of mine beside it;
``cpu`` with ROUNDS=6, content caches emptied before each round; base = ``git archive a1addf5a``
in /tmp/ci108d/base; the change = benchmarks/ci108d_rule.patch).  CPU s per round, base ->
change, six pairs (three at 15:29:40, three at 15:31:30)::

  0.4954 -> 0.3483 (0.703)   0.4845 -> 0.3595 (0.742)   0.4526 -> 0.3541 (0.782)
  0.4549 -> 0.3608 (0.793)   0.5027 -> 0.3624 (0.721)   0.4722 -> 0.3524 (0.746)
  mean ratio 0.748 (-25 %)

Per dataset (one process per tree, 6 cold reads each, 15:31): (a) sim 0.155-0.161 -> 0.146,
(b) fl_thermal 0.064 -> 0.062, (c) lab export 0.255-0.265 -> 0.164.  ``same``: all 13 datasets
read alike (frames, dtypes, index, column order, attrs, manifest, meta, report, log lines,
lab_bad's refusal word for word).  Against the bar: (1) NOT met (0.748 > 0.70); (2) met;
(3) met (259 + 72 tests of the reader's modules and neighbours pass, and the patch's 12
new; ruff clean).  Verdict REFUSED: src reverted, the change kept in
benchmarks/ci108d_rule.patch.

Usage::

    python benchmarks/bench_ci108d.py make OUT
    python benchmarks/bench_ci108d.py cpu TREE OUT ROUNDS
    python benchmarks/bench_ci108d.py dump TREE OUT
    python benchmarks/bench_ci108d.py same BASE_DUMP AFTER_DUMP

``make`` writes the datasets under OUT; ``cpu`` prints the CPU per round of (a)+(b)+(c) read with
TREE's ``src`` (in a child process); ``dump`` pickles what each dataset of OUT reads as with
TREE's ``src`` (OUT/dump-<tree name>.pkl); ``same`` compares two dumps.
"""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import made_folder, run_commands  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
FL_KEYS = {"roles": {"error": ["ch*"], "state": ["spindle*"]}, "test_fraction": 0.1}
THREADS = {k: "1" for k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}


def _german(src: Path, dest: Path, sep: str = ";", preamble: tuple = ()) -> None:
    """The folder ``src`` written as a lab's export: ``sep``, decimal commas, ``Zeit [s]``."""
    import pandas as pd
    dest.mkdir(parents=True, exist_ok=True)
    (dest / "campaigns.csv").write_text((src / "campaigns.csv").read_text())
    for f in sorted(src.glob("K*.csv")):
        df = pd.read_csv(f).rename(columns={"time": "Zeit [s]"})
        text = df.to_csv(sep=sep, decimal=",", index=False)
        (dest / f.name).write_text("".join(f"{line}\n" for line in preamble) + text)


def make(out: str) -> None:
    """The datasets under OUT: sim (a), lab (c) and the others ``same`` reads."""
    out = made_folder(out)
    py = [sys.executable, "-m", "thermocomp", "simulate", "track=false"]
    env = {**os.environ, **THREADS, "PYTHONPATH": str(ROOT / "src")}
    for name, extra in (("sim", ()), ("door", ("sim.generator.effects=[door]",)),
                        ("short", ("sim.generator.n_campaigns=9", "sim.generator.duration_h=[2.0,3.0]"))):
        subprocess.run([*py, f"data.path={out / name}", *extra], check=True, env=env, cwd=out)
    _german(out / "sim", out / "lab")
    _german(out / "short", out / "lab_tab", sep="\t")
    _german(out / "short", out / "lab_logger", preamble=("Logger: XY-200", "Datum: 28.11.2026"))
    bad = out / "lab_bad"
    _german(out / "short", bad)
    lines = (bad / "K02.csv").read_text().splitlines()
    lines[5] = lines[5].replace(";", ";x", 1)
    (bad / "K02.csv").write_text("\n".join(lines) + "\n")


def cases(out: Path, fl: Path) -> dict[str, tuple]:
    """``{name: (path, cfg)}``: (a), (b), (c) first, then the others."""
    lab = {"columns": {"Zeit [s]": "time"}}
    return {"a_sim": (out / "sim", None), "b_fl_thermal": (fl, FL_KEYS), "c_lab": (out / "lab", lab),
            "door": (out / "door", None), "short": (out / "short", None),
            "short_keep": (out / "short", {"__missing": "keep"}),
            "short_test": (out / "short", {"test_fraction": 0.3}),
            "fl_thirds": (fl, {**FL_KEYS, "test_fraction": 0.2, "val_fraction": 0.2,
                               "split_order": ["train", "test", "val"]}),
            "lab_tab": (out / "lab_tab", lab), "lab_logger": (out / "lab_logger", lab),
            "lab_bad": (out / "lab_bad", lab), "lab_no_cfg": (out / "lab", None),
            "short_one": (out / "short" / "K01.csv", None)}


def _in_child(tree: str, *args: str) -> None:
    env = {**os.environ, **THREADS, "PYTHONPATH": str(Path(tree).resolve() / "src")}
    subprocess.run([sys.executable, __file__, *args], check=True, env=env)


def cpu(tree: str, out: str, rounds: str) -> None:
    """CPU s per round of (a)+(b)+(c) read with TREE's src."""
    _in_child(tree, "_cpu", str(Path(tree).resolve()), out, rounds)


def _cpu(tree: str, out: str, rounds: str) -> None:
    import time

    import thermocomp
    from thermocomp.core.io.read import read_dataset
    assert Path(thermocomp.__file__).is_relative_to(tree), thermocomp.__file__
    three = list(cases(Path(out).resolve(), ROOT / "datasets/fl_thermal/spindle_test.csv").values())[:3]
    for path, cfg in three:            # warm-up: imports, first-time caches
        read_dataset(path, cfg)
    # a cache keyed on the text a read looks at (a change's) emptied before every round: the CPU
    # of reading each dataset afresh, not of reading the same text again (the suite does that too)
    caches = [f for f in _content_caches()]
    used = 0.0
    for _ in range(int(rounds)):
        for f in caches:
            f.cache_clear()
        start = time.process_time()
        for path, cfg in three:
            read_dataset(path, cfg)
        used += time.process_time() - start
    print(f"{Path(tree).name}: {used / int(rounds):.4f} CPU s per round "
          f"({len(caches)} content caches emptied each round)")


def _content_caches() -> list:
    """The reader's functions cached on the text they are given, in the tree imported."""
    from thermocomp.core.io import layout, sniff
    return [f for f in (getattr(layout, "_header_line", None), getattr(sniff, "_marks", None))
            if f is not None]


def dump(tree: str, out: str) -> None:
    """What every dataset reads as with TREE's src, pickled on OUT/dump-<tree>.pkl."""
    _in_child(tree, "_dump", str(Path(tree).resolve()), out)


def _dump(tree: str, out: str) -> None:
    import logging

    from thermocomp.core.io.contract import ContractError
    from thermocomp.core.io.read import read_dataset
    said = []
    handler = logging.Handler()
    handler.emit = lambda record: said.append(record.getMessage())
    logging.getLogger().addHandler(handler)
    logging.getLogger().setLevel(logging.INFO)
    got = {}
    out_path = Path(out).resolve()
    for name, (path, cfg) in cases(out_path, ROOT / "datasets/fl_thermal/spindle_test.csv").items():
        cfg = dict(cfg or {})
        missing = cfg.pop("__missing", "repair")
        del said[:]
        try:
            ds, report = read_dataset(path, cfg, missing=missing)
            got[name] = {"frames": {c: (f, dict(f.attrs)) for c, f in ds.campaigns.items()},
                         "manifest": ds.manifest, "meta": ds.meta, "name": ds.name, "report": report}
        except ContractError as exc:
            got[name] = {"error": str(exc)}
        got[name]["said"] = list(said)
    (out_path / f"dump-{Path(tree).name}.pkl").write_bytes(pickle.dumps(got))
    print(f"{len(got)} datasets dumped")


def same(base: str, after: str) -> None:
    """Every dataset of two dumps read alike (frames, manifest, meta, report, errors)."""
    a, b = (pickle.loads(Path(p).read_bytes()) for p in (base, after))
    assert a.keys() == b.keys()
    for name in a:
        x, y = a[name], b[name]
        assert x.keys() == y.keys(), name
        assert x["said"] == y["said"], (name, x["said"], y["said"])
        if "error" in x:
            assert x["error"] == y["error"], (name, x["error"], y["error"])
            print(f"{name}: the same refusal: {x['error'][:90]}")
            continue
        assert x["frames"].keys() == y["frames"].keys() and list(x["frames"]) == list(y["frames"]), name
        for cid, (f, attrs) in x["frames"].items():
            g, gattrs = y["frames"][cid]
            assert f.equals(g) and list(f.columns) == list(g.columns), (name, cid)
            assert (f.dtypes == g.dtypes).all() and f.index.equals(g.index) and attrs == gattrs, (name, cid)
        assert x["manifest"].equals(y["manifest"]) and list(x["manifest"].columns) == list(
            y["manifest"].columns), name
        assert x["meta"] == y["meta"] and x["report"] == y["report"] and x["name"] == y["name"], name
        print(f"{name}: the same ({len(x['frames'])} campaigns)")
    print(f"all {len(a)} datasets read alike")


COMMANDS = {"make": make, "cpu": cpu, "dump": dump, "same": same, "_cpu": _cpu, "_dump": _dump}


def main(argv: list[str]) -> int:
    return run_commands(__doc__, COMMANDS, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
