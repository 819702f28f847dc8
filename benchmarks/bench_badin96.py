"""Bad input everywhere a user can hand it in (badin96, issue 34): one clear error naming file,
column and row, exit status 2, nothing half-written -- swept case by case as a stranger meets it.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_badin96.py base ROOT          # the healthy inputs and models
    python benchmarks/bench_badin96.py cases ROOT [NAMES] # every case (or NAMES, comma-separated)

``base``: the healthy record -- ``thermocomp simulate seed=9780`` with the tests' short cut
(``sim.generator.n_campaigns=9 sim.generator.duration_h=[2.0,3.0]``: 6 train, 3 test campaigns of
300 s samples) -> ``ROOT/base/h`` -- and the shipped ``datasets/fl_thermal`` cut to its first 2000
rows (``ROOT/base/fl.csv``, read with ``data=fl_thermal``); ``run model=mlr track=false`` on each
-> ``ROOT/base/model_h`` / ``model_fl`` (``model.pkl`` and its signature).  ``cases``: each case
of :data:`CASES` in its own project root ``ROOT/cases/<name>`` (``conf/`` linked in,
``THERMOCOMP_ROOT`` set, tracking on as by default: ``sqlite:///mlruns/mlflow.db`` there), its
malformed input made under ``in/`` from the healthy one, the command run as a stranger runs it
(``python -m thermocomp <stage> ...`` in a child process, ``out=<case>/out``; ``serve`` given 60 s
and stopped if it listens).  Per case: the exit status, stderr's first line, whether it names the
file, the column and the row (the ones the case says apply), whether a traceback leaked, every
file new or changed under the case's root but ``in/`` (a listing with sizes and mtimes before
and after) and the MLflow runs the store holds with their status -> ``ROOT/cases.json`` and a
table on stdout.

Naming: the file is named when the message holds the bad file's name (its basename; a model's
path for a model case); the column when it holds the column's name as the file spells it; the row
when it holds ``data row N``, ``line N`` or ``row N``.

BAR (committed before any case was run; the healthy record seed 9780 and fl_thermal are the
inputs, the cases are the fresh part, scored once)
---
B1. Every case exits 2: not 1, not 0 (0 with a result read from garbage is a break).
B2. No traceback on stderr, and stderr's first line is the one ``thermocomp: error: ...`` line.
B3. The message names what applies of file / column / row (:data:`CASES` says which, per case).
B4. Nothing half-written: after the command no file new or changed under ``out/``, ``conf/`` or
    ``data/`` of the case's root, and no MLflow run with status FINISHED or RUNNING (a run the
    store marks FAILED is the store's record of the failure, not output; said per case anyway,
    as is every other file the command left).
Every case failing a clause is a finding: mended in src where small and clear (the existing
``ThermocompError`` family and the CLI's one handler, no second mechanism), with a test per mend
failing on 4afc74c7; the rest listed for the lead.  KEPT (mends) or TRACED (findings only).

Scored (2026-12-06, once; main = 4afc74c7's src, ``/tmp/badin96/main``; the mends = fix/badin96,
``/tmp/badin96/rule``; 2 cores shared with other helpers: 44 cases 3 min 25 s wall on main,
10 min 18 s on the branch under load; 118 / 128 s CPU, user + sys of the children)
---
Clauses met, main -> mends: B1 39 -> 40 of 44, B2 39 -> 40, B3 38 -> 39, B4 39 -> 40.  No
traceback in any case; every exit-2 case left nothing under out/ (7 left an MLflow run marked
FAILED, its config.yaml and log: the bar's reading).  Mended (tests/shell/test_bad_input96.py):
- role_matches_nothing: ``init lab.csv data.roles.error=[zz*]`` exit 0, the pattern written
  into the config beside the detected ch1..ch5 -> exit 2, ``file lab.csv: data.roles.error=
  ['zz*'] matches no column (its headers: ...)``, nothing written (a one-file record only).
- replay_missing_column: ``replay.model=... cannot be deployed: column 'T_nose': 1 of 6
  campaigns lack it (K08)`` -> ``file .../K08.csv, column 'T_nose': replay.model=...`` (and
  monitor's; ``deployable_model`` and monitor's ``_fitted`` check a loaded model's inputs
  against the train campaigns with their files before its stream is built).
Left as they are (not mended; for the lead):
- dup_header (init, exit 0): documented, the second 't1(°C)' read as 't1#2(°C)', warned with
  the file and both column numbers; B1/B2/B4 broken by design.
- gap_10_periods (run, exit 0): a warning naming file, column 'time', line 11 (data row 10),
  "a logger's outage?"; documented as a gap kept.
- constant_temperature (run, exit 0): a warning per campaign naming file and column, "constant
  over the whole campaign (a dead channel?)"; the model fitted.
- monitor_stream_extra_column (monitor on stdin, exit 0): a column the model does not read is
  streamed past without a word (monitor.json written, a FINISHED run).
- replay_other_records_model / monitor_other_records_model: exit 2, one line, naming file
  K01.csv (after the mend) and column 'T_t1', the model's name for fl's header 't1(°C)': B3 as
  the case was written (the header's spelling) not met; "leave it out of data.inputs" is the
  hint of a record, not of a model of another record.
- serve with a run's model.pkl reads data.path (made deployable on its train split) before the
  model's signature: the first run, without data.path, was refused naming the default
  data/raw/yearround_spindle.  The two serve cases were given data.path after that run (the
  only case changed) and re-run on main and the branch: exit 2 naming the model.pkl each.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import socket
import sqlite3
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import made_folder, run_commands  # noqa: E402

FL = HERE.parent / "datasets" / "fl_thermal" / "spindle_test.csv"
FL_ROWS = 2000
SEED = 9780
SHORT = ("sim.generator.n_campaigns=9", "sim.generator.duration_h=[2.0,3.0]")
QUIET = ("plots=none",)
ROW = re.compile(r"\b(data row|line|row) \d+")
WRITES = ("out", "conf", "data")          # the folders whose change is half-written output


def thermocomp(root: Path, args: list[str], stdin: str | None = None, timeout: float = 300):
    """``python -m thermocomp <args>`` with ``root`` as the project root: (status, stdout, stderr)."""
    env = {**os.environ, "THERMOCOMP_ROOT": str(root)}
    try:
        run = subprocess.run([sys.executable, "-m", "thermocomp", *args], cwd=root, env=env,
                             input=stdin, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired as exc:
        return None, exc.stdout or "", (exc.stderr or b"").decode() if isinstance(exc.stderr, bytes) \
            else (exc.stderr or "")
    return run.returncode, run.stdout, run.stderr


def _root(path: Path) -> Path:
    made_folder(str(path))
    if not (path / "conf").exists():
        (path / "conf").symlink_to(HERE.parent / "conf")
    return path


# -- the healthy base ----------------------------------------------------------------------------

def base(root: str) -> None:
    """The healthy record, fl_thermal's first rows and a model of each (module doc)."""
    folder = _root(Path(root).resolve()) / "base"
    folder.mkdir(exist_ok=True)
    rc, _, err = thermocomp(folder.parent, ["-q", "simulate", f"seed={SEED}", f"data.path={folder / 'h'}",
                                            "track=false", *SHORT])
    assert rc == 0, err
    with open(FL, encoding="utf-8") as src:
        lines = [next(src) for _ in range(FL_ROWS + 1)]
    (folder / "fl.csv").write_text("".join(lines), encoding="utf-8")
    for label, args in (("h", [f"data.path={folder / 'h'}"]),
                        ("fl", ["data=fl_thermal", f"data.path={folder / 'fl.csv'}"])):
        rc, _, err = thermocomp(folder.parent, ["-q", "run", *args, "model=mlr", "track=false", *QUIET,
                                                f"out={folder / ('model_' + label)}"])
        assert rc == 0, err
        print(f"{label}: {(folder / ('model_' + label) / 'model.pkl').stat().st_size} bytes of model.pkl")


# -- making the malformed inputs -----------------------------------------------------------------

def _lines(path: Path) -> list[str]:
    return path.read_text(encoding="utf-8").splitlines()


def _put(path: Path, lines: list[str]) -> None:
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def _cell(path: Path, row: int, column: str, value: str) -> None:
    """Data row ``row`` (1-based) of ``column`` set to ``value`` (text as written)."""
    lines = _lines(path)
    header = lines[0].split(",")
    cells = lines[row].split(",")
    cells[header.index(column)] = value
    lines[row] = ",".join(cells)
    _put(path, lines)


def _column(path: Path, column: str, fn) -> None:
    lines = _lines(path)
    j = lines[0].split(",").index(column)
    out = [lines[0]]
    for i, line in enumerate(lines[1:], 1):
        cells = line.split(",")
        cells[j] = fn(i, cells[j])
        out.append(",".join(cells))
    _put(path, out)


def _drop(path: Path, column: str) -> None:
    lines = _lines(path)
    j = lines[0].split(",").index(column)
    _put(path, [",".join(c for k, c in enumerate(line.split(",")) if k != j) for line in lines])


class Case:
    """One malformed input: ``make(case_dir, base_dir) -> args`` (the command's words after the
    stage); ``names``: what the message must name (``file``: that basename, ``column``: that name,
    ``row``: True)."""

    def __init__(self, name, stage, make, file=None, column=None, row=False, stdin=None):
        self.name, self.stage, self.make = name, stage, make
        self.file, self.column, self.row, self.stdin = file, column, row, stdin


def _h(case: Path, base: Path) -> Path:
    """A copy of the healthy record under ``in/h``."""
    dest = case / "in" / "h"
    shutil.copytree(base / "h", dest)
    return dest


def _fl(case: Path, base: Path, name: str = "lab.csv") -> Path:
    dest = case / "in" / name
    dest.parent.mkdir(parents=True, exist_ok=True)
    shutil.copy(base / "fl.csv", dest)
    return dest


def _run_h(edit):
    """``run`` on the healthy record with ``edit(folder)`` applied."""
    def make(case, base):
        folder = _h(case, base)
        edit(folder)
        return [f"data.path={folder}", "model=mlr", *QUIET]
    return make


def _replay_h(edit, model="h"):
    def make(case, base):
        folder = _h(case, base)
        edit(folder)
        return [f"data.path={folder}", f"replay.model={base / ('model_' + model) / 'model.pkl'}", *QUIET]
    return make


def _init_fl(edit, *more):
    def make(case, base):
        path = _fl(case, base)
        edit(path)
        return [str(path), *more]
    return make


def _model(case: Path, base: Path, how: str) -> Path:
    """A bad model.pkl under ``in/``: ``truncated`` (its first half, its signature kept),
    ``foreign`` (a pickle of a dict, no signature), ``text`` (not a pickle)."""
    dest = case / "in" / "model.pkl"
    dest.parent.mkdir(parents=True, exist_ok=True)
    good = base / "model_h" / "model.pkl"
    if how == "truncated":
        data = good.read_bytes()
        dest.write_bytes(data[: len(data) // 2])
        shutil.copy(good.with_name("model.pkl.sig"), dest.with_name("model.pkl.sig"))
    elif how == "foreign":
        import pickle
        dest.write_bytes(pickle.dumps({"coef": [1.0, 2.0]}))
    else:
        dest.write_text("this is not a model\n", encoding="utf-8")
    return dest


def _with_model(stage: str, how: str, *more: str):
    def make(case, base):
        model = _model(case, base, how)
        key = {"serve": "serve.model", "export": "export.model", "monitor": "monitor.model",
               "replay": "replay.model"}[stage]
        # (a run's model.pkl is served made deployable on data.path's train split: serve reads it
        # first, so the first run, without it, was refused naming the default data.path)
        extra = [f"data.path={base / 'h'}"] + ([f"serve.port={_free_port()}"] if stage == "serve" else [])
        return [f"{key}={model}", *extra, *more]
    return make


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _stream(case: Path, base: Path, drop: str | None = None, extra: str | None = None) -> str:
    """Test campaign K08's rows as a stream on stdin, less ``drop`` / plus ``extra`` column."""
    lines = _lines(base / "h" / "K08.csv")
    header = lines[0].split(",")
    rows = [line.split(",") for line in lines]
    if drop:
        j = header.index(drop)
        rows = [r[:j] + r[j + 1:] for r in rows]
    if extra:
        rows = [r + ([extra] if i == 0 else ["1.0"]) for i, r in enumerate(rows)]
    return "\n".join(",".join(r) for r in rows) + "\n"


def _monitor_stream(case, base):
    return [f"data.path={base / 'h'}", f"monitor.model={base / 'model_h' / 'model.pkl'}",
            "monitor.input=-", *QUIET]


def _manifest(edit):
    def apply(folder: Path):
        lines = _lines(folder / "campaigns.csv")
        _put(folder / "campaigns.csv", edit(lines))
    return apply


def _dup_campaign(lines):
    out = list(lines)
    out[3] = out[3].replace("K03,", "K02,", 1)
    return out


def _parquet_text(case, base):
    import pandas as pd
    frame = pd.read_csv(base / "fl.csv")
    col = frame.columns[8]
    frame[col] = frame[col].map(lambda v: f"{v:.3f} C")
    dest = case / "in" / "lab.parquet"
    dest.parent.mkdir(parents=True, exist_ok=True)
    frame.to_parquet(dest, index=False)
    return ["data=fl_thermal", f"data.path={dest}", "model=mlr", *QUIET]


def _write_file(name: str, data: bytes):
    def make(case, base):
        dest = case / "in" / name
        dest.parent.mkdir(parents=True, exist_ok=True)
        dest.write_bytes(data)
        return [str(dest)]
    return make


def _delim(path: Path):
    lines = _lines(path)
    _put(path, lines[:15] + [line.replace(",", ";") for line in lines[15:]])


def _ragged(extra: bool):
    def apply(folder: Path):
        lines = _lines(folder / "K02.csv")
        lines[10] = lines[10] + ",7.5" if extra else ",".join(lines[10].split(",")[:-3])
        _put(folder / "K02.csv", lines)
    return apply


def _gap(folder: Path):
    _column(folder / "K02.csv", "time", lambda i, v: str(int(v) + (2700 if i >= 10 else 0)))


def _all_files(folder: Path, fn):
    for f in sorted(folder.glob("K*.csv")):
        fn(f)


F, TE = "K02.csv", "K08.csv"
CASES = [
    # data files to run (a folder with a manifest), init (one lab file) and replay
    Case("empty_file", "run", _run_h(lambda d: (d / F).write_text("")), file=F),
    Case("header_only", "run", _run_h(lambda d: _put(d / F, _lines(d / F)[:1])), file=F),
    Case("dup_header", "init", _init_fl(lambda p: _put(p, [_lines(p)[0].replace("t2(°C)", "t1(°C)")]
                                                       + _lines(p)[1:])), file="lab.csv", column="t1(°C)"),
    Case("text_na", "run", _run_h(lambda d: _cell(d / F, 10, "T_nose", "n/a")), file=F, column="T_nose",
         row=True),
    Case("text_dashes", "run", _run_h(lambda d: _cell(d / F, 10, "T_nose", "--")), file=F, column="T_nose",
         row=True),
    Case("text_dots", "run", _run_h(lambda d: _cell(d / F, 10, "E_Z", "1.2.3")), file=F, column="E_Z",
         row=True),
    Case("init_text_dots", "init", _init_fl(lambda p: _cell(p, 500, "t3(°C)", "1.2.3")), file="lab.csv",
         column="t3(°C)", row=True),
    Case("time_backwards", "run", _run_h(lambda d: _cell(d / F, 10, "time", "600")), file=F, column="time",
         row=True),
    Case("dup_timestamps", "run", _run_h(lambda d: _cell(d / F, 10, "time", "2400")), file=F, column="time",
         row=True),
    Case("gap_10_periods", "run", _run_h(_gap), file=F, column="time", row=True),
    Case("all_nan_error", "run", _run_h(lambda d: _column(d / F, "E_Z", lambda i, v: "")), file=F,
         column="E_Z"),
    Case("constant_temperature", "run", _run_h(lambda d: _all_files(d, lambda f: _column(
        f, "T_nose", lambda i, v: "20.0"))), column="T_nose"),
    Case("inf_cell", "run", _run_h(lambda d: _cell(d / F, 10, "T_nose", "inf")), file=F, column="T_nose",
         row=True),
    Case("huge_cell", "run", _run_h(lambda d: _cell(d / F, 10, "E_Z", "1e308")), file=F, column="E_Z",
         row=True),
    Case("delimiter_midfile", "run", _run_h(lambda d: _delim(d / F)), file=F, row=True),
    Case("ragged_long_row", "run", _run_h(_ragged(True)), file=F, row=True),
    Case("ragged_short_row", "run", _run_h(_ragged(False)), file=F, row=True),
    Case("manifest_missing_file", "run", _run_h(_manifest(lambda ls: ls + [
        ls[2].replace("K02,K02.csv", "K99,K99.csv")])), file="K99.csv"),
    Case("manifest_campaign_twice", "run", _run_h(_manifest(_dup_campaign)), file="campaigns.csv",
         column="campaign", row=True),
    Case("parquet_text_dtype", "run", _parquet_text, file="lab.parquet", column="t2(°C)"),
    Case("binary_file", "init", _write_file("lab.csv", bytes(range(256)) * 40), file="lab.csv"),
    Case("json_as_csv", "init", _write_file("lab.csv", b'{"time": [0, 15], "t1": [20.1, 20.2]}\n'),
         file="lab.csv"),
    Case("json_file", "init", _write_file("lab.json", b'{"time": [0, 15], "t1": [20.1, 20.2]}\n'),
         file="lab.json"),
    Case("init_empty", "init", _write_file("lab.csv", b""), file="lab.csv"),
    Case("replay_text_cell", "replay", _replay_h(lambda d: _cell(d / TE, 10, "T_nose", "1.2.3")), file=TE,
         column="T_nose", row=True),
    Case("replay_missing_column", "replay", _replay_h(lambda d: _drop(d / TE, "T_nose")), file=TE,
         column="T_nose"),
    # overrides / configs
    Case("unknown_key", "run", lambda c, b: [f"data.path={b / 'h'}", "data.test_fractoin=0.1"]),
    Case("test_fraction_abc", "init", _init_fl(lambda p: None, "data.test_fraction=abc")),
    Case("test_fraction_1.5", "init", _init_fl(lambda p: None, "data.test_fraction=1.5")),
    Case("test_fraction_negative", "init", _init_fl(lambda p: None, "data.test_fraction=-0.1")),
    Case("role_matches_nothing", "init", _init_fl(lambda p: None, "data.roles.error=[zz*]"), file="lab.csv"),
    Case("two_roles_one_column", "init", _init_fl(lambda p: None, "data.roles.error=[ch*]",
                                                  "data.roles.state=[ch1*]"), file="lab.csv",
         column="ch1(um)"),
    Case("missing_data_path", "run", lambda c, b: [f"data.path={c / 'in' / 'nothere'}"], file="nothere"),
    # models and deployment inputs
    Case("replay_truncated_model", "replay", _with_model("replay", "truncated"), file="model.pkl"),
    Case("replay_foreign_model", "replay", _with_model("replay", "foreign"), file="model.pkl"),
    Case("export_truncated_model", "export", _with_model("export", "truncated", "export.format=c"),
         file="model.pkl"),
    Case("export_text_model", "export", _with_model("export", "text", "export.format=c"), file="model.pkl"),
    Case("monitor_truncated_model", "monitor", _with_model("monitor", "truncated"), file="model.pkl"),
    Case("serve_truncated_model", "serve", _with_model("serve", "truncated"), file="model.pkl"),
    Case("serve_foreign_model", "serve", _with_model("serve", "foreign"), file="model.pkl"),
    Case("replay_other_records_model", "replay", _replay_h(lambda d: None, model="fl"), column="t1(°C)"),
    Case("monitor_other_records_model", "monitor", lambda c, b: [
        f"data.path={b / 'h'}", f"monitor.model={b / 'model_fl' / 'model.pkl'}", *QUIET], column="t1(°C)"),
    Case("monitor_stream_missing_column", "monitor", _monitor_stream, column="T_nose",
         stdin=lambda c, b: _stream(c, b, drop="T_nose")),
    Case("monitor_stream_extra_column", "monitor", _monitor_stream, column="T_extra",
         stdin=lambda c, b: _stream(c, b, extra="T_extra")),
]


# -- running a case ------------------------------------------------------------------------------

def _listing(root: Path) -> dict[str, tuple[int, int]]:
    out = {}
    for path in root.rglob("*"):
        rel = path.relative_to(root)
        if rel.parts[0] == "in" or path.is_symlink():
            continue
        if path.is_file():
            st = path.stat()
            out[str(rel)] = (st.st_size, st.st_mtime_ns)
    return out


def _mlflow_runs(root: Path) -> list[str]:
    db = root / "mlruns" / "mlflow.db"
    if not db.exists():
        return []
    with sqlite3.connect(db) as con:
        try:
            return [f"{name}:{status}" for name, status in con.execute("select name, status from runs")]
        except sqlite3.Error:
            return []


def run_case(case: Case, cases_dir: Path, base_dir: Path) -> dict:
    folder = cases_dir / case.name
    if folder.exists():
        shutil.rmtree(folder)
    _root(folder)
    args = case.make(folder, base_dir)
    stdin = case.stdin(folder, base_dir) if case.stdin else None
    before = _listing(folder)
    rc, _, err = thermocomp(folder, [case.stage, *args, f"out={folder / 'out'}"], stdin=stdin,
                            timeout=60 if case.stage == "serve" else 300)
    after = _listing(folder)
    changed = sorted(k for k in after if before.get(k) != after[k])
    lines = [x for x in err.splitlines() if x.strip()]
    said = [x for x in lines if x.startswith("thermocomp: error:")]
    first = said[0] if said else (lines[0] if lines else "")
    runs = _mlflow_runs(folder)
    written = [k for k in changed if k.split(os.sep)[0] in WRITES]
    row = {"case": case.name, "stage": case.stage, "exit": rc, "first": first[:300],
           "traceback": "Traceback (most recent call last)" in err, "lines": len(lines),
           "names_file": None if case.file is None else case.file in first,
           "names_column": None if case.column is None else case.column in first,
           "names_row": None if not case.row else bool(ROW.search(first)),
           "written": written, "other_files": [k for k in changed if k not in written],
           "mlflow_runs": runs}
    row["b1"] = rc == 2
    row["b2"] = not row["traceback"] and bool(said) and lines[-1] == said[-1]
    row["b3"] = all(v is not False for v in (row["names_file"], row["names_column"], row["names_row"]))
    row["b4"] = not written and not any(r.endswith((":FINISHED", ":RUNNING")) for r in runs)
    return row


def cases(root: str, names: str = "") -> None:
    """Every case (or those ``names`` lists) -> ROOT/cases.json and a table."""
    folder = Path(root).resolve()
    base_dir = folder / "base"
    assert (base_dir / "model_h" / "model.pkl").exists(), "run `base ROOT` first"
    wanted = [n for n in names.split(",") if n]
    chosen = [c for c in CASES if not wanted or c.name in wanted]
    out = folder / "cases.json"
    rows = json.loads(out.read_text()) if out.exists() and wanted else []
    rows = [r for r in rows if r["case"] not in wanted]
    for case in chosen:
        row = run_case(case, folder / "cases", base_dir)
        rows.append(row)
        flags = "".join("." if row[b] else b[1] for b in ("b1", "b2", "b3", "b4"))
        print(f"{case.name:32s} {case.stage:8s} exit {row['exit']}  {flags}  {row['first'][:150]}",
              flush=True)
        out.write_text(json.dumps(rows, indent=1, ensure_ascii=False))
    order = [c.name for c in CASES]
    rows.sort(key=lambda r: order.index(r["case"]))
    out.write_text(json.dumps(rows, indent=1, ensure_ascii=False))
    for b in ("b1", "b2", "b3", "b4"):
        print(f"{b}: {sum(r[b] for r in rows)} of {len(rows)} met; broken: "
              f"{', '.join(r['case'] for r in rows if not r[b]) or '-'}")


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"base": base, "cases": cases},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
