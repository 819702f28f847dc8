"""`thermocomp init <file-or-folder>`: what the reader detects in a lab's data, and the data
config that reads it (roles proposed from the units in the headers:
:mod:`thermocomp.core.io.detect`), written to ``<out>/conf/data/<name>.yaml`` with the command to
run next.  The data are read with it first: a config that would not read them is refused as
``run`` would refuse it.
"""

from __future__ import annotations

import fnmatch
from contextlib import ExitStack, nullcontext
from dataclasses import replace
from statistics import median

import numpy as np
import pandas as pd
import yaml
from omegaconf import DictConfig, OmegaConf

from ...base.errors import ContractError, listed
from ...base.files import atomic_write_text
from ...base.log import held_back, said_after
from ...base.paths import conf_dir, resolve
from ...core import io
from ...core.io.bits import proposed as bits_proposed
from ...core.io.cells import Cells, scanned
from ...core.io.contract import MANIFEST, TIME
from ...core.io.dayfirst import WAY
from ...core.io.derived import probe_pairs, proposal
from ...core.io.detect import (
    TRAVEL_UM,
    axis_lengths,
    beyond,
    check_an_error_is_named,
    clock_column,
    data_config,
    detection_lines,
    elapsed_column,
    encoding,
    epoch_ms_column,
    excel_days_column,
    flag_headers,
    flags_as_states,
    folder_manifest,
    foreign_said,
    head,
    hours_column,
    ignored,
    length_errors,
    proposed_campaign,
    proposed_roles,
    sample_file,
    stated_units,
    travel_headers,
    weekday_headers,
    without_own_names,
)
from ...core.io.encoding import UTF8
from ...core.io.historian import (
    PERIOD_COMMENT,
    grid_runs,
    intervals_said,
    proposed_period,
    tag_samples,
)
from ...core.io.historian_layout import long_layout
from ...core.io.labfile import SHARED
from ...core.io.manifest import is_text
from ...core.io.options import AUTO, RUN_ROLE
from ...core.io.pairhead import error_files, pair_time, paired_head, paired_lines
from ...core.io.period_line import stated_period
from ...core.io.plain import converted_once, is_converted, is_lab_file, lab_as_csv, lab_dayfirst
from ...core.io.record import safe_id
from ...core.io.roles import idle_patterns, naming, split_unit
from ...core.io.slashed import record_order
from ...core.io.slashed_rows import RUN_SAID
from ...core.io.sniff import resolved
from ...core.io.starts import stated_start
from ...core.io.tables import peek_csv
from ...core.io.timestamps import ELAPSED, OF_DAY_KIND, PAUSE_PERIODS, pauses
from ...core.io.utf16 import is_utf16, utf8_options, utf16_as_utf8
from ...core.io.workbook import csv_options
from ...core.timerule import median_step
from ..config.checks import check_config, data_options
from ..source import check_declared, open_source
from .gathered import gathered


def lone_file(src, manifest, opts) -> bool:
    """``src`` is a folder without a manifest holding one data file (``manifest``: as read).
    (data88) A run of two loggers' files (:mod:`~thermocomp.core.io.loggers`) is no lone file:
    its temperature file was read alone, "no column reads as a measured error"."""
    from ...core.io.read import lone_run

    run = None if manifest is None else lone_run(src, opts, manifest)
    return run is not None and run[1] is None


def long_period(sample, given: dict) -> dict | None:
    """A historian's long file read without ``data.resample_s``: its tags' median intervals
    (s), ``given`` holding the fastest tag's as the grid's period until the roles say which
    tags are errors (:func:`.historian.proposed_period`); None for any other file, or where the
    period is given."""
    opts = io.ReadOptions.from_cfg(given)
    if is_lab_file(sample) and opts.resample_s is None:   # a TDMS log's channels at two rates
        with lab_as_csv(sample, encoding=opts.encoding, dayfirst=opts.dayfirst) as text:
            return _long_period(text, given, csv_options(opts))
    return _long_period(sample, given, opts)


def _long_period(sample, given: dict, opts) -> dict | None:
    layout = long_layout(sample, opts) if opts.resample_s is None else None
    if layout is None:
        return None
    intervals = tag_samples(sample, opts, layout)[1]
    given["resample_s"] = proposed_period(intervals, ())[0]
    return intervals


def text_files(src, manifest, opts) -> list:
    """The CSV texts of ``src`` (one record, or a folder's by ``manifest``), a UTF-16 one too:
    the files ``data.delimiter`` and ``data.decimal`` read."""
    files = [src] if manifest is None else [src / str(f) for f in manifest["file"]]
    return [f for f in files if is_text(f) and (is_utf16(f) or not is_converted(f, opts))]


def separator_groups(files: list, given: dict, opts) -> list[tuple[list, object]]:
    """``files`` grouped by the separators each is written with, ``[(files, opts)]`` (one group
    where ``data.delimiter`` and ``data.decimal`` are given): a folder of runs two PCs exported,
    ``;`` and decimal commas beside a TAB-separated UTF-16 file, which ``run`` reads each by its
    own (audit86: init read every file with the first's separators and refused the second)."""
    asked = io.ReadOptions.from_cfg(given)
    if AUTO not in (asked.delimiter, asked.decimal) or len(files) < 2:
        return [(files, opts)]
    groups: dict = {}
    for f in files:
        with utf16_as_utf8(f) if is_utf16(f) else nullcontext(f) as text:
            seps = resolved(text, utf8_options(asked) if is_utf16(f) else asked)
        groups.setdefault((seps.delimiter, seps.decimal), []).append(f)
    return [(fs, replace(opts, delimiter=d, decimal=m)) for (d, m), fs in groups.items()]


def number_cells(src, manifest, sample, given: dict, opts):
    """``(opts, found)``: ``opts`` (and ``given``, written to the config) with what the text
    files' number cells say (:mod:`.io.cells`: ``data.thousands``, ``data.missing_values``),
    each said with why, a doubt said, not written; ``found`` (None: no text file) for the gaps
    their marks leave, which :func:`mark_gaps` reads once the error columns are named."""
    files = [src] if manifest is None else [src / str(f) for f in manifest["file"]]
    # (lab75: a TOB1 table's, a TDMS log's gaps; lab77: a folder's, a Scope export's channels on
    # other clocks leaving cells at each other's times; stranger78: a folder of any lab files',
    # a DIAdem pair a day with a loose plug's NaN, refused at the read with no key proposed)
    labs = [f for f in files if is_lab_file(f)]
    if labs:
        with ExitStack() as stack:
            code = given.get("encoding") or opts.encoding
            # (stranger77: a sensor replaced from a run on: its channel's empty runs are no edge)
            shared = SHARED if manifest is None else None
            texts = [stack.enter_context(lab_as_csv(f, encoding=code, columns=shared,
                                                    dayfirst=opts.dayfirst)) for f in labs]
            return opts, scanned(texts, ",", ".", UTF8, None, [], peek_csv, decimal_given=True)
    files = [f for f in files if is_text(f) and not is_converted(f, opts)]
    if not files or not is_text(sample):
        return opts, None
    asked = io.ReadOptions.from_cfg(given)
    # (pair70: the runs' error files, another logger's, their own separators and marks)
    errors = [f for f in error_files(src, manifest, asked)
              if is_text(f) and not is_converted(f, asked)]
    found = None
    for group, group_opts in (*separator_groups(files, given, opts),
                              (errors, errors and resolved(errors[0], asked))):
        if group:
            cells = scanned(group, group_opts.delimiter, group_opts.decimal, opts.encoding,
                            opts.thousands, list(opts.missing_values), peek_csv,
                            decimal_given=str(given.get("decimal", "auto")) != "auto")
            found = cells if found is None else found.merged(cells)
    for line in found.said:
        print(f"{src.name}: {line}")
    if found.thousands is not None and opts.thousands is None:
        given["thousands"] = found.thousands
        opts = replace(opts, thousands=found.thousands)
    new = [m for m in found.marks if m not in opts.missing_values]
    if new:
        given["missing_values"] = [*opts.missing_values, *new]
        opts = replace(opts, missing_values=given["missing_values"])
    return opts, found


GAP_SAID = {"max_gap_samples": "the longest run of missing cells (empty or a mark) inside a "
                               "file is {n} sample{s}, {span} of {header}: "
                               "data.max_gap_samples={n} interpolates such runs linearly (each "
                               "repair counted in the ingest report)",
            "max_edge_samples": "a run of missing cells at a file's start or end, {n} sample{s} "
                                "at most, {span} of {header}: data.max_edge_samples={n} drops "
                                "those rows"}


def mark_gaps(src, found, errors: set, given: dict, opts, grid: dict | None = None):
    """``(opts, said)``: ``opts`` (and ``given``) with the ``data.max_gap_samples`` /
    ``max_edge_samples`` that read the longest runs of missing cells (empty, or a mark's), and
    the lines saying each (``{span}`` left for the sample period, known once read: :func:
    `gaps_said`); an error column (a header in ``errors``) read as a probe cycle sets neither
    (its empty cells are kept: :meth:`.io.cells.Cells.longest`); ``grid``: header -> grid
    rows a sample of it is held over, where the channels are held onto a grid (the runs then
    counted in the grid's rows, as the read checks them)."""
    if found is None:
        return opts, []
    gap, edge, said, where = found.longest(errors, opts.sparse_targets, grid)
    for line in said:
        print(f"{src.name}: {line}")
    pending = []
    for key, n in (("max_gap_samples", gap), ("max_edge_samples", edge)):
        if n > getattr(opts, key):
            given[key] = n
            opts = replace(opts, **{key: n})
            kind = key.split("_")[1]
            pending.append((key, n, where[kind], where.get(f"{kind}_at", "")))
    return opts, pending


def temperature_period(report: dict, headers: list) -> dict:
    """``{header: the temperature logger's period}`` of ``headers`` (the temperature file's)
    in a record of runs of two loggers: its gaps are counted in that file's samples."""
    periods = [e["paired"]["periods_s"][0] for e in report["campaigns"].values() if e.get("paired")]
    return dict.fromkeys(headers, median(periods)) if periods else {}


def temperature_scans(src, config: dict, report: dict) -> dict:
    """``{contract name: [its samples per run]}`` of the temperature files of a record's runs of
    two loggers, each read alone with ``config`` (its own scans, its gaps kept)."""
    opts = replace(io.ReadOptions.from_cfg(config), half=True, missing="keep")
    out: dict = {}
    for entry in report["campaigns"].values():
        if entry.get("paired"):
            table, _ = io.read_campaign(src / entry["paired"]["temperatures"], opts)
            for name in table.column_names[1:]:
                out.setdefault(name, []).append(table.column(name).to_numpy(zero_copy_only=False))
    return out


def held_cells(src, manifest, opts) -> Cells | None:
    """The runs of missing grid rows of a historian's text files, each tag's on its own
    (:func:`.io.historian.grid_runs`); None: none missing."""
    files = [src] if manifest is None else [src / str(f) for f in manifest["file"]]
    runs = [r for f in files if (layout := long_layout(f, opts)) is not None
            for r in grid_runs(f, opts, layout)]
    return Cells(runs=runs) if runs else None


def gaps_said(src, pending: list, period: float, periods: dict | None = None) -> None:
    """Say :func:`mark_gaps`' keys, each run's samples with the time they span (``period``: the
    record's sample period, s; ``periods``: a header's own, where its file's differs)."""
    for key, n, header, at in pending:
        each = (periods or {}).get(header, period)
        span = f"{n * each / 3600:.3g} h" if n * each >= 3600 else f"{n * each:.4g} s"
        header = (repr(header) + (f" ({at})" if at else "") if header is not None
                  else "one of its channels (grid rows)")
        print(f"{src.name}: " + GAP_SAID[key].format(n=n, s="s" * (n > 1), header=header,
                                                     span=span if each == each else "?"))


def stated_period_given(sample, plan, given: dict, opts):
    """``opts`` (and ``given``) with the sample period a preamble line of a file without a time
    column states (:mod:`.io.period_line`), said with the line; as they were otherwise."""
    if opts.sample_period_s is not None or TIME in plan.names.values():
        return opts
    said = stated_period(sample, opts.delimiter, opts.encoding)
    if said is None:
        return opts
    given["sample_period_s"] = said.seconds
    print(f"{sample.name}: no time column, and {said.said()}: data.sample_period_s="
          f"{said.seconds:g} (written into the config)")
    return replace(opts, sample_period_s=said.seconds)


def renamed(ds) -> dict:
    """``{data.columns key: (earlier name, later name)}`` of each sensor the campaigns of ``ds``
    read under one name up to some file and under another from it on (:func:`.frame.
    renamed_sensors`), each said: ``run`` refused it naming the entry, a run more a sensor."""
    from ...core.frame import renamed_sensors

    headers = {name: raw for raw, name in (ds.meta.get("column_map") or {}).items()}
    starts = ds.manifest["start"].to_dict() if "start" in ds.manifest.columns else None
    columns = list(dict.fromkeys(c for df in ds.campaigns.values() for c in df.columns
                                 if c[:2] in ("T_", "E_", "S_")))
    found = renamed_sensors(ds.campaigns, columns, headers, starts)
    for key, (old, new) in found.items():
        have = [cid for cid, df in ds.campaigns.items() if new in df.columns]
        print(f"{headers.get(new, new)!r} from {have[0]} on, in the campaigns without {old!r} "
              f"(in every other): one sensor renamed, read as {old} (data.columns: "
              f"{{{key!r}: {old}}})")
    return found


def stated_starts(src, ds, report: dict, opts) -> None:
    """Say which campaigns of a folder ``src`` take their ``start`` from their file's comment
    block (``# start: 2027-03-08 06:00:00``, a DAQ script's, over a time in seconds:
    :func:`.io.starts.commented_start`) and the order their last ones are held out in."""
    if not src.is_dir() or "file" not in ds.manifest.columns:
        return
    untimed = [cid for cid in ds.ids() if not report["campaigns"][cid].get("time_origin")]
    said = {cid: stated_start(src / str(ds.manifest.at[cid, "file"]), opts) for cid in untimed}
    stated = {cid: t for cid, (t, _) in said.items()}
    found = [cid for cid, t in stated.items() if pd.notna(t)]
    if not found:
        # (isoleft67) a header block's start key left: its time alone, a 'Date' maybe the export's
        left = [(c, why) for c, (_, why) in said.items() if why]
        if left:
            print(f"{ds.manifest.at[left[0][0], 'file']}: {left[0][1]}: not taken as its start"
                  + (f" (nor in {len(left) - 1} other file(s))" if len(left) > 1 else "")
                  + "; the campaigns are held out in name order (a 'Test start<TAB>"
                  "2027-05-07 12:00:00' line above the table, or the start column of a "
                  "campaigns.csv, orders them)")
        return
    first = ds.manifest.at[found[0], "file"]
    how = said[found[0]][1]
    line = (f"{len(found)} of {len(ds.ids())} files without timestamps state their start in "
            f"a {how} ({first}: {stated[found[0]]}): the campaign's start "
            "(data.test_fraction holds out the last by it)")
    lacking = [str(ds.manifest.at[c, "file"]) for c in stated if c not in found]
    if lacking:
        why = next((w for c, (_, w) in said.items() if c not in found and w), None)
        line += (f"; {', '.join(lacking[:3])}{' ...' * (len(lacking) > 3)} state{'s' * (len(lacking) == 1)} "
                 f"none{f' ({why})' if why else ''}: the campaigns are held out in name order")
    print(line)


def appended_runs(src, ds, opts) -> str | None:
    """Why one record ``src`` (read as ``ds``, cut into parts) is runs appended in one file: its
    time pauses (the reader's rule, :func:`.io.timestamps.pauses`) -- how many times and the longest;
    None where it does not, or where its runs are otherwise told (a run column, a folder)."""
    if not src.is_file() or opts.runs_at_pauses or opts.roles.get(RUN_ROLE):
        return None
    entries = ds.meta["read_report"]["campaigns"]
    if not all("record_rows" in entries[cid] for cid in ds.ids()):    # (a workbook's sheets)
        return None
    parts = sorted(ds.ids(), key=lambda cid: entries[cid]["record_rows"][0])
    time = np.concatenate([ds.campaigns[cid][TIME].to_numpy(float) for cid in parts])
    found = pauses(time)
    if not found.size:
        return None
    longest = float(np.diff(time)[found].max())
    return (f"its time pauses {found.size} time(s) for more than {PAUSE_PERIODS} sample periods "
            f"(the longest {longest / 3600:.3g} h): runs appended in one file, its {found.size + 1} "
            "stretches read as a campaign each (runs_at_pauses: true, written into the config)")


def config_name(name: str) -> str:
    """The data config's name for the record ``name``: one that ``data=<name>`` on the command
    line reads as itself.  Hydra reads ``data=inf`` / ``2024`` / ``true`` / ``null`` as a number,
    a bool or null ("Config group override must be a string"), and a folder's name may hold a
    space: such a name gets the prefix ``data_`` (``data_2024``), its unsafe characters ``_``."""
    from hydra.core.override_parser.overrides_parser import OverridesParser

    safe = safe_id(name)
    try:
        read = OverridesParser.create().parse_override(f"data={safe}").value()
    except Exception:           # (any name its grammar does not take as a plain word)
        read = None
    return safe if read == safe else f"data_{safe}"


def init(cfg: DictConfig) -> dict:
    """Detect, propose, check by reading, write ``<out>/conf/data/<name>.yaml``; print the run
    command.  A volumetric folder of one distance per row is refused as ``calibrate`` refuses
    it, naming the layout the reader takes (:func:`.volumetric.calibration.layout_refusal`)."""
    from ...apps.volumetric.calibration import layout_refusal

    try:
        with ExitStack() as held:
            return _init(cfg, held)
    except ContractError as exc:     # (it said "no 'time' column", which no setting mends)
        # (refusals100) the refusals a key settles, gathered: one try for a lab's file
        raise layout_refusal(exc, resolve(cfg.data.path)) or gathered(exc, cfg, _looked) from None


def _looked(cfg: DictConfig) -> None:
    """:func:`_init`'s read of ``cfg`` that writes nothing (:func:`.gathered.gathered`'s look)."""
    with ExitStack() as held:
        _init(cfg, held, write=False)


def _init(cfg: DictConfig, held: ExitStack, write: bool = True) -> dict:
    check_config(cfg)         # out never holds data.path: the lab's record is never written beside
    src = resolve(cfg.data.path)
    given = data_options(cfg)
    asked = io.ReadOptions.from_cfg(given)
    manifest = folder_manifest(src, asked)                  # a folder's, read once
    if lone_file(src, manifest, asked):
        # a lab's one export put in a folder (one long file, its runs numbered in a column):
        # read as the record it is, which `run` would be told to give
        src = src / str(manifest["file"].iloc[0])
        print(f"{src.parent}: one file and no {MANIFEST}: read as the record {src.name}")
        manifest = None
    given["encoding"] = encoding(src, asked, manifest)      # a Windows export's
    sample = sample_file(src, manifest)
    files = [src] if manifest is None else [src / f for f in manifest["file"]]
    if given.get("dayfirst") is None and (said := lab_dayfirst(files, given["encoding"])):
        given["dayfirst"] = said[0]            # (dates84: one order for the record's files)
        print(f"{src.name}: dates with slashes read {WAY[said[0]]}, as {said[1].name}'s "
              f"{said} says, in every file: data.dayfirst={str(said[0]).lower()}")
    # a lab's binary file (a TOB1 table, a TDMS log) converted once for every look and the read
    held.enter_context(converted_once(src if manifest is None else None, given["encoding"],
                                      io.ReadOptions.from_cfg(given).dayfirst))
    long = long_period(sample, given)        # a historian's long file: the grid it is held onto
    opts, header, first, layout = head(sample, io.ReadOptions.from_cfg(given))
    pair = paired_head(sample, manifest.index[0], manifest, io.ReadOptions.from_cfg(given),
                       head) if manifest is not None else None
    own_header = header     # (the temperature file's, where a run is two loggers' files)
    if pair is not None:    # a run of two loggers: both files' columns, its rows the errors'
        header, first, layout = pair.header, pair.first, pair.layout
    cells_of_first = dict(zip(header, first))       # the first data row, by header
    # every file's rows count: a folder's first may say nothing (days <= 12), a later one a 13th
    order = record_order([src] if manifest is None else [src / f for f in manifest["file"]],
                         io.ReadOptions.from_cfg(given))
    if order:              # (13/07/2026: day first, for every file: written to the config)
        given["time"] = order.format
        opts = replace(opts, time=order.format)
        why = ("a Keysight DAQ's Time, its ms after a colon: month first" if order.keysight
               else "its run" if order.run else "a day or month past 12")
        where = f": its data row {order.row}, {order.value!r}" + (RUN_SAID if order.run else "")
        print(f"{sample.name}: dates with slashes read as data.time={order.format!r}, the order "
              + (f"its rows say ({why}{where if order.run else ''})" if order.file == sample else
                 f"the rows of {order.file.name} say ({why}{where}), in every file"))
    elapsed = elapsed_column(src, manifest, opts, header, cells_of_first)
    if elapsed:            # (a run past 24:00:00: each file's, a shorter run's too, read so)
        print(f"{src.name}: {elapsed!r} h:mm:ss past 24 h in a file: read as data.time="
              f"{ELAPSED!r}, a logger's time since its start, in every file")
    elif pair is not None and pair_time(pair, sample, header, cells_of_first, opts):
        elapsed = ELAPSED  # (both loggers' time h:mm:ss: one file's header said it, or none)
        print(f"{sample.name} and {pair.errors.name}: {pair.error_time[0]!r} h:mm:ss as the "
              f"temperatures' time: read as data.time={ELAPSED!r}, each logger's time since "
              "its start, in both files (taken as started together)")
    if elapsed:
        given["time"] = ELAPSED
        opts = replace(opts, time=ELAPSED)
    elif clock := clock_column(header, cells_of_first, opts):
        given["time"] = OF_DAY_KIND      # (data92b) written, so that a stream and the C read so
        opts = replace(opts, time=OF_DAY_KIND)
        print(f"{sample.name}: {clock!r} h:mm:ss, its header a time of day, no date column "
              f"beside it: read as data.time={OF_DAY_KIND!r}, the time since midnight, a day "
              "added where it passes midnight")
    elif hours := hours_column(sample, opts, header, cells_of_first):
        # (data93) a lab's decimal hours of the day (21.5, 21.58 ...): read as seconds, a record
        # within 24 s of midnight; the unit and the key written, so a stream and the C read so
        given["units"] = {**(given.get("units") or {}), hours: "h"}
        given["time"] = OF_DAY_KIND
        opts = replace(opts, units={**opts.units, hours: "h"}, time=OF_DAY_KIND)
        print(f"{sample.name}: {hours!r} from {cells_of_first[hours]}, numbers within a day's "
              f"hours under a time-of-day header: decimal hours, read as data.units={{{hours!r}: "
              f"h}} data.time={OF_DAY_KIND!r}, the time since midnight, a day added where it "
              "passes midnight")
    epoch = epoch_ms_column(header, cells_of_first, opts)
    if epoch:              # (a gateway's time stamp: read as seconds, 1000 times too long)
        given["units"] = {**(given.get("units") or {}), epoch: "ms"}
        opts = replace(opts, units={**opts.units, epoch: "ms"})
        print(f"{sample.name}: {epoch!r} from {cells_of_first[epoch]}: milliseconds "
              f"since 1970, read as data.units={{{epoch}: ms}}")
    days = (excel_days_column(sample, opts, header, cells_of_first)
            if opts.roles.get("time", "auto") == "auto" else None)
    if days:               # (a date cell saved as a number: days, read as seconds otherwise)
        given["units"] = {**(given.get("units") or {}), days: "d"}
        opts = replace(opts, units={**opts.units, days: "d"},
                       roles={**opts.roles, "time": days})
        print(f"{sample.name}: {days!r} from {cells_of_first[days]}: Excel's serial "
              f"days (since 1899-12-30), read as the time, data.roles.time={days!r} "
              f"data.units={{{days!r}: d}}")
    opts, cells = number_cells(src, manifest, sample, given, opts)   # thousands, marks
    stated = stated_units(sample, opts)             # (a TOA5 file's units row)
    idle = idle_patterns(header, opts.roles) if src.is_file() else []
    if idle:     # (badin96: kept in the config written, naming nothing, a detected role beside it)
        raise ContractError(f"{listed(idle)} matches no column (its headers: {listed(header, 8)})",
                            file=sample)
    roles = proposed_roles(header, cells_of_first, opts, stated)
    for line in foreign_said(header, roles, opts, stated):   # W/m^2, m/s: left out, said
        print(f"{sample.name}: {line}")
    check_an_error_is_named(header, cells_of_first, roles, opts, sample)
    either = axis_lengths(header, roles, opts)     # read as errors for their span, below
    roles = {**roles, "error": [*roles["error"], *either]}
    roles = proposed_campaign(src, roles, opts)     # a long file's run-number column
    roles, own = without_own_names(header, cells_of_first, roles, opts)
    if own:                # (a volumetric export's 420 distances: not one pattern each)
        print(f"{sample.name}: {len(own)} contract name{'s' * (len(own) > 1)} with a unit "
              f"({', '.join(map(repr, own[:2]))}{', ...' * (len(own) > 2)}) read as "
              f"{'their names' if len(own) > 1 else 'its name'}, converted: no data.roles "
              "pattern written for them")
    plan = naming(header, roles, opts.columns, cells_of_first, opts.decimal, sample,
                  opts.units)
    errors = [h for h, n in plan.names.items() if str(n).startswith("E_")]
    opts = stated_period_given(sample, plan, given, opts)    # `Abtastrate 15 s` above the table
    grid = None
    if long is not None:                     # the period: the fastest error tag's, said
        # a length in mm last: more likely an axis' position than a probe, known once read
        # (stranger80: the period was said to be "the fastest error tag 'W Pinole [mm]'", the
        # quill's travel proposed a state a few lines on)
        period, tag = proposed_period(long, sorted(errors, key=lambda h: split_unit(h)[1]
                                                   in ("mm", "cm", "m")))
        given["resample_s"] = period
        opts = replace(opts, resample_s=period)
        grid = {t: max(v / period, 1.0) for t, v in long.items() if np.isfinite(v)}
        kind = ("its channels logged at their own rates" if is_lab_file(sample) else
                "a historian's long file, each tag logged at its own times")
        print(f"{sample.name}: {kind}: held "
              f"onto a grid of data.resample_s={period:g} s, the median interval of the fastest "
              f"error tag {tag!r} (written into the config: check it; the tags': "
              f"{intervals_said(long)})")
    # a gap counted in the grid's rows where the channels are held onto one (stranger80); a
    # historian's text file on the grid itself, each tag's runs its own (lab83: its cells were
    # never scanned, and init's own read refused a probe's Bad samples)
    if long is not None and not is_lab_file(sample):
        cells, grid = held_cells(src, manifest, opts), None
    opts, gaps = mark_gaps(src, cells, set(errors), given, opts, grid)   # a probe's left out
    if long is not None:     # (a long text's 'value' column: no header of the lab's, stranger80)
        gaps = [(k, n, h if h in plan.names else None, at) for k, n, h, at in gaps]
    defaults = OmegaConf.to_container(OmegaConf.load(conf_dir() / "data" / "default.yaml"))
    decimal = opts.decimal             # the first row's (an error file's cells read so: pairhead)
    if pair is not None and not pair.same_separators:   # each logger's file its own: detected
        opts = replace(opts, delimiter="auto", decimal="auto")
    groups = separator_groups(text_files(src, manifest, opts), given, opts) if pair is None else []
    if len(groups) > 1:                                  # each run's file its own: detected
        opts = replace(opts, delimiter=AUTO, decimal=AUTO)
        if asked.thousands is None and given.get("thousands") is not None:
            # (data87) a mark found grouping one group's digits may be another's decimal mark
            print(f"{src.name}: the thousands separator {given['thousands']!r} of some files: "
                  "each file's own read, data.thousands=auto")
            given["thousands"] = AUTO
            opts = replace(opts, thousands=AUTO)
        print(f"{src.name}: its files are written with different separators ("
              + "; ".join(f"{g.delimiter!r} and decimal {g.decimal!r}: {len(fs)} "
                          f"({', '.join(f.name for f in fs[:3])}{', ...' * (len(fs) > 3)})"
                          for fs, g in groups)
              + "): each read with its own, data.delimiter=auto data.decimal=auto")
    config = data_config(src, given, opts, roles, defaults, manifest)
    # refused here as `run` would refuse it; a length read as an error for a look at its span
    # is not held to data.max_abs_error (stranger75: a boring mill's `Y head (mm)`, 150-1850
    # mm, was refused as an error of 1.85e6 µm before it could be proposed as a state)
    spans = length_errors(plan.names, asked.roles, opts)
    with held_back() as first_look:   # said once the roles stand (a span read as an error)
        ds = open_source(cfg, detected={**config, "max_abs_error": None} if spans else config)
    looked_again = False
    days = weekday_headers(ds, plan.names, opts)  # a logger's day of the week: left out
    # 0 / 1 under a header that did not say a flag (a weekday over two days is no flag)
    flags = [h for h in flag_headers(ds, plan.names) if h not in days]
    travels = travel_headers(ds, plan.names, asked.roles, opts)   # an axis' position in mm
    undecided = [p for p in either if p in roles["error"] and not any(
        fnmatch.fnmatchcase(split_unit(h)[0], p) for h in travels)]
    if flags or travels or undecided or days or beyond(ds, spans, asked.max_abs_error):
        # proposed as states, the record read once more (an error beyond its bound: refused)
        # (an axis' length of a thermal error's span stays unread: the reader asks which)
        roles = flags_as_states({**roles, "error": [p for p in roles["error"]
                                                    if p not in undecided]},
                                [*flags, *travels], opts)
        roles = ignored(roles, days)
        # (stranger83: 'auto' where two loggers' decimal marks differ: a DAQ970A's
        # '+2,04390000E+01' on a German PC was refused as not numeric)
        plan = naming(header, roles, opts.columns, cells_of_first, decimal, sample, opts.units)
        config = data_config(src, given, opts, roles, defaults, manifest)
        ds, looked_again = open_source(cfg, detected=config), True   # says what holds of these
    if not looked_again:
        said_after(first_look)
    if flags:
        print(f"{', '.join(map(repr, flags))}: only two values one apart (0 / 1) over the "
              "record: an on/off flag, proposed as a state (data.roles.state)")
    if days:
        print(f"{', '.join(map(repr, days))}: the day of the week (whole numbers 0-7), a "
              "calendar number, not a temperature: left out (data.roles.ignore)")
    if travels:
        print("; ".join(f"{h!r} spans {span:.4g} mm" for h, span in travels.items())
              + f": more than a thermal error does ({TRAVEL_UM / 1000:g} mm), an axis position, "
              "proposed as a state (data.roles.state; data.roles.error=[<header>] if it is "
              "the error)")
    renames = renamed(ds)                       # a sensor renamed from some file on
    if renames:
        given["columns"] = {**(given.get("columns") or {}), **{k: o for k, (o, _) in renames.items()}}
        opts = replace(opts, columns={**opts.columns, **given["columns"]})
        config = data_config(src, given, opts, roles, defaults, manifest)
        ds = open_source(cfg, detected=config)
    appended = appended_runs(src, ds, opts)     # a week of tests in one export (catman70)
    if appended:
        split = data_config(src, {**given, "runs_at_pauses": True}, opts, roles, defaults, manifest)
        try:
            ds, config = open_source(cfg, detected=split), split
            given["runs_at_pauses"], opts = True, replace(opts, runs_at_pauses=True)
            print(f"{src.name}: {appended}")
        except ContractError as exc:            # (runs the reader refuses: one record, as before)
            print(f"{src.name}: {appended.split(': runs')[0]}: not read at them ({exc}), one record")
    check_declared(cfg, ds, model=False)        # (a folder's run with a sensor the others lack)
    for raw, name in plan.names.items():        # a PLC's status word: proposed, never decoded
        # (a unit says a measurement: a position's 0 / 100 / 200 mm are no bits)
        if raw in opts.bits or not str(name).startswith("S_") or split_unit(raw)[1] is not None:
            continue
        said = bits_proposed(raw, np.concatenate([df[name].to_numpy(float)
                                                  for df in ds.campaigns.values() if name in df]))
        if said:
            print(f"{sample.name}: {said}")
    air = [h for h, why in plan.roles.items() if why == "ambient" and not asked.roles["ambient"]]
    if air:                                     # by its words (the reader's default: a temperature)
        print(f"ambient: {', '.join(map(repr, air))} ({'their names' if len(air) > 1 else 'its name'}"
              f": the air around the machine, data.roles.ambient; ati reads it)")
    report = ds.meta["read_report"]
    stated_starts(src, ds, report, opts)        # a DAQ's '# start:' line over a time in s
    for line in paired_lines(report):           # the runs of two loggers: what was paired
        print(line)
    name = config_name(ds.name)
    path = resolve(cfg.out) / "conf" / "data" / f"{name}.yaml"
    text = yaml.safe_dump({"defaults": ["default"], **config}, allow_unicode=True, sort_keys=False)
    if long is not None:
        text = text.replace("\nresample_s:", f"\n{PERIOD_COMMENT}\nresample_s:", 1)
    pairs = [] if asked.derive else probe_pairs(report["columns"]["E"])
    if pairs:              # an ISO 230-3 nest's probes: their tilts, the spacing the lab's to say
        text += proposal(pairs)
        print(f"probe pairs {', '.join(f'{a} / {b}' for a, b, _ in pairs)}: their tilts as "
              f"targets, data.derive={{{pairs[0][2]}: '({pairs[0][0]} - {pairs[0][1]}) / "
              "<spacing in m>'}, proposed as a comment in the config")
    if not write:
        return {"config": None, "columns": plan.names}
    atomic_write_text(path, f"# written by `thermocomp init {src}`\n{text}")
    period = median_step([df[TIME].to_numpy(float) for df in ds.campaigns.values()]) or float("nan")
    # (stranger83: a DAQ file's 3 scans of 60 s were said to span 2700 s, the probe's 900 s rows)
    gaps_said(src, gaps, period, temperature_period(report, own_header) if pair else {})
    scans = temperature_scans(src, config, report) if pair else None
    print("\n".join(detection_lines(layout, opts, header, plan, ds, report, period, path, name,
                                     scans)))
    return {"config": str(path), "columns": plan.names}
