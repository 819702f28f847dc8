"""CI time (issue 34; stop 101, ci101b): the served and mirror per-row loops, exact CPU cuts.

cProfile of lr9126 (cmon88's record, R1b after its lead-in, 4321 rows; 7676398c): the served
stream (``stream_rows``) 0.22 ms a row, ``streaming._step`` six times a row (the model and five
fallbacks), ``SensorMonitor._fast``, ``settled``; the numpy mirror (``Simulator.step``) 0.30 ms a
row, ``CodeMonitor._step`` the most of it, then ``statespace._model``, ``_judge``, ``vstack`` of
one row, ``np.errstate``; numpy reductions on arrays of ten (``any``, ``flatnonzero``) ~30
calls a row in each.

Rule (no key; src only where a row is stepped): the same arithmetic in the same order, only its
bookkeeping cut -- a reduction asked where only the error path reads its index, work repeated
each row hoisted or kept, a copy made where nothing mutates it dropped.  No result may move: the
mirror follows the C's order of operations on purpose.

BAR (the brief's; written and committed here before any after-measurement; no seeds: exact):
(1) outputs bitwise identical to BASE (7676398c's src; arrays compared with ==, NaN at the same
    places, as bytes): the served streams (``y``, ``n_clamped``, every event), the mirror's
    corrections, exclusions and flags, and every file of the conformance pack, on the scenarios
    of >= 8 export / monitor modules (long records lr8841: cmon85, cmon86; lr9032: cmon87,
    cmon93; lr9126: cmon88; lr9132: cmon89, cmon92b, st93, st94) and of 3 CLI records (the
    default scenario, fl_thermal, column_moving_source);
(2) per-row CPU of the served streaming and of the mirror each down >= 25 % paired (base and
    after in turn, 2 reps; lr9126 and lr9132, the served ``stream_rows`` and the mirror's
    ``Simulator`` loop from a reset, each twice a rep);
(3) those modules' summed pytest CPU down >= 10 % paired (``-n 0``, ``nice``, each module alone,
    bench_ci100b's ``cpu``; 2 reps).
KEPT only if (1) holds exactly and (2) and (3) are met; else REFUSED (the rule saved as
``benchmarks/ci101b_rule.patch``).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_ci101b.py outputs OUT TAG        # (1): OUT/TAG.pkl
    python benchmarks/bench_ci101b.py same OUT BASE AFTER    # (1): two ``outputs`` compared, bytes
    python benchmarks/bench_ci101b.py rows OUT TAG           # (2): OUT/rows.txt, a line a stream
    python benchmarks/bench_ci101b.py rowtable OUT [BEFORE AFTER]

(3) is bench_ci100b's ``cpu TREE TAG OUT SPEC`` (each module alone) and its ``table``.
"""
from __future__ import annotations

import json
import pickle
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path[1:1] = [str(ROOT / "tests" / "shell"), str(ROOT / "tests")]
from _cli import made_folder, run_commands  # noqa: E402

LONG = (8841, 9032, 9126, 9132)         # the modules' long records (docstring)
TIMED = (9126, 9132)


class _Folders:
    """pytest's ``tmp_path_factory`` as the modules' fixtures use it (``mktemp``)."""

    def __init__(self, root: Path):
        self.root = root

    def mktemp(self, name: str) -> Path:
        return Path(tempfile.mkdtemp(prefix=name, dir=self.root))


def _simulated(root: Path, name: str, *words: str) -> tuple:
    """``deployed_mlr``'s tuple of a record ``thermocomp simulate`` draws with ``words``."""
    from test_export_cmon87 import deployed_mlr
    from thermocomp.shell.cli import main

    data = root / name
    assert main(["-q", "simulate", f"data.path={data}", "track=false", *words]) == 0
    return deployed_mlr(f"data.path={data}")


def _records(root: Path, names=None) -> dict[str, tuple]:
    """``{name: (deployed, ss, frame, lead, tests, leads)}``: the long records, then the CLI ones."""
    from conftest import fl_thermal_served
    from test_export_cmon87 import long_record

    made = {}
    for seed in LONG:
        if names is None or seed in names:
            made[f"lr{seed}"] = long_record(_Folders(root), seed)
    if names is None:
        made["default"] = _simulated(root, "default", "sim.generator.n_campaigns=6")
        made["column_moving_source"] = _simulated(root, "cms", "sim=column_moving_source")
        deployed, ss, frame = fl_thermal_served()
        made["fl_thermal"] = (deployed, ss, frame, 0, {"test": frame}, {})
    return made


def _mirror(ss, frame) -> tuple:
    """The mirror from a reset over ``frame``: corrections, ``(row, flags, sensor, rule, missed)``."""
    from thermocomp.apps.deploy.export.statespace import Simulator

    U, times = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    sim, got, flags = Simulator(ss), [], []
    sim.reset()
    for i in range(len(frame)):
        got.append(sim.step(U[i], times[i]))
        w = sim.watch
        if w is not None and w.flags:
            flags.append((i, int(w.flags), int(w.sensor), int(w.rule), int(w.missed)))
    return np.array(got), flags


def outputs(out: str, tag: str) -> None:
    """(1) Every record's served rows, mirror and pack -> OUT/TAG.pkl."""
    from thermocomp.apps.deploy.export.pack import conformance_pack
    from thermocomp.apps.deploy.export.served import ServedStreams

    folder = made_folder(out)
    work = Path(tempfile.mkdtemp(prefix=f"{tag}-", dir=folder))
    got = {}
    for name, (deployed, ss, frame, lead, tests, leads) in _records(work).items():
        streams = ServedStreams(deployed)
        (cid, campaign), = tests.items()
        rows = streams.rows(campaign, cid, lead_in=leads.get(cid))
        files, summary = conformance_pack(deployed, ss, tests, leads, served=streams)
        got[name] = {"served_y": rows.y, "served_clamped": rows.clamped,
                     "served_guarded": rows.guarded, "served": json.dumps(
                         [rows.events, rows.excluded, rows.warm_events], default=str),
            "mirror": _mirror(ss, frame), "pack": files,
            "summary": json.dumps(summary, sort_keys=True, default=str)}
        print(name, len(frame), "rows,", len(files), "pack files", flush=True)
    (folder / f"{tag}.pkl").write_bytes(pickle.dumps(got))


def _bytes(value) -> bytes:
    return value.tobytes() if isinstance(value, np.ndarray) else pickle.dumps(value)


def same(out: str, base: str, after: str) -> None:
    """(1) ``outputs`` BASE against AFTER: each record's items equal as bytes (arrays: their
    shape and every bit)."""
    folder = Path(out)
    a, b = (pickle.loads((folder / f"{t}.pkl").read_bytes()) for t in (base, after))
    differ = 0
    for name in a:
        for key in a[name]:
            x, y = a[name][key], b[name][key]
            if key == "mirror":
                ok = x[0].shape == y[0].shape and _bytes(x[0]) == _bytes(y[0]) and x[1] == y[1]
            elif key == "pack":
                ok = x == y
            else:
                ok = getattr(x, "shape", None) == getattr(y, "shape", None) and _bytes(x) == _bytes(y)
            differ += not ok
            print(f"{name:22s} {key:10s} {'same' if ok else 'DIFFERS'}"
                  + (f" ({len(x)} files)" if key == "pack" else ""))
    print(f"(1) {'MET' if not differ else 'NOT met'}: {differ} items differ")


def rows(out: str, tag: str, reps: str = "2") -> None:
    """(2) Per-row CPU (µs) of the served stream and of the mirror on lr9126 / lr9132, each
    ``reps`` times from a reset -> OUT/rows.txt ``TAG record kind rows seconds``."""
    from thermocomp.apps.deploy.report import stream_rows

    folder = made_folder(out)
    work = Path(tempfile.mkdtemp(prefix=f"rows-{tag}-", dir=folder))
    lines = []
    for name, (deployed, ss, frame, lead, tests, leads) in _records(work, TIMED).items():
        (cid, _), = tests.items()
        for kind in ("served", "mirror"):
            start = time.process_time()
            for _ in range(int(reps)):
                if kind == "served":            # (from a reset, the lead-in's rows its first)
                    stream_rows(deployed, frame, cid)
                else:
                    _mirror(ss, frame)
            spent = time.process_time() - start
            lines.append(f"{tag} {name} {kind} {int(reps) * len(frame)} {spent:.3f}")
            print(lines[-1], flush=True)
    with open(folder / "rows.txt", "a") as f:
        f.write("\n".join(lines) + "\n")


def rowtable(out: str, before: str = "base", after: str = "after") -> None:
    """(2) Per kind: µs a row, BEFORE against AFTER, summed over records and runs."""
    seen: dict = {}
    for line in (Path(out) / "rows.txt").read_text().splitlines():
        tag, name, kind, n, s = line.split()
        k = seen.setdefault((tag, kind), [0, 0.0])
        k[0] += int(n)
        k[1] += float(s)
    for kind in ("served", "mirror"):
        b, a = seen.get((before, kind)), seen.get((after, kind))
        if b and a:
            ub, ua = 1e6 * b[1] / b[0], 1e6 * a[1] / a[0]
            print(f"{kind:7s} {ub:7.1f} -> {ua:7.1f} us/row  {100 * (ua / ub - 1):+.1f} %  "
                  f"(bar -25 %: {'met' if ua <= 0.75 * ub else 'NOT met'})")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"outputs": outputs, "same": same, "rows": rows,
                                  "rowtable": rowtable}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
