"""The conformance pack ``export`` writes beside the code (``check/``): rows the code must take and
the corrections it must give for them (pure core).

A lab compiles the exported code with its own toolchain (another compiler, an ST runtime) and
needs to know that the build computes what the served model computes.  :func:`conformance_pack`
writes, per campaign, ``check/<campaign>/rows.csv`` (``time`` and the code's inputs, in the order
``TC_INPUT_NAMES`` lists them, under their contract names, in the contract's units: degC, um, s;
a missing cell empty) in the form ``stream.c`` reads, and ``check/<campaign>/expected.csv`` (one
``C_<axis>`` row per row of ``rows.csv``): the served model's corrections for those rows, streamed
row by row from the campaign's start as ``replay`` streams it (:func:`~..report.stream_rows`),
with the reference update's gain and bias as exported.  The rows come from the dataset as
thermocomp read it, so a record in any form it reads (fixed-width, JSON Lines, a historian's
long export, a workbook) reaches the code as the CSV ``stream.c`` takes.

* A campaign that continues others (``data.reference=none``) starts with their rows: the stream
  the served model is warmed on, which the code must be fed too.
* A campaign is cut before its first row with an input the code refuses (a missing value of a
  declared input: ``stream.c`` stops there), as ``replay``'s plain stream stops; of a monitored
  input (the C's monitor, cdrop77) only where the code's monitor cannot rebuild it.
* Where the served model does what the code does not (its sensor monitor: :func:`~.output.
  not_in_code`; the C holds a slice of it, :mod:`.watch`), the corrections are checked against
  the exported arithmetic in numpy (:class:`~.statespace.Simulator`, the code's monitor in it)
  and the campaign is cut before the first row where the two part (the served monitor did what
  the code's does not; the rule the code flagged there named): no build can reproduce that row.

Of an export whose code holds the sensor monitor (the C's, :mod:`.watch`), two copies of the
first campaign with a fault planted follow (:func:`~.watch.planted`: a jump, a freeze and a
dropout of a monitored sensor from its middle row on, ``planted`` in their entries), the served
model's monitor acting on them: every pack checks the code's monitor, cut where it parts.  A copy
is its source up to the plant: their shared rows (and a shared lead-in, perf87b) are streamed once
and each goes on from a copy of the states there (:func:`_shares`, :class:`_Lead`; ci101), the
pack the same as each streamed from its start.

(deploy89) Each campaign that continues others follows once more as ``<campaign>.cold``, streamed
from a reset at its first row, not warmed on their rows (``cold_start`` in its entry: the campaign
it copies): a controller restarted mid-campaign, or ``stream`` fed the campaign's file alone,
starts there, and what the code gives from that state is checked like the continued stream (its
figure is ``replay``'s ``rmse_cold_start``).

Of a model that reads no ambient sensor and picks its laws by a campaign's initial ambient
(``ambient_given``: the manifest's ``ambient_c``), each campaign's value is in check.json's entry
and in an ``ambient_c`` column of its rows.csv, which ``stream.c`` reads at a campaign's first row.

(packflags100) Where the code holds the sensor monitor, each campaign's ``flags.csv`` beside its
``expected.csv`` holds per row the monitor's flags as ``stream --flags`` prints them
(:func:`~.watch.flag_row` of the :class:`Simulator` :func:`_parted` steps), which ``stream
--check-flags`` compares exactly: a build with right corrections and wrong flags fails.

``check/check.json`` lists the campaigns (rows, cuts and why) and the tolerance
(:data:`TOLERANCE_UM`, :data:`TOLERANCE_RELATIVE`); with the C, ``check/check.sh`` runs
``stream --check`` on each.
"""

from __future__ import annotations

import copy
import io
import json
import re
from collections import Counter
from collections.abc import Mapping

import numpy as np
import pandas as pd

from ....core.io.contract import AMBIENT_C, manifest_ambient
from ..naming import correction_column
from ..report import stream_rows
from ..streaming import OutOfEnvelopeError
from .left_out import not_in_code
from .served import ServedLead, ServedStreams
from .statespace import Simulator, StateSpace
from .watch import FLAG_KINDS, NOT_IN_CODE, REASONS, flag_row, planted

CHECK = "check"
# |C - expected| <= TOLERANCE_UM + TOLERANCE_RELATIVE * |expected| (um).  float64 arithmetic in
# another order, with or without fused multiply-adds, rounds each sum differently by a few ulp of
# its largest term (a lag bank's opposed weights make terms far larger than the correction): on
# the vendored spindle record gcc -O0, -O2 and -O3 -ffast-math parted from the Python stream by
# 6.3e-13 um at most (benchmarks/bench_export_check61.py).  1e-9 leaves a margin of 1600 over
# that and is still a millionth of a micrometre: a coefficient moved by a millionth of itself
# (tests/shell/test_export_check61.py) or a float32 build (1e-2 um there) shows up.  The
# relative part keeps the margin for corrections of thousands of um.
TOLERANCE_UM = 1e-9
TOLERANCE_RELATIVE = 1e-9
WHY = ("float64 sums in another order (another compiler, optimiser, fused multiply-add) part by "
       "a few units in the last place of their largest term: 6.3e-13 um at most on the vendored "
       "spindle record (gcc -O0, -O2, -O3 -ffast-math; mlr, lagbank, hammerstein, auto); the "
       "tolerance keeps a margin of 1600 over that and is still far below what a machine shows, "
       "while a coefficient moved by a millionth fails; a float32 build parts by up to 0.017 um "
       "there and needs a tolerance of its own (stream --tolerance)")

GIVEN = ("the model reads no ambient sensor: each campaign's initial ambient A0 (degC, its "
         "manifest ambient_c) is its ambient_c here and the ambient_c column of its rows.csv (the "
         "same value on every row), given before its first sample: C tc_set_ambient after "
         "tc_reset (stream.c reads the column), ST the input ambient_c")

# (packflags100) check/<campaign>/flags.csv: per row the code's monitor flags as ``stream --flags``
# prints them (watch.flag_row of the mirror, :class:`Simulator`), where the code holds the monitor
FLAGS = "flags.csv"
FLAG_COLUMNS = [*(f"mon_{kind}" for kind, _ in FLAG_KINDS), "excluded_inputs"]
FLAGS_WHY = ("the code holds the sensor monitor: each campaign's flags.csv is, per row of its "
             "rows.csv, the monitor's flags the exported arithmetic (numpy) sets there, as stream "
             "--flags prints them (0/1 per kind, the sensors out in the order they went out, ';' "
             "between them); stream --check-flags compares them exactly, the first row that "
             "differs named with the flag and both values")

_UNSAFE = re.compile(r"[^A-Za-z0-9._-]+")


def folder_names(campaigns) -> dict[str, str]:
    """``{campaign: folder}``: a campaign's id as a file name (characters other than letters,
    digits, ``._-`` replaced by ``_``), distinct (a suffix ``~2`` where two read alike)."""
    out, taken = {}, set()
    for cid in campaigns:
        base = _UNSAFE.sub("_", str(cid)).strip("._") or "campaign"
        name, k = base, 1
        while name.lower() in taken:      # (a file system that folds case)
            k += 1
            name = f"{base}~{k}"
        taken.add(name.lower())
        out[cid] = name
    return out


def csv_text(frame: pd.DataFrame) -> str:
    """CSV as ``stream.c`` reads it: ``,``, ``.``, a number to the last bit (17 digits), NaN empty."""
    buf = io.StringIO()
    frame.to_csv(buf, index=False, float_format="%.17g", na_rep="", lineterminator="\n")
    return buf.getvalue()


def fed(campaign: pd.DataFrame, lead_in: pd.DataFrame | None) -> pd.DataFrame:
    """The rows the code is fed for ``campaign``: its ``lead_in``'s first (the campaigns it
    continues; its manifest ambient the chain's first's, as ``run`` joins them)."""
    if lead_in is None or not len(lead_in):
        return campaign.reset_index(drop=True)
    joined = pd.concat([lead_in, campaign], ignore_index=True)
    joined.attrs = dict(lead_in.attrs)
    return joined


def cold_copies(campaigns: Mapping[str, pd.DataFrame], lead_ins: Mapping[str, pd.DataFrame]
                ) -> dict[str, tuple[pd.DataFrame, str]]:
    """``{<campaign>.cold: (campaign, the campaign it copies)}``: each campaign with a lead-in (one
    that continues others), to be streamed from a reset at its first row (deploy89)."""
    return {f"{cid}.cold": (df, cid) for cid, df in campaigns.items()
            if lead_ins.get(cid) is not None and len(lead_ins[cid])}


def _refused_row(frame: pd.DataFrame, ss: StateSpace) -> tuple[int, str] | None:
    """``(row, input)`` of the first row with an input the code refuses (not measured, not held,
    not monitored: the code's monitor takes a missing reading where it can rebuild it, cdrop77,
    and :func:`_parted` cuts where it cannot)."""
    held = np.asarray(ss.held or [0] * len(ss.inputs), bool)
    if ss.monitor:
        held = held.copy()
        held[np.asarray(ss.monitor["inputs"], int)] = True
    checked = [c for c, h in zip(ss.inputs, held) if not h]
    bad = ~ss.measured(frame[ss.inputs].to_numpy(float))[:, ~held]
    if not bad.any():
        return None
    i = int(np.argmax(bad.any(axis=1)))
    return i, checked[int(np.argmax(bad[i]))]


def corrections(ss: StateSpace, y: np.ndarray) -> np.ndarray:
    """``C = -y``, with the reference update ``-(gain * y + bias)`` at its exported values (the
    pack feeds no reference measurement: what was learned stays as served)."""
    if ss.adapt == "none":
        return -y
    return -(np.asarray(ss.adapt_gain, float) * y + np.asarray(ss.adapt_bias, float))


def beyond(got: np.ndarray, want: np.ndarray) -> np.ndarray:
    """Per row and target, True where ``got`` is farther from ``want`` than the tolerance."""
    return ~(np.abs(got - want) <= TOLERANCE_UM + TOLERANCE_RELATIVE * np.abs(want))


def _parted(ss: StateSpace, frame: pd.DataFrame, want: np.ndarray, start: int = 0,
            sim: Simulator | None = None, flags: list | None = None) -> dict | None:
    """The cut (``row``, ``why``) before the first row where the exported arithmetic
    (:class:`Simulator`) parts from ``want`` or refuses the row (a missing reading its monitor
    cannot rebuild), naming the rule not in the code its monitor flagged there.  ``sim``: a
    Simulator already stepped over the first ``start`` rows (a shared lead-in, :class:`_Lead`);
    ``flags``: each row's :func:`~.watch.flag_row` appended to it (its first ``start`` given)."""
    if sim is None:
        sim, start = Simulator(ss), 0
        sim.reset(manifest_ambient(frame))
    U, t = frame[ss.inputs].to_numpy(float), _times(frame)
    names = [ss.inputs[k] for k in ss.monitor.get("inputs", [])] if ss.monitor else []
    for i in range(start, len(frame)):
        c = sim.step(U[i], t[i])
        if flags is not None and sim.watch is not None:
            flags.append(flag_row(sim.watch, names))
        if sim.refused or beyond(c, want[i]).any():
            w = sim.watch
            flagged = w is not None and w.flags & NOT_IN_CODE
            note = REASONS[w.missed].split(": ", 1)[1] if flagged else ""
            if sim.refused and flagged:
                return {"row": i + 1, "why": f"{ss.inputs[w.idx[w.sensor]]} has no value there, "
                        f"which the code refuses ({note}; "
                        "stream.c stops; the served model rebuilds it)"}
            return {"row": i + 1, "why": "the served model's sensor monitor acted there, which is "
                    "not in the code" + (f" ({note})" if note else "")}
    return None


def _times(frame: pd.DataFrame) -> np.ndarray:
    """``frame``'s time column (NaN without one: a stream timed by its sample period)."""
    return frame["time"].to_numpy(float) if "time" in frame.columns else np.full(len(frame), np.nan)


class _Lead:
    """A prefix shared by campaigns (:func:`_shares`: a lead-in, perf87b; a campaign and its
    planted copies up to the plant, ci101): streamed once through the served model (``served``:
    :class:`~.served.ServedLead`, once per prefix of a :class:`~.served.ServedStreams`) and the
    :class:`Simulator`, each campaign's stream started from a deep copy of their states; its rows
    formatted once.  Each campaign's pack is as streamed from its start (the whole stream is taken
    instead wherever the shortcut does not apply: a cut within the prefix, a refusal, a column
    not float)."""

    def __init__(self, served: ServedLead, ss: StateSpace, frame: pd.DataFrame, monitor: bool,
                 after: _Lead | None = None):
        self.served, self.rows, self.sim, self.parted = served, served.rows, None, None
        self.flags: list = []         # (packflags100) the mirror's flags of the prefix's rows
        if served.state is not None and monitor:
            if after is not None and after.sim is not None and after.parted is None:
                sim, start = copy.deepcopy(after.sim), after.rows    # (from a shorter prefix)
                self.flags = list(after.flags)
            else:
                sim, start = Simulator(ss), 0
                sim.reset(manifest_ambient(frame))
            self.parted = _parted(ss, frame.iloc[:self.rows], corrections(ss, served.y), start,
                                  sim, self.flags)
            self.sim = sim

    def fits(self, frame: pd.DataFrame) -> bool:
        """Whether ``frame`` (the prefix's rows first) can start from the prefix's states."""
        return self.served.state is not None and len(frame) > self.rows and self.parted is None

    def csv(self, frame: pd.DataFrame) -> str:
        """:func:`csv_text` of ``frame`` (the prefix's rows first), those rows formatted once
        (float columns only: each value formatted on its own, so the text is the same)."""
        key, text = tuple(frame.columns), self.served.text
        if not all(frame.dtypes == np.float64):
            return csv_text(frame)
        if key not in text:
            text[key] = csv_text(frame.iloc[:self.rows])
        rest = csv_text(frame.iloc[self.rows:])
        return text[key] + rest[rest.index("\n") + 1:]


def _same_rows(campaign: pd.DataFrame, changed: pd.DataFrame) -> int:
    """How many first rows of ``changed`` equal ``campaign``'s (every column, NaN alike; 0 where
    their columns or attributes differ)."""
    if list(campaign.columns) != list(changed.columns) or repr(campaign.attrs) != repr(changed.attrs):
        return 0
    n = min(len(campaign), len(changed))
    a, b = campaign.iloc[:n].to_numpy(), changed.iloc[:n].to_numpy()
    differ = (~((a == b) | (pd.isna(a) & pd.isna(b)))).any(axis=1)
    return int(np.argmax(differ)) if differ.any() else n


def _shares(campaigns: Mapping[str, pd.DataFrame], lead_ins: Mapping[str, pd.DataFrame | None],
            faults: Mapping[str, tuple]) -> dict[str, list[tuple[object, int]]]:
    """``{campaign: [(key, rows), ...]}``, shortest first: the first ``rows`` of the campaign's
    fed rows, the same for every campaign of ``key``, to be streamed once (:class:`_Lead`), each
    from the one before: a lead-in shared by campaigns (perf87b); of a campaign with planted
    copies (``faults``, :func:`~.watch.planted`), its lead-in and its own rows before the first a
    copy changes, shared by it and its copies (ci101: a copy is its source up to the plant).
    Only keys of more than one campaign."""
    out: dict[str, list] = {}
    for cid in campaigns:
        lead = lead_ins.get(cid)
        if lead is not None and len(lead):
            out[cid] = [(id(lead), len(lead))]
    copies: dict[str, list[str]] = {}
    for cid, (frame, _, source) in faults.items():
        if campaigns.get(cid) is frame and source in campaigns:
            copies.setdefault(source, []).append(cid)
    for source, planted_ in copies.items():
        lead = lead_ins.get(source)
        before = min(_same_rows(campaigns[source], campaigns[c]) for c in planted_)
        for cid in (source, *planted_) if before else ():
            out.setdefault(cid, []).append(
                (("planted", source), (0 if lead is None else len(lead)) + before))
    counts = Counter(key for shares in out.values() for key, _ in shares)
    return {c: [s for s in shares if counts[s[0]] > 1] for c, shares in out.items()}


def conformance_pack(deployed, ss: StateSpace, campaigns: Mapping[str, pd.DataFrame],
                     lead_ins: Mapping[str, pd.DataFrame] | None = None,
                     files: Mapping[str, object] | None = None, script: bool = True,
                     served: ServedStreams | None = None) -> tuple[dict[str, str], dict]:
    """``({path under out: text}, check.json's dict)`` of the pack for ``campaigns`` streamed
    through ``deployed`` (module doc); ``ss``: its exported system; ``files``: each campaign's
    file, for a refusal's message; ``script``: ``check/check.sh`` too (the C's ``stream``);
    ``served``: the served streams of ``deployed`` another pack or the caller made already (an
    explicit cache, :class:`~.served.ServedStreams`; ci99), else this pack's own."""
    served = ServedStreams(deployed) if served is None else served
    lead_ins = dict(lead_ins or {})
    faults = planted(ss, campaigns)     # (the code's monitor checked on planted faults, cmon76)
    for cid, (_, _, source) in faults.items():
        lead_ins[cid] = lead_ins.get(source)
    # (deploy89) a continuing campaign from a reset too: the code's cold start, no lead-in
    colds = {c: f for c, f in cold_copies(campaigns, lead_ins).items() if c not in campaigns}
    campaigns = {**campaigns, **{c: f[0] for c, f in faults.items() if c not in campaigns},
                 **{c: f[0] for c, f in colds.items()}}
    folders = folder_names(campaigns)
    shares = _shares(campaigns, lead_ins, faults)
    outputs = [correction_column(t) for t in ss.targets]
    monitor = bool(not_in_code(deployed))
    out, listed, leads = {}, [], {}
    for cid, campaign in campaigns.items():
        frame = fed(campaign, lead_ins.get(cid))
        lead = len(frame) - len(campaign)
        columns = (["time"] if "time" in frame.columns else []) + list(ss.inputs)
        if ss.ambient_given:     # the campaign's A0 on each of its rows (stream.c: its first)
            frame[AMBIENT_C] = a0 = manifest_ambient(frame)
            columns.append(AMBIENT_C)
        cut = None
        refused = _refused_row(frame, ss)
        if refused is not None:
            cut = {"row": refused[0] + 1, "why": f"{refused[1]} has no value there, which the "
                   "code refuses (stream.c stops; the served model holds it)"}
            frame = frame.iloc[:refused[0]]
        entry = {"campaign": str(cid), "folder": f"{CHECK}/{folders[cid]}", "lead_in_rows": lead}
        if cid in faults:
            entry["planted"] = faults[cid][1]
        if cid in colds:
            entry["cold_start"] = colds[cid][1]
        if ss.ambient_given:
            entry[AMBIENT_C] = a0
        if not len(frame):
            listed.append({**entry, "rows": 0, "cut": cut})
            continue
        shared = after = None
        for key, rows in shares.get(cid, ()):     # shortest first; the longest that fits taken
            if len(frame) <= rows:                # (a frame cut within the prefix)
                break
            if key not in leads:
                leads[key] = _Lead(served.lead(frame, rows, after and after.served), ss, frame,
                                   monitor, after)
            after = leads[key]
            shared = after if after.fits(frame) else shared
        if shared is not None:
            try:
                y = served.y(frame, lambda: shared.served.stream(frame))
            except OutOfEnvelopeError:
                shared = None            # (the whole stream below raises it, file and row named)
        if shared is None:
            y = served.y(frame, lambda: stream_rows(deployed, frame, str(cid),
                                                    (files or {}).get(cid)).y)
        want, flags = corrections(ss, y), list(shared.flags) if shared else []
        if monitor:
            parted = (_parted(ss, frame, want, shared.rows, copy.deepcopy(shared.sim), flags)
                      if shared
                      else _parted(ss, frame, want, flags=flags))
            if parted is not None:
                cut = parted
                frame, want = frame.iloc[:cut["row"] - 1], want[:cut["row"] - 1]
        entry.update(rows=len(frame), cut=cut)
        listed.append(entry)
        if len(frame):
            out[f"{entry['folder']}/rows.csv"] = (
                shared.csv(frame[columns]) if shared and len(frame) > shared.rows
                else csv_text(frame[columns]))
            out[f"{entry['folder']}/expected.csv"] = csv_text(pd.DataFrame(want, columns=outputs))
            if ss.monitor:     # (packflags100) the code's monitor flags the mirror expects
                out[f"{entry['folder']}/{FLAGS}"] = csv_text(
                    pd.DataFrame(flags[:len(frame)], columns=FLAG_COLUMNS))
    written = [e for e in listed if e["rows"]]
    summary = {"campaigns": listed, "inputs": ["time", *ss.inputs, *[AMBIENT_C] * ss.ambient_given],
               "outputs": outputs,
               "tolerance_um": TOLERANCE_UM, "tolerance_relative": TOLERANCE_RELATIVE,
               "rule": "|C - expected| <= tolerance_um + tolerance_relative * |expected|",
               "why": WHY,
               "command": "./stream --check <folder>/expected.csv < <folder>/rows.csv",
               "reference_measurements": "none fed: what was learned stays as exported"}
    if ss.ambient_given:
        summary["ambient"] = GIVEN
    if ss.monitor:
        summary["flags"] = FLAGS_WHY
        summary["command"] += f" --check-flags <folder>/{FLAGS}"
    out[f"{CHECK}/check.json"] = json.dumps(summary, indent=1, ensure_ascii=False) + "\n"
    if script:
        out[f"{CHECK}/check.sh"] = _script([e["folder"] for e in written], bool(ss.monitor))
    return out, summary


def _script(folders: list[str], flags: bool = False) -> str:
    """``check/check.sh``: every campaign of the pack through ``./stream --check`` (run from the
    folder ``stream`` was built in), ``flags``: its monitor's flags too (``--check-flags``); the
    first that fails stops it, its message on stderr."""
    lines = ["#!/bin/sh", "# Run from the folder of the built stream: sh check/check.sh",
             "set -e"]
    lines += [f"./stream --check '{f}/expected.csv'"
              + (f" --check-flags '{f}/{FLAGS}'" if flags else "")
              + f" < '{f}/rows.csv' > /dev/null" for f in folders]
    lines.append(f"echo 'check: {len(folders)} campaign(s) within tolerance'")
    return "\n".join(lines) + "\n"
