"""The exported C's monitor on the check pack's planted copies of fresh long records (cmon89,
issue 34): where the code and the served monitor part.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon89.py trace [ROOT] [SEEDS]

``trace``: in ``ROOT`` (default ``/tmp/cmon89-bench``) per seed of ``SEEDS`` (default
:data:`SEEDS`) bench_cmon87's long record (``_record``: 3 days, R1b continuing R1a, MLR deployed
adaptive, a spike planted on each sensor no other predicts) and the pack's planted copies of R1b
(:func:`~thermocomp.apps.deploy.export.watch.planted`: a jump, a freeze, a dropout, a reading
beyond its range of the first sensor the code holds out, from R1b's middle row on); per copy
(rows 1-based in R1b): the served monitor's events, the numpy mirror's exclusions, its first flag,
the first row where its corrections part from the served ones and the pack's rows.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import made_folder, run_commands, seed_list  # noqa: E402

SEEDS = "9132,9135"


def _parted_at(ss, frame, want, lead: int) -> tuple[int | None, list, str]:
    """``(first parting row, exclusions, first flag)`` of the numpy mirror on ``frame``."""
    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.export.pack import beyond
    from thermocomp.apps.deploy.export.watch import EXCLUDED, NOT_IN_CODE, READMITTED, RULES

    sim = Simulator(ss)
    sim.reset()
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    parted, out, first = None, [], None
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        c = sim.step(u, t)
        w = sim.watch
        row = i + 1 - lead
        if i >= lead and w.flags & (EXCLUDED | READMITTED):
            out.append((row, names[w.sensor], RULES[w.rule]))
        if i >= lead and (w.flags & NOT_IN_CODE or sim.refused) and first is None:
            first = f"{RULES[w.missed or w.rule]}@{row} ({names[w.sensor]})"
        if parted is None and (sim.refused or beyond(c, want[i]).any()):
            parted = row
            if sim.refused:
                break
    return parted, out, first or "none"


def trace(root: str = "/tmp/cmon89-bench", seeds: str = SEEDS) -> None:
    """Per planted copy of R1b: served events, the mirror's exclusions, first flag and parting."""
    from bench_cmon87 import _record

    from thermocomp.apps.deploy.export.pack import corrections, fed
    from thermocomp.apps.deploy.export.watch import planted
    from thermocomp.apps.deploy.report import stream_rows

    folder = made_folder(root)
    for seed in seed_list(seeds):
        deployed, ss, tests, leads, spikes = _record(folder, seed)
        print(f"lr{seed}: spikes {spikes}", flush=True)
        copies = planted(ss, tests)
        for cid, (df, what, source) in {**{t: (f, "as drawn", t) for t, f in tests.items()},
                                        **copies}.items():
            frame = fed(df, leads.get(source))
            lead = len(frame) - len(df)
            served = stream_rows(deployed, frame, str(cid))
            times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
            print(f"lr{seed} {cid}: {what}")
            for e in served.events:
                row = int(np.searchsorted(times, e["time"])) + 1 - lead
                if row > 0 and e.get("sensor"):
                    print(f"  served row {row}: {e['sensor']} {e['to']}: {e['reason'][:110]}")
            want = corrections(ss, served.y)
            parted, out, first = _parted_at(ss, frame, want, lead)
            print(f"  mirror: parts at row {parted}; first flag {first}; exclusions {out}",
                  flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"trace": trace}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
