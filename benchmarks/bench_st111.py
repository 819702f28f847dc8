"""A lone JUMP of a sensor the others predict, in range, re-referenced as the C does (st111, issue 34
"deployed as scored").

Found by st109b (on its BASE too): the C re-references such a jump by its step less the change the
others predict for it since the last row (watch_c.py ``other[k] - mon_prev_other[k]``), the block
by its whole step: T_1 -3 from row 60 on the seen model, 0.52 um off the C to the campaign's end,
unflagged from row 81; fresh 10207's +30 returns (bench_st109b ``fresh``), 680 rows unflagged.

The bar is benchmarks/st111_bar.md (committed first).  A row *differs* where max |ST - C| > 1e-9
um (C = the JSON mirror ``Simulator``), *unflagged* where it differs and neither ``mon_flag``,
``mon_unsure`` nor ``refused`` is set.  B2 / B3 are bench_st109b ``fresh``; B4 bench_st108b.

RULE (st_watch.py): while the C's set is whole as far as the block knows (``mon_whole``: nothing
flagged, held or followed late, no reading beyond range, the others' last prediction known), a
lone jump of a judged sensor the C holds out (``MON_STEP_HELD``) is re-referenced by its step less
``(d - e) - mon_other`` (``e`` with every sensor in, ``MON_SELF`` / ``MON_SCALE``: the C's
``other``, which does not read its own ``d``); any other lone jump of a judged sensor sets
``mon_junsure`` (``mon_unsure`` to the campaign's end).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st111.py seen BASESRC
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests" / "apps"),
                str(HERE.parent / "tests")]
from _cli import run_commands  # noqa: E402

TOL = 1e-9      # um
STEP = -3.0     # degC, from FROM on
FROM = 60


def _jumped(df, column: str):
    """``df`` with ``column`` + STEP from row FROM to the end."""
    df = df.reset_index(drop=True).copy()
    df.loc[FROM:, column] += STEP
    return df


def _said(who: str, i: int, r: dict) -> None:
    gap = np.max(np.abs(r["c"] - r["st"]), axis=1)
    differ = gap > TOL
    lone = np.flatnonzero(differ & ~(r["flag"] | r["unsure"] | r["refused"]))
    where = f" rows {lone.min()}-{lone.max()}" if len(lone) else ""
    late = np.flatnonzero(differ[FROM + 1:]) + FROM + 1
    print(f"  {who} campaign {i}: {len(gap)} rows; differing {int(differ.sum())} (max {gap.max():.3g} um; "
          f"after row {FROM} {len(late)}, max {gap[FROM + 1:].max():.3g}), unflagged {len(lone)}{where}; "
          f"unsure {int(r['unsure'].sum())}", flush=True)


def seen(basesrc: str) -> None:
    """B1: test_export_lean107b's dep108 model (diag107's ``_room``), T_1 - 3 from row 60."""
    import tempfile

    from bench_st108d import _block, _run

    from test_diagnose_level107 import _room
    from test_export import _compose
    from test_export_lean107b import _deployed_scaled
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.shell.source import read_streamed

    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp) / "data"
        root.mkdir()
        ds = _room(7)
        for cid, df in ds.campaigns.items():
            df.to_csv(root / f"{cid}.csv", index=False)
        ds.manifest.reset_index().to_csv(root / "campaigns.csv", index=False)
        os.chdir(tmp)
        deployed, _ = _deployed_scaled(root)
        ds, _, test_ids, _ = read_streamed(_compose(f"data.path={root}", "track=false"))
    ss = state_space(deployed, monitor=True)
    tests = [_jumped(ds.campaigns[c], "T_1") for c in test_ids]
    for who, block in (("BASE", _block(deployed, basesrc)), ("RULE", _block(deployed, None))):
        for i, df in enumerate(tests):
            _said(who, i, _run(block, ss, df))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": seen}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
