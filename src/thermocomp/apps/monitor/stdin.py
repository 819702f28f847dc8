"""Where a stream on stdin starts: from a reset, or warmed on the campaign of the dataset it
continues (``monitor.continues``), as ``replay`` warms a continuing test campaign."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ...base.errors import ConfigError, listed
from ...base.log import logger
from ...core.continuation import campaign_period, chain, preceding, predecessors
from ...core.io.contract import TIME
from ...core.io.instants import START, start_instants
from ...core.io.own_headers import named_one
from ...core.io.stdin import HEADERS, SOURCE
from ..deploy.surveillance import COMMON_MIN


def stdin_chain(ds, campaign: str | None, *, ambient_given: bool, reference: str,
                data_path, ambient_c: float | None = None) -> list[str]:
    """The campaigns the stream is warmed on (those ``campaign`` continues, and itself), or
    none.  A model that reads the campaign's ambient from the manifest (no ambient sensor)
    needs it given (``ambient_c``, ``monitor.ambient_c``) for a stream of its own; a model that
    reads changes from each campaign's first sample carries no state over: refused."""
    if campaign is None:
        if ambient_given and ambient_c is None:
            raise ConfigError("monitor.input=-: the model reads each campaign's ambient from the "
                              "manifest's ambient_c (no T_amb sensor), which a stream on stdin "
                              "lacks; give it (monitor.ambient_c=<°C>), record a T_amb sensor, "
                              "or say the campaign it continues (monitor.continues)")
        return []
    campaign = str(campaign)
    if campaign not in ds.ids():
        raise ConfigError(f"monitor.continues={campaign}: no such campaign in {data_path} "
                          f"(campaigns: {', '.join(ds.ids())})")
    if reference != "none":
        raise ConfigError(f"monitor.continues={campaign}: the model reads temperature changes "
                          f"from each campaign's first sample (data.reference={reference}), "
                          "so no state carries over; fit it with data.reference=none")
    return chain(ds, campaign)


def stdin_lead_in(ds, ids: list[str], cid: str, times: pd.Series | None,
                  origin: pd.Timestamp | None = None) -> dict:
    """``{cid: lead-in}`` of the warming campaigns ``ids`` (:func:`stdin_chain`) for the stream's
    first campaign ``cid`` (a run after it starts from a reset), ending one sample period
    before its first row, whose ``times`` (None: no time column, the rows from 0 s) may begin
    with missing ones: the first time read less a period per row before it (the stream's
    guard substitutes the lead-in's last time plus a period there).  ``origin``: the instant
    the stream's ``times`` count from where they were timestamps (its ``time_origin``), which
    puts its first row on the continued campaign's clock (its ``start``) for :func:`said_if_gap`."""
    if not ids:
        return {}
    read = np.flatnonzero(times.notna().to_numpy()) if times is not None else []
    first = (float(times.iloc[read[0]]) - read[0] * campaign_period(ds.campaigns[ids[-1]])
             if len(read) else 0.0)
    on_its_clock = first + _clock_offset(ds, ids[-1], origin)
    if np.isfinite(on_its_clock):        # (timestamps continuing a campaign of no known start)
        said_if_gap(ds.campaigns[ids[-1]], ids[-1], on_its_clock)
    return {cid: preceding(ds, ids, first)}


def _clock_offset(ds, name: str, origin: pd.Timestamp | None) -> float:
    """Seconds from campaign ``name``'s start (its time 0) to ``origin``, a stream's first
    timestamp: 0 for a stream timed in seconds (on the campaign's clock, or restarting), NaN
    where the campaign has no start (timed in seconds, none in the manifest)."""
    if origin is None:
        return 0.0
    start = (start_instants(ds.manifest[START])[name] if START in ds.manifest.columns
             else pd.NaT)
    return float("nan") if pd.isna(start) else (origin - start).total_seconds()


GAP_PERIODS = 1.5   # a stream's first time this many periods or more after the campaign's last


def said_if_gap(campaign: pd.DataFrame, name: str, first: float) -> None:
    """Say a stream said to continue ``campaign`` (named ``name``) whose first time ``first``
    is on that campaign's clock (beyond its last time) but more than ``GAP_PERIODS`` sample
    periods after it: the lead-in is moved to end one period before the stream, so the rows in
    between are bridged as one period and the warm-up they carry is lost (restart58: a lab's
    test part streamed from the restart, 84 rows after the train part it was said to
    continue).  A stream whose clock restarts (``first`` at or before the last time) tells
    nothing of a gap: not said."""
    if TIME not in campaign.columns or len(campaign) < 2:
        return
    last, period = float(campaign[TIME].iloc[-1]), campaign_period(campaign)
    if not np.isfinite(period) or period <= 0 or first <= last + GAP_PERIODS * period:
        return
    missing = round((first - last) / period) - 1
    logger.warning(
        f"monitor.continues={name}: stdin's first row (time {first:g} s) is {missing} "
        f"sample(s) ({(first - last - period) / 60:.3g} min) after {name}'s last "
        f"({last:g} s): the rows in between are missing and the warm-up they carry is lost "
        f"(the stream is warmed as if it followed at once); stream from the row after {name}'s last")


JUMPS = 3.0        # a step beyond this x a sensor's largest step in the continued campaign


def check_continued(lead: pd.DataFrame, stream: pd.DataFrame, campaign: str) -> None:
    """Refuse a stream said to continue ``campaign`` (its lead-in ``lead``) whose first row is
    not where that campaign ended: at least ``COMMON_MIN`` (the monitor's common step) and more
    than half of the temperatures step beyond ``JUMPS`` x their largest step in the lead-in.  A
    later day's file so started was
    warmed on a state it does not continue, and the monitor read the junction as the logger's
    common step and re-referenced every sensor by it for good (a lathe's production run said
    to continue its calibration, two weeks apart: adaptive 27.4 um against the fixed 1.85)."""
    cols = [c for c in stream.columns if str(c).startswith("T_") and c in lead.columns]
    last = lead[cols].ffill().iloc[-1]
    first = stream[cols].bfill().iloc[0]
    largest = lead[cols].diff().abs().max()
    step = (first - last).dropna()
    beyond = step[step.abs() > JUMPS * largest[step.index].fillna(0.0)]
    if len(beyond) < COMMON_MIN or 2 * len(beyond) <= len(step):
        return
    worst = beyond.abs().idxmax()
    raise ConfigError(
        f"monitor.continues={campaign}: stdin's first row is not where {campaign} ended: "
        f"{len(beyond)} of {len(step)} temperatures step beyond {JUMPS:g}x their largest step "
        f"in it (median {float(beyond.median()):+.3g} °C; {worst} {float(last[worst]):.4g} -> "
        f"{float(first[worst]):.4g} °C); a later record, not its continuation? leave "
        "monitor.continues out, or stream from the row after its last")


PERIOD_RATIO = 1.5   # a streamed campaign's period this far from training's is said


def said_if_other_period(streamed: dict, train: dict) -> None:
    """Say each streamed campaign whose sample period is not the training's (beyond
    ``PERIOD_RATIO`` either way): the monitor counts samples (its window, confirm and the
    per-sample jump limit), the guard's rate limit and a model's sample lags read another span
    of time.  Not refused: a static model corrects such rows as well (a lathe logged at 120 s
    against 60 s in training: MLR E_dX 1.316 against 1.291 µm), and nothing said it before."""
    periods = [campaign_period(df) for df in train.values() if TIME in df.columns]
    trained = float(np.nanmedian(periods)) if periods else float("nan")
    if not np.isfinite(trained) or trained <= 0:
        return
    for cid, df in streamed.items():
        period = campaign_period(df) if TIME in df.columns else float("nan")
        if np.isfinite(period) and period > 0 and max(period / trained,
                                                      trained / period) > PERIOD_RATIO:
            logger.warning(f"campaign {cid}: samples {period:g} s apart, the training's "
                           f"{trained:g} s: the monitor's window and jump limit count samples, "
                           "and a model's lags may too; resample the rows to the training's "
                           "period (or fit on data logged as this is)")


MID_CAMPAIGN = 0.25   # a first row this share of a warm-up away from every training start


def said_if_mid_campaign(ds, train_ids: list[str], stream: pd.DataFrame, cid: str) -> None:
    """Say a stream (not said to continue a campaign) whose first row looks like the middle of a
    campaign, not its start: the temperatures' pattern (each less their mean: the common level
    is the room's) is farther than ``MID_CAMPAIGN`` x a training campaign's warm-up (the median
    largest distance of its rows from its first) from every training campaign's first row
    (those that continue no other).  The stream starts from a reset there: a model that reads
    changes from a campaign's first sample misses the warm-up before it (a Swiss lathe's 6 h
    production run streamed from 2 h in, 0.51 of a warm-up: E_X 1.529 against 1.291 um from its
    start).  Said, not refused: a machine may start warm.  Measured (lead58): the first rows of
    the test campaigns of 9 simulated records (5 scenarios) at most 0.11; rows half an hour or
    more into a campaign mostly above 0.25, not all (a climate-room campaign can come back
    near its start's pattern)."""
    cols = [c for c in stream.columns if str(c).startswith("T_")
            and all(c in ds.campaigns[t].columns for t in train_ids)]
    links = predecessors(ds)
    starts = [t for t in train_ids if t not in links]
    if len(cols) < 2 or not starts:
        return

    def pattern(df: pd.DataFrame) -> np.ndarray:
        x = df[cols].to_numpy(float)
        return x - np.nanmean(x, axis=1, keepdims=True)

    first, warmups = [], []
    for t in starts:
        x = pattern(ds.campaigns[t])
        first.append(x[0])
        warmups.append(np.nanmax(np.sqrt(np.nansum((x - x[0]) ** 2, axis=1))))
    row = pattern(stream.bfill().iloc[:1])[0]
    if not np.isfinite(row).all() or not np.isfinite(first).all():
        return
    scale = float(np.median(warmups))
    distance = np.sqrt(((np.asarray(first) - row) ** 2).sum(axis=1))
    nearest = int(np.argmin(distance))
    if scale <= 0 or distance[nearest] <= MID_CAMPAIGN * scale:
        return
    logger.warning(
        f"campaign {cid}: its first row does not look like a campaign's start: its temperatures' "
        f"pattern is {distance[nearest]:.3g} K from the nearest training start ({starts[nearest]}), "
        f"{distance[nearest] / scale:.2f} of a training warm-up ({scale:.3g} K); started "
        "mid-campaign? The stream starts from a reset here (a model of changes from a "
        "campaign's first sample misses the warm-up before it): stream from the campaign's "
        "start, or with data.reference=none say the campaign it continues (monitor.continues)")


MEMORY_ROWS = 60   # rows before a training row that show whether the model remembers them


def _remembers(deployed, rows: pd.DataFrame) -> bool:
    """Whether ``deployed``'s prediction of ``rows``' last row depends on the rows before it (a
    lag, an ARX feedback, an LSTM's state): that row streamed from a reset against streamed
    after them.  The stream is left as it was found."""
    snap = deployed._snapshot()
    try:
        deployed.reset()
        warmed = deployed.predict(rows).to_numpy(float)[-1, :-1]
        deployed.reset()
        cold = deployed.predict(rows.iloc[-1:]).to_numpy(float)[-1, :-1]
    except ValueError:       # a row the policy refuses: not this check's to say
        return False
    finally:
        deployed._restore(snap)
    return not np.allclose(warmed, cold, rtol=1e-6, atol=1e-6)


def said_if_cold_continuation(ds, deployed, cid: str) -> None:
    """Say a stream not said to continue a campaign, streamed from a reset by a model that
    remembers, where the model was scored on test campaigns that continue the record (each
    warmed on the campaign before it, as ``run`` joins them): a machine that runs on has no
    campaign start, so the first row's pattern (:func:`said_if_mid_campaign`) looks like any
    other and nothing was said (newmachine59: a wire EDM's 21-day record cut 3:1, its last 300
    rows streamed from a reset, a Hammerstein model 1.46 um against 0.31 warmed)."""
    if deployed.compensator.reference != "none":
        return
    links = predecessors(ds)
    scored = [t for t in ds.ids("test") if t in links]
    if not scored:
        return
    before = ds.campaigns[links[scored[0]]]
    if len(before) < 2 or not _remembers(deployed, before.iloc[-MEMORY_ROWS:]):
        return
    logger.warning(
        f"campaign {cid}: streamed from a reset, but the model remembers the rows before a row "
        f"(its prediction of {links[scored[0]]}'s last row differs streamed alone) and was scored "
        f"on {scored[0]} warmed on {links[scored[0]]}, the record it continues: if this stream "
        f"goes on from the machine's record, say the campaign it continues "
        f"(monitor.continues=<campaign>); else its first rows are a cold start")


def said_if_unknown(streamed: dict, ds) -> None:
    """(names97) A stream's columns the model's record holds none of (a sensor added since, a
    logger's channel the data config never read) said once, by the stream's own headers: the
    model does not read them (undeclared, docs/data-format.md).  badin96: a stream with an extra
    column was read without a word, where a lacking one is refused naming the unread ones."""
    known = {TIME, *ds.columns}
    unknown = list(dict.fromkeys(c for frame in streamed.values() for c in frame.columns
                                 if c not in known))
    if unknown:
        own = next(iter(streamed.values())).attrs.get(HEADERS, {})
        logger.warning(f"{SOURCE}: column(s) {listed([named_one(c, own) for c in unknown], 6)} "
                       "not in the data the model was fitted on: not read")
