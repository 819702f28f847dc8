"""Two columns alike but for their unit are read as twins (stop 98, twins98; issue 34 item 1, "a
lab's file in one command", "the deployed model accepts the lab's own names").

names97b (``bench_names97b.py``; seen) found: a lab's header holding one name in two units,
``Temperatura basamento [°C]`` and ``Temperatura basamento [K]`` (two sensors, or one logged
twice), is refused by init and run ("... both give T_Temperatura_basamento; give each ... a name
(data.columns)"), and a ``data.columns`` key with spaces or brackets is no command-line override:
the user must edit init's yaml.  The same header written twice in ONE unit is read (twins.py
``occurrences``: ``Temp#2 [°C]``, ``T_Temp_2``, with a warning).

Rule (``core/io/roles.py`` ``naming`` / ``again_in``; the warning in ``twins.said``; no key): the
name before a header's unit (``split_unit``'s, every spelling it reads: ``t1(°C)``, ``t1 [K]``,
``t1_degC``) that an earlier header with a unit gave already is numbered ``<name>#<k>`` before
its contract name is derived (``T_Temp``, ``T_Temp_2``), as the second of a header written twice
is.  Each header keeps its own text: ``data.columns`` / ``data.roles`` address it as before, the
stored model's lab names hold it as written (``Temp [K]`` -> ``T_Temp_2``, its kelvin converted),
and the exported ``stream.c`` reads the header by that text (or joined to its unit row,
``unit_named``): no split in the C, so no spelling the C cannot split; a bare ``Temp`` in the
streamed header beside the two is refused by the C as names97 refuses it.  Only a header WITH a
unit is numbered: a bare ``T`` beside ``T [K]`` is still refused by the reader ("both give T_T").
A twin whose values are the other's reading in the other unit (K = °C + 273.15 within the file's
rounding) is READ, not left out as ``same_cells`` leaves an identical copy: same_cells' rule is
text identity, no tolerance; "within the rounding" is a guess about how a logger rounds each
column (0.01 K beside 0.1 °C), and two sensors mounted side by side agree within it as well;
reading both is what the file says, said in a warning.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_twins98.py repro ROOT        # the brief's `;`/decimal-comma file
    python benchmarks/bench_twins98.py lab ROOT SEED     # bench_names97b's twinit, no key

``repro``: ``time [s];Temp basamento [°C];Temp basamento [K];Temp colonna [°C];dX [µm]`` (480
rows, 60 s, seed 98, dX from both basamento sensors and the colonna) written to
``ROOT/labrepro/repro.csv``.  ``lab``: bench_names97b's ``twinit.csv`` of bench_audit96's lab SEED
(``Temperatura basamento`` over ``°C`` and over ``K``, ``Temperatura portautensile`` twice over
``°C``, a unit row, ``sep=;``, decimal commas).  Each through bench_data92's stage (init with NO
key -> run ``data.test_fraction=0.25`` mlr -> replay -> export C with its check pack -> the C fed
the file's raw bytes), then the served session (bench_data94's ``sent``: blocks, the first
continuing the train part) fed the test rows under the lab's own names as the reader names them,
a column read in another unit under its contract name converted (the served model takes such a
column so: ``deploy.naming.lab_units``; bench_names97b's session likewise): max |C - session| µm.

BAR (written and committed BEFORE fresh lab 9858 is drawn; repro and lab 9829 are seen: 9829 was
names97b's fresh lab, stopped at init)
-----------------------------------------------------------------------------------------------
T1. seen repro and lab 9829: on main init exit 2 "... both give T_..." (as measured); with the
    rule init .. run .. replay .. export .. pack 0 .. C exit 0 with no key, the C's rows = the
    file's data rows, max |C - session| <= 1e-9 µm.
T2. FRESH lab 9858 (twinit, no key, mlr; drawn after this bar, scored once): as T1 with the rule.
T3. unchanged with the rule: ``bench_names97b twounits`` (a) exit 0, 48 rows, <= 1e-9 µm; (b)
    <= 1e-9 µm; (c) a bare ``T`` beside ``T [K]`` exit 2, names97's line; ``bench_names97b lab
    ROOT 9774 keyed`` replay 1.823539367 / 1.207312034 µm, C 0, 1441 rows, |C - session| <= 1e-9;
    ``bench_names97b lab ROOT 9830 keyed`` replay 2.038472787 / 1.385004397 µm, C 0, 1441 rows,
    |C - session| <= 1e-9 µm.
T4. tests (< 10 s) failing on 4b9de3c8: the pair read (T_t1, T_t1_2, the kelvin converted) and
    the C fed the file = the served session; a bare ``T`` beside ``T [K]`` still refused by the
    reader, and by the exported stream.c in a streamed header.
KEPT if T1-T4 hold with src + tests + docs; a clause not met is said and the rule REFUSED (patch
kept as benchmarks/twins98_rule.patch) or the finding TRACED.

Status: the bar committed in adef5e74, the rule in e0eafe61, before lab 9858 was drawn (its lab
simulated by the fresh run itself).  Scored 2026-12-06 09:31-09:38 UTC (2 cores shared, load
~20, ``nice``), main = 4b9de3c8's src (``git archive``), rule = e0eafe61's src (``git archive``).

  record                         main (4b9de3c8)                    rule
  repro (seen, T1)               init exit 2 "'Temp basamento [°C]'  init .. pack 0, C 0, 480 rows;
                                 and 'Temp basamento [K]' both give  replay = run 0.04505 µm;
                                 T_Temp_basamento ..."               |C - session| 7.1e-15 µm (120)
  lab 9829 twinit (seen, T1)     init exit 2 "'Temperatura           init .. pack 0, C 0, 1441 rows;
                                 basamento [°C]' and 'Temperatura    replay 1.158816394 / 0.846494797;
                                 basamento [K]' both give            |C - session| 2.1e-13 µm (360)
                                 T_Temperatura_basamento ..."
  lab 9858 twinit (FRESH, T2,    (not run: drawn for the rule)       init .. pack 0, C 0, 1441 rows;
  once)                                                              replay 1.642938936 / 1.147578659;
                                                                     |C - session| 1.7e-13 µm (360)
  names97b twounits (T3)         (names97b's: (a) 3.6e-15, (b)       (a) exit 0, 48 rows, 3.6e-15 µm;
                                 3.6e-15, (c) exit 2)                (b) 3.6e-15 µm; (c) exit 2,
                                                                     "column 2: 'T' may be 'T [°C]'
                                                                     or 'T [K]' ..."
  names97b lab 9774 keyed (T3)   (names97b's: 1.823539367 /          replay 1.823539367 /
                                 1.207312034, 1.3e-13)               1.207312034; C 0, 1441 rows;
                                                                     |C - session| 1.3e-13 µm
  names97b lab 9830 keyed (T3)   (names97b's: 2.038472787 /          replay 2.038472787 /
                                 1.385004397, 1.8e-13)               1.385004397; C 0, 1441 rows;
                                                                     |C - session| 1.8e-13 µm

T1-T3 met; T4: tests/shell/test_twins98.py, 2 cases (7.4 s + 0.1 s), both fail on 4b9de3c8
("'T [°C]' and 'T [K]' both give T_T", "'t1(°C)' and 't1 [K]' both give T_t1").  After the
fresh run (no name, value nor refusal changed): the reader's warning finds a numbered twin by
its name's ``_<k>`` (``T_2`` was not said: e0eafe61 asked ``T_T_``), and ``_scored`` / ``lab``
share bench_names97b's ``reported`` / ``twin_file`` (duplicates D1): repro, 9829 and names97b's
9774 keyed run again on them with 5edff0ec's src: every figure the same (9858 not run again).
CPU of the bench process: repro 3.0-3.3 s, lab 3.3-4.4 s (stage subprocesses not counted: 16-21 s
user of the whole); wall: main's init refusals ~9-10 s, repro ~74 s, lab ~78-95 s on an existing
lab root (9858 simulated in its ~87 s).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402

REPRO_HEADER = "time [s];Temp basamento [°C];Temp basamento [K];Temp colonna [°C];dX [µm]"


def _repro_text(n: int = 480, seed: int = 98) -> str:
    """The brief's file (module doc): ``;``, decimal commas, one name in °C and in K."""
    rng = np.random.default_rng(seed)
    day = np.sin(np.arange(n) * 2 * np.pi / 240)
    a = 20 + 2 * day + np.cumsum(rng.normal(0, 0.03, n))
    b = 21 + 1.5 * np.roll(day, 20) + np.cumsum(rng.normal(0, 0.03, n))
    c = 22 + np.cumsum(rng.normal(0, 0.03, n))
    dx = 3 * (a - a[0]) - 2 * (b - b[0]) + 1.5 * (c - c[0]) + rng.normal(0, 0.05, n)

    def cells(*values: float) -> str:
        return ";".join(f"{v:.3f}".replace(".", ",") for v in values)

    return "\n".join([REPRO_HEADER, *(f"{60 * i};" + cells(a[i], b[i] + 273.15, c[i], dx[i])
                                      for i in range(n))]) + "\n"


def _scored(base: Path, label: str, rows) -> None:
    """bench_data92's stage on ``base/label.csv`` (no key), then the served session fed
    ``rows(config)``'s test rows (:func:`_in_contract_units`): what each said, max |C - session|."""
    from bench_data92 import _stage
    from bench_names97b import reported

    reported(_stage(base, label, "mlr", ()), base, label,
             lambda model, config: _in_contract_units(rows(config), model), "the lab's names")


def _in_contract_units(frame: pd.DataFrame, model) -> pd.DataFrame:
    """``frame`` (the lab's names) with each column the reader read in another unit under its
    contract name, converted as the reader converts it (value * scale, then + offset): the
    served model takes such a column by its contract name only (``deploy.naming.lab_units``)."""
    frame = frame.copy()
    for header, (contract, scale, offset) in (model.streaming.lab_units_ or {}).items():
        if header in frame.columns:
            frame[contract] = frame.pop(header) * scale + offset
    return frame


def repro(root: str) -> None:
    """The brief's file through init .. C with no key, and the served session (module doc)."""
    import bench_audit91
    from bench_data94 import _raw_rows

    base = bench_audit91.lab_root(root, "repro")
    path = base / "repro.csv"
    path.write_text(_repro_text(), encoding="utf-8")
    print(f"repro: header {REPRO_HEADER!r}, {len(_repro_text().splitlines()) - 1} rows", flush=True)
    _scored(base, "repro", lambda config: _raw_rows(path, config))


def lab(root: str, seed: str) -> None:
    """bench_names97b's twin-header export of lab SEED with no key (module doc)."""
    from bench_names97b import LABEL, reader_rows, twin_file

    base, path = twin_file(root, seed)
    _scored(base, LABEL, lambda config: reader_rows(path)[0])


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"repro": repro, "lab": lab}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
