"""A campaign's values piped in (``monitor.input=-``) checked as a streamed campaign file's are
(data87): a test campaign in kelvin from a row on, a probe switched from µm to mm or a logger
from °C to °F under the header it had was refused on the file (``data.kelvin_threshold_c``,
``data.fahrenheit_threshold_c``, :mod:`.steps`) and monitored on stdin as a sensor fault or a
worse error, with exit 0.  The rules are the file reader's, with its ``missing="keep"`` (a few
faulty readings stay, for the monitor to catch); each run of the stream is judged on its own,
as each file is."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pyarrow as pa

from .contract import ContractError, role
from .read import check_kept_values


def check_streamed(df: pd.DataFrame, blocks: list | None, opts, source: str,
                   headers: dict) -> None:
    """Refuse the values of ``df`` (the stream's frame, contract names, before ``data.derive``)
    that a campaign file's read refuses, run by run (``blocks``: ``(id, first row, end row)``,
    None for one run); a row is the stream's data row, a column named with its own header
    (``headers``: contract name -> the stream's)."""
    names = [c for c in df.columns if role(str(c)) in ("T", "E", "S")]
    for _, start, end in blocks or [(None, 0, len(df))]:
        part = df.iloc[start:end]
        columns = {c: pa.array(part[c].to_numpy(float)) for c in names
                   if np.isfinite(part[c].to_numpy(float)).any()}
        try:
            check_kept_values(columns, source, opts)
        except ContractError as exc:
            raise _in_stream(exc, start, headers) from None


def _in_stream(exc: ContractError, start: int, headers: dict) -> ContractError:
    """``exc`` (a run's rows counted from 1) at the stream's data row, its column's own header
    said where the stream names it otherwise."""
    reason = exc.reason
    if exc.column in headers:
        reason += f" (its header in the stream: {headers[exc.column]!r})"
    row = None if exc.row is None else exc.row + start
    return ContractError(reason, file=exc.file, column=exc.column, row=row)
