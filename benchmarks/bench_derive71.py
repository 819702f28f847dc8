"""Derived targets (derive71): ISO 230-3 tilts from two probes, ``data.derive``, on catman70's rig_a.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_derive71.py write ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_derive71.py check ROOT [family ...]

The record is ``bench_catman70``'s ``rig_a`` (seed 7131: one catman Easy file per test, German
PC, five probes ``Sonde X1`` / ``Y1`` at the nose, ``X2`` / ``Y2`` 100 mm lower, ``Sonde Z``).
``write`` writes it twice: ``rig_a`` as catman70 does, and ``rig_a_hand``, the same files with
two channels the lab computed in its logger, ``Neigung X`` and ``Neigung Y`` in ``µm/m``
(``(X1 - X2) / 0.1``, ``(Y1 - Y2) / 0.1`` of the values the file prints, every digit kept).

``check`` (per family, mlr by default): ``init`` of both folders (one try each), then ``run``
on ``rig_a`` with ``data.derive={E_Neigung_X: '(E_Sonde_X1 - E_Sonde_X2) / 0.1', E_Neigung_Y:
...}`` and on ``rig_a_hand`` as read; ``replay`` of the derived run's model; C ``export`` with
its check pack.

What must hold (written before any run)
---------------------------------------
* C1: every figure of ``metrics.json`` of each tilt (test / CV RMSE, before, Rsd) from the
  derived run equals the hand file's within 1e-9 (µm/m), and the five probes' figures are the
  same in both runs (a derived column changes no other target);
* C2: ``replay`` of the derived run's model: each target's RMSE equals ``run``'s within 1e-9,
  the tilts included;
* C3: the C pack of the derived run's model passes (``check/check.sh`` exit 0) and its
  outputs include ``C_Neigung_X``.
No rule is chosen here: a check, not a tuning set.

Measured (2026-12-02, after the bar above was committed; 2 shared cores)
-----------------------------------------------------------------------
``check ROOT mlr lagbank`` (``derive71.jsonl``): C1 holds exactly, every figure of both tilts
equal (largest |difference| 0.0) for mlr and lagbank; C2 replay - run <= 4.4e-16 (mlr) and
3.9e-16 (lagbank), stream - batch 1.4e-14 / 5.1e-14; C3 the pack passed for both (1440 rows
within 1e-9, cc 0), outputs ``C_Neigung_X``, ``C_Neigung_Y``.  Test RMSE (µm/m) of the tilts
X / Y: mlr 1.574 / 2.690, lagbank 1.622 / 1.786 (before 23.08 / 9.96); the probes' as catman70's
(mlr 0.16 / 0.19 / 0.16 / 0.30 / 1.20).  CPU (user + sys) of ``run``: mlr 6.65 s derived (the
process's first stage: its imports) / 1.77 s hand, lagbank 3.77 / 3.00 s; replay 1.1 / 1.5 s.
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]

import bench_catman70 as catman  # noqa: E402
import lab_matrix  # noqa: E402

SEEDS = {"rig_a": 7131}
SPACING_M = 0.1            # X1 above X2, Y1 above Y2 (catman70.py)
TILTS = {"E_Neigung_X": ("E_X1", "E_X2", "Neigung X"), "E_Neigung_Y": ("E_Y1", "E_Y2", "Neigung Y")}
DERIVE = ("data.derive={" + ", ".join(
    f"{t}: '(E_Sonde_{a[2:]} - E_Sonde_{b[2:]}) / {SPACING_M}'" for t, (a, b, _) in TILTS.items())
    + "}")


def hand_text(text: str) -> str:
    """A catman Easy file with the lab's tilt channels appended, computed from the probe
    values as printed (decimal commas), every digit kept."""
    lines = text.split("\r\n")
    head = next(i for i, line in enumerate(lines) if line.startswith(catman.TIME_CHANNEL[0]))
    names = lines[head].split("\t")
    index = {c: names.index(catman.CHANNELS[c][0][0]) for c in ("E_X1", "E_X2", "E_Y1", "E_Y2")}
    out = lines[:head]
    out.append(lines[head] + "".join(f"\t{t[2]}" for t in TILTS.values()))
    out.append(lines[head + 1] + "\tµm/m" * len(TILTS))
    out.append(lines[head + 2] + "\tberechnet" * len(TILTS))
    for line in lines[head + 3:]:
        if not line:
            out.append(line)
            continue
        cells = line.split("\t")
        value = {c: float(cells[i].replace(",", ".")) for c, i in index.items()}
        tilts = [(value[a] - value[b]) / SPACING_M for a, b, _ in TILTS.values()]
        out.append(line + "".join("\t" + repr(v).replace(".", ",") for v in tilts))
    return "\r\n".join(out)


def write(root: Path) -> None:
    catman.SEEDS = SEEDS
    catman.write(root)
    hand = root / "rig_a_hand"
    hand.mkdir(exist_ok=True)
    for path in sorted((root / "rig_a").glob("*.TXT")):
        text = path.read_bytes().decode("cp1252")
        (hand / path.name).write_bytes(hand_text(text).encode("cp1252"))


def check(root: Path, families: list[str]) -> None:
    lab_matrix.project(root)
    for name in ("rig_a", "rig_a_hand"):
        if not (root / f"init-{name}").exists():
            lab_matrix.initialised(root, name, [])
    for family in families or ["mlr"]:
        row: dict = {"family": family}
        runs = {}
        for name, extra in (("rig_a", [DERIVE]), ("rig_a_hand", [])):
            out = root / "out" / f"{name}-{family}"
            rc, said, cpu = lab_matrix.stage("run", *lab_matrix.data_args(root, name), *extra,
                                             f"model={family}", "plots=none", f"out={out}")
            row[f"{name}_cpu"] = round(cpu, 2)
            if rc:
                row[name] = f"exit {rc}: {said[:300]}"
                break
            runs[name] = json.loads((out / "metrics.json").read_text())["targets"]
        if len(runs) == 2:
            derived, hand = runs["rig_a"], runs["rig_a_hand"]
            row["targets"] = list(derived)
            row["C1_max_diff"] = max(_diffs(derived[t], hand[t]) for t in hand)
            row["tilt_test_rmse"] = {t: derived[t]["test"]["rmse"] for t in TILTS}
            row["probe_test_rmse"] = {t: derived[t]["test"]["rmse"] for t in derived
                                      if t not in TILTS}
            data = [*lab_matrix.data_args(root, "rig_a"), DERIVE]
            model = str(root / "out" / f"rig_a-{family}" / "model.pkl")
            row.update(lab_matrix.replayed(data, model, root / "out" / f"replay-{family}",
                                           list(derived)))
            if isinstance(row.get("replay"), dict):
                row["C2_replay_minus_run"] = max(abs(row["replay"][t] - derived[t]["test"]["rmse"])
                                                 for t in derived)
            code = root / "out" / f"c-{family}"
            row.update(lab_matrix.exported(data, model, code))
            row["C3_outputs"] = sorted(set(_outputs(code)))
        print(json.dumps(row, default=str), flush=True)
        with open(root / "derive71.jsonl", "a") as f:
            f.write(json.dumps(row, default=str) + "\n")


def _diffs(a, b) -> float:
    """Largest |a - b| over the numbers of two metrics.json entries (nested alike)."""
    if isinstance(a, dict):
        return max([_diffs(a[k], b[k]) for k in a if k in b] or [0.0])
    if isinstance(a, list):
        return max([_diffs(x, y) for x, y in zip(a, b)] or [0.0])
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and a is not None:
        return abs(float(a) - float(b))
    return 0.0


def _outputs(code: Path) -> list[str]:
    text = (code / "compensator.c").read_text() if (code / "compensator.c").exists() else ""
    return re.findall(r"C_Neigung_[XY]", text)


def main(argv: list[str]) -> int:
    return lab_matrix.main(__doc__, argv, SEEDS, {}, (), {
        "write": lambda root, rest: write(root),
        "check": lambda root, rest: check(root, rest),
    })


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
