"""The deployable compensator as an ``mlflow.pyfunc`` model.

It holds a :class:`StreamingCompensator` or, as ``promote`` registers it by
default (``monitor.adaptive=true``), an :class:`~thermocomp.apps.deploy.AdaptiveCompensator`
(the same stream behind sensor surveillance and a correction guard).

Input: a table of sensor readings (declared ``T_``/``S_`` inputs, all float;
an optional ``time`` column in s, or as wall-clock timestamps, read as seconds since the
campaign's first), one row per sample, in time order.
Output: the correction per axis in µm, ``C_<axis> = -Ê_<axis>`` (what to add
to the axis command to cancel the predicted thermal error ``E_<axis>``), and
``n_clamped``, the number of inputs of that row clamped to the training envelope.
The adaptive compensator adds, per row, ``excluded_inputs`` (the sensors it
has excluded after that row, comma-separated, ``""`` when none) and
``events`` (a JSON list of that row's events: ``time``, ``sensor``, ``from``,
``to``, ``reason``, and ``target`` for a guarded correction).  A missing value
(NaN or JSON ``null``) in a row, a missing, repeated or backward ``time`` then
still gives a finite correction, within the guard's bound, with the event
that says what was held, reconstructed or substituted; the plain streaming
compensator refuses such a row (HTTP 400).

State is kept between calls, one stream per ``session`` parameter
(``params={"session": "machine-7"}``; callers that send none share the session
``"default"``), so several machines can call one server.  A call with
``params={"reset": true}`` starts a new campaign in its session: its first row
becomes the reference sample (``T_`` inputs are taken relative to it) and every
memory (AR terms, causal denoiser, sensor monitor, guard) is cleared.  A new
session starts reset; at most :data:`MAX_SESSIONS` are kept (the least recently
used one is dropped and starts reset if it calls again).  The state lives in
the serving *process*: with several server workers each worker holds its own
sessions, so serve with one worker (``thermocomp serve`` does).

A model deployed with ``adapt.method`` other than ``none`` (``adapt_``, extension) learns from
reference measurements: a row that carries a finite measured error ``E_<axis>`` (optional
input columns; a probe touch, an artefact cycle; a ``data.derive`` target computed from the
errors it carries, as a file's is) is one; that row's correction is given with
what was learned before it, then the gain/bias of :mod:`thermocomp.apps.deploy.adapt` is updated,
per session (each machine learns its own; ``reset`` keeps what the session learned, a new
session starts from the model as promoted).

A campaign that continues one the model was deployed on (a long record cut in
two, ``data.reference=none``: the machine did not stop) starts from the state
that campaign left, as ``run`` scores it: ``params={"continues": "<campaign>"}``
starts the session there instead of from a reset (``promote`` saves every
campaign's end state in the model, ``end_states_``); the session's ``time`` is
then shifted so that its first row follows that campaign's last sample by one
sample period (event times are given back in the caller's clock).

(audit106) A model whose record was read with ``data.runs_at_pauses`` (``pause_s_``, the step
of the time after which the reader starts a run) starts a campaign from a reset where a
session's time pauses longer, between blocks or within one, as the file's read and ``stream.c``
(``TC_PAUSE_S``) do, said in an event of that row (``to``: ``new campaign``); it went on as one
campaign without a word (a lab's 3 h gap: 2.82 µm off the C).  (dep106b) A block refused in its
part after a pause leaves the session as it found it, the part before the pause not taken either
(it kept that part's state, though the caller got no correction of the block).

A model that needs the campaign's ambient (ATI) but reads no ambient sensor (its
record had the manifest's ``ambient_c``) takes it as ``params={"ambient_c": <°C>}``
when a session starts (new or ``reset``); without it the session's rows are refused.

Columns may come under the lab's own names (``data.columns`` of the record the
model was deployed from, carried as ``lab_names_``) or contract names; a block
naming one column by both is refused.

The pickled compensator travels with its signature (:mod:`thermocomp.base.signing`),
checked before it is unpickled: the serving machine needs the project key
(``THERMOCOMP_SIGNING_KEY`` or the key file) of the machine that promoted the model.

Depends on the core and MLflow only: no Hydra, no stages.  The model carries
the ``thermocomp`` package source (``code_paths``), so a serving environment
needs only its third-party requirements.
"""

from __future__ import annotations

import copy
import json
import logging
import tempfile
import threading
import warnings
from collections import OrderedDict
from pathlib import Path, PurePosixPath

import mlflow
import numpy as np
import pandas as pd
import pyarrow as pa
from mlflow.exceptions import MlflowException
from mlflow.models import ModelSignature
from mlflow.protos.databricks_pb2 import INVALID_PARAMETER_VALUE
from mlflow.types import ColSpec, ParamSchema, ParamSpec, Schema
from mlflow.types.schema import AnyType

import thermocomp

from ...base import signing
from ...base.errors import ContractError
from ...base.log import NAME as LOG_NAME
from ...base.log import configure as configure_log
from ...core.context import TIME
from ...core.io import marks
from ...core.io.bits import STATE, words_decoded
from ...core.io.derived import on_frame
from ...core.io.rates import FOUND, SAID_AT_MOST, StepWatch, found_words
from ...core.io.slashed import stream_format
from ...core.io.stdin import since, stream_stamps, with_clock_joined
from ...core.io.timestamps import CLOCK, continued, names_day_seconds
from .adaptive import AdaptiveCompensator
from .naming import accepted_names, correction_column, raw_names, to_contract
from .streaming import EndState, StreamingCompensator

MODEL_NAME = "compensator"          # artifact name of the pyfunc model inside a run
COMPENSATOR_ARTIFACT = "compensator"  # the pickled (streaming or adaptive) compensator
SIGNATURE_ARTIFACT = "compensator_sig"  # its signature (HMAC, thermocomp.base.signing)
DEFAULT_SESSION = "default"
MAX_SESSIONS = 1024
log = logging.getLogger(__name__)
DEPLOYABLE = (StreamingCompensator, AdaptiveCompensator)   # what the model may hold
REPORT_COLUMNS = ("excluded_inputs", "events")              # the adaptive compensator's extras


def is_adaptive(deployed) -> bool:
    """True for the compensator that watches its inputs (and reports exclusions and events)."""
    return isinstance(deployed, AdaptiveCompensator)


class CompensatorModel(mlflow.pyfunc.PythonModel):
    """``mlflow.pyfunc`` wrapper of a :class:`StreamingCompensator` or an
    :class:`~thermocomp.apps.deploy.AdaptiveCompensator` (see module doc).

    Logged as *model from code* (``model_code.py``); the compensator itself is
    the pickled artifact ``compensator``, loaded in :meth:`load_context`.

    Parameters
    ----------
    streaming : StreamingCompensator or AdaptiveCompensator, optional
        The deployed object (both have ``reset``, ``predict``, ``_snapshot``/``_restore``).
    """

    def __init__(self, streaming: StreamingCompensator | AdaptiveCompensator | None = None):
        self.streaming = streaming
        self._lock = threading.Lock()
        self._sessions: OrderedDict = OrderedDict()   # session -> stream state, LRU order
        self._learned0 = self._learned_at_promotion()

    def _learned_at_promotion(self):
        adapt = getattr(self.streaming, "adapt_", None)
        return None if adapt is None else adapt.snapshot()

    def load_context(self, context) -> None:
        # a serving process (MLflow's, started by `thermocomp serve`) has no thermocomp logging
        # of its own: its warnings (a session it does not hold) came as bare stderr lines
        if not logging.getLogger(LOG_NAME).handlers:
            configure_log()
        artifacts = (context.artifacts or {}) if context is not None else {}
        if COMPENSATOR_ARTIFACT in artifacts:
            # the signature is checked on the bytes before anything is unpickled
            self.streaming = signing.load(artifacts[COMPENSATOR_ARTIFACT], DEPLOYABLE,
                                          sig=artifacts.get(SIGNATURE_ARTIFACT))
            said_if_unordered(self.streaming, str(artifacts[COMPENSATOR_ARTIFACT]))
        self.streaming.reset()
        self._sessions.clear()
        self._learned0 = self._learned_at_promotion()

    def _end_state(self, campaign: str) -> EndState:
        ends = self.streaming.end_states_
        if campaign not in ends:
            have = ", ".join(sorted(ends)) or ("none: the model reads temperature changes from "
                                               "each campaign's first sample (data.reference="
                                               "first_sample)" if self.streaming.compensator
                                               .reference != "none" else "none")
            raise MlflowException(f"continues={campaign!r}: the model holds no end state of that "
                                  f"campaign (it holds: {have})", error_code=INVALID_PARAMETER_VALUE)
        return ends[campaign]

    def _state(self, session: str, reset: bool, continues: str = "", ambient_c=None) -> list:
        """``[stream state, time shift, learned, clock origin, time of day, last time, step watch]`` of
        ``session`` (dep107c: the watch, :class:`.rates.StepWatch`, says its time's rate and gaps),
        most recent last (the origin: the campaign's first timestamp, ns, once a block gave one;
        data91, the time of day: the last read and the days added, :func:`_no_clock`): a fresh one
        when new or reset (with the campaign's ``ambient_c``, for a model that reads no ambient
        sensor); the end state of campaign ``continues`` when given (its time shift, an
        :class:`EndState` until the session's first row fixes it).  ``learned`` (what the
        adaptation learned) survives a reset: the session is the same machine."""
        learned = self._sessions[session][2] if session in self._sessions else self._learned0
        if continues:
            end = self._end_state(continues)
            self._sessions[session] = [copy.deepcopy(end.state), end, learned, None, _no_clock(),
                                       float("nan"), StepWatch()]
        elif reset or session not in self._sessions:
            if not reset:
                log.warning(unheld_session(session))
            self.streaming.reset(float("nan") if ambient_c is None else float(ambient_c))
            self._sessions[session] = [self.streaming._snapshot(), 0.0, learned, None, _no_clock(),
                                       float("nan"), StepWatch()]
        while len(self._sessions) > MAX_SESSIONS:
            self._sessions.popitem(last=False)
        self._sessions.move_to_end(session)
        return self._sessions[session]

    def predict(self, context, model_input: pd.DataFrame, params: dict | None = None) -> pd.DataFrame:
        params = params or {}
        session = str(params.get("session") or DEFAULT_SESSION)
        names = self.streaming.lab_names_
        try:
            # a PLC's status word under its header: its declared bits, as the reader's (bits85)
            frame = words_decoded(pd.DataFrame(model_input), getattr(self.streaming, "bits_", {}))
            frame = to_contract(frame, names, getattr(self.streaming, "lab_units_", {}))
            # (data94) a date and its time of day (Datum;Uhrzeit) as one time, as the file's
            frame = with_clock_joined(frame)
            # data.missing_values' marks (-9999 however written) missing, as the reader's (lab74)
            frame = marks.in_frame(frame, getattr(self.streaming, "missing_values_", ()), TIME)
            # a reference measurement's derived targets (data.derive), as a file's are computed
            frame = on_frame(frame, getattr(self.streaming, "derived_", {}), "the request")
        except ValueError as exc:
            raise MlflowException(str(exc), error_code=INVALID_PARAMETER_VALUE) from exc
        # Serving may call from several threads: one session's samples in order, one at a time.
        with self._lock:
            reset, continues = bool(params.get("reset")), str(params.get("continues") or "")
            outs, paused, found, done = [], None, None, 0
            try:
                while frame is not None:
                    state = self._state(session, reset, continues, params.get("ambient_c"))
                    found = list(state) if found is None else found   # (its fields are replaced, not changed)
                    out, frame, gap = self._block(state, frame, session, done)
                    done += len(out)
                    if paused is not None and len(out) and "events" in out:
                        out.loc[out.index[0], "events"] = _with_event(out["events"].iloc[0], paused)
                    outs.append(out)
                    reset, continues, paused = True, "", gap
            except MlflowException:
                # (dep106b) refused after a pause: the part before it is not taken either (no
                # half state: the caller got no row's correction), as one part rolls back
                if found is not None:
                    self._sessions[session] = found
                raise
        outs = [out for out in outs if len(out)] or outs[:1]    # (a pause before the block's first row)
        return outs[0] if len(outs) == 1 else pd.concat(outs, ignore_index=True)

    def _block(self, state: list, frame: pd.DataFrame, session: str = DEFAULT_SESSION, done: int = 0
               ) -> tuple[pd.DataFrame, pd.DataFrame | None, dict | None]:
        """The corrections of ``frame``'s rows in ``state``'s campaign up to a pause (the model's
        ``pause_s_``, :func:`_pause_at`), the rows from it (None: none) and its event; ``done``:
        the rows of the caller's block before ``frame`` (its rows named in the caller's block)."""
        raw, carried = frame, list(state[4])        # (kept below only where the block is taken)
        if TIME in frame.columns:
            frame = _on_campaign_clock(frame, state, self.streaming.slashed_, carried,
                                       _reads_day_seconds(self.streaming))
        if isinstance(state[1], EndState):
            # a continuing campaign's clock follows its predecessor's last sample by one
            # period, as `run` joins them (the client's own clock may restart at 0)
            end = state[1]
            state[1] = (end.time + end.period - float(frame[TIME].iloc[0])
                        if TIME in frame.columns and len(frame) else 0.0)
        shift = state[1]
        if shift and TIME in frame.columns:
            frame = frame.assign(**{TIME: pd.to_numeric(frame[TIME], errors="coerce") + shift})
        cut, gap = _pause_at(frame, state[5], getattr(self.streaming, "pause_s_", 0.0) or 0.0, shift)
        rest = None
        if cut is not None:
            frame, rest = frame.iloc[:cut], raw.iloc[cut:].reset_index(drop=True)
        self.streaming._restore(state[0])
        try:
            pred = self.streaming.predict(frame)
        except ValueError as exc:  # OutOfEnvelopeError, ContractError: the caller's input
            raise MlflowException(str(exc), error_code=INVALID_PARAMETER_VALUE) from exc
        finally:  # a refused block leaves the session where it was (predict rolls back)
            state[0] = self.streaming._snapshot()
        state[4] = carried
        if TIME in frame.columns and len(frame):
            read = pd.to_numeric(frame[TIME], errors="coerce").dropna()
            state[5] = float(read.iloc[-1]) if len(read) else state[5]
        adapt = getattr(self.streaming, "adapt_", None)
        if adapt is not None:
            targets = self.streaming.targets_
            adapt.restore(state[2])
            pred[targets] = adapt.correct(pred[targets].to_numpy(float), np.full(len(pred), np.nan),
                                          references(frame, targets))
            state[2] = adapt.snapshot()
        out = pd.DataFrame({correction_column(t): -pred[t].to_numpy(float)
                            for t in self.streaming.targets_})
        out["n_clamped"] = pred["n_clamped"].to_numpy(np.int64)
        if is_adaptive(self.streaming):
            for c in REPORT_COLUMNS:
                out[c] = pred[c].to_numpy(object)
            if shift:      # event times in the caller's clock
                out["events"] = [_shifted(e, -shift) for e in out["events"]]
        if TIME in frame.columns:
            state[6] = _said_steps(copy.deepcopy(state[6]), frame, out, session, done, shift)
        return out, rest, gap


def _pause_at(frame: pd.DataFrame, last: float, pause_s: float, shift: float
              ) -> tuple[int | None, dict | None]:
    """(audit106) The first row of ``frame`` whose time is more than ``pause_s`` after the last
    read (``last``, the session's before the block), as stream.c's ``TC_PAUSE_S`` starts a
    campaign there, and the event that says it (the time in the caller's clock); ``(None,
    None)`` where none (or ``pause_s`` 0: the record was not read with data.runs_at_pauses)."""
    if not pause_s or TIME not in frame.columns:
        return None, None
    times = pd.to_numeric(frame[TIME], errors="coerce").to_numpy(float)
    read = np.flatnonzero(np.isfinite(times))
    steps = np.diff(np.r_[last, times[read]])        # (NaN before a session's first time)
    hit = np.flatnonzero(steps > pause_s)
    if not hit.size:
        return None, None
    row, gap = int(read[hit[0]]), float(steps[hit[0]])
    return row, {"time": float(times[row]) - shift, "sensor": TIME, "from": "ok", "to": "new campaign",
                 "reason": f"the time pauses {gap / 3600:.3g} h, more than {pause_s:g} s "
                           "(data.runs_at_pauses): a campaign started from a reset here, as the "
                           "record's read and stream.c start one"}


def _said_steps(watch: StepWatch, frame: pd.DataFrame, out: pd.DataFrame, session: str, done: int,
                shift: float) -> StepWatch:
    """(dep107c) ``watch`` read on over ``frame``'s times (a taken block's, on the campaign's
    clock): a sample period changing or a stretch without rows said in a warning naming the
    session and the row of the caller's block, as the file reader and stream.c say it of the same
    rows, and in an event of that row (``sensor`` time) where ``out`` has events (the adaptive
    model); the corrections as they are.  It streamed on without a word (audit107: 100 s rows,
    then 1000 s ones from data row 202, said by replay of the file)."""
    times = pd.to_numeric(frame[TIME], errors="coerce").to_numpy(float)
    for i, t in enumerate(times):
        for kind, at, was, now in watch.read(float(t), i):
            said = found_words(kind, was, now)
            watch.said[kind] = watch.said.get(kind, 0) + 1
            if watch.said[kind] <= SAID_AT_MOST:      # (as stream.c's: a jittery clock's gaps)
                log.warning(f"session {session!r}, column {TIME!r}, data row {done + at + 1} of the "
                            f"block: {said}; the corrections go on"
                            + (" (no more said)" if watch.said[kind] == SAID_AT_MOST else ""))
            if "events" in out:
                event = {"time": float(times[at]) - shift, "sensor": TIME, "from": "ok",
                         "to": FOUND[kind], "reason": said}
                out.loc[out.index[at], "events"] = _with_event(out["events"].iloc[at], event)
    return watch


def _with_event(events: str, event: dict) -> str:
    """A row's events (JSON list) with ``event`` first."""
    return json.dumps([event, *json.loads(events or "[]")], ensure_ascii=False)


def unheld_session(session: str) -> str:
    """What the server says of a block for a session it does not hold, neither ``reset`` nor
    ``continues``: the session starts from a reset at that block's first row.  Right for a new
    campaign; wrong, silently, for a machine whose campaign went on while the server restarted
    (a new process holds no session): measured (restart58) on a lag bank, a Swiss lathe's 8 h run
    resumed 4 h in, E_X RMSE 26.1 um after the restart against 1.29 uninterrupted."""
    return (f"session {session!r} is not held by this server (new, the server restarted, or "
            f"dropped as the least recently used of {MAX_SESSIONS}): started from a reset at this "
            "block's first row. A campaign that was already running misses its warm-up: resend "
            "its rows since the campaign's start with reset=true (their corrections discarded) "
            "to resume it; start a new campaign with reset=true to say so")


def _no_clock() -> list:
    """A session's time of day before its first block (:func:`.timestamps.continued`): none
    read, no day added."""
    return [float("nan"), 0.0]


def _reads_day_seconds(streaming) -> bool:
    """(dep108d) Its ``day_seconds_``; a model pickled before it: as its lab's headers say (the C's)."""
    if (said := getattr(streaming, "day_seconds_", None)) is not None:
        return bool(said)
    return names_day_seconds(raw_names(streaming.lab_names_ or {}, TIME))


def _on_campaign_clock(frame: pd.DataFrame, state: list, slashed: str | None = None,
                       carried: list | None = None, day_seconds: bool = False) -> pd.DataFrame:
    """``frame`` with wall-clock times (a lab's logger: ``07.01.2023 08:45:00``, ISO 8601) as
    seconds since its campaign's first (the session's origin, kept over its blocks until a
    reset), as ``run`` and ``replay`` read a campaign's timestamps, dates with slashes in the
    record's order ``slashed`` (code71: a block's first row alone decided); seconds as they are.
    (data91) A time of day without its date (``h:mm:ss``) read on from the last the session
    read, ``carried`` (updated in place), a day added where it passes midnight, as a file's rows
    are (each block was refused, read alone); (dep108d) so plain seconds where ``day_seconds``
    (the model's time is the time of day: stream.c's TC_DAY_SECONDS), by the same function."""
    try:
        stamps = stream_stamps(frame[TIME], stream_format(frame[TIME], slashed, "the request")
                               or "auto", served=True, carried=carried)
        if stamps is None and day_seconds and carried is not None:
            seconds = pd.to_numeric(frame[TIME], errors="coerce").to_numpy(float)
            stamps = pd.Series(continued(pa.array(seconds, from_pandas=True), carried, "the request")
                               .to_numpy(zero_copy_only=False), index=frame.index)
    except ContractError as exc:     # a time that is no time: its row of the block, not of stdin
        where = f"column {exc.column!r}, data row {exc.row} of the block: " if exc.row else ""
        raise MlflowException(where + exc.reason, error_code=INVALID_PARAMETER_VALUE) from exc
    except ValueError as exc:
        raise MlflowException(str(exc), error_code=INVALID_PARAMETER_VALUE) from exc
    if stamps is None:
        return frame
    if isinstance(stamps, pd.Series):      # h:mm:ss elapsed since the start
        return frame.assign(**{TIME: stamps.to_numpy(float)})
    ns, valid = stamps
    if state[3] is None:
        state[3] = int(ns[np.argmax(valid)])
    return frame.assign(**{TIME: since(ns, valid, state[3])})


def references(frame: pd.DataFrame, targets) -> np.ndarray | None:
    """The measured errors a block carries (rows x targets, NaN where none), or None."""
    if not any(t in frame.columns for t in targets):
        return None
    return np.column_stack([pd.to_numeric(frame[t], errors="coerce").to_numpy(float)
                            if t in frame.columns else np.full(len(frame), np.nan) for t in targets])


def _shifted(events: str, by: float) -> str:
    """A row's events (JSON list) with their ``time`` moved by ``by`` s."""
    listed = json.loads(events)
    if not listed:
        return events
    return json.dumps([{**e, "time": e["time"] + by} if isinstance(e.get("time"), (int, float))
                       else e for e in listed], ensure_ascii=False)


def signature(streaming: StreamingCompensator | AdaptiveCompensator) -> ModelSignature:
    """Input/output schema (and the ``reset``, ``session``, ``continues`` parameters) of the
    deployed compensator.  With the lab's names (``lab_names_``) every input may come under
    either name, so none is required by the schema; the model checks that each is there."""
    names = streaming.lab_names_
    converted = getattr(streaming, "lab_units_", {}) or {}
    # a header bare above its unit row too (Temperatura ambiente): a bare name two columns share
    # in the schema as well, so that the model refuses it by name rather than MLflow dropping it
    accepted, unsure = accepted_names(names, converted)
    bits = getattr(streaming, "bits_", {}) or {}
    decoded = {STATE + n for named in bits.values() for n in named.values()}
    required = {c: not names and c not in decoded for c in streaming.columns_}
    required[TIME] = streaming.time_required_ and not names
    if getattr(streaming, "adapt_", None) is not None:   # reference measurements, when taken
        required.update({t: False for t in streaming.targets_ if t not in required})
    # the time in seconds or as wall-clock timestamps (a lab's logger's), under either name
    inputs = Schema([ColSpec(_kind(c), c, required=r) for c, r in required.items()]
                    + [ColSpec(_kind(c), raw, required=False) for c in required
                       for raw in dict.fromkeys(raw_names(accepted, c))]
                    + [ColSpec(AnyType(), form, required=False) for form in unsure]
                    # (data94) the time of day beside the date (Datum;Uhrzeit), joined to it:
                    # outside the schema MLflow drops it, and the date alone is refused
                    + [ColSpec(AnyType(), raw, required=False) for raw in raw_names(names, CLOCK)]
                    # a status word, which the model decodes into the bits it reads (bits85)
                    + [ColSpec("double", word, required=False) for word in bits
                       if word not in required])
    outputs = Schema([ColSpec("double", correction_column(t)) for t in streaming.targets_]
                     + [ColSpec("long", "n_clamped")]
                     + ([ColSpec("string", c) for c in REPORT_COLUMNS]
                        if is_adaptive(streaming) else []))
    return ModelSignature(inputs=inputs, outputs=outputs,
                          params=ParamSchema([ParamSpec("reset", "boolean", False),
                                               ParamSpec("session", "string", DEFAULT_SESSION),
                                               ParamSpec("continues", "string", ""),
                                               ParamSpec("ambient_c", "double", None)]))


def _kind(column: str):
    return AnyType() if column == TIME else "double"


# Third-party distributions the core imports when a compensator is unpickled (the package
# source itself travels in ``code_paths``); torch only for models that hold torch objects.
_CORE_REQUIREMENTS = ("mlflow", "numpy", "pandas", "pyarrow", "scipy", "scikit-learn",
                      "EMD-signal", "scikit-fuzzy")


def _requirements(pickled: bytes = b"") -> list[str]:
    from importlib.metadata import version

    names = list(_CORE_REQUIREMENTS) + (["torch"] if b"torch" in pickled else [])
    return [f"{p}=={version(p)}" for p in names]


def _model_kwargs(streaming, pickle_path: Path) -> dict:
    here = Path(__file__).resolve().parent
    return dict(python_model=str(here / "model_code.py"),
                artifacts={COMPENSATOR_ARTIFACT: str(pickle_path),
                           SIGNATURE_ARTIFACT: str(signing.sig_path(pickle_path))},
                signature=signature(streaming),
                code_paths=[str(Path(thermocomp.__file__).resolve().parent)],   # the package
                pip_requirements=_requirements(Path(pickle_path).read_bytes()))


def _pickled(streaming, folder: str) -> Path:
    """``<folder>/compensator.pkl`` and its signature ``compensator.pkl.sig``."""
    streaming.reset()
    return signing.dump(streaming, Path(folder) / "compensator.pkl")


def save_compensator(streaming: StreamingCompensator | AdaptiveCompensator, path,
                     input_example=None) -> Path:
    """Write the pyfunc model to a local folder (no tracking server): ``mlflow.pyfunc.load_model(path)``."""
    with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
        # the signature is given: MLflow's "no input example" advice says nothing to a user
        warnings.filterwarnings("ignore", message=".*input example was not provided")
        mlflow.pyfunc.save_model(str(path), input_example=input_example,
                                 **_model_kwargs(streaming, _pickled(streaming, tmp)))
    return Path(path)


def log_compensator(streaming: StreamingCompensator | AdaptiveCompensator,
                    input_example: pd.DataFrame | None = None,
                    registered_model_name: str | None = None, name: str = MODEL_NAME,
                    run_id: str | None = None, **kwargs):
    """Log the compensator as a pyfunc model; returns the ``ModelInfo``.

    Into run ``run_id`` (its experiment) without resuming it, so a finished run stays
    FINISHED whatever happens to this process; without ``run_id``, into the active run.
    ``registered_model_name`` also registers it (a new version) in the Model Registry.
    """
    with tempfile.TemporaryDirectory() as tmp:
        model_kwargs = _model_kwargs(streaming, _pickled(streaming, tmp))
        if run_id is None:
            return mlflow.pyfunc.log_model(
                name=name, input_example=input_example,
                registered_model_name=registered_model_name, **model_kwargs, **kwargs)
        from mlflow.models import Model

        # the logged model belongs to the run's experiment (else MLflow's Default one)
        mlflow.set_experiment(experiment_id=mlflow.get_run(run_id).info.experiment_id)
        return Model.log(artifact_path=None, name=name, flavor=mlflow.pyfunc, run_id=run_id,
                         input_example=input_example,
                         registered_model_name=registered_model_name, **model_kwargs, **kwargs)


class ModelFiles:
    """The files of one stored model fetched one by one, each as it is read: ``source`` (a
    registered ``models:/<name>@<alias>`` or ``models:/<name>/<version>``, a logged model's
    ``models:/<model_id>``, a run's ``runs:/<run_id>``) is resolved once, here (an alias that
    moves meanwhile cannot mix two versions' files), then :meth:`fetch` copies a file into
    ``dst``.  A whole model came down before to read three of its files (MLmodel and the signed
    pickle: 3 of 270, the rest the package source of ``code_paths``).  ``uri``: the tracking
    store and registry (default: MLflow's current ones)."""

    def __init__(self, source: str, dst: str | Path, uri: str | None = None):
        from mlflow.store.artifact.artifact_repository_registry import get_artifact_repository

        self.source, self.dst = str(source), Path(dst)
        self._repo = get_artifact_repository(self.source, tracking_uri=uri, registry_uri=uri)

    def fetch(self, path: str, what: str = "") -> Path:
        """The local copy of the model's file ``path`` (relative to its root; ``what`` names it in
        a refusal).  A path that leaves the model (absolute, ``..``) or a file the store does not
        hold is refused (ContractError, exit 2) naming it."""
        named = f"{path!r}" + (f" ({what})" if what else "")
        rel = PurePosixPath(str(path))
        if not rel.parts or rel.is_absolute() or ".." in rel.parts:
            raise ContractError(f"the artifact {named} lies outside the model folder", file=self.source)
        try:
            return Path(self._repo.download_artifacts(str(rel), str(self.dst)))
        except Exception as exc:     # MLflow says each store's "no such file" its own way,
            lines = [line for line in str(exc).splitlines() if line.strip()]   # the reason last
            why = " ".join(lines[-1].split())[:200] if lines else type(exc).__name__
            raise ContractError(f"the model has no readable {named} ({why})",
                                file=self.source) from None


def load_deployed(source: str, folder: str | Path | None = None):
    """The signed compensator inside a pyfunc model, loaded by *this* installed package.

    ``folder``: the model's local folder; else ``source`` (``models:/<name>@<alias>``) is
    read from the registry, file by file (:class:`ModelFiles`): ``MLmodel``, then the pickle
    and its signature it names, nothing else.  Only the pickle is taken from the model, after
    its HMAC signature is checked: the model's own code (``model_code.py``, ``code/``, the loader
    ``MLmodel`` names) is never run, since any of them could be edited in a store and the
    signature covers the pickle alone.  A ContractError (exit 2) names what is wrong.
    """
    import yaml

    from ...base.files import scratch_folder

    with scratch_folder("thermocomp-model-") as tmp:
        files = None if folder is not None else ModelFiles(source, tmp)
        root = Path(folder) if folder is not None else None
        spec = root / "MLmodel" if files is None else files.fetch("MLmodel")
        try:
            flavor = yaml.safe_load(spec.read_text())["flavors"]["python_function"]
            arts = flavor["artifacts"]
            named = {k: str(arts[k]["path"]) for k in (COMPENSATOR_ARTIFACT, SIGNATURE_ARTIFACT)}
        except (OSError, yaml.YAMLError, KeyError, TypeError) as exc:
            raise ContractError(f"not a thermocomp compensator model ({type(exc).__name__}: {exc})",
                                file=spec if files is None else f"{source} MLmodel") from None
        if files is None:
            pickled, sig = (root / named[k] for k in (COMPENSATOR_ARTIFACT, SIGNATURE_ARTIFACT))
            inside = root.resolve()
            if not all(inside in p.resolve().parents for p in (pickled, sig)):
                raise ContractError("the artifacts it names lie outside the model folder", file=spec)
        else:
            pickled, sig = (files.fetch(named[k], k) for k in (COMPENSATOR_ARTIFACT, SIGNATURE_ARTIFACT))
        deployed = signing.load(pickled, DEPLOYABLE, sig=sig)
    said_if_unordered(deployed, source)
    return deployed


def said_if_unordered(deployed, model: str) -> None:
    """A model deployed before code71 carries no order of its record's dates with slashes
    (``slashed_``, none in its pickle): said where it is loaded, naming it ``model``, and marked
    said (``slashed_`` None of its own), so that a copy of it (``serve``'s trusted copy) does not
    say it again (small72).  Its record is not in it: the order cannot be read again here."""
    if "slashed_" in vars(deployed):
        return
    log.warning(f"model {model} carries no order of its training record's dates with slashes "
                "(deployed before code71, or built outside thermocomp's deploy): a block's or "
                "connect.warm's dates with slashes (03/11/2027 ...) are read in the order each "
                "block's first row says (10/03 then 11/03: October, then November); promote its "
                "run's model.pkl again (thermocomp promote reads its record) to read them in its "
                "record's order. Times in seconds or ISO 8601 are read as before")
    deployed.slashed_ = None
