"""A lab's data in, the last gaps (stop 88, data88): a stranger's new exports of fresh simulated
records, each fed to ``thermocomp init <file>`` then ``run`` with no hand work.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_data88.py write ROOT SEED      # the exports of one seed
    python benchmarks/bench_data88.py score ROOT SEED      # init + run of each, the table
    python benchmarks/bench_data88.py warm ROOT            # connect.warm on a two-session log

``write``: ``thermocomp simulate seed=SEED`` (the default scenario, 3 campaigns of 4-5 h, a
sample every 300 s), its longest campaign taken as a lab's one record, written
``ROOT/<SEED>/contract.csv`` as the data contract has it (``time`` in s, ``T_``/``E_``/``S_``)
and then as acquisition software writes it (the same rows, the same numbers):

* ``excel2``: an Excel "CSV UTF-8" save: a BOM, CRLF, a row of names (``Time``, ``bearing f1``
  ... lab names, no prefixes) then a row of units (``s``, ``°C``, ``µm``, ``rpm``);
* ``tabcomment``: a logger's tab file: three ``#`` comment lines before the header, every line
  ending in a TAB (a trailing empty column), names with units in brackets;
* ``midnight``: ``Time`` as ``hh:mm:ss`` of the wall clock from 21:30:00, no date, past
  midnight (``23:55:00`` then ``00:00:00``), names with units in brackets;
* ``latin1``: ISO-8859-1, ``;``, decimal commas, the speed grouped by a point (``6.000``), units
  ``°C`` / ``µm`` / ``1/min`` in the headers;
* ``groups``: a folder of two loggers' files of the run (``run01_temp.csv``: time + the
  temperatures and the speed; ``run01_disp.csv``: time + the errors), timestamps both;
* ``catman``: HBM catman's ASCII export with the channel header (as bench_stranger84 writes it,
  en: TAB, ``.``, ``T0`` month first), its channels renamed (``Lager vorn 1`` ..., ``Weg X``).

``score``: per export ``init <path> out=ROOT/<SEED>/<export>-init`` and, where it passes,
``run`` on the data config it wrote, ``model=mlr data.test_fraction=0.25`` (the last quarter
of the record its test, as for the contract file); the exit codes, the refusal's first line,
and the test RMSE per target against the contract file's.

``warm``: test_data86b's en-GB LabVIEW record, ``init`` + ``run model=lagbank``; ``connect.warm``
read (the connect stage's own reader) from a log of two sessions (run 2 whole, then the running
run 3's first half) against the running session alone.

BAR (written before the fresh seeds 9216-9220 were scored): every export either goes in by
``init`` + ``run`` with no key typed, its test RMSE equal to the contract file's to 1e-6 µm on
every target, or is refused with exit 2 by a message naming the file and the column or row
and saying the fix.  An export read silently wrong (exit 0, RMSE not the contract's) is a
defect to mend; a refusal without file / column / row or fix is a defect to mend.  ``warm``:
the two-session log gives the rows of its last session, as that session alone (was exit 2).

Scored (2026-12-04, fresh seeds 9216-9220, each ``write`` once, then ``score`` on main d76bdde2
(a copy of the same files) and on fix/data88; dev seed 4242 only before the bar was scored)
------------------------------------------------------------------------------------------
Contract file test RMSE (µm, E_X / E_Y / E_Z; mlr, the last quarter held out): 9216 0.443990 /
0.596272 / 0.717147; 9217 0.369889 / 0.915128 / 0.952699; 9218 0.363564 / 0.482966 / 0.805421;
9219 1.900709 / 0.539785 / 3.314286; 9220 0.502702 / 0.439096 / 1.497833.  Same on both trees.

=============  ===========================================  ===========================================
export         main d76bdde2 (5 of 5 seeds alike)           fix/data88 (5 of 5 seeds alike)
=============  ===========================================  ===========================================
excel2         accepted, RMSE = contract (1e-6)             same
tabcomment     accepted, RMSE = contract                    same
latin1         accepted, RMSE = contract                    same
midnight       exit 2 "time of day without its date ...     exit 2, the fix now "leave it out and time
               or set data.sample_period_s"; that key       the rows by their period, data.roles.ignore=
               typed: exit 2, the SAME refusal (WRONG       ['Time'] data.sample_period_s=<s>"; typed:
               fix)                                         accepted, RMSE = contract
groups         exit 2 "file .../run01_temp.csv: no column   exit 2 naming the folder and both files ("one
               reads as a measured error" (init took the    run is two loggers' files ..., one campaign:
               pair for a lone file; the error logger's     none to hold out ... not cut in two"), the
               file never named: WRONG refusal)             fix: more runs, or one joined file (right,
                                                            but no acceptance: see Left)
catman         exit 2 T0 '03/05/2027' day or month first?   same (the date truly reads two ways: right);
               (file, column T0, line 11, the key); with    with the key: accepted, RMSE = contract
               data.dayfirst=false: accepted, RMSE =        (channels renamed: E_Weg_X ...)
               contract
=============  ===========================================  ===========================================

Against the BAR: on main two of six exports failed it on every seed (midnight: the fix the
refusal gave was refused again; groups: a refusal naming the wrong file and a wrong cause);
on fix/data88 every export passes (accepted with the contract's RMSE, with no key or with the
one key its refusal named, or refused naming file and fix).  The pair folder is refused, not
accepted: the bar allows it, the brief wanted it in (Left).

``warm`` (test_data86b's record, lagbank): main exit 2 "the LabVIEW Measurement File streamed
holds 2 sessions ...: stream one run"; fix/data88: the log's last session read, its 60 rows
equal to that session alone (same time origin), and a connection warmed on it corrects the
joined campaign as the client that never stopped (max diff <= 1e-9 µm; cold > 1e-3).

Also (not exports of this bench; tests/shell/test_data88.py): a catman file whose T0
``05/05/2027`` reads one date either way was refused "day or month first?": now read, no order
written; a folder of catman files none of whose T0 settles the order (8 en-GB tests 03/05 ...
12/05/2027) was refused at its first file alone: now the same refusal goes on to name the 7
files whose dates read two ways (T03's 05/05 reads one) and their spans, day first 2027-05-03
to 2027-05-12, month first 2027-03-05 to 2027-12-05.  ``init`` CPU on that folder 1.75 s both
trees (the first file's reader runs again only on the refusal path).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from _cli import run_commands

HERE = Path(__file__).resolve().parent
LIGHT = ["track=false", "plots=none"]
START = pd.Timestamp("2027-03-05 21:30:00")
EXPORTS = ("excel2", "tabcomment", "midnight", "latin1", "groups", "catman")
UNIT = {"T": "°C", "E": "µm", "S": "rpm"}
GERMAN = {"bearing": "Lager", "motor": "Motor", "box": "Gehäuse", "nose": "Nase", "amb": "Luft"}


def _cli(*args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run([sys.executable, "-m", "thermocomp", *args], capture_output=True, env=env)
    return subprocess.CompletedProcess(done.args, done.returncode,
                                       *(b.decode("utf-8", "replace") for b in (done.stdout,
                                                                               done.stderr)))


def _refusal(done: subprocess.CompletedProcess) -> str:
    return next((ln for ln in done.stderr.splitlines() if ln.startswith("thermocomp: error")),
                done.stderr.strip()[-300:])


def _lab(column: str) -> str:
    """A lab's name for a contract column (no prefix, words apart)."""
    if column == "time":
        return "Time"
    return column[2:].replace("_", " ")


def _record(root: Path, seed: int) -> pd.DataFrame:
    ds = root / "sim"
    done = _cli("simulate", f"seed={seed}", f"data.path={ds}", "sim.generator.n_campaigns=3",
                "sim.generator.duration_h=[4.0,5.0]", *LIGHT)
    assert done.returncode == 0, done.stderr[-2000:]
    index = pd.read_csv(ds / "campaigns.csv")
    longest = index.loc[index["duration_h"].idxmax(), "file"]
    return pd.read_csv(ds / longest)


def _text(rows: pd.DataFrame, sep: str, head: list[str], cell=str, end: str = "\n",
          trailing: str = "") -> str:
    lines = [*head, *(sep.join(cell(v) for v in r) + trailing for r in rows.itertuples(index=False))]
    return end.join(lines) + end


def write(root: str, seed: str) -> None:
    """The contract file and each export of ``seed`` (module docstring)."""
    base = Path(root) / seed
    base.mkdir(parents=True, exist_ok=True)
    rows = _record(base, int(seed))
    rows.to_csv(base / "contract.csv", index=False)
    names = list(rows.columns)
    units = ["s", *(UNIT[c[0]] for c in names[1:])]
    # excel2: names, then units; BOM, CRLF
    (base / "excel2.csv").write_bytes(("\ufeff" + _text(
        rows, ",", [",".join(map(_lab, names)), ",".join(units)], end="\r\n")).encode("utf-8"))
    # tabcomment: comment lines, units in brackets, a trailing TAB
    head = ["# DT85 logger export", f"# job spindle seed {seed}", "# interval 300 s",
            "\t".join(f"{_lab(n)} [{u}]" for n, u in zip(names, units)) + "\t"]
    (base / "tabcomment.txt").write_text(_text(rows, "\t", head, trailing="\t"), encoding="utf-8")
    # midnight: hh:mm:ss with no date
    clock = rows.assign(time=[(START + pd.Timedelta(seconds=float(t))).strftime("%H:%M:%S")
                              for t in rows["time"]])
    head = [",".join(["Time", *(f"{_lab(n)} [{u}]" for n, u in zip(names[1:], units[1:]))])]
    (base / "midnight.csv").write_text(_text(clock, ",", head), encoding="utf-8")
    # latin1: ; , decimal commas, grouped thousands, units in the header

    def german(v) -> str:
        if isinstance(v, float) and abs(v) >= 1000 and float(v).is_integer():
            return f"{int(v):,}".replace(",", ".")
        if isinstance(v, (int, np.integer)) and abs(v) >= 1000:
            return f"{int(v):,}".replace(",", ".")
        return str(v).replace(".", ",")

    latin_units = ["s", *("1/min" if u == "rpm" else u for u in units[1:])]
    head = [";".join(f"{_lab(n)} [{u}]" for n, u in zip(names, latin_units))]
    (base / "latin1.csv").write_bytes(_text(rows, ";", head, german, end="\r\n")
                                      .encode("iso-8859-1"))
    # groups: two loggers' files of one run, timestamps both
    stamped = rows.assign(time=[(START + pd.Timedelta(seconds=float(t))).isoformat()
                                for t in rows["time"]])
    folder = base / "groups"
    folder.mkdir(exist_ok=True)
    temp = [c for c in names if c[0] in "TS"]
    stamped[["time", *temp]].to_csv(folder / "run01_temp.csv", index=False)
    stamped[["time", *(c for c in names if c[0] == "E")]].to_csv(folder / "run01_disp.csv",
                                                                 index=False)
    # catman: the channel header, channels renamed
    (base / "catman.TXT").write_bytes(_catman(rows, seed).encode("cp1252"))
    print(f"wrote {base}: {len(rows)} rows, {len(names) - 1} channels, exports {', '.join(EXPORTS)}")


def _renamed(column: str) -> str:
    kind, rest = column[0], column[2:]
    if kind == "E":
        return f"Weg {rest}"
    if kind == "S":
        return "Drehzahl"
    word, *more = rest.split("_")
    return " ".join([GERMAN.get(word, word), *more])


def _catman(rows: pd.DataFrame, seed: str) -> str:
    """bench_stranger84's catman AP export (en: TAB, ``.``, T0 month first), one rate group."""
    sep = "\t"
    period = float(rows["time"].iloc[1] - rows["time"].iloc[0])
    stamp = f"{START:%m/%d/%Y %H:%M:%S}"
    columns = [("Time  1 - default sample rate", "s", rows["time"])]
    columns += [(_renamed(c), UNIT[c[0]], rows[c]) for c in rows.columns[1:]]
    head = [f"File:{sep}D:\\catman\\SPINDLE\\SEED{seed}.BIN", f"Comment:{sep}seed {seed}",
            f"catman Version:{sep}catmanAP 5.6.1", f"Export:{sep}{stamp}",
            f"Channels:{sep}{len(columns)}", ""]
    for k, (name, unit, cells) in enumerate(columns, start=1):
        head += [f"Channel {k}:{sep}{name}", f"Unit:{sep}{unit}", f"Comment:{sep}",
                 f"Sample rate:{sep}{1 / period:.5f}", f"T0:{sep}{stamp}",
                 f"Length:{sep}{len(cells)}", ""]
    lines = head + [sep.join(c[0] for c in columns)]
    lines += [sep.join(str(c[2].iloc[i]) for c in columns) for i in range(len(rows))]
    return "\r\n".join(lines) + "\r\n"


def _run(base: Path, path: Path, label: str, *keys: str) -> tuple[str, dict | None]:
    """``init`` then ``run`` of ``path``: (what happened, the test RMSE per target or None)."""
    init = base / f"{label}-init"
    done = _cli("init", str(path), f"out={init}", *keys)
    if done.returncode:
        return f"init exit {done.returncode}: {_refusal(done)}", None
    data = next((init / "conf" / "data").glob("*.yaml")).stem
    out = base / f"{label}-run"
    done = _cli("run", f"hydra.searchpath=[file://{init / 'conf'}]", f"data={data}", "model=mlr",
                "data.test_fraction=0.25", f"out={out}", *LIGHT)
    if done.returncode:
        return f"init 0, run exit {done.returncode}: {_refusal(done)}", None
    metrics = json.loads((out / "metrics.json").read_text())
    return "init 0, run 0", _rmse(metrics)


def _rmse(metrics: dict) -> dict:
    return {t: float(said["test"]["rmse"]) for t, said in metrics["targets"].items()}


# the key a refusal's own message gives, typed once as a stranger follows it (the first fix it
# offers that fits what the stranger knows: an en-US PC wrote the catman file; the clock is the
# wall clock, its period 300 s)
FOLLOWED = {"data.dayfirst=true|false": ("data.dayfirst=false",),
            "data.roles.ignore=['Time'] data.sample_period_s=<s>": ("data.roles.ignore=['Time']",
                                                                   "data.sample_period_s=300"),
            "or set data.sample_period_s": ("data.sample_period_s=300",)}   # (main's words)


def followed(base: Path, path: Path, label: str) -> tuple[str, dict | None, tuple]:
    """:func:`_run` of ``path``, and where it is refused naming a key (FOLLOWED), once more with
    that key typed: (what happened, the test RMSE per target or None, the key typed); each
    refusal printed."""
    said, got = _run(base, path, label)
    if got is not None:
        return said, got, ()
    print(f"  {label}: REFUSED {said}")
    key = next((typed for asked, typed in FOLLOWED.items() if asked in said), ())
    if not key:
        return said, None, ()
    said, got = _run(base, path, label, *key)
    if got is None:
        print(f"    with {' '.join(key)} as it says: REFUSED {said}")
    return said, got, key


def score(root: str, seed: str) -> None:
    """Each export of ``seed`` through init + run against the contract file (module docstring)."""
    base = Path(root) / seed
    said, want = _run(base, base / "contract.csv", "contract")
    print(f"seed {seed} contract: {said}; test RMSE {want}")
    paths = {"excel2": "excel2.csv", "tabcomment": "tabcomment.txt", "midnight": "midnight.csv",
             "latin1": "latin1.csv", "groups": "groups", "catman": "catman.TXT"}
    for label in EXPORTS:
        said, got, key = followed(base, base / paths[label], label)
        if got is None:
            continue
        if key:
            label = f"  with {' '.join(key)} as it says"
        same = want is not None and len(got) == len(want) and all(
            abs(a - b) <= 1e-6 for a, b in zip(sorted(got.values()), sorted(want.values())))
        print(f"  {label}: ACCEPTED {said}; RMSE {_short(got)} "
              f"{'= contract' if same else '!= contract ' + _short(want or {})}")


def _short(rmse: dict) -> str:
    return " / ".join(f"{k} {v:.6f}" for k, v in rmse.items())


def warm(root: str) -> None:
    """connect.warm of a two-session LabVIEW log (module docstring)."""
    sys.path.insert(0, str(HERE.parent / "tests" / "shell"))
    sys.path.insert(0, str(HERE.parent / "tests"))
    import pytest

    Path(root).mkdir(parents=True, exist_ok=True)
    code = pytest.main(["-q", "-p", "no:cacheprovider", "--basetemp", str(Path(root) / "warm"),
                        str(HERE.parent / "tests" / "shell" / "test_data88.py") + "::"
                        "test_connect_warm_on_a_log_of_two_sessions_warms_on_the_last"])
    print(f"connect.warm on a two-session log: {'the last session read' if code == 0 else 'FAILED'}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "score": score, "warm": warm}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
