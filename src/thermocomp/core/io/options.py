"""The ``data`` config keys that steer reading (:class:`ReadOptions`) and the reader's limits."""

from __future__ import annotations

import math
import re
import zoneinfo
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field

import numpy as np

from ...base.params import MAX_COUNT
from ...base.paths import resolve
from .bits import parsed as parsed_bits
from .clocksets import clock_sets
from .contract import SPLITS, ContractError
from .derived import parsed as parsed_derive
from .encoding import UTF8, codec
from .marks import is_number_mark
from .separators import NO_BREAK_SPACES, any_number

TIME_FORMATS = ("auto", "seconds", "iso8601", "elapsed", "of_day")   # (data91: of_day)
AUTO = "auto"                     # data.delimiter / data.decimal / data.roles.time: detected
ROLE_PATTERNS = ("error", "state", "ambient", "ignore")   # data.roles.<key>: glob patterns
RUN_ROLE = "campaign"     # data.roles.campaign: the one column numbering a long file's runs
SPLIT_ORDER = ("train", "val", "test")
ROLE_ORDER = ("T", "E", "S")
MISSING_MODES = ("repair", "keep", "keep_errors")
SPARSE_TARGETS = ("auto", "true", "false")   # data.sparse_targets: an E_ column measured now and then

_OTHER_DELIMITERS = (";", "\t", "|", ",")
# ReadOptions fields that are no data config key (the reader's own)
INTERNAL = ("missing", "skip_rows", "data_bytes", "drop_bytes", "half", "order_in_rows")
# ReadOptions fields read from a nested data config key (``data.join.offset_s``)
NESTED = {"join_offset_s": "join.offset_s", "join_tolerance_s": "join.tolerance_s"}


# ---------------------------------------------------------------------------
# Options


@dataclass(frozen=True)
class ReadOptions:
    """The ``data`` config keys that steer reading; see :func:`read_dataset`.

    Build it with :meth:`from_cfg`; every field has the default a missing key
    gets.
    """

    columns: dict = field(default_factory=dict)
    sample_period_s: float | None = None
    time: str = "auto"
    split_overrides: dict = field(default_factory=dict)
    max_gap_samples: int = 0
    max_edge_samples: int = 0
    sparse_targets: str = "auto"
    resample_s: float | None = None
    kelvin_threshold_c: float = 200.0
    fahrenheit_threshold_c: float | None = 45.0
    max_abs_error: float | None = 1e6
    max_abs_state: float | None = 1e9
    max_period_ratio: float | None = 100.0
    max_duration_days: float | None = 366.0
    max_resample_factor: float = 10.0
    max_step_ratio: float | None = 5.0
    delimiter: str = AUTO
    decimal: str = AUTO
    thousands: str | None = None
    encoding: str = UTF8          # the CSV files' character set (Python's codec name)
    timezone: str | None = None   # the zone of timestamps written without an offset (local)
    roles: dict = field(default_factory=dict)     # see io.roles; {} (or all empty): none
    units: dict = field(default_factory=dict)     # header -> unit where the header has none
    missing_values: list = field(default_factory=list)  # read as missing besides empty, nan
    test_fraction: float | None = None
    val_fraction: float | None = None
    split_order: list = field(default_factory=lambda: list(SPLIT_ORDER))
    sheet: str | None = None      # a workbook's sheet (None: the first)
    # data.join: a run logged by two loggers (:mod:`.joined`): how far the error logger's clock
    # runs ahead of the temperature logger's (s), and the longest temperature step an error
    # sample is interpolated across (None: 3 times the temperature logger's median step)
    join_offset_s: float = 0.0
    join_tolerance_s: float | None = None
    runs_at_pauses: bool = False  # one file's runs parted where its time pauses (.runs)
    dayfirst: bool | None = None  # a lab file's dates with slashes day first (None: the file's)
    derive: dict = field(default_factory=dict)    # derived error columns (.derived): name -> text
    bits: dict = field(default_factory=dict)      # status words' bits as states (.bits)
    # (deploy73) the server's clock sets connect told, undone in a log's timestamps (.clocksets)
    clock_sets: tuple = ()
    # internal (no data config key): "keep" leaves missing values NaN; "keep_errors" only the
    # E_ columns' (a volumetric dataset's distances not measured), the rest repaired
    missing: str = "repair"
    skip_rows: int = 1        # internal: lines above a CSV's first data row (preamble, header, units)
    data_bytes: int | None = None   # internal: the bytes of a CSV above its footer (None: unknown)
    drop_bytes: tuple = ()    # internal: byte spans of a CSV left out (its header written again)
    half: bool = False        # internal: one logger's file of a run of two (:mod:`.joined`)
    # internal: a one-file record whose dates with slashes take the order its rows say, decided
    # in its read (:mod:`.slashed`), not in a read of its own before
    order_in_rows: bool = False

    def __post_init__(self):
        if self.missing not in MISSING_MODES:  # a caller's mistake, not the user's
            raise ValueError(f"missing must be one of {MISSING_MODES}, got {self.missing!r}")

    @classmethod
    def from_cfg(cls, cfg: Mapping | None) -> "ReadOptions":
        """Options from a mapping (dict or OmegaConf ``DictConfig``).

        Raises
        ------
        ContractError
            If a value has the wrong type or range.
        """
        cfg = {} if cfg is None else cfg
        opts = cls(
            columns=_str_mapping(cfg, "columns"),
            sample_period_s=_positive_float(cfg, "sample_period_s"),
            time=str(cfg.get("time", "auto") or "auto"),
            split_overrides=_str_mapping(cfg, "split_overrides"),
            max_gap_samples=_count(cfg, "max_gap_samples"),
            max_edge_samples=_count(cfg, "max_edge_samples"),
            sparse_targets=_sparse_targets(cfg),
            resample_s=_positive_float(cfg, "resample_s"),
            kelvin_threshold_c=_float(cfg, "kelvin_threshold_c", 200.0),
            fahrenheit_threshold_c=_float(cfg, "fahrenheit_threshold_c", 45.0, nullable=True),
            max_abs_error=_positive_float(cfg, "max_abs_error", 1e6, nullable=True),
            max_abs_state=_positive_float(cfg, "max_abs_state", 1e9, nullable=True),
            max_period_ratio=_positive_float(cfg, "max_period_ratio", 100.0, nullable=True),
            max_duration_days=_positive_float(cfg, "max_duration_days", 366.0, nullable=True),
            max_resample_factor=_positive_float(cfg, "max_resample_factor", 10.0),
            max_step_ratio=_positive_float(cfg, "max_step_ratio", 5.0, nullable=True),
            delimiter=_delimiter(cfg),
            decimal=_text(cfg, "decimal", AUTO),
            thousands=None if cfg.get("thousands") is None else str(cfg.get("thousands")),
            encoding=codec(_text(cfg, "encoding", UTF8)),
            timezone=_timezone(cfg),
            roles=_roles(cfg),
            units=_str_mapping(cfg, "units"),
            missing_values=_missing_values(cfg),
            test_fraction=_fraction(cfg, "test_fraction"),
            val_fraction=_fraction(cfg, "val_fraction"),
            split_order=_split_order(cfg),
            sheet=None if cfg.get("sheet") is None else str(cfg.get("sheet")),
            **_join(cfg),
            runs_at_pauses=_flag(cfg, "runs_at_pauses"),
            dayfirst=None if cfg.get("dayfirst") is None else _flag(cfg, "dayfirst"),
            derive=parsed_derive(cfg.get("derive")),
            bits=parsed_bits(cfg.get("bits")),
            clock_sets=(() if cfg.get("clock_sets") is None
                        else clock_sets(resolve(str(cfg.get("clock_sets"))))),
        )
        opts._check()
        return opts

    def data_keys(self) -> dict:
        """(data89) The options under the data config keys a user types (``join.offset_s``,
        dotted where nested), the internal fields left out: what an ingest's
        ``ingested_with.settings`` names, so that a changed one is said by the key that
        changes it (it named ``data.join_offset_s`` and internal ``data.skip_rows``)."""
        return {NESTED.get(k, k): v for k, v in asdict(self).items() if k not in INTERNAL}

    def _check(self) -> None:
        if self.time not in TIME_FORMATS and "%" not in self.time:
            raise ContractError(f"data.time must be one of {', '.join(TIME_FORMATS)} or a "
                                f"strptime format ('%d/%m/%Y %H:%M:%S'), got {self.time!r}")
        bad_split = {k: v for k, v in self.split_overrides.items() if v not in SPLITS}
        if bad_split:
            cid, split = next(iter(bad_split.items()))
            raise ContractError(f"data.split_overrides.{cid}: split {split!r} is not one of "
                                f"{', '.join(SPLITS)}")
        for key in ("delimiter", "decimal"):
            if len(getattr(self, key)) != 1 and getattr(self, key) != AUTO:
                raise ContractError(f"data.{key} must be one character or 'auto', "
                                    f"got {getattr(self, key)!r}")
        if (self.test_fraction or 0.0) + (self.val_fraction or 0.0) >= 1.0:
            raise ContractError(f"data.test_fraction + data.val_fraction must be < 1 (a train "
                                f"part is left), got {self.test_fraction} + {self.val_fraction}")
        # (the field separator may be it: a CSV writer quotes "6,000")
        if self.thousands not in (None, AUTO) and (len(self.thousands) != 1 or self.thousands
                                           == self.decimal or re.match(r"[\w+\-]", self.thousands)
                                           or self.thousands.isspace() and self.thousands
                                           not in NO_BREAK_SPACES):
            raise ContractError(f"data.thousands must be one character other than the decimal "
                                "mark, not a digit, letter, sign or plain space (',', '.', \"'\", "
                                f"a no-break space or null), got {self.thousands!r}")
        # (',' and ',': a comma-separated file quoting its decimal-comma cells, "0,38", reads)
        if self.decimal == self.delimiter != AUTO and self.delimiter != ",":
            raise ContractError(f"data.decimal={self.decimal!r} is the field separator too "
                                "(data.delimiter): a lab writing decimal commas separates with ';'")
        if self.kelvin_threshold_c <= 0.0:    # every reading above it is refused as kelvin
            raise ContractError(f"data.kelvin_threshold_c must be > 0 (°C), got "
                                f"{self.kelvin_threshold_c:g}")


def _text(cfg: Mapping, key: str, default: str) -> str:
    """``cfg[key]`` as text, ``default`` when missing or null (an empty text stays, refused)."""
    value = cfg.get(key)
    return default if value is None else str(value)


def _delimiter(cfg: Mapping) -> str:
    """``data.delimiter``; a tab also as the shell types it (``data.delimiter='\\t'`` reaches here
    as a backslash and a ``t``: no command line passes a tab character) or as ``tab``."""
    value = _text(cfg, "delimiter", AUTO)
    return "\t" if value in ("\\t", "tab", "TAB") else value


def _timezone(cfg: Mapping) -> str | None:
    """``data.timezone``: an IANA zone (``Europe/Berlin``), or null."""
    value = cfg.get("timezone")
    if value is None:
        return None
    try:
        zoneinfo.ZoneInfo(str(value))
    except (zoneinfo.ZoneInfoNotFoundError, ValueError):
        raise ContractError(f"data.timezone must be a time zone such as Europe/Berlin or UTC (or "
                            f"null), got {value!r}") from None
    return str(value)


def _roles(cfg: Mapping) -> dict:
    """``data.roles`` as ``{error, state, ambient, ignore: list of patterns, time: name|auto
    or [date, time of day] (two headers joined into one timestamp), campaign: a header (or
    pattern) whose value numbers the runs of one long file, or None}``."""
    value = cfg.get("roles") or {}
    if not hasattr(value, "items"):
        raise ContractError(f"data.roles must be a mapping, got {value!r}")
    unknown = [k for k in value if k not in (*ROLE_PATTERNS, "time", RUN_ROLE)]
    if unknown:
        raise ContractError(f"data.roles.{unknown[0]}: unknown role; roles: "
                            f"{', '.join((*ROLE_PATTERNS, 'time', RUN_ROLE))}")
    run = value.get(RUN_ROLE)
    if run is not None and not (isinstance(run, str) and run.strip()):
        raise ContractError(f"data.roles.{RUN_ROLE} must be one header (or a pattern matching "
                            f"one), the column numbering the runs, got {run!r}")
    out = {}
    for key in ROLE_PATTERNS:
        patterns = value.get(key) or []
        patterns = [patterns] if isinstance(patterns, str) else patterns
        if not all(isinstance(p, str) and p for p in patterns):
            raise ContractError(f"data.roles.{key} must be a list of header patterns, got "
                                f"{value.get(key)!r}")
        out[key] = list(patterns)
    time = value.get("time", AUTO)
    if time is not None and not isinstance(time, str) and hasattr(time, "__iter__"):
        time = list(time)
        if len(time) != 2 or not all(isinstance(h, str) and h for h in time):
            raise ContractError(f"data.roles.time must be a header, or two: [date, time of day] "
                                f"(e.g. [Datum, Uhrzeit]), got {time!r}")
        out["time"] = time
    else:
        out["time"] = AUTO if time is None else str(time)
    if run is not None:
        out[RUN_ROLE] = run.strip()
    return out


def _join(cfg: Mapping) -> dict:
    """``data.join`` (``offset_s``, ``tolerance_s``) as the ReadOptions fields ``join_*``."""
    value = cfg.get("join") or {}
    if not hasattr(value, "items"):
        raise ContractError(f"data.join must be a mapping (offset_s, tolerance_s), got {value!r}")
    unknown = [k for k in value if k not in ("offset_s", "tolerance_s")]
    if unknown:
        raise ContractError(f"data.join.{unknown[0]}: unknown key; keys: offset_s, tolerance_s")
    named = {f"join.{k}": v for k, v in value.items()}     # (named so in a refusal)
    return {"join_offset_s": _float(named, "join.offset_s", 0.0),
            "join_tolerance_s": _positive_float(named, "join.tolerance_s", nullable=True)}


def _flag(cfg: Mapping, key: str) -> bool:
    value = cfg.get(key, False)
    if not isinstance(value, bool):
        raise ContractError(f"data.{key} must be true or false, got {value!r}")
    return value


def _missing_values(cfg: Mapping) -> list:
    """``data.missing_values``: what a lab writes for a value not measured (``-``, ``n/a``; a
    number only where it is no reading, :func:`.marks.is_number_mark`: an instrument's overload
    mark, faults71, or AmeriFlux's -9999, below absolute zero, lab74).  A number written as a
    YAML number (``[-9999]``) is taken as its text."""
    value = cfg.get("missing_values") or []
    value = [value] if isinstance(value, (str, int, float)) else value
    value = [str(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v
             for v in value]
    # (a bound switched off, null: a mark is beyond the other's, or its default's)
    beyond = max(_positive_float(cfg, "max_abs_error", 1e6, nullable=True) or 1e6,
                 _positive_float(cfg, "max_abs_state", 1e9, nullable=True) or 1e9)
    if not all(isinstance(v, str) and v.strip() and (not any_number(v) or is_number_mark(v, beyond))
               for v in value):
        raise ContractError(f"data.missing_values must be a list of marks that are no number "
                            f"(e.g. ['-', 'n/a', '#DIV/0!']) or a number beyond any reading: "
                            f"below absolute zero (AmeriFlux's -9999), or above "
                            f"data.max_abs_error and data.max_abs_state (an instrument's "
                            f"overload mark, '+9.90000000E+37'), got "
                            f"{cfg.get('missing_values')!r}")
    return [str(v) for v in value]


def _fraction(cfg: Mapping, key: str) -> float | None:
    number = _float(cfg, key, None)
    if number is not None and not 0.0 < number < 1.0:
        raise ContractError(f"data.{key} must be in (0, 1) (a share of the record), got {number:g}")
    return number


def _split_order(cfg: Mapping) -> tuple:
    value = cfg.get("split_order") or SPLIT_ORDER
    order = tuple(str(v) for v in ([value] if isinstance(value, str) else value))
    if sorted(order) != sorted(SPLIT_ORDER):
        raise ContractError(f"data.split_order must order train, val and test once each "
                            f"(chronologically), got {list(order)}")
    return list(order)


def _str_mapping(cfg: Mapping, key: str) -> dict:
    value = cfg.get(key, None) or {}
    if not hasattr(value, "items"):
        raise ContractError(f"data.{key} must be a mapping, got {value!r}")
    return {str(k): str(v) for k, v in value.items()}


def _float(cfg: Mapping, key: str, default: float | None, nullable: bool = False
           ) -> float | None:
    """``cfg[key]`` as a finite float; a missing key gives ``default``, and so does null
    unless ``nullable`` (then null switches the check it steers off)."""
    if key not in cfg:
        return default
    value = cfg.get(key)
    if value is None:
        return None if nullable else default
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ContractError(f"data.{key} must be a number, got {value!r}") from None
    if isinstance(value, bool) or not math.isfinite(number):
        raise ContractError(f"data.{key} must be a finite number, got {value!r}")
    return number


def _positive_float(cfg: Mapping, key: str, default: float | None = None,
                    nullable: bool = False) -> float | None:
    number = _float(cfg, key, default, nullable)
    if number is not None and number <= 0:
        raise ContractError(f"data.{key} must be > 0, got {number:g}")
    return number


def _sparse_targets(cfg: Mapping) -> str:
    """``data.sparse_targets``: ``auto``, ``true`` or ``false`` (YAML's booleans read as such)."""
    value = cfg.get("sparse_targets", "auto")
    text = "auto" if value is None else str(value).lower()
    if text not in SPARSE_TARGETS:
        raise ContractError(f"data.sparse_targets must be one of {', '.join(SPARSE_TARGETS)}, "
                            f"got {value!r}")
    return text


def _count(cfg: Mapping, key: str) -> int:
    value = cfg.get(key, 0)
    value = 0 if value is None else value
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 0 <= value <= MAX_COUNT:
        raise ContractError(f"data.{key} must be an integer >= 0, at most {MAX_COUNT:,}, got {value!r}")
    return int(value)


def _first_line(exc: BaseException) -> str:
    """The first line of an exception's message (its type when it has none)."""
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__
