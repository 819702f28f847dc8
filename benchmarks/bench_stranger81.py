"""A stranger's pass on a wire EDM and its SINUMERIK trace XML files (stranger81).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger81.py write ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger81.py faults ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger81.py matrix ROOT SEED CONF

The machine is ``benchmarks/edm81.py`` (SCORED BELOW)
"""
from __future__ import annotations

import sys
from datetime import timedelta
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402
from bench_stranger75 import matrix  # noqa: E402

GUD = "/NC/_N_NC_GD9_ACX/"                 # the lab's global user data the PLC writes
MISSING_RUN, MISSING_SIGNAL, MISSING_ROW = 4, "T_MUTTER_X", 2400
SPLIT_RUN, SPLIT_ROW, SPLIT_GAP = 8, 3000, 60     # the trace restarted 8.3 h in, 10 min later


def signals() -> list[tuple[str, str, str]]:
    """``(name in the trace, its unit or '', the simulation's key or sensor)`` in trace order."""
    import edm81 as e
    out = [(GUD + "DX_DRAHT", "um", "E_dX"), (GUD + "DY_DRAHT", "um", "E_dY")]
    out += [(f"/Channel/MachineAxis/aaIm[u1,{i}]", "mm", k) for i, k in ((1, "x"), (2, "y"),
                                                                       (3, "z"))]
    out += [(GUD + "GEN_LEISTUNG", "kW", "power"), (GUD + "SPUELDRUCK", "bar", "flush"),
            ("/Plc/I7.3", "", "chiller")]
    out += [(GUD + name, "°C", name) for name, _, _ in e.SENSORS]
    return out


def channels(seed: int):
    """The record: ``(edm81 result, [(run label, local start, rows)])``."""
    import edm81 as e
    r = e.simulate(int(seed))
    runs = []
    for n, (start, rows) in enumerate(e.run_windows(), start=1):
        idx = np.arange(rows.start, rows.stop)
        if n == SPLIT_RUN:
            runs.append((f"{n:02d}a", start, idx[:SPLIT_ROW]))
            runs.append((f"{n:02d}b", start + timedelta(seconds=(SPLIT_ROW + SPLIT_GAP) * e.STEP_S),
                         idx[SPLIT_ROW + SPLIT_GAP:]))
        else:
            runs.append((f"{n:02d}", start, idx))
    return r, runs


def _column(r, key, idx):
    import edm81 as e
    names = [s[0] for s in e.SENSORS]
    return r["sensors"][idx, names.index(key)] if key in names else r[key][idx]


def write_file(path: Path, r, label: str, start, idx, fault=None) -> None:
    """One run's trace (its XML as SINUMERIK Operate saves a trace, module docstring);
    ``fault(name, values)`` alters a temperature signal."""
    import edm81 as e
    sig = signals()
    cols = []
    for name, _, key in sig:
        v = np.asarray(_column(r, key, idx), dtype=float)
        cols.append(fault(key, v) if fault is not None else v)
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<traceCaptureFile version="1.0">',
             ' <traceCaptureSetup name="Thermik_Drahterodieren" comment="KT Lauf '
             f'{label}">',
             ' </traceCaptureSetup>', ' <traceData>',
             f' <dataFrame name="Trace 1" startTime="{start:%Y-%m-%dT%H:%M:%S}.000" '
             f'samplingTime="{e.STEP_S:.3f}">', '  <frameHeader>']
    for i, (name, unit, _) in enumerate(sig, start=1):
        kind = "BOOL" if name.startswith("/Plc/I") else "DOUBLE"
        lines.append(f'   <dataSignal id="{i}" name={quoteattr(name)} type="{kind}" '
                     f'unit={quoteattr(unit)}/>')
    lines.append('  </frameHeader>')
    miss = MISSING_SIGNAL if label == f"{MISSING_RUN:02d}" else None
    for k in range(idx.size):
        cells = []
        for i, ((name, _, key), v) in enumerate(zip(sig, cols), start=1):
            if (key == miss and MISSING_ROW <= k < MISSING_ROW + 6) or np.isnan(v[k]):
                continue                       # (the PLC's value not delivered: no attribute)
            text = str(int(v[k])) if name.startswith("/Plc/I") else f"{v[k]:.4f}"
            cells.append(f'f{i}="{text}"')
        lines.append(f'  <rec time="{k * e.STEP_S:.3f}" ' + " ".join(cells) + "/>")
    lines += [' </dataFrame>', ' </traceData>', '</traceCaptureFile>', '']
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines), encoding="utf-8")


def _write_all(folder: Path, r, runs, fault=None) -> None:
    for n, (label, start, idx) in enumerate(runs):
        last = n == len(runs) - 1
        write_file(folder / f"KT_{start:%Y%m%d_%H%M}_Lauf{label}.xml", r, label, start, idx,
                   fault if last else None)


def write(root: str, seed: str) -> None:
    """The lab's files of seed ``seed``: ``ROOT/edm<SEED>/``."""
    r, runs = channels(int(seed))
    folder = Path(root) / f"edm{seed}"
    _write_all(folder, r, runs)
    print(f"wrote {folder} ({len(runs)} files, {sum(i.size for _, _, i in runs)} rows)")


def faults(root: str, seed: str) -> None:
    """``ROOT/fault_<kind>_<SEED>/``: the files, the last run with one fault (docstring)."""
    r, runs = channels(int(seed))
    rows = np.arange(runs[-1][2].size)
    hours = np.clip(rows - 3000, 0, None) * 10.0 / 3600.0
    cases = {"frozen": ("T_OBERARM", lambda x: np.where(rows < 3600, x, x[3600])),
             "jump": ("T_STAENDER_H", lambda x: x + 2.0 * (rows >= 4000)),
             "drift": ("T_VORRAT", lambda x: x + hours),
             "dropout": ("T_MUTTER_X", lambda x: np.where((rows >= 4500) & (rows < 4590), np.nan, x))}
    for kind, (label, change) in cases.items():
        def fault(name, x, label=label, change=change):
            return change(x) if name == label else x
        folder = Path(root) / f"fault_{kind}_{seed}"
        _write_all(folder, r, runs, fault)
        print(f"wrote {folder}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "faults": faults, "matrix": matrix}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
