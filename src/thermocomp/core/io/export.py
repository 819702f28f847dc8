"""Write a dataset the way a lab's logger exports it: its own column names, delimiter and decimal
mark, no ``time`` column.  It lets the README's own-data recipe (and tests of the data config)
run on data that is not in the contract's shape, with a known source to compare against::

    python -m thermocomp.core.io.export <src> <dest> T_headstock=T0 T_guidebush=T1 "E_X=delta L" \\
        --delimiter ";" --decimal ","

The manifest stays the contract's ``campaigns.csv`` (``campaign,file,split``); only the campaign
files are foreign.  Samples must be uniform (the reader then needs ``data.sample_period_s``).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pandas as pd

from ...base.files import atomic_dir
from ...base.log import configure, logger
from ...base.paths import resolve
from ..timerule import median_step
from .contract import ContractError
from .read import read_manifest


def export_foreign(src: str | Path, dest: str | Path, columns: dict[str, str], *,
                   delimiter: str = ";", decimal: str = ",", keep_time: bool = False) -> Path:
    """Copy the campaigns of dataset ``src`` to ``dest``, keeping and renaming only ``columns``
    (contract name -> lab name), written with ``delimiter`` and ``decimal``.

    Returns ``dest``.
    """
    src, dest = Path(src), Path(dest)
    manifest = read_manifest(src)
    with atomic_dir(dest) as tmp:
        rows = []
        for cid, entry in manifest.iterrows():
            frame = pd.read_csv(src / entry["file"]) if str(entry["file"]).endswith(".csv") \
                else pd.read_parquet(src / entry["file"])
            missing = [c for c in columns if c not in frame.columns]
            if missing:
                raise ValueError(f"{src / entry['file']}: no column(s) {missing}")
            keep = (["time"] if keep_time else []) + list(columns)
            name = f"{cid}.csv"
            frame[keep].rename(columns=columns).to_csv(tmp / name, sep=delimiter, decimal=decimal,
                                                       index=False)
            rows.append({"campaign": cid, "file": name, "split": entry["split"]})
        pd.DataFrame(rows).to_csv(tmp / "campaigns.csv", index=False)
    return dest


def sample_period(src: str | Path) -> float | None:
    """The (uniform) sample period in s of dataset ``src``'s first campaign
    (:func:`~thermocomp.core.timerule.median_step`)."""
    src = Path(src)
    first = read_manifest(src).iloc[0]
    return median_step(pd.read_csv(src / first["file"])["time"].to_numpy(float))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m thermocomp.core.io.export", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("src")
    parser.add_argument("dest")
    parser.add_argument("columns", nargs="+", metavar="CONTRACT=LAB")
    parser.add_argument("--delimiter", default=";")
    parser.add_argument("--decimal", default=",")
    parser.add_argument("--keep-time", action="store_true")
    args = parser.parse_args(argv)
    pairs = [c.split("=", 1) for c in args.columns]
    if any(len(p) != 2 for p in pairs):
        parser.error("columns are CONTRACT=LAB pairs, e.g. \"E_X=delta L\"")
    configure()
    src = resolve(args.src)          # relative to the project root, as every thermocomp path
    try:
        dest = export_foreign(src, resolve(args.dest), dict(pairs), delimiter=args.delimiter,
                              decimal=args.decimal, keep_time=args.keep_time)
    except (ContractError, ValueError) as exc:   # one line, exit 2: as the CLI says bad input
        print(f"thermocomp: error: {exc}", file=sys.stderr)
        return 2
    logger.info("%s: sample period %g s", dest, sample_period(src) or float("nan"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
