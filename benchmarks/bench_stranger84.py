"""A stranger's pass on an ISO 230-3 spindle test rig (five capacitive probes) logged by HBM
catman, exported as catman's ASCII file (stranger84).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger84.py write ROOT SEED [LOCALE] [clean]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger84.py faults ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger84.py broken ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger84.py matrix ROOT SEED CONF

The rig is ``benchmarks/spindle84.py`` (a motor spindle in a housing flange on a fixture plate,
a chiller-fed stator jacket, oil-air bearings; five capacitive probes at a test mandrel, X1 / Y1
20 mm and X2 / Y2 120 mm from the nose, Z at its end; ten 8 h ISO 230-3 tests over two weeks
from Monday 2027-05-03, a constant speed or a speed spectrum then a cool-down; PLANTED: the
shaft's centrifugal pull of the nose, ``-2.5 (n / 10 krpm)^2`` µm on Z at once with the speed,
which no thermocouple sees; seeds 8726-8730 only).

``write``: ``ROOT/spindle<SEED>/SP84_T<NN>.TXT``, a file a test, as catman (AP / Easy) exports a
measurement to ASCII with the channel header (written from memory of catman's export dialogue
and its files, NOT checked against a file a real installation wrote): Windows-1252, CRLF;

* a header block: ``File:`` (the measurement's ``.BIN``), ``Comment:``, ``catman Version:``,
  ``Export:`` (the export's date and time), ``Channels:``, an empty line;
* a block a channel, in the table's column order: ``Channel <k>:`` and its name, ``Unit:``,
  ``Comment:``, ``Sample rate:`` (Hz), ``T0:`` (the group's start, the PC's date and time),
  ``Length:`` (its samples), an empty line;
* the table: a row of the channels' names, then a row a sample; each rate group its own time
  channel first (``Time  1 - default sample rate``, ``Time  2 - 0.01667 Hz``: seconds from its
  T0), a slower group's cells empty under its last sample.

``LOCALE`` ``en`` (the default; seed 8726): catman AP on an English PC, TAB between cells,
``.`` decimals, ``05/03/2027 07:00:00`` (month first); TWO rate groups: the probes (``MCS X1``
... ``MCS Z``, ``µm``) and the speed (``Spindle speed``, ``rpm``) at 0.1 Hz, the eight
thermocouples (``T air`` ... ``T oil``, ``°C``) at 1/60 Hz.  ``de`` (the fresh draw 8727):
catman Easy on a German PC, ``;`` between cells, decimal commas, ``03.05.2027 07:00:00``, the
keys in German (``Datei:``, ``Kommentar:``, ``Kanal 1:``, ``Einheit:``, ``Abtastrate:``,
``Länge:``), ONE group, every channel at 1/30 Hz (``Zeit  1 - Standardmessrate``, ``Sonde X1``
..., ``T Luft`` ..., ``Drehzahl`` in ``1/min``).  The probes are zeroed at each test's start
(catman's zero balance).  ``clean``: the same draws without the planted pull
(``ROOT/clean<SEED>/``), the control diagnose should accept nothing on Z's speed in.

``faults``: ``ROOT/fault_<kind>_<SEED>/``, the files (``en``), the last test with one fault
(its temperature group's rows): ``frozen`` (``T_STATOR`` held from row 200, 3.3 h in),
``jump`` (+2 K on ``T_HOUSING`` from row 220), ``drift`` (``T_OIL`` +1 K/h from row 150),
``dropout`` (60 samples of ``T_REAR`` empty cells from row 260).

``broken``: ``ROOT/broken_<kind>_<SEED>/``, tests 1-4 (``en``) with one file spoiled: ``cut``
(test 3 cut 200 bytes before its end, inside a row, as a PC stopped while writing leaves it),
``cell`` (test 2's ``MCS Y2`` on its 1000th sample ``1.2#4``), ``short`` (test 4's last 100
rows gone at a line's end: fewer rows than its blocks' ``Length:``).

``matrix``: bench_stranger75's (run -> replay per family on the data config init wrote).

What is measured (written before anything ran): ``init`` as a stranger types it (tries, each
refusal's message followed); ``matrix`` (every family, run = replay = batch); ``diagnose``
(MLR, defaults; with 8 train campaigns: the planted speed effect on Z accepted?); ``monitor``
(the matrix's mlr) on the healthy last test and the four faults; a tracked sweep, ``promote``,
C ``export`` with its check pack, ``thermocomp rows`` through ``./stream`` = run; CPU (user +
sys) of each command.  No rule is adopted from these records: they are a check, not a tuning
set.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402
from _faults import fault_folders, four_faults  # noqa: E402
from bench_stranger75 import matrix  # noqa: E402

SLOW = 6                         # en: the temperatures every 6th sample (60 s)
ONE_GROUP = 3                    # de: every channel every 3rd sample (30 s)
NAMES = {  # contract's -> (en, de, unit en, unit de, comment)
    "E_X1": ("MCS X1", "Sonde X1", "µm", "µm", "MCS capacitive 0-250 µm, 20 mm"),
    "E_Y1": ("MCS Y1", "Sonde Y1", "µm", "µm", "MCS capacitive 0-250 µm, 20 mm"),
    "E_X2": ("MCS X2", "Sonde X2", "µm", "µm", "MCS capacitive 0-250 µm, 120 mm"),
    "E_Y2": ("MCS Y2", "Sonde Y2", "µm", "µm", "MCS capacitive 0-250 µm, 120 mm"),
    "E_Z": ("MCS Z", "Sonde Z", "µm", "µm", "MCS capacitive 0-250 µm, end face"),
    "speed": ("Spindle speed", "Drehzahl", "rpm", "1/min", "Drive analogue out"),
    "T_AIR": ("T air", "T Luft", "°C", "°C", "MX1609 type K"),
    "T_BASE": ("T base", "T Grundplatte", "°C", "°C", "MX1609 type K"),
    "T_HOUSING": ("T housing", "T Gehäuse", "°C", "°C", "MX1609 type K"),
    "T_FRONT": ("T front bearing", "T Lager vorn", "°C", "°C", "MX1609 type K"),
    "T_REAR": ("T rear bearing", "T Lager hinten", "°C", "°C", "MX1609 type K"),
    "T_STATOR": ("T stator", "T Stator", "°C", "°C", "MX1609 type K"),
    "T_COOLANT": ("T coolant", "T Kühlwasser", "°C", "°C", "MX1609 type K"),
    "T_OIL": ("T oil", "T Öl", "°C", "°C", "MX1609 type K"),
}
KEYS = {"en": ("File", "Comment", "Channels", "Channel", "Unit", "Sample rate", "Length"),
        "de": ("Datei", "Kommentar", "Kanäle", "Kanal", "Einheit", "Abtastrate", "Länge")}


def runs(seed: int, clean: bool = False):
    """The record: ``(spindle84 result, [(label, local start, rows)])``; ``clean``: without the
    planted pull."""
    import spindle84 as m
    r = m.simulate(int(seed), 0.0 if clean else m.PULL_UM)
    return r, [(f"{n:02d}", start, np.arange(rows.start, rows.stop))
               for n, (start, rows) in enumerate(m.run_windows(), start=1)]


def _num(v: float, digits: int, comma: bool) -> str:
    text = "" if np.isnan(v) else f"{v:.{digits}f}"
    return text.replace(".", ",") if comma else text


def _stamp(at, locale: str) -> str:
    return f"{at:%m/%d/%Y %H:%M:%S}" if locale == "en" else f"{at:%d.%m.%Y %H:%M:%S}"


def export_text(r, label: str, start, idx: np.ndarray, locale: str = "en", fault=None) -> str:
    """One test's catman ASCII export (module docstring)."""
    import spindle84 as m
    de = locale == "de"
    sep, lang = (";", 1) if de else ("\t", 0)
    fast = idx[::ONE_GROUP] if de else idx
    slow = idx[::ONE_GROUP] if de else idx[::SLOW]
    temps = {name: r["sensors"][slow, j] for j, (name, _, _) in enumerate(m.SENSORS)}
    if fault is not None:
        temps = {name: fault(name, v) for name, v in temps.items()}
    probes = {e: r[e][fast] - r[e][idx[0]] for e in ("E_X1", "E_Y1", "E_X2", "E_Y2", "E_Z")}
    groups = [(fast, {**probes, "speed": r["speed"][fast]})]
    if de:
        groups[0][1].update(temps)
    else:
        groups.append((slow, temps))
    key = dict(zip(("file", "comment", "channels", "channel", "unit", "rate", "length"), KEYS[locale]))
    columns = []                                # (name, unit, comment, rate Hz, cells)
    for g, (rows, chans) in enumerate(groups, start=1):
        period = (rows[1] - rows[0]) * m.STEP_S
        time_name = (("Zeit" if de else "Time") + f"  {g} - "
                     + (("Standardmessrate" if de else "default sample rate") if g == 1
                        else _num(1 / period, 5, de) + " Hz"))
        columns.append((time_name, "s", "", 1 / period, [_num(k * period, 1, de)
                                                          for k in range(rows.size)]))
        for name, v in chans.items():
            spec = NAMES[name]
            digits = 0 if name == "speed" else 2 if name.startswith("E_") else 3
            columns.append((spec[lang], spec[2 + lang], spec[4], 1 / period,
                            [_num(float(x), digits, de) for x in v]))
    head = [f"{key['file']}:{sep}D:\\catman\\SP84\\SP84_T{label}.BIN",
            f"{key['comment']}:{sep}ISO 230-3 test {label} - motor spindle MS-18, rig 2",
            f"catman Version:{sep}{'catmanEasy 5.6.1' if de else 'catmanAP 5.6.1'}",
            f"Export:{sep}{_stamp(start.replace(hour=15, minute=4, second=12), locale)}",
            f"{key['channels']}:{sep}{len(columns)}", ""]
    for k, (name, unit, comment, rate, cells) in enumerate(columns, start=1):
        head += [f"{key['channel']} {k}:{sep}{name}", f"{key['unit']}:{sep}{unit}",
                 f"{key['comment']}:{sep}{comment}",
                 f"{key['rate']}:{sep}{_num(rate, 5, de)}", f"T0:{sep}{_stamp(start, locale)}",
                 f"{key['length']}:{sep}{len(cells)}", ""]
    lines = head + [sep.join(c[0] for c in columns)]
    for i in range(max(len(c[4]) for c in columns)):
        lines.append(sep.join(c[4][i] if i < len(c[4]) else "" for c in columns))
    return "\r\n".join(lines) + "\r\n"


def _write_all(folder: Path, r, runs_, locale: str = "en", fault=None) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    for n, (label, start, idx) in enumerate(runs_):
        last = fault if n == len(runs_) - 1 else None
        (folder / f"SP84_T{label}.TXT").write_bytes(
            export_text(r, label, start, idx, locale, last).encode("cp1252"))


def write(root: str, seed: str, locale: str = "en", clean: str = "") -> None:
    """The lab's files of seed ``seed``: ``ROOT/spindle<SEED>/`` (``clean``: ``clean``, without
    the planted pull, ``ROOT/clean<SEED>/``)."""
    r, runs_ = runs(int(seed), clean == "clean")
    folder = Path(root) / f"{'clean' if clean == 'clean' else 'spindle'}{seed}"
    _write_all(folder, r, runs_, locale)
    print(f"wrote {folder} ({len(runs_)} files, {sum(i.size for _, _, i in runs_)} samples)")


def faults(root: str, seed: str) -> None:
    """``ROOT/fault_<kind>_<SEED>/``: the files, the last test with one fault (docstring)."""
    r, runs_ = runs(int(seed))
    n = runs_[-1][2][::SLOW].size
    cases = four_faults(n, 60.0, frozen=("T_STATOR", 200), jump=("T_HOUSING", 220),
                        drift=("T_OIL", 150), dropout=("T_REAR", 260, 320))
    fault_folders(root, seed, cases, lambda folder, fault: _write_all(folder, r, runs_, "en", fault))


def broken(root: str, seed: str) -> None:
    """``ROOT/broken_<kind>_<SEED>/``: tests 1-4 with one file spoiled (docstring)."""
    r, runs_ = runs(int(seed))
    for kind in ("cut", "cell", "short"):
        folder = Path(root) / f"broken_{kind}_{seed}"
        _write_all(folder, r, runs_[:4])
        if kind == "cut":
            path = folder / "SP84_T03.TXT"
            path.write_bytes(path.read_bytes()[:-200])
        elif kind == "cell":
            path = folder / "SP84_T02.TXT"
            lines = path.read_bytes().decode("cp1252").split("\r\n")
            top = next(k for k, line in enumerate(lines) if line.startswith("Time  1"))
            cells = lines[top + 1000].split("\t")
            cells[4] = "1.2#4"                  # MCS Y2, its 1000th sample
            lines[top + 1000] = "\t".join(cells)
            path.write_bytes("\r\n".join(lines).encode("cp1252"))
        else:
            path = folder / "SP84_T04.TXT"
            lines = path.read_bytes().split(b"\r\n")
            path.write_bytes(b"\r\n".join(lines[:-101]) + b"\r\n")
        print(f"wrote {folder}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "faults": faults, "broken": broken,
                                  "matrix": matrix}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
