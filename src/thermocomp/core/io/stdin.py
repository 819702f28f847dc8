"""A campaign streamed as CSV text (``thermocomp monitor monitor.input=-``): read as a campaign
file is (``data.delimiter``, ``data.decimal``, ``data.columns``, ``data.time``), so a lab's logger
rows stream as they are written; empty cells stay NaN, a non-numeric one is refused with its row."""

from __future__ import annotations

from io import StringIO

import numpy as np
import pandas as pd

from ..context import TIME
from .contract import ContractError
from .encoding import UTF8, text_codec
from .sniff import SNIFF_LINES, detected
from .timestamps import time_kind

SOURCE = "<stdin>"


def stdin_text(stream, encoding: str = UTF8) -> str:
    """What ``stream`` (``sys.stdin``) holds, decoded with ``data.encoding`` (a Windows
    logger's rows: cp1252) rather than the locale's; a byte it does not read is refused."""
    raw = getattr(stream, "buffer", None)
    if raw is None:                   # already text (a caller's StringIO)
        return stream.read()
    data = raw.read()
    try:
        return data.decode(text_codec(encoding))
    except UnicodeDecodeError as exc:
        row = data[:exc.start].count(b"\n")
        raise ContractError(f"byte 0x{data[exc.start]:02x} is not {encoding} text (set "
                            "data.encoding to the stream's character set, e.g. cp1252)",
                            file=SOURCE, row=row or None) from None


def read_stream(text: str, columns: list[str], opts) -> tuple[pd.DataFrame, dict]:
    """``(frame, missing cells per column)`` of CSV ``text`` (header first) holding ``columns``
    (those the compensator reads).  ``time`` in seconds or as ISO 8601 timestamps (``auto``: as
    the first row reads, like a campaign file)."""
    text = text.lstrip("\ufeff")
    opts = detected(text.splitlines()[:SNIFF_LINES], opts, SOURCE)   # data.delimiter=auto ...
    try:
        df = pd.read_csv(StringIO(text), sep=opts.delimiter, decimal=opts.decimal,
                         thousands=opts.thousands, na_values=list(opts.missing_values))
    except Exception as exc:    # pandas raises several kinds for a bad stream
        raise ContractError(f"stdin is not a CSV table with a header, data.delimiter="
                            f"{opts.delimiter!r} ({' '.join(str(exc).split())})",
                            file=SOURCE) from None
    df = df.rename(columns={k: v for k, v in opts.columns.items() if k in df.columns})
    absent = [c for c in columns if c not in df.columns]
    if not absent and df.empty:
        raise ContractError("stdin has a header but no data row", file=SOURCE)
    if absent:
        raise ContractError("stdin lacks a column the compensator reads", file=SOURCE,
                            column=",".join(absent))
    if TIME in df.columns:
        df[TIME] = stream_seconds(df[TIME], opts.time)
    # every data column is numeric (the contract's T_, E_, S_ and time), not only those the
    # model reads: the measured errors and the context are read from the same frame
    numeric = list(dict.fromkeys([*columns, *(c for c in df.columns
                                              if c == TIME or str(c)[:2] in ("T_", "E_", "S_"))]))
    for c in numeric:
        bad = pd.to_numeric(df[c], errors="coerce").isna() & df[c].notna()
        if bad.any():
            raise ContractError("non-numeric value", file=SOURCE, column=c,
                                row=int(np.flatnonzero(bad)[0]) + 1)
        df[c] = pd.to_numeric(df[c], errors="coerce")
    return df, {c: int(n) for c, n in df[numeric].isna().sum().items() if n}


def stream_seconds(time: pd.Series, time_format: str) -> pd.Series:
    """The stream's ``time`` in seconds since its first row when it holds ISO 8601 timestamps
    (as given otherwise: the numeric check refuses what is no number).  A time that goes back
    is no refusal here: the stream's guard judges it, as on the machine."""
    first, kind = time.iloc[0], time_format
    if kind == "auto" and isinstance(first, str):      # read as a campaign file's
        kind = time_kind(first.strip(), kind, not pd.isna(pd.to_numeric(first, errors="coerce")),
                         SOURCE, stream=True)
    if kind in ("auto", "seconds"):
        return time
    stamps = pd.to_datetime(time.astype(str).where(time.notna()), utc=True, errors="coerce",
                            format="ISO8601" if kind == "iso8601" else kind)
    bad = stamps.isna() & time.notna()
    if bad.any() or pd.isna(stamps.iloc[0]):
        row = int(np.flatnonzero(bad)[0]) + 1 if bad.any() else 1
        what = "an ISO 8601 time" if kind == "iso8601" else f"a time in the format {kind!r}"
        raise ContractError(f"not {what} (data.time={time_format}: the stream's first row is a "
                            "timestamp)", file=SOURCE, column=TIME, row=row)
    return (stamps - stamps.iloc[0]).dt.total_seconds()
