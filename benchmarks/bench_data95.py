"""Data in, as a stranger (stop 95, data95): a temperature's word at a header's END, ``Tmp``, and
a stored config or model naming a derived name an earlier rule gave.

Usage (from ``benchmarks/``, ``PYTHONPATH=<tree>/src``: the code measured is that tree's; its
``conf/`` beside its ``src/``; MAIN a tree of main 34af1fcb's ``src`` and ``conf``, ``git
archive``)::

    python benchmarks/bench_data95.py write ROOT SEED          # the lab's exports of SEED
    python benchmarks/bench_data95.py score ROOT SEED          # init -> run -> ... -> C, served
    python benchmarks/bench_data95.py stored ROOT SEED MAIN    # main's config and model here
    python benchmarks/bench_data95.py names MAIN               # fl_thermal, audit93: names kept

``write``: bench_audit93's ``lab_files`` (seed SEED's swiss lathe production campaign, 1441 rows
at 60 s from 21:30:00, past midnight: ``contract.csv``; ``rawpair.csv``, a BOM, ``;``, decimal
commas, ``Datum;Uhrzeit``, the lab's headers ``Temp. headstock [°C]`` ...) and two more, rawpair's
rows under other temperature headers: ``rawend.csv`` (the word after the name, in turn ``amb
temp``, ``headstock Temperatur``, ``guidebush temperature``, ``toolholder1 Temp.``,
``toolholder2 temperatura``, ``frame1 Température``, ...) and ``rawtmp.csv`` (``Tmp. amb``,
``headstock Tmp``, ``Tmp guidebush``, ... : ``Tmp`` / ``Tmp.`` before and after).
``score`` (mlr): per file (``contract``, ``rawpair``, ``rawend``, ``rawtmp``) bench_data92's
stage with NO key typed (``init`` on the file alone, ``run data.test_fraction=0.25``, replay as
deployed, plain replay, ``export export.format=c export.check=true``, the compiled ``stream``
fed the RAW bytes) and bench_data94's session (the model.pkl served in process, the test rows
sent as the lab wrote them in blocks of 60, the first continuing the train campaign).
``stored``: main's stage on ``rawend`` (its init's config, its run's model.pkl: the names main
derives, ``T_headstock_Temperatur`` ...), then this tree given them: (s1) ``replay`` of main's
model under main's config; (s2) ``run`` under main's config with ``data.inputs`` listing main's
model's inputs (as ``diagnose`` writes a refit's); (s3) main's config plus the ``data.columns``
(s1)'s refusal gives: replay as deployed, plain, export C fed the raw file, and the session.
``names``: the contract names this tree's and main's ``naming`` derive from fl_thermal's and
bench_audit93's raw headers (and a few with no temperature word).

The rules measured:
1. a temperature's word after a sensor's name (``temp``, ``tmp``, ``Temperatur``,
   ``temperature``, ``temperatura``, ``température``, ``temperatuur``, after ``_``, ``-`` or a
   space -- not ``.``, a historian's tag path --, a ``.`` after it) is not repeated after the
   ``T_`` prefix (``headstock Temperatur`` -> ``T_headstock``, was ``T_headstock_Temperatur``);
   ``Tmp`` / ``Tmp.`` before the name as data94's words (``Tmp. headstock`` -> ``T_headstock``);
   with data94's care: the word alone stays (``T_Temp``, ``T_Tmp``), an ambient's name left keeps
   the word, a short name another header (or a ``data.columns`` name) reads as keeps the long
   one, ``tempo`` / ``temps`` are a time's words, a lab's own contract name with a unit
   (``T_spindle_temp [°C]``) is kept;
2. a stored config's ``data.inputs`` or a stored model (``replay.model``, ``export.model``,
   ``serve.model``, ``monitor``) naming a column by an earlier rule's name of a header
   (``T_Temp_Luft``, ``T_headstock_Temperatur``) is refused, exit 2, saying ``T_Temp_Luft is no
   column of <file>, the derived name is T_Luft (header 'Temp Luft [°C]')`` and the
   ``data.columns={'Temp Luft [°C]': T_Temp_Luft}`` that keeps the old name (main: a missing
   ``data.inputs`` name was a warning, the model fitted without that sensor; a stored model was
   refused as "1 of 1 campaigns lack it", the new name unsaid).  Not an alias: an alias would
   keep the old name alive in every place a name is read (``data.inputs`` globs, the model's
   columns, the served signature, the exported code's names, monitor.json), each a second
   spelling of one sensor; ``data.columns`` (what exists) restores the old name exactly, for a
   model one cannot refit.

BAR (written before the fresh seeds 9759-9760 were drawn; dev seed 4242 only before)
------------------------------------------------------------------------------------
KEPT where, on 2 of 2 fresh seeds (mlr): (a) every raw file (``rawpair``, ``rawend``,
``rawtmp``) is accepted with NO key; each of its figures -- run, plain, replay as deployed, C
(test RMSE per target) -- equals the contract file's to 1e-9 µm, C(file) = C(contract) on every
row to 1e-9 µm, and the session = the C on every test row to 1e-9 µm; (b) ``init`` names
``rawend``'s and ``rawtmp``'s temperatures as the contract does (``T_headstock`` ...; main:
``T_headstock_Temperatur``, ``T_Tmp._guidebush`` ...); (c) stored: (s1) and (s2) refused exit 2,
each naming every one of main's names that changed with its new name and its header, and the
``data.columns`` that keeps them; (s3) accepted, its replay as deployed and plain figures = main's
replay of the same model to 1e-9 µm, its C = main's C on every row to 1e-9 µm, the session = main's
C on every test row to 1e-9 µm; (d) no case main accepts changes a number: main's figures of
``contract`` and ``rawpair`` = this tree's to 1e-9 µm, and ``names`` (seen records, not seeded)
gives the same names on both trees for every header holding no temperature word at its end nor
``Tmp``; (e) the tests fail on 34af1fcb and pass here.  Rule 1 is judged by (a), (b), (d); rule
2 by (c), (d).

Seen (dev seed 4242, before the bar): score: contract, rawpair, rawend, rawtmp each E_X / E_Y run
1.696556848 / 1.185737074, replay = C 1.697627973 / 1.186419548, max|fig - contract's| 0,
max|C - C(contract)| 0, session = C to 2.4e-13 µm; init's names of rawend / rawtmp the contract's.
stored: main's figures of contract and rawpair = here's (0 µm); main names rawend
``T_headstock_Temperatur, ..., T_nc_cabinet_Temp.`` (11 of 12; ``amb temp`` is the ambient,
``T_amb``, on both); (s1), (s2) exit 2 naming the 11 with their new names; (s3) replay, plain, C
= main's (0 µm); its session first refused (the bench's copied config named main's file, so its
campaigns ``mainend_*``: fixed in the bench before the bar, the config now the copy's own file).
``names``: fl_thermal 23, audit93 rawpair 19, others 13 headers: 0 named otherwise.

Scored (2026-12-06, fresh seeds 9759-9760, once, after the bar's commit 67f1b8fc; main 34af1fcb's
src and conf by ``git archive``; the bar and the rule unchanged after the numbers)
-------------------------------------------------------------------------------------------------
Test RMSE (µm, E_X / E_Y), mlr; every file of a seed (contract, rawpair, rawend, rawtmp) equal to
every printed digit, run = plain = replay as deployed = C:

=====  ===========================  ======================  ==============================
seed   every file, here and main    max |session - C|       (s3) main's model here
=====  ===========================  ======================  ==============================
9759   1.577889817 / 1.071975665    1.5e-13 µm, 4 files     = main's 0 µm; session 1.5e-13
9760   2.000113985 / 1.417219057    2.0e-13 µm, 4 files     = main's 0 µm; session 2.0e-13
=====  ===========================  ======================  ==============================

(a) max|fig - contract's| 0 and max|C(file) - C(contract)| 0 µm, all 1441 rows, 3 raw files x 2
seeds.  (b) init's names of rawend and rawtmp: ``T_amb, T_headstock, ... T_nc_cabinet`` (the
contract's); main's of rawend ``T_headstock_Temperatur ... T_nc_cabinet_Temp.`` (11 of 12).
(c) (s1) replay of main's model and (s2) run under main's config with its 12 inputs: exit 2, 2 of
2 seeds each, naming the 11 old names, 11 new names with their headers, an 11-entry data.columns;
(s3) with that data.columns: replay, plain, C = main's (0 µm), session = main's C to 2.0e-13 µm.
(d) main's figures and C of contract and rawpair = here's, 0 µm, both seeds; ``names`` 0 of 55.
(e) tests/shell/test_lab_names95.py: 13 of 18 fail on 34af1fcb (the 5 guards pass there).
Against the BAR: (a)-(e) met, both rules: KEPT.  CPU: score ~3.3 s of this process (its
subprocesses ~6 min wall per seed, under nice, 2 seeds in parallel), stored ~6 min wall.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import shutil
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import yaml
from _cli import made_folder, run_commands
from bench_audit93 import lab_files as write_lab
from bench_data88 import LIGHT, _cli, _refusal
from bench_data92 import _stage, _targets, deployed_and_fed
from bench_data93 import _lines, _save
from bench_data94 import lab_rawpair, session

FILES = ("contract", "rawpair", "rawend", "rawtmp")
FAMILY = "mlr"
# the temperature word after the name, in turn (rawend), and Tmp before / after (rawtmp)
END_WORDS = ("temp", "Temperatur", "temperature", "Temp.", "temperatura", "Température",
             "temperatuur", "Tmp")
TMP_FORMS = ("Tmp. {}", "{} Tmp", "Tmp {}", "{} Tmp.")


def _headers(cells: list[str], form) -> list[str]:
    """rawpair's ``Temp. <name> [°C]`` headers re-written by ``form(k, name)``."""
    out, k = [], 0
    for c in cells:
        if c.startswith("Temp. ") and c.endswith(" [°C]"):
            out.append(form(k, c[len("Temp. "):-len(" [°C]")]) + " [°C]")
            k += 1
        else:
            out.append(c)
    return out


def write(root: str, seed: str) -> None:
    """bench_audit93's lab exports of ``seed``, ``rawend.csv`` and ``rawtmp.csv``."""
    base, cells, body = lab_rawpair(root, seed)
    end = _headers(cells, lambda k, n: f"{n} {END_WORDS[k % len(END_WORDS)]}")
    tmp = _headers(cells, lambda k, n: TMP_FORMS[k % len(TMP_FORMS)].format(n))
    _save(base / "rawend.csv", [";".join(end), *body])
    _save(base / "rawtmp.csv", [";".join(tmp), *body])
    print(f"wrote {base}: rawend.csv ({', '.join(end[2:6])} ...), rawtmp.csv "
          f"({', '.join(tmp[2:6])} ...)")


def _names(base: Path, label: str) -> list[str]:
    """The temperatures' names ``init`` gives ``label`` (this process's tree)."""
    init = _cli("init", str(base / f"{label}.csv"), f"out={base / 'names'}")
    return [ln.split()[-1] for ln in init.stdout.splitlines()
            if ln.startswith("  ") and ln.split()[-1].startswith("T_")]


def _c_rmse(got: dict, test: pd.DataFrame, n_test: int) -> tuple[dict, np.ndarray]:
    """The C's test RMSE per target (E_X ...) and its corrections (rows x targets)."""
    c = got["C"][[col for col in got["C"].columns if col.startswith("C_")]]
    corr = c.to_numpy(float)
    return ({f"E_{col[-1]}": float(np.sqrt(np.mean((test[f"E_{col[-1]}"].to_numpy(float)
                                                     + corr[-n_test:, j]) ** 2)))
             for j, col in enumerate(c.columns)}, corr)


def _figures(got: dict, test: pd.DataFrame) -> tuple[dict, np.ndarray]:
    c, corr = _c_rmse(got, test, got["n_test"])
    run, rep, plain = (_targets(got[k]) for k in ("run", "replay", "plain"))
    return {t: {"run": run[t], "plain": plain.get(t, np.nan), "replay": rep[t], "C": c[t]}
            for t in c}, corr


def _said(figures: dict) -> str:
    return "; ".join(f"{t} " + " ".join(f"{k} {v:.9f}" for k, v in f.items())
                     for t, f in figures.items())


def score(root: str, seed: str) -> None:
    base = Path(root).resolve() / f"lab{seed}"
    rows = pd.read_csv(base / "contract.csv")
    reference: dict = {}
    for label in FILES:
        got = _stage(base, label, FAMILY, ())
        print(f"seed {seed} {label}: {got['said']}  [names: {', '.join(_names(base, label))}]",
              flush=True)
        if "C" not in got:
            continue
        n_test = got["n_test"]
        figures, corr = _figures(got, rows.iloc[-n_test:])
        if label == "contract":
            reference = {"figures": figures, "C": corr}
        served = session(base, label, FAMILY, n_test)
        off = max(abs(v - reference["figures"][t][k]) for t, f in figures.items()
                  for k, v in f.items() if np.isfinite(v))
        print(f"  {_said(figures)}\n  max|fig - contract's| {off:.2g}  max|C - C(contract)| "
              f"{np.max(np.abs(corr - reference['C'])):.2g}  session: "
              + (served if isinstance(served, str) else
                 f"max |session - C| {np.max(np.abs(served - corr[-n_test:])):.2g} µm "
                 f"({len(served)} rows)"), flush=True)
        (base / f"{label}-{FAMILY}-figures.json").write_text(json.dumps(
            {"figures": figures, "C": corr.tolist()}))


@contextlib.contextmanager
def _tree(src: str):
    """The CLI runs ``src``'s code (PYTHONPATH) inside the block."""
    before = os.environ.get("PYTHONPATH")
    os.environ["PYTHONPATH"] = src
    try:
        yield
    finally:
        if before is None:
            os.environ.pop("PYTHONPATH")
        else:
            os.environ["PYTHONPATH"] = before


def _search(base: Path, label: str) -> list[str]:
    conf = next((base / f"{label}-init" / "conf" / "data").glob("*.yaml"))
    return [f"hydra.searchpath=[file://{conf.parents[1]}]", f"data={conf.stem}", *LIGHT,
            "data.test_fraction=0.25"]


def _kept_columns(said: str) -> dict:
    """The ``data.columns={...}`` a refusal gives, as a mapping."""
    found = re.search(r"data\.columns=(\{.*\})", said)
    return yaml.safe_load(found.group(1)) if found else {}


def stored(root: str, seed: str, main: str) -> None:
    base = Path(root).resolve() / f"lab{seed}"
    rows = pd.read_csv(base / "contract.csv")
    main_src = str(Path(main).resolve() / "src")
    for label in ("contract", "rawpair", "mainend"):
        if label == "mainend":
            shutil.copyfile(base / "rawend.csv", base / "mainend.csv")
        source = {"contract": "main-contract", "rawpair": "main-rawpair"}.get(label, label)
        if source != label:
            shutil.copyfile(base / f"{label}.csv", base / f"{source}.csv")
        with _tree(main_src):
            got = _stage(base, source, FAMILY, ())
            names = _names(base, source)
        print(f"seed {seed} main {source}: {got['said']}  [names: {', '.join(names)}]", flush=True)
        if "C" not in got:
            continue
        figures, corr = _figures(got, rows.iloc[-got["n_test"]:])
        print(f"  {_said(figures)}", flush=True)
        if label != "mainend":
            here = json.loads((base / f"{label}-{FAMILY}-figures.json").read_text())
            off = max(abs(v - here["figures"][t][k]) for t, f in figures.items()
                      for k, v in f.items() if np.isfinite(v))
            print(f"  max|fig(main) - fig(here)| {off:.2g}  max|C(main) - C(here)| "
                  f"{np.max(np.abs(corr - np.array(here['C']))):.2g}", flush=True)
            continue
        main_fig, main_c, n_test = figures, corr, got["n_test"]
    model = base / f"mainend-{FAMILY}" / "model.pkl"
    search = _search(base, "mainend")
    done = _cli("replay", *search, f"replay.model={model}", f"out={base / 's1'}")
    s1 = _refusal(done) if done.returncode else "accepted"
    print(f"(s1) replay of main's model: exit {done.returncode}: {s1}", flush=True)
    from thermocomp.shell.model_store import load_model
    inputs = list(load_model(model).inputs_)
    _config_as(base, "inputsend", inputs=inputs)       # (as diagnose writes a refit's config)
    done = _cli("run", *_search(base, "inputsend"), f"out={base / 's2'}")
    print(f"(s2) run, data.inputs={inputs}: exit {done.returncode}: "
          f"{_refusal(done) if done.returncode else 'accepted'}", flush=True)
    kept = _kept_columns(s1)
    _config_as(base, "keepend", columns=kept)
    (base / f"keepend-{FAMILY}").mkdir(exist_ok=True)
    for name in ("model.pkl", "model.pkl.sig"):       # (its signature: a model is read signed)
        shutil.copyfile(model.parent / name, base / f"keepend-{FAMILY}" / name)
    got = _given(base, "keepend", FAMILY)
    print(f"(s3) main's config + data.columns={kept}: {got['said']}", flush=True)
    if "C" not in got:
        return
    c, corr = _c_rmse(got, rows.iloc[-n_test:], n_test)
    figures = {t: {"plain": _targets(got["plain"]).get(t, np.nan),
                   "replay": _targets(got["replay"])[t], "C": c[t]} for t in c}
    off = max(abs(v - main_fig[t][k]) for t, f in figures.items() for k, v in f.items()
              if np.isfinite(v))
    served = session(base, "keepend", FAMILY, n_test)
    print(f"  {_said(figures)}\n  max|fig - main's| {off:.2g}  max|C - C(main)| "
          f"{np.max(np.abs(corr - main_c)):.2g}  session: "
          + (served if isinstance(served, str) else
             f"max |session - C(main)| {np.max(np.abs(served - main_c[-n_test:])):.2g} µm "
             f"({len(served)} rows)"), flush=True)


def _config_as(base: Path, label: str, **keys) -> None:
    """main's data config of ``mainend`` (its init's) as ``label``'s, ``keys`` set (a mapping
    merged into its own), and ``label.csv`` a copy of ``rawend.csv``."""
    conf = next((base / "mainend-init" / "conf" / "data").glob("*.yaml"))
    folder = base / f"{label}-init" / "conf" / "data"
    folder.mkdir(parents=True, exist_ok=True)
    config = yaml.safe_load(conf.read_text())
    config["path"] = str(base / f"{label}.csv")      # (its campaigns named as the session's)
    for key, value in keys.items():
        config[key] = {**(config.get(key) or {}), **value} if isinstance(value, dict) else value
    (folder / conf.name).write_text(yaml.safe_dump(config, allow_unicode=True))
    shutil.copyfile(base / "rawend.csv", base / f"{label}.csv")


def _given(base: Path, label: str, family: str) -> dict:
    """bench_data92's stage from replay on (its ``deployed_and_fed``), ``label``'s model.pkl
    given (no init, no run)."""
    import io

    row = deployed_and_fed(_search(base, label), base / f"{label}-{family}", base / f"{label}.csv")
    if "fed" not in row:
        return row
    fed = row.pop("fed")
    row = {"said": f"replay 0, export 0, C {fed.returncode}", "replay": row["replay"],
           "plain": row["plain"]}
    if not fed.returncode:
        row["C"] = pd.read_csv(io.BytesIO(fed.stdout))
    return row


NAMES_PROBE = """
import json, sys
from thermocomp.core.io.roles import naming
out = {}
for label, headers, roles in json.loads(sys.argv[1]):
    out[label] = naming(headers, roles, {}).names
print(json.dumps(out))
"""


def names(main: str) -> None:
    """fl_thermal's and bench_audit93's raw headers (and a few more) named by both trees."""
    import subprocess

    here = Path(__file__).resolve().parents[1]
    fl = pd.read_csv(here / "datasets" / "fl_thermal" / "spindle_test.csv", nrows=0).columns
    audit = (made_folder("/tmp/data95") / "names-audit")
    audit.mkdir(exist_ok=True)
    write_lab(audit, 4242)
    raw = _lines(audit, "rawpair.csv")[0].split(";")
    cases = [("fl_thermal", list(fl), {"error": ["ch*"], "state": ["spindle*"]}),
             ("audit93 rawpair", raw, {"error": ["Fehler*"], "state": ["Drehzahl*"]}),
             ("others", ["Zeit [s]", "Temp [°C]", "Tmp [°C]", "T_spindle_temp [°C]",
                         "tempo_ciclo [°C]", "ciclo temps [°C]", "Temp amb [°C]", "amb temp [°C]",
                         "Temp. bed [°C]", "headstock [°C]", "temperature_1 [°C]",
                         "MC07.Spindle.Bearing.Temp [°C]", "dX [µm]"],
              {"error": ["dX"]})]
    got = {}
    for tree in (str(here / "src"), str(Path(main).resolve() / "src")):
        done = subprocess.run([sys.executable, "-c", NAMES_PROBE, json.dumps(cases)],
                              capture_output=True, text=True,
                              env={**os.environ, "PYTHONPATH": tree})
        got[tree] = json.loads(done.stdout) if not done.returncode else done.stderr[-300:]
    ours, theirs = got.values()
    for label, headers, _ in cases:
        differ = {h: (theirs[label].get(h), ours[label].get(h)) for h in headers
                  if theirs[label].get(h) != ours[label].get(h)}
        print(f"{label}: {len(headers)} headers, {len(differ)} named otherwise (main -> here)"
              + "".join(f"\n  {h!r}: {a} -> {b}" for h, (a, b) in differ.items()), flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "score": score, "stored": stored,
                                  "names": names}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
