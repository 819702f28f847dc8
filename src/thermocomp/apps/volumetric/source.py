"""A volumetric folder opened as a dataset: its distances calibrated once into the parameter series.

A volumetric dataset (``volumetric.json`` beside the distance columns) is read through the one
reader (:func:`~thermocomp.core.io.read_dataset`), then every cycle is identified
(:func:`~.calibration.calibrate_folder`): the stages model the parameter series like any dataset.
The calibration stays in the dataset's ``meta`` (``calibration``: the report of
``calibration.json``; ``calibrator``: the fitted :class:`~.identify.ArtefactCalibration`;
``distances``: the distance dataset it was identified from), and the result is cached by the
folder's digest and the settings, so a process opening it again does not calibrate again.
"""

from __future__ import annotations

import dataclasses
import json
import logging
from collections.abc import Mapping
from pathlib import Path

from ...base.files import folder_digest
from ...base.log import logger
from ...core import io
from .artefact import SETUP_FILE
from .calibration import calibrate_folder, fitted, prior_sd
from .identify import ArtefactCalibration
from .series import check_columns, load_setup

# the calibrate.* settings a parameter series depends on (calibrate.format: how it is written)
SETTINGS = ("outlier_z", "column_share", "require_seen", "prior")
_CACHE: dict[tuple, tuple[io.Dataset, list]] = {}   # and the log records it made
_CACHED = 2      # datasets kept: a fleet's or a test's, not every folder a process ever read


def is_volumetric(root: str | Path) -> bool:
    """``root`` is a volumetric dataset (``volumetric.json`` in it)."""
    return (Path(root) / SETUP_FILE).is_file()


def open_volumetric(root: str | Path, options: Mapping | None, settings: Mapping) -> io.Dataset:
    """The parameter series of the volumetric dataset in ``root`` (``options``: the ``data``
    options; ``settings``: the ``calibrate.*`` keys of :data:`SETTINGS`)."""
    digest = folder_digest(root)
    read = dataclasses.asdict(io.ReadOptions.from_cfg(options))    # not where the stages write
    key = (digest, json.dumps(read, sort_keys=True, default=str),
           json.dumps({k: settings.get(k) for k in SETTINGS}, sort_keys=True, default=str))
    if key in _CACHE:
        ds, said = _CACHE[key]
        for record in said:      # what the calibration said (its warnings) is said again
            logger.handle(record)
    else:
        said = []
        keep = logging.Handler()
        keep.emit = said.append
        logger.addHandler(keep)
        try:
            ds, cal, report, raw = calibrate_folder(
                Path(root), options, settings["outlier_z"], settings["column_share"],
                settings.get("require_seen"), settings.get("prior"))
        finally:
            logger.removeHandler(keep)
        ds.meta.update(digest=digest, calibration=report, calibrator=cal, distances=raw)
        while len(_CACHE) >= _CACHED:
            _CACHE.pop(next(iter(_CACHE)))
        _CACHE[key] = ds, said
    # a copy a caller may change (campaigns, meta) without touching the cache
    return io.Dataset(ds.manifest.copy(), dict(ds.campaigns), ds.name, dict(ds.meta))


def open_distances(root: str | Path, options: Mapping | None, outlier_z: float,
                   prior: Mapping | None) -> tuple[io.Dataset, ArtefactCalibration]:
    """``(distance dataset, calibration)`` of ``root`` without identifying its cycles: what
    ``evaluate`` validates the parameter models of an ingested series against."""
    setup = load_setup(Path(root))
    raw, _ = io.read_dataset(root, options, missing="keep_errors")   # as calibrate reads it
    check_columns(raw, setup)
    return raw, fitted(setup, outlier_z, prior_sd(setup.model, prior))


def ingest_series(params: io.Dataset, dest, extra: dict, finish=None) -> dict:
    """:func:`~thermocomp.core.io.ingest` of the parameter series ``params`` (opened by
    :func:`open_volumetric`) into ``dest``: written, then read back through the one validating
    reader (its splits and names are already the configured ones: no data option applies
    twice); the report holds the calibration, and the repairs made reading the distances."""
    import tempfile

    calibration = params.meta["calibration"]
    with tempfile.TemporaryDirectory(prefix="thermocomp-params-") as tmp:
        name = params.meta["distances"].name or "parameters"
        folder = io.write_dataset(params, f"{tmp}/{name}", "parquet")
        return io.ingest(folder, dest, extra={"calibration": calibration,
                                              "repairs": calibration["repairs"], **extra},
                         finish=finish)
