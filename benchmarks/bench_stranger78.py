"""A stranger's pass on a vertical turning lathe and its DIAdem TDM/TDX files (stranger78).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger78.py write ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger78.py faults ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger78.py matrix ROOT SEED CONF

The machine is ``benchmarks/vtl78.py`` (a portal vertical turning lathe, its own lumped network
and kinematics: a base on a foundation, a rotary table on a hydrostatic oil film with its
cooled hydraulic unit, a table gearbox, two columns, a cross-rail, a saddle and a ram; the
hall heated on working days only; 18 sensors at 60 s, a laser probe dX / dZ; twelve days from
Monday 2027-04-05, the weekend included; seeds 7846-7848 only).

``write``: the record as the lab's DIAdem script saves it, a TDM/TDX pair a day in
``ROOT/vtl<SEED>/``: ``KV2500_<yyyymmdd>.tdm``, the XML header (NI's USI schema, ``usi:tdm``:
a ``tdm_root``, one ``tdm_channelgroup`` ``Messung``, its ``tdm_channel`` s with ``name``,
``unit_string``, ``datatype``, a ``localcolumn`` each pointing to its values) and
``KV2500_<yyyymmdd>.tdx``, the values (little-endian ``block`` s: the time ``Zeit`` a
``DT_DATE`` channel, float64 seconds since 0000-01-01 on the lab PC's clock, no zone; the
temperatures float32, the probes and states float64); an operator's text channel inline in
the XML (``string_sequence``). Quirks: 8 samples of ``Tisch Rand`` NaN on day 3 (DIAdem's
NoValue), the logger down 5 min on day 6 (its rows missing), the sensor ``Stößel unten``
replaced on day 8 (0.3 K off), its channel ``Stößel unten neu``.

``faults``: ``ROOT/fault_<kind>_<SEED>/``, the pairs, the last day with one fault:
``frozen`` (Hydrostatik Vorlauf held from row 600), ``jump`` (+2 K on Ständer links oben from
row 700), ``drift`` (Getriebe +1 K/h from row 500), ``dropout`` (30 NaN of Support from row
800).

``matrix``: bench_stranger75's (run -> replay per family on the data config init wrote).

Measured 2026-12-03, seed 7846 (``write`` 0.5 s CPU). Before stranger78 ``thermocomp init
ROOT/vtl7846`` refused the folder ("manifest not found ...; its files, .tdx (12), .tdm (12), are
no kind read as a run"); with core/io/tdm.py, init's own read refused the NaN ("gap of 8
missing values ... longer than data.max_gap_samples=0": its gap look read no lab file of a
folder but a Scope export); with it, ``init`` alone (no key) wrote the roles, the renamed sensor's
``data.columns`` entry and ``max_gap_samples: 8``. ``matrix`` on its config: test RMSE dX / dZ
(µm; 45.07 / 105.12 before) mlr 16.193 / 0.975, pcr 19.112 / 8.643, arx 16.863 / 1.183, lagbank
18.095 / 1.993, hammerstein 4.026 / 1.052, lstm 16.227 / 0.866, auto 4.026 / 0.972 (hammerstein /
mlr + lstm chosen), mlr ``ati=cmeans`` as mlr; replay = run in every cell. Fresh draws 7847 /
7848 (``init`` with no key; MLR 16.719 / 0.959, 12.051 / 1.294 µm): ``monitor`` no event.
Faults, C, promote, diagnose: docs/own-data.md, "A vertical turning lathe's DIAdem TDM/TDX
pairs".
"""
from __future__ import annotations

import sys
from pathlib import Path
from xml.sax.saxutils import escape

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402
from _faults import four_faults  # noqa: E402
from bench_stranger75 import matrix  # noqa: E402

STEM = "KV2500"
DIADEM_EPOCH = 62167132800.0          # s from DIAdem's 0000-01-01 to 1970-01-01 (tdm.DIADEM_EPOCH_S)
STATES = (("Tisch Drehzahl", "rpm", "rpm"), ("Radius X", "radius", "mm"),
          ("Stößel Auszug", "ram", "mm"))
PROBES = (("Laser dX", "E_dX"), ("Laser dZ", "E_dZ"))
REPLACED, REPLACED_DAY, OFFSET = "Stößel unten", 8, 0.3
GAP_DAY, GAP_ROW, GAP_ROWS = 6, 610, 5
NAN_DAY, NAN_CHANNEL, NAN_ROW = 3, "Tisch Rand", 400
ROWS_A_DAY = 1440


def channels(seed: int) -> tuple[np.ndarray, dict[str, tuple[np.ndarray, str, str]]]:
    """The record's local seconds since 1970 and channels ``name -> (values, unit, type)``."""
    import vtl78 as v
    r = v.simulate(int(seed))
    local = (v.FIRST_DAY - v.FIRST_DAY.replace(year=1970, month=1, day=1)).total_seconds() + r["t"]
    out = {name: (r["sensors"][:, j], "°C", "eFloat32Usi") for j, (name, _, _) in enumerate(v.SENSORS)}
    out.update({name: (r[key], unit, "eFloat64Usi") for name, key, unit in STATES})
    out.update({name: (np.round(r[key], 3), "µm", "eFloat64Usi") for name, key in PROBES})
    return local, out


def _tdm(tdx: str, title: str, rows: int, chans: list[tuple[str, str, str, str]], notes: list[str]) -> str:
    """The XML header: ``chans`` ``(name, unit, datatype, valueType)`` in the TDX's order."""
    ids = [f"usi{10 + 3 * k}" for k in range(len(chans) + 1)]
    blocks, offset, seqs, chan_xml, cols = [], 0, [], [], []
    for k, (name, unit, dtype, vtype) in enumerate(chans):
        size = 4 if vtype == "eFloat32Usi" else 8
        blocks.append(f'      <block byteOffset="{offset}" id="inc{k}" length="{rows}" valueType="{vtype}"/>')
        offset += size * rows
        seq = "float_sequence" if size == 4 else "double_sequence"
        seqs.append(f'    <{seq} id="{ids[k]}v"><values external="inc{k}"/></{seq}>')
        chan_xml.append(
            f'    <tdm_channel id="{ids[k]}"><name>{escape(name)}</name><description/>'
            f'<unit_string>{escape(unit)}</unit_string><datatype>{dtype}</datatype>'
            f'<group>#xpointer(id("usi2"))</group>'
            f'<local_columns>#xpointer(id("{ids[k]}c"))</local_columns></tdm_channel>')
        cols.append(
            f'    <localcolumn id="{ids[k]}c"><name>{escape(name)}</name>'
            f'<measurement_quantity>#xpointer(id("{ids[k]}"))</measurement_quantity>'
            f'<submatrix>#xpointer(id("usi3"))</submatrix><global_flag>15</global_flag>'
            f'<independent>{1 if dtype == "DT_DATE" else 0}</independent>'
            f'<sequence_representation>explicit</sequence_representation>'
            f'<values>#xpointer(id("{ids[k]}v"))</values></localcolumn>')
    note = ids[-1]
    seqs.append(f'    <string_sequence id="{note}v"><values>'
                + "".join(f"<s>{escape(n)}</s>" for n in notes) + "</values></string_sequence>")
    chan_xml.append(f'    <tdm_channel id="{note}"><name>Bediener</name><description/>'
                    f'<datatype>DT_STRING</datatype><group>#xpointer(id("usi2"))</group>'
                    f'<local_columns>#xpointer(id("{note}c"))</local_columns></tdm_channel>')
    cols.append(f'    <localcolumn id="{note}c"><name>Bediener</name><measurement_quantity>'
                f'#xpointer(id("{note}"))</measurement_quantity><submatrix>#xpointer(id("usi4"))'
                f'</submatrix><sequence_representation>explicit</sequence_representation>'
                f'<values>#xpointer(id("{note}v"))</values></localcolumn>')
    every = " ".join(f'id("{i}")' for i in ids)
    numeric = " ".join(f'id("{i}c")' for i in ids[:-1])
    return "\n".join([
        '<?xml version="1.0" encoding="UTF-8" standalone="no" ?>',
        '<usi:tdm xmlns:usi="http://www.ni.com/Schemas/USI/1_0" version="1.0">',
        '  <usi:documentation><usi:exporter>National Instruments USI</usi:exporter>'
        '<usi:exporterVersion>1.5</usi:exporterVersion></usi:documentation>',
        '  <usi:model modelName="National Instruments USI generated meta file" '
        'uri="http://www.ni.com/Schemas/USI/1_0"><usi:include nsUri="http://www.ni.com/DataModels/USI/TDM/1_0"/></usi:model>',
        f'  <usi:include>\n    <file byteOrder="littleEndian" url="{tdx}">',
        *blocks, '    </file>\n  </usi:include>', '  <usi:data>', *seqs,
        f'    <tdm_root id="usi1"><name>{escape(title)}</name><description>KV 2500, '
        'Waermegang</description><title/><author>Messlabor</author>'
        '<channelgroups>#xpointer(id("usi2"))</channelgroups></tdm_root>',
        f'    <tdm_channelgroup id="usi2"><name>Messung</name><description/><root>#xpointer(id("usi1"))'
        f'</root><channels>#xpointer({every})</channels><submatrices>#xpointer(id("usi3") id("usi4"))'
        '</submatrices></tdm_channelgroup>',
        *chan_xml,
        f'    <submatrix id="usi3"><name>Messung</name><measurement>#xpointer(id("usi2"))</measurement>'
        f'<number_of_rows>{rows}</number_of_rows><local_columns>#xpointer({numeric})</local_columns></submatrix>',
        f'    <submatrix id="usi4"><name>Notizen</name><measurement>#xpointer(id("usi2"))</measurement>'
        f'<number_of_rows>{len(notes)}</number_of_rows><local_columns>#xpointer(id("{note}c"))</local_columns></submatrix>',
        *cols, '  </usi:data>', '</usi:tdm>', ''])


def write_folder(folder: Path, local: np.ndarray, chans: dict, fault=None) -> None:
    """A TDM/TDX pair a day; ``fault(name, day, values)`` alters a day's channel."""
    import vtl78 as v
    folder.mkdir(parents=True, exist_ok=True)
    for day, start in enumerate(v.day_starts(), start=1):
        rows = np.arange((day - 1) * ROWS_A_DAY, day * ROWS_A_DAY)
        if day == GAP_DAY:
            rows = np.delete(rows, np.arange(GAP_ROW, GAP_ROW + GAP_ROWS))
        stem = f"{STEM}_{start:%Y%m%d}"
        listed = [("Zeit", "s", "DT_DATE", "eFloat64Usi")]
        data = [local[rows] + DIADEM_EPOCH]
        for name, (values, unit, vtype) in chans.items():
            vals = values[rows].astype(float)
            label = name
            if name == REPLACED and day >= REPLACED_DAY:
                label, vals = f"{name} neu", vals + OFFSET
            if name == NAN_CHANNEL and day == NAN_DAY:
                vals[NAN_ROW:NAN_ROW + 8] = np.nan
            if fault is not None:
                vals = fault(name, day, vals)
            listed.append((label, unit, "DT_FLOAT" if vtype == "eFloat32Usi" else "DT_DOUBLE", vtype))
            data.append(vals)
        with open(folder / f"{stem}.tdx", "wb") as f:
            for (_, _, _, vtype), vals in zip(listed, data):
                f.write(np.asarray(vals, dtype="<f4" if vtype == "eFloat32Usi" else "<f8").tobytes())
        (folder / f"{stem}.tdm").write_text(
            _tdm(f"{stem}.tdx", stem, rows.size, listed, ["Schicht A", "Schicht B"]), encoding="utf-8")


def write(root: str, seed: str) -> None:
    """The pairs of seed ``seed``: ``ROOT/vtl<SEED>/``."""
    local, chans = channels(int(seed))
    folder = Path(root) / f"vtl{seed}"
    write_folder(folder, local, chans)
    print(f"wrote {folder} ({local.size} samples)")


def faults(root: str, seed: str) -> None:
    """``ROOT/fault_<kind>_<SEED>/``: the pairs, the last day with one fault (docstring)."""
    import vtl78 as v
    local, chans = channels(int(seed))
    cases = four_faults(ROWS_A_DAY, 60.0, frozen=("Hydrostatik Vorlauf", 600),
                        jump=("Ständer links oben", 700), drift=("Getriebe", 500),
                        dropout=("Support", 800, 830))
    for kind, (label, change) in cases.items():
        def fault(name, day, x, label=label, change=change):
            return change(x) if name == label and day == v.DAYS else x
        folder = Path(root) / f"fault_{kind}_{seed}"
        write_folder(folder, local, chans, fault)
        print(f"wrote {folder}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "faults": faults, "matrix": matrix}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
