"""Campaigns that continue one another: state carried over across a cut record.

A long record cut into consecutive files (train = the first part, test = the
last) is one experiment: the machine's thermal state at the test part's first
sample is what the train part left.  Predicting the test file on its own
restarts every dynamic state (lags, AR feedback, LSTM memory, the previous
measured error of one-step prediction) at its first sample; here it is
predicted *joined* to its predecessor(s) instead -- one campaign, times made
continuous -- and only its own rows are scored.  Predictions of the joined
campaign sliced to the last file are exactly what a model streaming through
the whole record would output there.

A campaign continues another when the manifest says so (column
``continues``, as ``thermocomp simulate sim=long_record`` writes), or, for a
user's own files without that column, when its ``start`` (ISO 8601) is the
other's end -- start + last ``time`` + one sample period -- within half a
period.  State is carried over only with ``data.reference=none``: in the
first-sample frame each file is referenced to its own first sample and the
joined campaign is not in that frame.  Under ``data.reference=auto`` a link found
by time whose later file's errors all start again at 0 is a restart
(:mod:`.restart`), left out of :func:`predecessors`.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd

from ..base.log import logger, once_per_run, say
from .io.contract import TIME, Dataset, role
from .io.instants import START, start_instants
from .restart import RESTARTED
from .timerule import median_step

CONTINUES = "continues"

# monitor and deploy fit the same train campaigns twice (fixed and adaptive): one note a run
# (stranger78's monitor said the join twice); the filter knows a record by the module that logs
# it, so these notes go to the logger here, not through base.log.say
once_per_run(Path(__file__))


def campaign_period(df: pd.DataFrame) -> float:
    """The campaign's sample period (:func:`~thermocomp.core.timerule.median_step`; NaN
    without a step)."""
    return median_step(df[TIME].to_numpy(float)) or float("nan")


def predecessors(ds: Dataset) -> dict[str, str]:
    """``{campaign: the campaign it continues}`` for the campaigns of ``ds`` that continue one.

    A campaign continues another when the manifest's ``continues`` names it, when its
    ``time`` does not restart at 0 but starts one sample period after the other's last
    ``time`` (one clock), or when its ``start`` is the other's start + last ``time`` + one
    period (within half a period).  A link found by time that ``data.reference=auto`` read as a
    restart (``ds.meta``'s :data:`~.restart.RESTARTED`, :func:`time_links`) is left out."""
    ids = set(ds.ids())
    out: dict[str, str] = {}
    man = ds.manifest
    if CONTINUES in man.columns:
        for cid, prev in man[CONTINUES].items():
            if isinstance(prev, str) and prev.strip() in ids and prev.strip() != cid:
                out[cid] = prev.strip()
    # one clock: a file whose time does not restart at 0 but picks up one sample period after
    # another file's last time (a record cut in a spreadsheet keeps its time column)
    last = {c: (float(df[TIME].iloc[-1]), campaign_period(df)) for c, df in ds.campaigns.items()
            if len(df) >= 2}
    found: dict[str, list[str]] = {}
    for cid, df in ds.campaigns.items():
        t0 = float(df[TIME].iloc[0]) if len(df) else 0.0
        if cid in out or t0 <= 0:
            continue
        found[cid] = [prev for prev, (end, period) in last.items()
                      if prev != cid and abs(t0 - (end + period)) <= period / 2]
    if START in man.columns:
        starts = start_instants(man[START])   # (with and without an offset: compared in UTC)
        ends = {}
        for cid, t0 in starts.items():
            df = ds.campaigns.get(cid)
            if pd.isna(t0) or df is None or len(df) < 2:
                continue
            period = campaign_period(df)
            ends[cid] = (t0 + pd.to_timedelta(float(df[TIME].iloc[-1]) + period, unit="s"), period)
        for cid, t0 in starts.items():
            if cid in out or found.get(cid) or pd.isna(t0):
                continue
            found[cid] = [prev for prev, (end, period) in ends.items()
                          if prev != cid and abs((t0 - end).total_seconds()) <= period / 2]
    restarted = ds.meta.get(RESTARTED, {})
    out.update({c: p for c, p in _unambiguous(found).items() if c not in restarted})
    return out


def time_links(ds: Dataset) -> dict[str, str]:
    """The links of :func:`predecessors` found by time alone (not named in ``continues``)."""
    named = ds.manifest[CONTINUES] if CONTINUES in ds.manifest.columns else {}
    return {c: p for c, p in predecessors(ds).items()
            if not (isinstance(named.get(c), str) and named.get(c).strip() == p)}


# a step at a junction this many times the largest one-sample step inside the two campaigns
# is no sample of one record (the sensor monitor's jump rule, jump_factor=3, reads it a fault)
JUNCTION_FACTOR = 3.0


def junction_steps(ds: Dataset, links: Mapping[str, str]) -> dict[str, list[tuple]]:
    """``{campaign: [(column, step °C, largest step inside), ...]}`` for each campaign of
    ``links`` whose first row steps a temperature from its predecessor's last by more than
    :data:`JUNCTION_FACTOR` times the largest one-sample step of that column inside the two:
    files whose times continue but whose readings restart (stranger64: weekly files of one
    clock, T_column_R -2.46 °C and T_amb +2.32 °C at a junction, 0.18 °C the largest step
    inside; run carried the state over silently, replay's monitor excluded five sensors)."""
    out: dict[str, list[tuple]] = {}
    for cid, prev in links.items():
        before, after = ds.campaigns.get(prev), ds.campaigns.get(cid)
        if before is None or after is None or not len(before) or not len(after):
            continue
        for col in (c for c in after.columns if role(c) == "T" and c in before.columns):
            a, b = before[col].to_numpy(float), after[col].to_numpy(float)
            inner = [np.abs(np.diff(x)) for x in (a, b) if len(x) > 1]
            inner = [x[np.isfinite(x)] for x in inner]
            largest = max((float(x.max()) for x in inner if x.size), default=0.0)
            step = float(b[0] - a[-1])
            if largest > 0 and np.isfinite(step) and abs(step) > JUNCTION_FACTOR * largest:
                out.setdefault(cid, []).append((col, step, largest))
    return out


def said_junction_steps(ds: Dataset, links: Mapping[str, str]) -> None:
    """Warn, once per run, of the junctions :func:`junction_steps` finds (their largest steps)."""
    for cid, steps in junction_steps(ds, links).items():
        steps = sorted(steps, key=lambda s: -abs(s[1]))
        shown = ", ".join(f"{c} {d:+.3g} °C" for c, d, _ in steps[:3])
        logger.warning(
            f"{cid} continues {links[cid]} by its time, but its first row steps {len(steps)} "
            f"temperature(s) more than {JUNCTION_FACTOR:g}x their largest step inside the two "
            f"({shown}{' ...' if len(steps) > 3 else ''}; inside at most "
            f"{max(s[2] for s in steps):.3g} °C): a restart rather than one record? The state is "
            "carried over across it and the sensor monitor reads it as a jump; files that each "
            "restart: data.reference=first_sample")


def _unambiguous(found: Mapping[str, list]) -> dict[str, str]:
    """``{campaign: the one it continues}`` of the links found by time (``found``: campaign ->
    the campaigns ending where it starts), where one campaign ends there and it alone starts
    there.  Two machines' files in one folder (a fleet) end and start at the same times: which
    continues which the times cannot say (probe61: PG32's week carried PG31's state over), so
    neither is linked, and a line says how to say it."""
    takers: dict[str, list[str]] = {}
    for cid, prevs in found.items():
        for prev in prevs:
            takers.setdefault(prev, []).append(cid)
    out, unsure = {}, []
    for cid, prevs in found.items():
        if len(prevs) == 1 and len(takers[prevs[0]]) == 1:
            out[cid] = prevs[0]
        elif prevs:
            unsure.append(f"{cid} starts where {' and '.join(sorted(prevs))} end")
    if unsure:
        logger.warning(f"{'; '.join(unsure[:3])}{' ...' if len(unsure) > 3 else ''}: which "
                       "campaign continues which the times cannot say (several machines' files "
                       "in one folder?), no state carried over between them: name it in the "
                       "manifest's 'continues' column, or fit one model per machine "
                       "(data.group_by)")
    return out


def chain(ds: Dataset, cid: str, links: Mapping[str, str] | None = None) -> list[str]:
    """The campaigns ``cid`` continues, oldest first, then ``cid`` (``[cid]`` for none)."""
    links = predecessors(ds) if links is None else links
    out = [cid]
    while out[0] in links and links[out[0]] not in out:   # guard against a cyclic manifest
        out.insert(0, links[out[0]])
    return out


def chains(ds: Dataset, ids=None) -> dict[str, list[str]]:
    """``{campaign: its chain}`` (:func:`chain`) for the campaigns of ``ids`` (default: all, in
    the manifest's order) that continue others."""
    links = predecessors(ds)
    return {c: chain(ds, c, links) for c in (ds.ids() if ids is None else ids) if c in links}


# a junction whose own clock (the campaigns' ``start``) shows more than this many sample periods
# between the rows read is kept as that gap (below)
GAP_PERIODS = 1.5


def joined(ds: Dataset, ids: list[str], campaigns: Mapping[str, pd.DataFrame] | None = None
           ) -> pd.DataFrame:
    """The campaigns ``ids`` end to end as one campaign, ``time`` continuous (their frames from
    ``campaigns`` where given, e.g. denoised, else ``ds``'s).

    Each file's time is shifted so that its first sample follows the previous
    file's last one by the previous file's sample period; or, where the campaigns' ``start``
    (their time origins) shows a longer gap between those rows (rows not read: a campaign
    trimmed at an incomplete edge, ``data.max_edge_samples``), by that gap, as the record has it
    (probe61: six and a half hours of a Monday's warm-up, then trimmed before its first probe,
    read as one sample; frames62 reads those rows, :mod:`.io.sparse`).
    """
    frames, offset = [], 0.0
    campaigns = ds.campaigns if campaigns is None else campaigns
    starts = start_instants(ds.manifest[START]) if START in ds.manifest.columns else None
    for k, cid in enumerate(ids):
        df = campaigns[cid]
        t = df[TIME].to_numpy(float)
        if k:
            step = _junction(starts, ids[k - 1], campaigns[ids[k - 1]], cid, float(t[0]))
            offset = frames[-1][TIME].iloc[-1] + step - t[0]
        frames.append(df.assign(**{TIME: t + offset}))
    out = pd.concat(frames, ignore_index=True)
    out.attrs = dict(frames[0].attrs)      # the chain's start: its manifest ambient_c (DATA_FORMAT)
    return out


def _junction(starts, before: str, frame: pd.DataFrame, cid: str | None, first: float) -> float:
    """Seconds from ``before``'s last sample (its ``frame``) to ``cid``'s first (``first``, its
    time): the gap their ``start`` instants show where that is longer than :data:`GAP_PERIODS`
    periods (rows not read between them); else, where ``first`` is on ``before``'s clock (the
    time picks up within half a period of one period after its last: :func:`predecessors`' one
    clock), the step that clock shows, as a stream of the record reads it; else one sample
    period of ``before``.

    On one clock the step is the record's (weekjoin66): the lab's weekly files in elapsed hours
    to four decimals step 59.76 or 60.12 s, at a week's join as inside a week; one period there
    (60.00 s) put a step into the scored stream that the compiled stream, reading the files
    on in one process or one per file with ``--state``, never sees (4.9e-4 µm at the joins,
    dying away over ~800 rows)."""
    period = campaign_period(frame)
    last = float(frame[TIME].iloc[-1])
    own = first - last
    if not (np.isfinite(own) and abs(own - period) <= period / 2):
        own = period                     # the time restarts (or no period): one period
    if starts is None or cid is None or pd.isna(starts.get(before)) or pd.isna(starts.get(cid)):
        return own
    gap = ((starts[cid] + pd.to_timedelta(first, unit="s"))
           - (starts[before] + pd.to_timedelta(last, unit="s"))).total_seconds()
    return gap if gap > GAP_PERIODS * period else own


def lead_in(ds: Dataset, ids: list[str]) -> pd.DataFrame:
    """The campaigns before the last of ``ids`` (a :func:`chain`), joined: what a stream is
    warmed on before that campaign (:func:`preceding` its first sample)."""
    return preceding(ds, ids[:-1], float(ds.campaigns[ids[-1]][TIME].iloc[0]), ids[-1])


def preceding(ds: Dataset, ids: list[str], first_time: float, cid: str | None = None
              ) -> pd.DataFrame:
    """The campaigns ``ids`` :func:`joined`, moved in time as a whole so that they end one
    sample period (the last one's) before ``first_time``: the lead-in of a campaign that starts
    there and continues them (keeping the campaign's own clock); for a campaign ``cid`` of
    ``ds``, by the gap the ``start`` instants show instead where it is longer (as :func:`joined`)."""
    whole = joined(ds, ids)
    starts = start_instants(ds.manifest[START]) if START in ds.manifest.columns else None
    step = _junction(starts, ids[-1], ds.campaigns[ids[-1]], cid, first_time)
    shift = first_time - step - float(whole[TIME].iloc[-1])
    return whole.assign(**{TIME: whole[TIME] + shift})


def carry_over(comp, ds: Dataset) -> dict[str, list[str]]:
    """``{campaign: its chain}`` for the campaigns ``comp`` predicts with state carried over.

    Empty unless the compensator reads data absolute (``reference='none'``).
    """
    if getattr(comp, "reference", "first_sample") != "none":
        return {}
    return chains(ds)


def fit_campaigns(ds: Dataset, campaigns: Mapping[str, pd.DataFrame], ids, reference: str
                  ) -> dict[str, pd.DataFrame]:
    """The campaigns ``ids`` (frames from ``campaigns``) as a model is fitted on them: with
    ``reference='none'`` each run of them that continue one another :func:`joined` into one
    campaign, named by its last, as :func:`predict` joins them (else as they are).

    Fitted apart, every dynamic state (a lag bank's lags, an AR term) restarts at each file's
    first sample, but :func:`predict` carries it over: the model is scored in a frame it was not
    fitted in (probe61's grinder, three weekly files of one record: the lag bank fitted week by
    week tested E_Z 5.04 µm, 9.7 in the test week's first sixth, where the state carried over
    from the train weeks differs most from a restart; fitted on the two weeks joined 0.70,
    MLR 1.69).
    """
    ids = list(ids)
    if reference != "none":
        return {c: campaigns[c] for c in ids}
    inside = set(ids)
    links = {c: before for c, before in predecessors(ds).items() if c in inside and before in inside}
    continued = set(links.values())
    out = {}
    for c in ids:
        if c in continued:
            continue
        members = chain(ds, c, links)
        out[c] = joined(ds, members, campaigns) if len(members) > 1 else campaigns[c]
    if len(out) < len(ids):
        logger.info("train campaigns that continue one another fitted as one (their state carried over, "
            "as they are predicted): " + carried_text(
                {c: chain(ds, c, links) for c in out if c in links}))
    return out


def continue_inside(ds: Dataset, ids) -> bool:
    """Whether a campaign of ``ids`` continues another of ``ids`` (:func:`predecessors`)."""
    inside = set(ids)
    return any(c in inside and before in inside for c, before in predecessors(ds).items())


def fit_joined(comp, ds: Dataset, ids, campaigns: Mapping[str, pd.DataFrame] | None = None):
    """``comp`` fitted on the campaigns ``ids`` (frames from ``campaigns``, default ``ds``'s) as
    ``run`` fits it (:func:`fit_campaigns`): runs that continue one another joined, in the frame
    :func:`predict` scores them in.  The one mechanism for every fit of train campaigns
    (``diagnose``, validation folds, ``monitor``, ``deploy``...), so that their figures are of the
    deployed model's frame.

    A denoiser is fitted on the files and denoises each on its own (offline), before they are
    joined, as ``run``'s denoise step does; ``comp`` then holds it fitted and frozen.
    """
    from sklearn.frozen import FrozenEstimator

    from .denoise import fit_denoiser
    from .frame import resolve_columns

    frames = ds.campaigns if campaigns is None else campaigns
    ids = list(ids)
    reference = getattr(comp, "reference", "first_sample")
    if reference != "none" or not continue_inside(ds, ids):
        return comp.fit({c: frames[c] for c in ids})
    if getattr(comp, "denoiser", None) is None:
        return comp.fit(fit_campaigns(ds, frames, ids, reference))
    columns = list(dict.fromkeys(col for c in ids for col in frames[c].columns))
    inputs = resolve_columns(columns, comp.inputs, comp.targets)[0]
    fitted, denoised = fit_denoiser(comp.denoiser, {c: frames[c] for c in ids}, inputs)
    comp.set_params(denoiser=None if fitted is None else FrozenEstimator(fitted))
    return comp.fit(fit_campaigns(ds, denoised, ids, reference), denoised=True)


def predict(comp, ds: Dataset, ids, mode: str = "simulation", carried: Mapping | None = None
            ) -> tuple[dict[str, pd.DataFrame], dict[str, pd.DataFrame]]:
    """Predicted and measured errors of the campaigns ``ids``, state carried over where it applies.

    Campaigns without a predecessor (or with ``reference='first_sample'``) are
    predicted together as usual; each continuing campaign is predicted as its
    :func:`joined` chain and sliced to its own rows.  ``carried`` is
    :func:`carry_over`'s result (computed when None).

    Returns
    -------
    predicted, measured : dict campaign -> DataFrame (columns = targets)
    """
    carried = carry_over(comp, ds) if carried is None else carried
    ids = list(ids)
    plain = [c for c in ids if c not in carried]
    pred, meas = {}, {}
    if plain:
        camps = {c: ds.campaigns[c] for c in plain}
        pred.update(comp.predict(camps, mode=mode))
        meas.update(_measured(comp, camps, pred, mode))
    for c in ids:
        if c in carried:
            n = len(ds.campaigns[c])
            whole = {c: joined(ds, carried[c])}
            predicted = comp.predict(whole, mode=mode)
            pred[c] = predicted[c].iloc[-n:].reset_index(drop=True)
            meas[c] = _measured(comp, whole, predicted, mode)[c].iloc[-n:].reset_index(drop=True)
    return {c: pred[c] for c in ids}, {c: meas[c] for c in ids}


def _measured(comp, campaigns, predicted, mode: str):
    """``comp.measured(campaigns)``, given the simulation ``predicted`` when that is what
    ``mode`` predicted (a late first measurement is completed by it, :mod:`.first_probe`)."""
    return comp.measured(campaigns, predicted=predicted if mode == "simulation" else None)


def persistence(comp, ds: Dataset, ids, carried: Mapping | None = None) -> dict[str, pd.DataFrame]:
    """Persistence prediction (previous measured error; 0 at a campaign start) per campaign,
    from the predecessor's last sample for a continuing campaign."""
    from .models.one_step import persistence as law

    carried = carry_over(comp, ds) if carried is None else carried
    out = {}
    for c in ids:
        chain_ids = carried.get(c, [c])
        n = len(ds.campaigns[c])
        whole = joined(ds, chain_ids) if len(chain_ids) > 1 else ds.campaigns[c]
        meas = comp.measured({c: whole})[c]
        out[c] = meas.apply(lambda col: law(col.to_numpy())).iloc[-n:].reset_index(drop=True)
    return out


def carried_text(carried: dict) -> str:
    """``A continues B + C; ...`` of ``{campaign: chain}`` (:func:`carry_over`): a chain inside
    a longer one said by the longer one alone, and a chain of more than three campaigns by its
    ends (stranger65: a week of day files made a line of 28 names, each campaign with every one
    before it; a year's, 66,000)."""
    inner = {c for chain in carried.values() for c in chain[:-1]}
    return "; ".join(f"{c} continues {_ends(chain[:-1])}" for c, chain in carried.items()
                     if c not in inner)


def _ends(names: list) -> str:
    return (" + ".join(names) if len(names) <= 3 else
            f"{names[0]} + {names[1]} + ... + {names[-1]} ({len(names)} campaigns)")


def lead_ins(comp, ds: Dataset, ids) -> dict:
    """``{campaign: lead-in}`` for the campaigns of ``ids`` that continue others: their stream
    is warmed on their predecessors (unscored) so that it predicts what ``run`` scores
    (:func:`carry_over`, :func:`lead_in`); says which."""
    carried = {c: chain for c, chain in carry_over(comp, ds).items() if c in ids}
    said_if_not_carried(comp, ds, ids)
    leads = {c: lead_in(ds, chain) for c, chain in carried.items()}
    said_warmed(carried, leads)
    return leads


def said_warmed(carried: dict[str, list[str]], leads: dict[str, pd.DataFrame]) -> None:
    """Say the campaigns a stream is warmed on (``{campaign: its chain}``) and how many rows
    their lead-ins ``leads`` hold, so that a year's minutes of warming are expected (scale58)."""
    if carried:
        rows = sum(len(df) for df in leads.values())
        say("stream warmed on the campaigns it continues (state carried over, unscored): "
            + carried_text(carried) + f"; {rows:,} rows streamed before scoring")


def said_if_not_carried(comp, ds: Dataset, ids) -> None:
    """Say a test campaign of ``ids`` that continues another (a logger's file rotated, a record
    cut in two) streamed by a model that reads changes from each campaign's first sample: its
    stream starts from a reset at its first row, not warmed on the campaign before it, and its
    errors are taken from that row too, so its RMSE does not show the warm-up the deployed
    stream misses (restart58: a lag bank on a Swiss lathe's 8 h run cut in two files 4 h in,
    E_X 26.1 um from the campaign's zero after the cut against 1.29 uninterrupted; the reading
    of the data, ``data.reference=auto: none``, had said its state was carried over)."""
    if getattr(comp, "reference", "first_sample") == "none":
        return
    tests = set(ds.ids("test"))
    cut = chains(ds, [c for c in ids if c in tests])
    if cut:
        logger.warning(
            f"{carried_text(cut)}, but the model reads each campaign's changes from its first "
            f"sample (fitted with data.reference={getattr(comp, 'reference', 'first_sample')}): "
            "streamed from a reset at its first row, not warmed on the campaign(s) before it, "
            "its errors also taken from that row (its RMSE does not show the warm-up it misses); "
            "fit with data.reference=none to carry the state over")
