"""What the rows of a record say of the order of its dates with slashes (small72): the shapes of
its time cells, one decision for the record's files (:mod:`.slashed` looks at a folder's files;
a one-file record's read decides from the cells it reads, :mod:`.tables`).  Where no row says it
(no day or month past 12, no Keysight stamp), the files' runs do, as a lab file's dates
(:func:`.dayfirst.run_order`, dates85): a run across midnight settles the order."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.compute as pc

from ...base.log import logger
from .contract import ContractError
from .dayfirst import KEY, ORDER, RUN_SAID, WAY, fields, parts_fields, run_order, swapped
from .timestamps import slashed_format


@dataclass(frozen=True)
class Order:
    """A record's order (``format``, strptime's) and the first row that says it."""

    format: str
    file: Path
    header: str      # the time column's header in ``file``
    row: int         # 1-based data row
    value: str
    keysight: bool   # said only by a Keysight DAQ's ms after a colon (no day or month past 12)
    run: bool = False   # said by the file's run (``row``: where the other order breaks it)

    @property
    def day_first(self) -> bool:
        return self.format.startswith("%d/")


def decided(saids: Iterable[tuple[dict, dict] | None]) -> Order | None:
    """:func:`record_order` of what each file's rows said (:func:`said_by`; None: its first
    time is no date with slashes, the first file's saying the record's is none)."""
    strong, weak = {}, {}          # format -> its first Order, by a field past 12 / by Keysight
    for i, said in enumerate(saids):
        if said is None:
            if i == 0:             # (the record's time is no date with slashes)
                return None
            continue
        own, keysight = said
        if len(own) > 1:
            return None
        for found, into in ((own, strong), (keysight, weak)):
            for order in found.values():
                into.setdefault(order.format, order)
    orders = list((strong or weak).values())      # (a row past 12 outweighs a Keysight stamp)
    day = next((o for o in orders if o.day_first), None)
    month = next((o for o in orders if not o.day_first), None)
    if day and month:
        raise _contradiction(day, month)
    return orders[0] if len(orders) == 1 else None


def read_in(order: Order | None, opts, record: Path, first: Path):
    """``opts`` with ``time`` the record's ``order`` (unchanged where None), said where a row
    other than the first of ``record``'s first file ``first`` says it.  ``data.dayfirst``
    (dates84), where set, outweighs a Keysight stamp's month first and is refused where a row's
    day or month past 12 says the other order."""
    if order is not None and opts.dayfirst is not None:
        if order.day_first != opts.dayfirst and not order.keysight:
            raise ContractError(f"value {order.value!r} says its dates with slashes are "
                                f"{WAY[order.day_first]}, but data.dayfirst="
                                f"{str(opts.dayfirst).lower()} says {WAY[opts.dayfirst]}",
                                file=order.file, column=order.header, row=order.row)
        order = None if order.day_first != opts.dayfirst else order
    if order is None:
        return opts
    if (order.file, order.row) != (first, 1):     # (else the first row says it, as before)
        logger.info(f"{record.name}: dates with slashes read as data.time={order.format!r}, the "
                    f"order {order.file.name}'s data row {order.row} says ({order.value!r}"
                    + (RUN_SAID if order.run else "") + ")")
    return replace(opts, time=order.format)


def settled(read: list, dayfirst: bool | None, located=None) -> Order | None:
    """:func:`decided` of the record's files ``read`` (each ``(said, path, header, cells)``,
    :func:`said_by`'s and the time cells it looked at; None: as :func:`decided`'s), else, where
    no row of any says an order and ``data.dayfirst`` is unset, the order their runs settle
    (:func:`by_runs`; ``located``: its refusal naming the file's line too)."""
    saids = [None if r is None else r[0] for r in read]
    order = decided(saids)
    if (order is None and dayfirst is None and saids and saids[0] is not None
            and not any(s and (s[0] or s[1]) for s in saids)):
        try:
            return by_runs([r[1:] for r in read if r is not None])
        except ContractError as exc:
            raise exc if located is None else located(exc) from None
    return order


# a CSV table's dates with slashes as :func:`.timestamps.slashed_format` reads them, month first
# (a second's fraction cut off first: it changes no date; Arrow's %Y reads '27' too: %y first)
_FORMS = tuple(f"%m/%d/{year}{sep}%H:%M{seconds}" for year in ("%y", "%Y") for sep in " T"
               for seconds in (":%S", ""))
_ALSO = ", or data.time to its format, e.g. data.time='%d/%m/%Y %H:%M:%S'"
_FRACTION = r"(\d:\d\d:\d\d)[.,:]\d+$"


def by_runs(files: list[tuple[Path, str, pa.Array | pa.ChunkedArray]]) -> Order:
    """The order the runs of the time cells of ``files`` (``(path, header, cells)``, no row of
    any saying one) settle (:func:`.dayfirst.run_order`): one file's decides for all, as a row
    past 12 does.

    Raises
    ------
    ContractError
        Where no file's run settles an order (the first file's refusal, naming ``data.dayfirst``),
        or two files' runs settle other orders (naming both).
    """
    said, refusal = {}, None
    for path, header, cells in files:
        text = pc.utf8_trim_whitespace(cells)
        rows = np.flatnonzero(fields(text)[0] >= 0)
        if not rows.size:
            continue
        values = text.take(pa.array(rows))
        if isinstance(values, pa.ChunkedArray):
            values = values.combine_chunks()
        try:
            order, at = run_order(values, _parse, path, header, row=rows + 1, also=_ALSO)
        except ContractError as exc:
            refusal = refusal or exc
            continue
        said.setdefault(order, Order(slashed_format(values[0].as_py(), order=ORDER[order]), path,
                                     header, int(rows[at]) + 1, values[at].as_py(), False, True))
    if len(said) == 2:
        raise _contradiction(said[True], said[False])
    if said:
        return next(iter(said.values()))
    raise refusal


def _parse(cells: pa.Array, day_first: bool) -> np.ndarray:
    """``cells`` read by the first of :data:`_FORMS` (``day_first``: swapped) that reads each,
    NaT where none does: Arrow's strptime, not a Python loop over a large table's rows."""
    whole, read = pc.replace_substring_regex(cells, _FRACTION, r"\1"), None
    for form in swapped(_FORMS, day_first):
        one = pc.strptime(whole, format=form, unit="s", error_is_null=True)
        read = one if read is None else pc.coalesce(read, one)
    return read.to_numpy(zero_copy_only=False)


def _contradiction(day: Order, month: Order) -> ContractError:
    first, second = sorted((day, month), key=lambda o: str(o.file))
    return ContractError(
        f"value {first.value!r} says its dates with slashes are {WAY[first.day_first]} "
        f"({first.format!r}), but file {second.file}, column {second.header!r}, data row "
        f"{second.row}: {second.value!r} says {WAY[second.day_first]} ({second.format!r}): the "
        f"files of one record are read in one order (data.time, {KEY}); export them from one "
        "PC, or read each as a record of its own", file=first.file, column=first.header, row=first.row)


# a date with slashes and a time of day, its parts that decide its format (Arrow's regex: no
# unnamed group; the cell trimmed first), as timestamps.slashed_format reads them
_PARTS = (r"^(?P<a>\d{1,2})/(?P<b>\d{1,2})/(?P<y>\d{4}|\d\d)(?P<sep>[ T])\d{1,2}:\d\d"
          r"(?P<s>:\d\d(?:[.,:]\d+)?)?$")
_KEYSIGHT = r"\d:\d\d:\d\d:\d{3}$"


def said_by(cells: pa.Array | pa.ChunkedArray, path: Path, header: str
            ) -> tuple[dict[str, Order], dict[str, Order]]:
    """The orders the time cells ``cells`` (position: data row - 1) of ``path``'s column
    ``header`` say (``format``: its first row saying it) by a field past 12, and by a Keysight
    stamp.  A cell's format depends on its parts alone (a field past 12, the year's digits, the
    separator, the seconds, a Keysight stamp's ms), so each shape is looked at once, at its first
    row, not every row in Python (small72: the scan was the read's dearest part)."""
    text = pc.utf8_trim_whitespace(cells)
    parts = pc.extract_regex(text, _PARTS)
    if parts.null_count == len(parts):     # (none, or no cell a date with slashes)
        return {}, {}
    field = {n: pc.struct_field(parts, n) for n in ("y", "sep", "s")}
    shape = [x > 12 for x in parts_fields(parts)] + [
        pc.fill_null(flag, False).to_numpy(zero_copy_only=False) for flag in (
            pc.equal(pc.utf8_length(field["y"]), 4), pc.equal(field["sep"], "T"),
            pc.not_equal(field["s"], ""), pc.match_substring_regex(text, _KEYSIGHT))]
    code = sum(flag.astype(np.int8) << bit for bit, flag in enumerate(shape))
    code[~parts.is_valid().to_numpy(zero_copy_only=False)] = -1     # (no date with slashes)
    kinds, first = np.unique(code, return_index=True)
    rows = np.sort(first[kinds >= 0])
    own, keysight = {}, {}
    for row in rows.tolist():      # each shape at its first row, in the order of the rows
        value = text[row].as_py()
        told = slashed_format(value, keysight=False)
        found, into = (told, own) if told else (slashed_format(value), keysight)
        if found and found not in into:
            into[found] = Order(found, path, header, row + 1, value, keysight=into is keysight)
    return own, keysight
