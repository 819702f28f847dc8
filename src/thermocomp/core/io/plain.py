"""A campaign file as the CSV reader reads it: a workbook's sheet (:mod:`.workbook`), a UTF-16
text (:mod:`.utf16`), JSON Lines (:mod:`.jsonlines`), a fixed-width text (:mod:`.fixedwidth`), a
TDMS log or a MATLAB file (:mod:`.labfile`) through the temporary UTF-8 CSV it is converted to,
any other file as it is.  One place for the
choice, so that every look at a file (its rows, its first time) reads it the same way."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

from .catman import catman_records, is_catman
from .contract import ContractError
from .dayfirst import KEY, Unsettled, record_dayfirst
from .encoding import AUTO, UTF8, own, text_codec
from .fixedwidth import fixed_as_csv, is_fixed_width
from .graphtec import graphtec_records, is_graphtec
from .hdf5 import hdf5_records, is_hdf5
from .historian import long_as_wide, wide_options
from .historian_layout import long_layout
from .jsonlines import is_json_lines, json_lines_as_csv
from .labfile import SHARED, records_as_csv, replaced_joined, shared
from .lvm import is_lvm, lvm_records
from .matfile import is_mat, mat_records
from .scope import headerless, is_scope, refuse_headerless, scope_records
from .sinumerik import is_trace, trace_records
from .tdm import is_tdm, tdm_records
from .tdms import is_tdms, tdms_records
from .tob1 import is_tob
from .tob3 import tob_records
from .utf16 import is_utf16, utf8_options, utf16_as_utf8
from .workbook import csv_options, is_workbook, run_sheets, sheet_as_csv
from .yokogawa import is_yokogawa, yokogawa_records


def is_lab_file(path) -> bool:
    """``path`` is a lab's record of channels: a TDMS log, a MATLAB file, (stranger69) a
    LabVIEW Measurement File, (lab75) a Campbell Scientific TOB1 table (lab76: TOB2, TOB3) or
    (stranger76) a TwinCAT Scope CSV export, (stranger77) an HDF5 file or (stranger78) a DIAdem
    TDM/TDX pair or (stranger81) a SINUMERIK trace's XML or (stranger82) a Graphtec logger's CSV
    or (stranger82b) a Yokogawa recorder's ASCII conversion or (stranger84) HBM catman's ASCII
    export with its channel header (:mod:`.labfile`)."""
    return (is_tdms(path) or is_mat(path) or is_lvm(path) or is_tob(path) or is_scope(path)
            or is_hdf5(path) or is_tdm(path) or is_trace(path) or headerless(path)
            or is_graphtec(path) or is_yokogawa(path) or is_catman(path))


def lab_dayfirst(files, encoding: str = UTF8) -> tuple[bool, Path, str] | None:
    """The order of the dates with slashes a file of the record ``files`` says by a field past
    12, among the lab files whose reader parses its own dates (a catman T0, a Scope View date,
    a LabVIEW Date: :func:`.dayfirst.record_dayfirst`).  (data88) Where none says one and
    several read either way, the first one's reader's refusal (file, column, line, the key),
    the others and what each answer makes of their dates named after it."""
    try:
        return record_dayfirst(files, lambda p: is_catman(p) or is_scope(p) or is_lvm(p),
                               text_codec(UTF8 if encoding == AUTO else encoding))  # (ASCII dates)
    except Unsettled as exc:
        # (data88) the first file's reader's own refusal (its column and line), and the record's
        try:
            _records(exc.files[0], encoding)
        except ContractError as own:
            raise ContractError(f"{own.reason}; {exc.reason}", file=own.file, column=own.column,
                                row=own.row, line=own.line) from None
        raise ContractError(f"day or month first? {exc.reason}: set {KEY}=true|false to the order "
                            "of the PC that wrote them", file=exc.file) from None


def is_converted(path, opts=None) -> bool:
    """``path`` is read through a converted copy (a workbook, a UTF-16 text, JSON Lines, a
    fixed-width text, a TDMS or MATLAB file; with the read ``opts``: a historian's long file)."""
    return is_workbook(path) or is_utf16(path) or is_json_lines(path) or is_fixed_width(path) or (
        is_lab_file(path)) or (opts is not None and long_layout(path, opts) is not None)


_HELD: dict[Path, tuple] = {}    # a lab file -> (its conversion, its records), `converted_once`'s


@contextmanager
def converted_once(path: Path | None, encoding: str = UTF8, dayfirst: bool | None = None
                   ) -> Iterator[None]:
    """Within the block, every look at the lab file ``path`` reads one conversion of it (lab76:
    ``init`` converted a TOB1 table or a TDMS log for its head, its cells, its runs and its read,
    a binary file parsed and written four times more, its warnings said again); any other
    ``path`` (None: none) as it is."""
    if path is None or not is_lab_file(path) or Path(path) in _HELD:
        yield
        return
    records = _records(path, encoding, dayfirst)
    with records_as_csv(records, path) as text:
        _HELD[Path(path)] = text, records
        try:
            yield
        finally:
            del _HELD[Path(path)]


def _records(path: Path, encoding: str, dayfirst: bool | None = None) -> list:
    """``path``'s records (``dayfirst``: ``data.dayfirst``, its dates with slashes, .dayfirst)."""
    encoding = own(path, encoding)
    return (tdms_records(path) if is_tdms(path) else lvm_records(path, encoding, dayfirst) if is_lvm(path)
            else scope_records(path, encoding, dayfirst) if is_scope(path)
            else graphtec_records(path, encoding) if is_graphtec(path)
            else yokogawa_records(path, encoding) if is_yokogawa(path)
            else catman_records(path, encoding, dayfirst) if is_catman(path)
            else refuse_headerless(path) if headerless(path)
            else hdf5_records(path) if is_hdf5(path)
            else tdm_records(path) if is_tdm(path)
            else trace_records(path) if is_trace(path)
            else tob_records(path) if is_tob(path) else mat_records(path))


@contextmanager
def lab_as_csv(path: Path, one_run: bool = False, encoding: str = UTF8,
               columns: dict | None = None, dayfirst: bool | None = None) -> Iterator[Path]:
    """A TDMS log, a MATLAB file or a LabVIEW Measurement File (a text: read in ``encoding``,
    ``data.encoding``) as the temporary CSV file its channels are written to (held by
    :func:`converted_once`: that one); ``one_run``: a folder's file, refused where it holds
    several runs (its runs would be read as one campaign, the days between them a pause nothing
    said); ``columns`` (``data.columns``): a sensor replaced from a run on, its new channel
    mapped onto the old one's name, written as one column (:func:`.labfile.replaced_joined`);
    :data:`SHARED`: the channels every run holds alone (a look at the cells' gaps: a replaced
    sensor's channel is empty in the runs before it, none of a run's gaps); ``dayfirst``:
    ``data.dayfirst``."""
    if not one_run and Path(path) in _HELD:
        text, records = _HELD[Path(path)]
        joined = replaced_joined(records, columns) if columns is not SHARED else shared(records)
        if joined is records:
            yield text
        else:
            with records_as_csv(joined, path) as text:
                yield text
        return
    records = _records(path, encoding, dayfirst)
    if one_run and len(records) > 1:
        labels = ", ".join(repr(r.label) for r in records[:4]) + (", ..." if len(records) > 4 else "")
        raise ContractError(f"{len(records)} runs in one file ({labels}): a folder's file is one "
                            "campaign; give this file as data.path (each run a campaign, "
                            "data.roles.campaign=run as thermocomp init proposes), or save one "
                            "run per file", file=path)
    records = replaced_joined(records, columns) if columns is not SHARED else shared(records)
    with records_as_csv(records, path) as text:
        yield text


@contextmanager
def as_read(path: Path, opts, rows: int | None = None, one_run: bool = False
            ) -> Iterator[tuple[Path, object]]:
    """``(file, options)`` the CSV or Parquet reader reads for ``path`` (``rows``: a workbook's
    first rows only, what a look at its head needs; ``one_run``: a folder's campaign file, a
    TDMS or MATLAB file of several runs refused)."""
    opts = replace(opts, encoding=own(path, opts.encoding))    # (data87: auto, the file's own)
    if is_workbook(path):
        if one_run and opts.sheet is None and len(runs := run_sheets(path).runs) > 1:
            raise ContractError(f"{len(runs)} runs in one workbook, a sheet each ("
                                + ", ".join(map(repr, runs[:4])) + (", ..." if len(runs) > 4
                                                                   else "")
                                + "): a folder's file is one campaign; give this workbook as "
                                "data.path (each sheet a campaign), or data.sheet", file=path)
        with sheet_as_csv(path, opts, rows=rows) as sheet:
            yield sheet.csv, csv_options(opts)
    elif is_utf16(path):            # Excel's 'Unicode Text': its UTF-8 text
        with utf16_as_utf8(path) as text:
            yield text, utf8_options(opts)
    elif is_json_lines(path):       # an MQTT bridge's messages: flattened
        with json_lines_as_csv(path, rows=rows) as text:
            yield text, utf8_options(opts)
    elif is_lab_file(path):         # a DAQ's TDMS, a MATLAB file: its channels (long: a grid)
        with lab_as_csv(path, one_run, opts.encoding, opts.columns, opts.dayfirst) as text, \
                as_read(text, csv_options(opts), rows) as read:
            yield read
    elif is_fixed_width(path):      # an old program's report: its columns told by the numbers
        with fixed_as_csv(path, opts.encoding) as text:
            yield text, utf8_options(opts)
    elif (layout := long_layout(path, opts)) is not None:   # a historian's: its grid, wide
        with long_as_wide(path, opts, layout, rows=rows) as wide:
            yield wide, wide_options(opts, layout)
    else:
        yield path, opts
