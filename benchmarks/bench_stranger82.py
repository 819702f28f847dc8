"""A stranger's pass on a precision lathe and its Graphtec GL840 CSV files (stranger82).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger82.py write ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger82.py faults ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger82.py matrix ROOT SEED CONF

The machine is ``benchmarks/lathe82.py`` (a flat-bed precision lathe, its own lumped network
and kinematics: a headstock with a front and a rear bearing set and its motor, a Z carriage and
an X cross slide on ball screws heated by their nuts, a turret, a tailstock and its quill, the
coolant and the chuck's hydraulic unit (not logged); a tempered shop (20.5 +- 1 K); 12 day runs
of 10 h from 07:00 on 12 of 19 days from Monday 2027-06-07, the shop using the machine unlogged
on other weekdays; 16 thermocouples, the mandrel's dX / dZ at two eddy-current probes; planted
position effects X x the X screw's rise (dX), Z x the Z screw's rise (dZ) and Z x the
tailstock's against the headstock's rise (dX); seeds 8211-8215 only).

``write``: the runs as the lab's Graphtec GL840 midi logger saves them to its SD card in CSV,
a file a run ``ROOT/lathe<SEED>/<yyMMdd>-<HHmmss>.CSV`` (the logger's own name, its capital
extension): a header block (``"Model","GL840"``, ``"Title"``, ``"Trigger Time"`` written
``'2027/06/07 07:00:00`` with the apostrophe that keeps a spreadsheet from reading it),
``"Amp settings"``: a row a channel (``CH``, ``Signal name``, ``Input``, ``Range``,
``Filter``, ``Span``, ``Scaling``, ``Unit``): the names the lab gave live here only), then
``"Data"``: the column row ``NO.``, ``Time``, ``ms``, ``CH1`` .. ``CH21``, ``Alarm1-10``,
``Alarm11-20``, ``Alarm21-30``, ``AlarmOut``, a unit row (``um``, ``mm``, ``rpm``, ``degC``),
then a row a sample (its number, ``2027/06/07 07:00:20``, ``0`` ms, values signed ``+21.3``, a
broken thermocouple ``BURNOUT``, the alarms ``LLLLLLLLLL``).  Channels: CH1 / CH2 the probes
(DC 1 V scaled to µm), CH3 - CH5 the drives' analog monitor outputs (X, Z mm, the spindle's
rpm), CH6 - CH21 the thermocouples (type K).  Quirks: ``LAGER_H``'s plug loose for 5 samples in
run 5 (``BURNOUT``), the logger stopped and restarted in run 9 (two files, 10 min apart).  The
structure is the GL840's CSV as Graphtec's manual and users' posts describe it; no file a
GL840 wrote was at hand to check it.

``faults``: ``ROOT/fault_<kind>_<SEED>/``, the files, the last run with one fault: ``frozen``
(``SPINDELKASTEN`` held from row 900, 5 h in), ``jump`` (+2 K on ``BETT_R`` from row 1000),
``drift`` (``KUEHLMITTEL`` +1 K/h from row 700), ``dropout`` (90 ``BURNOUT`` of ``MUTTER_Z``
from row 1200).

``matrix``: bench_stranger75's (run -> replay per family on the data config init wrote).
"""
from __future__ import annotations

import sys
from datetime import timedelta
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402
from _faults import four_faults  # noqa: E402
from bench_stranger75 import matrix  # noqa: E402

LOOSE_RUN, LOOSE_SIGNAL, LOOSE_ROW = 5, "LAGER_H", 700
SPLIT_RUN, SPLIT_ROW, SPLIT_GAP = 9, 1000, 30     # the logger restarted 5.6 h in, 10 min later


def channels() -> list[tuple[str, str, str, str]]:
    """``(signal name, input, unit, the simulation's key or sensor)`` in channel order."""
    import lathe82 as m
    out = [("DX_DORN", "DC", "um", "E_dX"), ("DZ_DORN", "DC", "um", "E_dZ"),
           ("X_ISTWERT", "DC", "mm", "x"), ("Z_ISTWERT", "DC", "mm", "z"),
           ("DREHZAHL", "DC", "rpm", "speed")]
    return out + [(name, "TEMP", "degC", name) for name, _, _ in m.SENSORS]


def runs(seed: int):
    """The record: ``(lathe82 result, [(run label, local start, rows)])``."""
    import lathe82 as m
    r = m.simulate(int(seed))
    out = []
    for n, (start, rows) in enumerate(m.run_windows(), start=1):
        idx = np.arange(rows.start, rows.stop)
        if n == SPLIT_RUN:
            out.append((f"{n:02d}a", start, idx[:SPLIT_ROW]))
            out.append((f"{n:02d}b", start + timedelta(seconds=(SPLIT_ROW + SPLIT_GAP) * m.STEP_S),
                        idx[SPLIT_ROW + SPLIT_GAP:]))
        else:
            out.append((f"{n:02d}", start, idx))
    return r, out


def _column(r, key, idx):
    import lathe82 as m
    names = [s[0] for s in m.SENSORS]
    return r["sensors"][idx, names.index(key)] if key in names else r[key][idx]


def _value(v: float, unit: str) -> str:
    if np.isnan(v):
        return "BURNOUT"
    return f"{v:+.0f}" if unit == "rpm" else f"{v:+.1f}" if unit in ("degC", "mm") else f"{v:+.2f}"


def write_file(path: Path, r, label: str, start, idx, fault=None) -> None:
    """One run's CSV as the GL840 saves it (module docstring); ``fault(name, values)`` alters a
    temperature."""
    import lathe82 as m
    chans = channels()
    cols = []
    for name, _, _, key in chans:
        v = np.asarray(_column(r, key, idx), dtype=float)
        if label == f"{LOOSE_RUN:02d}" and name == LOOSE_SIGNAL:
            v = v.copy()
            v[LOOSE_ROW:LOOSE_ROW + 5] = np.nan
        cols.append(fault(key, v) if fault is not None else v)
    q = '"{}"'.format
    lines = ['"Model","GL840"', '"Title","WAERMEGANG DM-3 LAUF ' + label + '"',
             f'"Trigger Time","\'{start:%Y/%m/%d %H:%M:%S}"', '', '"Amp settings"',
             '"CH","Signal name","Input","Range","Filter","Span","Scaling","Unit"']
    for i, (name, kind, unit, _) in enumerate(chans, start=1):
        rng, span, scale = (("TC_K", '"0.0,100.0"', '"Off"') if kind == "TEMP" else
                            ("1V", '"-1.000,1.000"', '"On"'))
        lines.append(",".join([q(f"CH{i}"), q(name), q(kind), q(rng), q("Off"), span, scale,
                               q(unit)]))
    lines += ['', '"Data"',
              ",".join(q(c) for c in ["NO.", "Time", "ms", *(f"CH{i}" for i in range(1, len(chans) + 1)),
                                      "Alarm1-10", "Alarm11-20", "Alarm21-30", "AlarmOut"]),
              ",".join(q(c) for c in ["", "", "", *(u for _, _, u, _ in chans), "", "", "", ""])]
    for k in range(idx.size):
        when = start + timedelta(seconds=k * m.STEP_S)
        cells = [str(k + 1), f"{when:%Y/%m/%d %H:%M:%S}", "0"]
        cells += [_value(c[k], u) for c, (_, _, u, _) in zip(cols, chans)]
        lines.append(",".join(cells + ["LLLLLLLLLL", "LLLLLLLLLL", "L", "LLLL"]))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\r\n".join(lines) + "\r\n", encoding="ascii")


def _write_all(folder: Path, r, runs_, fault=None) -> None:
    for n, (label, start, idx) in enumerate(runs_):
        last = n == len(runs_) - 1
        write_file(folder / f"{start:%y%m%d-%H%M%S}.CSV", r, label, start, idx,
                   fault if last else None)


def write(root: str, seed: str) -> None:
    """The lab's files of seed ``seed``: ``ROOT/lathe<SEED>/``."""
    r, runs_ = runs(int(seed))
    folder = Path(root) / f"lathe{seed}"
    _write_all(folder, r, runs_)
    print(f"wrote {folder} ({len(runs_)} files, {sum(i.size for _, _, i in runs_)} rows)")


def faults(root: str, seed: str) -> None:
    """``ROOT/fault_<kind>_<SEED>/``: the files, the last run with one fault (docstring)."""
    import lathe82 as m
    r, runs_ = runs(int(seed))
    cases = four_faults(runs_[-1][2].size, m.STEP_S, frozen=("SPINDELKASTEN", 900),
                        jump=("BETT_R", 1000), drift=("KUEHLMITTEL", 700),
                        dropout=("MUTTER_Z", 1200, 1290))
    for kind, (label, change) in cases.items():
        def fault(name, x, label=label, change=change):
            return change(x) if name == label else x
        folder = Path(root) / f"fault_{kind}_{seed}"
        _write_all(folder, r, runs_, fault)
        print(f"wrote {folder}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "faults": faults, "matrix": matrix}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
