"""Where every stage gets its data: ``open_source(cfg)`` and what is judged of a dataset by the config.

``data.path`` is opened once per stage through :func:`thermocomp.core.io.source.open_dataset`
(a batch, or a stream: test campaigns as recorded) or, for a volumetric folder, through its
adapter (:func:`thermocomp.apps.volumetric.source.open_volumetric`: calibrated into the
parameter series, the calibration in ``meta``); ``data.reference=auto`` is resolved on what
was read.  The DVC stages after ``ingest`` read ``data.interim`` (:func:`load_ingested`), refused
when it was ingested from another source or with other options.  ``meta["digest"]`` is the one
dataset digest (:func:`~thermocomp.base.files.folder_digest`).
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

from omegaconf import DictConfig, OmegaConf, open_dict

from ..apps.volumetric.source import SETTINGS
from ..apps.volumetric.source import is_volumetric as _volumetric_folder
from ..base.errors import ConfigError
from ..base.files import folder_digest
from ..base.log import logger, say
from ..base.paths import resolve
from ..core import io
from ..core.io.source import open_dataset
from .config.checks import data_options
from .fingerprint import CONFIG, DIGEST, json_hash, matches, plain

AUTO_REFERENCE = "auto"   # data.reference: none where test/val campaigns continue others
SETTINGS_KEY = "settings"  # in ``ingested_with``: what the config hash was taken of


def is_volumetric(cfg: DictConfig) -> bool:
    """``data.path`` is a volumetric dataset (``volumetric.json`` in it)."""
    return _volumetric_folder(resolve(cfg.data.path))


def calibration_prior(c: DictConfig) -> dict | None:
    """``calibrate.prior`` as a plain mapping (its interpolations resolved), or None."""
    return None if c.get("prior") is None else OmegaConf.to_container(c.prior, resolve=True)


def calibrate_settings(cfg: DictConfig) -> dict:
    """The ``calibrate.*`` keys a parameter series depends on, plain."""
    c = OmegaConf.to_container(cfg.calibrate, resolve=True)
    return {k: c.get(k) for k in SETTINGS}


def open_source(cfg: DictConfig, *, stream: bool = False, ingested: bool = False,
                volumetric: bool | None = None, campaigns=None, digest: str | None = None,
                detected: dict | None = None, needs_errors: bool = True) -> io.Dataset:
    """``data.path`` as a batch (``stream=False``) or a stream sees it, ``data.reference``
    resolved on it; a volumetric folder calibrated into its parameter series (``calibrate.*``
    checked by ``check_config``).  ``volumetric=True``: only a volumetric folder (``calibrate``;
    another is refused naming the missing set-up).  ``ingested=True``: ``data.interim`` as
    ``ingest`` wrote it from this source (the DVC stages after it: :func:`load_ingested`).
    ``campaigns``: only those (a fleet's group; ``digest``: the folder's, digested once).
    ``detected``: read with this data config instead (``init``: what it detected), as it is.
    ``needs_errors``: False, a file without an error column read too (``rows``)."""
    if ingested:
        return load_ingested(cfg)
    root = resolve(cfg.data.path)
    if detected is not None:         # (its path: a folder's lone file init reads as the record)
        path = resolve(detected.get("path", root))
        if _volumetric_folder(path):
            # its distances as calibrate (and run) reads them: an empty cell is a distance not
            # measured (volstranger66: init refused a ball not probed in 20 cycles as a gap)
            ds, report = io.read_dataset(path, detected, missing="keep_errors")
            ds.meta.update(digest=folder_digest(path), read_report=report)
            return ds
        return open_dataset(path, detected)
    if campaigns is None:       # a fleet says its folder once, not per group
        say(f"reading {root}")
    if volumetric or (volumetric is None and campaigns is None and _volumetric_folder(root)):
        # here: the simulator's package (its BLAS helper) is a volumetric dataset's, not every run's
        from ..apps.sim.scenario import single_threaded_blas
        from ..apps.volumetric.source import open_volumetric

        say("volumetric dataset: calibrating the artefact distances into the error parameters")
        with single_threaded_blas():   # 1430-wide matrices: threads on 2 busy cores only thrash
            ds = open_volumetric(root, data_options(cfg), calibrate_settings(cfg))
    else:
        ds = open_dataset(root, data_options(cfg), stream=stream, campaigns=campaigns,
                          digest=digest, needs_errors=needs_errors)
        said_misread(cfg, ds)
    resolve_reference(cfg, ds)
    return ds


def said_misread(cfg: DictConfig, ds) -> None:
    """Warn of each column a role read by its unit alone as what it is not, as ``init`` would
    propose it: an error whose values span an axis' travel
    (:func:`~thermocomp.core.io.detect.travel_headers`; stranger64's ``Z ram [mm]``, 0-800 mm,
    scored as a thermal error of 0.8 m), a temperature naming the day of the week
    (:func:`~thermocomp.core.io.detect.weekday_headers`; stranger75's ``Weekday``, 1-7)."""
    from ..core.io.detect import TRAVEL_UM, travel_headers, weekday_headers
    from ..core.io.roles import header_pattern

    names = ds.meta.get("column_map") or {}
    if not names:
        return
    opts = io.ReadOptions.from_cfg(data_options(cfg))
    for header, span in travel_headers(ds, names, opts.roles, opts).items():
        logger.warning(f"{header!r} ({names[header]}), an error by its unit, spans {span:.4g} mm "
                       f"over the record, more than a thermal error does ({TRAVEL_UM / 1000:g} "
                       f"mm): an axis position? data.roles.state=[{header_pattern(header)!r}] "
                       "(thermocomp init proposes it)")
    for header in weekday_headers(ds, names, opts):
        logger.warning(f"{header!r} ({names[header]}) names the day of the week (whole numbers "
                       f"0-7): a calendar number read as a temperature; data.roles.ignore="
                       f"[{header_pattern(header)!r}] leaves it out (thermocomp init does)")


def calibration_of(ds: io.Dataset):
    """``(distance dataset, calibration, its report)`` of a source opened from a volumetric
    folder, else None."""
    cal = ds.meta.get("calibrator")
    return None if cal is None else (ds.meta["distances"], cal, ds.meta["calibration"])


def source_report(cfg: DictConfig, ds: io.Dataset) -> dict:
    """What was read, as ``ingest_report.json`` records it (``run`` writes it into ``out``): the
    reader's report (of a volumetric folder: the distances' name and the calibration) and the
    resolved ``data.reference``."""
    volumetric = calibration_of(ds)
    report = (dict(ds.meta["read_report"]) if volumetric is None else
              {"dataset": volumetric[0].name, "calibration": volumetric[2]})
    return {**report, "reference": str(cfg.data.reference)}


def volumetric_distances(cfg: DictConfig, ds: io.Dataset):
    """``(distance dataset, calibration, its report)`` when ``data.path`` is a volumetric dataset,
    else None: what ``evaluate`` validates the parameter models of ``ds`` (``data.interim``, which
    ``ingest`` calibrated from the same folder) against; the calibration's model is fitted again,
    not its cycles.  An ingest without this calibration's parameter series is refused."""
    from ..apps.volumetric.calibration import without_cut_cycles
    from ..apps.volumetric.source import open_distances

    if not is_volumetric(cfg):
        return None
    raw, cal = open_distances(resolve(cfg.data.path), data_options(cfg), cfg.calibrate.outlier_z,
                              calibration_prior(cfg.calibrate))
    lacking = [n for n in cal.names_ if n not in ds.columns]
    if lacking:
        raise io.ContractError(f"it does not hold the parameter series of the volumetric dataset "
                               f"{resolve(cfg.data.path)} (no {lacking[0]}); rerun ingest",
                               file=resolve(cfg.data.interim))
    report = ds.meta["ingest_report"].get("calibration") or {}
    return without_cut_cycles(raw, report), cal, report


def reference(cfg: DictConfig) -> str:
    """``data.reference`` as resolved by :func:`resolve_reference`; ``auto`` before the data are
    read (a library caller building from the config alone) is the contract's ``first_sample``."""
    given = str(cfg.data.reference)
    return "first_sample" if given == AUTO_REFERENCE else given


def resolve_reference(cfg: DictConfig, ds) -> str:
    """``data.reference=auto`` made ``none`` where a test or val campaign of ``ds`` continues
    another (its state is carried over, :mod:`thermocomp.core.continuation`), else ``first_sample``;
    said in one line.  A link found by time whose later file's errors all start again at 0 is
    read there as a restart (:mod:`thermocomp.core.restart`; left out of every stage's links,
    said).  An explicit ``first_sample`` there is warned about: each part restarts."""
    from ..core.continuation import predecessors, said_junction_steps, time_links
    from ..core.restart import RESTARTED, restarts

    given = cfg.data.reference
    if given == AUTO_REFERENCE and (restarted := restarts(ds, time_links(ds))):
        ds.meta[RESTARTED] = restarted
        say(f"data.reference=auto: {'; '.join(restarted.values())} (an explicit data.reference=none "
            "carries the state over)")
    links = predecessors(ds)
    if str(cfg.data.reference) != "first_sample":   # (each file restarts: no junction)
        said_junction_steps(ds, links)
    scored = [c for c in ds.ids() if c in links and ds.manifest.loc[c, "split"] in ("test", "val")]
    if given == AUTO_REFERENCE:
        resolved = "none" if scored else "first_sample"
        restarting = [c for c in ds.meta.get(RESTARTED, {})
                      if ds.manifest.loc[c, "split"] in ("test", "val")]
        why = (f"{scored[0]} continues {links[scored[0]]}: its state is carried over" if scored
               else "no test or val campaign continues another"
               + (f"; {restarting[0]} restarts" if restarting else ""))
        say(f"data.reference=auto: {resolved} ({why})")
        with open_dict(cfg):
            cfg.data.reference = resolved
    elif given == "first_sample" and scored:
        logger.warning(f"data.reference=first_sample: {scored[0]} continues {links[scored[0]]}, "
                       "but each campaign restarts at its own first sample, no state carried "
                       "over (data.reference=none or auto carries it)")
    return cfg.data.reference


def read_streamed(cfg: DictConfig, test: bool = True):
    """``(dataset, train ids, test ids, missing cells per test campaign)`` of ``data.path`` as a
    stream sees it (:func:`open_source` with ``stream=True``); ``test=False``: no test split
    needed (the stream comes from elsewhere).  A volumetric dataset streams its error
    parameters, every cycle identified, as ``run`` models them."""
    from ..core.scoring.evaluation import require_split

    ds = open_source(cfg, stream=True)
    train = require_split(ds, "train")
    return ds, train, require_split(ds, "test") if test else [], ds.meta.get("missing", {})


def slashed_time(cfg: DictConfig, ds) -> str | None:
    """The strptime format the record ``data.path`` (``ds`` as read) reads its dates with slashes
    in: ``data.time`` where it is one, else (``auto``) the order every row of its files says or
    their runs settle, as its read took it (:func:`~thermocomp.core.io.slashed.record_order`),
    ``data.dayfirst``'s where it is set (dates85), else the order a catman, Scope View or LabVIEW
    file of the record settled (:func:`~thermocomp.core.io.plain.lab_dayfirst`, data86); None
    where there is none.
    What a stream of the lab's rows reads them in (``monitor.input=-``, the served model, the
    exported ``TC_SLASHED``): a stream cannot see the future (code71)."""
    from ..core.io.contract import ContractError
    from ..core.io.dayfirst import ORDER
    from ..core.io.plain import lab_dayfirst
    from ..core.io.slashed import record_order

    given = str(cfg.data.get("time") or "auto")
    if given != "auto":
        return given if given.startswith(tuple(ORDER.values())) else None
    if ds is None:
        return None

    root = resolve(cfg.data.path)
    files = [root] if root.is_file() else [root / str(f) for f in ds.manifest["file"]]
    opts = io.ReadOptions.from_cfg(data_options(cfg))
    try:
        order = record_order(files, opts)
        if order is None and opts.dayfirst is None and (said := lab_dayfirst(files, opts.encoding)):
            opts = dataclasses.replace(opts, dayfirst=said.day_first)   # (data86) as the read
    except (ContractError, OSError, ValueError):     # (no text file: nothing said by its cells)
        order = None
    if opts.dayfirst is not None and (order is None or order.day_first != opts.dayfirst):
        # (dates85) the key's order, as the reader took it (the shape: each stream's own)
        return f"{ORDER[opts.dayfirst]}%Y %H:%M:%S"
    return None if order is None else order.format


def dataset_digest(cfg: DictConfig) -> str | None:
    """The digest of ``data.path`` (what :func:`open_source` records in ``meta["digest"]``), None
    when it is gone."""
    root = resolve(cfg.data.path)
    return folder_digest(root) if root.exists() else None


def ingest_fingerprint(cfg: DictConfig) -> dict:
    """What an ingest of ``data.path`` depends on (``ingested_with``): the folder's digest and the
    hash of its reading settings (every ``data.*`` reading option as read, the ``calibrate.*``
    keys of a volumetric dataset's parameter series), which are kept beside (``settings``, with
    the folder) to name what changed.  ``ingest`` records it; the stages reading
    ``data.interim`` compare."""
    # (data89) by the keys a user types: a changed one is named so in the refusal
    settings = {f"data.{k}": v
                for k, v in io.ReadOptions.from_cfg(data_options(cfg)).data_keys().items()}
    if is_volumetric(cfg) and cfg.get("calibrate") is not None:
        # a volumetric dataset's parameter series depend on its calibration too (an outside
        # probe's ingest with a prior was evaluated without one: 33 targets, 25 rows, exit 0)
        settings.update({f"calibrate.{k}": v for k, v in calibrate_settings(cfg).items()})
    return {DIGEST: dataset_digest(cfg), CONFIG: json_hash(settings),
            SETTINGS_KEY: plain({"data.path": str(resolve(cfg.data.path)), **settings})}


def load_ingested(cfg: DictConfig):
    """``data.interim`` as ``ingest`` left it, refused when it was ingested from other data (the
    digest of ``data.path``) or with other ``data.*`` reading options: a stage would otherwise
    score a stale dataset under this config's name (an ingest predating the record is read as it
    is, and so is one whose ``data.path`` is gone)."""
    root = resolve(cfg.data.interim)
    ds = io.load_interim(root)
    made = ds.meta["ingest_report"].get("ingested_with")
    if made is not None:
        want = ingest_fingerprint(cfg)
        if want[DIGEST] is None:
            want[DIGEST] = made.get(DIGEST)
        if not matches(made, want):
            raise io.ContractError(f"{_changed(cfg, made, want)}: run `thermocomp ingest` with "
                                   "this config first (or give another name= to keep both)",
                                   file=root / io.INGEST_REPORT)
    resolve_reference(cfg, ds)
    return ds


def _changed(cfg: DictConfig, made: dict, want: dict) -> str:
    """What differs between the ingest ``made`` and the one ``want``ed, said."""
    if CONFIG not in made:
        return "it was ingested by an earlier version (no digest and config hash in ingested_with)"
    was, now = made.get(SETTINGS_KEY) or {}, want[SETTINGS_KEY]
    gone = [k for k in was if k not in now]
    if gone:         # (data89) recorded under names this version no longer records
        return (f"it was ingested by an earlier version, which recorded its settings under "
                f"other names ({', '.join(gone[:4])}{' ...' if len(gone) > 4 else ''}; now "
                "the data config's keys): ingest again, once")
    key = next((k for k in now if was.get(k) != now[k]), None)
    if key is None:
        return f"data.path={cfg.data.path} changed since it was ingested (its files differ)"
    if key not in was:       # a reading option added since: the ingest's code never read it
        return f"it was ingested by an earlier version, which had no {key}"
    return f"it was ingested with {key}={was.get(key)!r}, not {now[key]!r}"


def declared_columns(cfg: DictConfig, ds) -> tuple[list, list]:
    """``(inputs, targets)`` of ``ds`` as ``data.inputs``/``data.targets`` declare them."""
    from ..core.frame import resolve_columns

    targets = cfg.data.get("targets")
    return resolve_columns(ds.columns, list(cfg.data.inputs),
                           None if targets is None else list(targets))


def check_declared(cfg: DictConfig, ds, model: bool = True) -> None:
    """Every campaign of ``ds`` holds every column ``data.inputs``/``data.targets`` declare
    (before anything is fitted): the error names the odd campaign's file; ``model``: and the
    columns the model's config reads (``init`` has none)."""
    from ..core.frame import check_common_columns

    check_former_names(cfg, ds)
    inputs, targets = declared_columns(cfg, ds)
    missing = named_inputs_missing(cfg, ds)
    if missing:
        logger.warning(f"{ds.name}: {missing}")
    headers = {name: raw for raw, name in (ds.meta.get("column_map") or {}).items()}
    starts = ds.manifest["start"].to_dict() if "start" in ds.manifest.columns else None
    check_common_columns(ds.campaigns, inputs + targets, {cid: ds.file_path(cid) for cid in ds.ids()},
                         headers, starts)
    if model:
        check_model_columns(cfg, ds)


def check_former_names(cfg: DictConfig, ds) -> None:
    """(data95) A ``data.inputs`` entry (a stored config's: a run's, ``diagnose``'s refit) that
    names a column by the name an earlier rule derived from a lab's header (``T_Temp_Luft``,
    now ``T_Luft``) is refused saying the name now: it was fitted without that sensor, said
    only as a warning (:func:`named_inputs_missing`), or refused as matching no column."""
    from ..core.io.roles import former_names, former_said

    named = [str(p) for p in list(cfg.data.inputs) if not any(ch in str(p) for ch in "*?[")]
    column_map = ds.meta.get("column_map") or {}
    former = former_names(column_map)
    absent = [p for p in named if p not in ds.columns and p in former]
    if absent:
        raise io.ContractError(f"data.inputs: {former_said(absent, column_map, cfg.data.path)}",
                               file=cfg.data.path, column=absent[0])


def named_inputs_missing(cfg: DictConfig, ds) -> str | None:
    """What to say where a ``data.inputs`` entry names one column (no glob) the data lack: the
    model is fitted without it (a fleet machine without the others' second air sensor was fitted
    on one in silence; a pattern that matches nothing, ``S_*`` on a machine without states, is
    not said)."""
    named = [p for p in list(cfg.data.inputs) if not any(ch in str(p) for ch in "*?[")]
    missing = [p for p in named if p not in ds.columns]
    return (f"data.inputs names {', '.join(missing)}, no column of these data: the model is "
            "fitted without it") if missing else None


# model keys that name one column of the data (ARX+RF's machine state, S_door by default)
COLUMN_KEYS = ("state_column",)


def check_model_columns(cfg: DictConfig, ds) -> None:
    """A column the model's config names is one of the data's, before anything is fitted (a
    machine without a door: ARX+RF's default ``S_door`` was refused after the ARX fit, naming
    the column but not the key)."""
    estimator = cfg.model.get("estimator") or {}
    for key in COLUMN_KEYS:
        column = estimator.get(key)
        if column is not None and column not in ds.columns:
            states = [c for c in ds.columns if c.startswith("S_")]
            raise ConfigError(f"model.estimator.{key}={column!r} is no column of {cfg.data.path} "
                              f"(its S_ columns: {', '.join(states) or 'none'}): name one, or "
                              "null for none")


def check_volumetric_targets(cfg: DictConfig, ds, targets, what: str) -> None:
    """On a volumetric dataset, every parameter ``what`` predicts is one this calibration
    identifies: a model trained with another ``calibrate.*`` (a prior estimates all 33, GLS the
    25 seen) streamed 8 targets as NaN with exit 0 (an outside probe)."""
    if not is_volumetric(cfg):
        return
    missing = [t for t in targets if t not in ds.columns]
    if missing:
        raise ConfigError(f"{what} predicts {', '.join(missing[:5])}"
                          f"{f' and {len(missing) - 5} more' if len(missing) > 5 else ''}, which "
                          f"this calibration of {cfg.data.path} does not identify: calibrate with "
                          "the calibrate.* settings it was trained with (calibrate.prior?)")


def simulated_truth(cfg: DictConfig) -> tuple[Path, dict | None]:
    """``(<data.path>.truth.json, its content)``: None when there is none, or one that is no JSON
    object (said; the truth only adds figures, so a bad one costs them, not the run)."""
    path = Path(f"{resolve(cfg.data.path)}.truth.json")
    if not path.is_file():
        return path, None
    try:
        truth = json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        logger.warning("%s is not readable JSON (%s): no comparison with the truth",
                       path, " ".join(str(exc).split()))
        return path, None
    if not isinstance(truth, dict):
        logger.warning("%s is no JSON object: no comparison with the truth", path)
        return path, None
    return path, truth
