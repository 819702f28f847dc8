"""Helpers shared by the stages: config checks, model files, progress, the result table."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

from omegaconf import DictConfig, OmegaConf, open_dict

from ...base.errors import ConfigError
from ...base.log import logger, say
from ...base.paths import resolve
from ...core import io
from ...core.compensator import Compensator
from ...core.continuation import carried_text
from ..build import build
from ..config.checks import _check_writable, check_component, check_config, data_options  # noqa: F401
from ..config.rules import AUTO_REFERENCE, check_keys  # noqa: F401  (re-exported to the stages)
from ..model_store import load_model, model_family
from .auto import as_chosen, auto_scheme, build_candidates, is_auto, val_split_scores


def build_compensator(cfg: DictConfig, ati: bool = True, ds=None) -> Compensator:
    """The configured compensator; ``ati=False`` leaves out the ATI wrapper (``ati=cmeans``).
    ``ds``: the dataset it will be fitted on, whose split ``model=auto`` validates like."""
    estimator = build(cfg.model.estimator, "model.estimator")
    if is_auto(cfg):           # model=auto: the families it chooses among, from their configs
        estimator = estimator(candidates=build_candidates(cfg), **auto_scheme(cfg, ds))
    if ati and cfg.get("ati") is not None and cfg.ati.estimator is not None:
        estimator = build(cfg.ati.estimator, "ati.estimator")(base_estimator=estimator)
    comp = Compensator(
        estimator=estimator,
        selector=build(cfg.select.selector, "select.selector"),
        inputs=list(cfg.data.inputs),
        targets=None if cfg.data.targets is None else list(cfg.data.targets),
        reference=reference(cfg),
        denoiser=build_denoiser(cfg),
        offsets="drop" if identified_targets(cfg) else "predict",
    )
    if is_auto(cfg) and ds is not None and ds.ids("val"):   # chosen on the val split, as validated
        comp.estimator.set_params(val_scores=val_split_scores(comp, ds))
    return comp


def validation_template(cfg: DictConfig, fitted: Compensator, ds) -> Compensator:
    """What a run's validation refits per fold: the configured compensator, with the family
    model=auto chose per target in ``fitted`` (:func:`~.auto.as_chosen`); validated like the
    test split of ``ds`` unless a val split scores ``fitted`` itself."""
    return as_chosen(build_compensator(cfg, ds=None if ds.ids("val") else ds), fitted)


def is_volumetric(cfg: DictConfig) -> bool:
    """``data.path`` is a volumetric dataset (``volumetric.json`` in it)."""
    from ...apps.volumetric import SETUP_FILE

    return (resolve(cfg.data.path) / SETUP_FILE).is_file()


def identified_targets(cfg: DictConfig) -> bool:
    """The targets are error parameters identified from a volumetric dataset, each referenced to
    its first cycle: that cycle's identification error is on every row of the campaign, and a
    fitted intercept learns it (:class:`~thermocomp.core.compensator.Compensator`, ``offsets``).
    On probe data (an aligned 7-ball bar, E_XX1 u = 13.4 µm) predicting it raised the VCE from
    11.0 to 44.1 µm; with the intercept left out, 4.5 µm."""
    return reference(cfg) == "first_sample" and is_volumetric(cfg)


def build_denoiser(cfg: DictConfig):
    """The configured input denoiser (``denoise=emd``), or None (``denoise=none``)."""
    den = cfg.get("denoise")
    if den is None or den.get("denoiser") is None:
        return None
    denoiser = build(den.denoiser, "denoise.denoiser")
    check_component(denoiser, "denoise.denoiser")
    return denoiser


def check_replaceable(cfg: DictConfig, key: str, marker: str) -> None:
    """The folder of ``key`` is replaced whole by the stage: a non-empty one that no earlier run
    of it wrote (no ``marker`` in it) is refused before any work.  An ingest once deleted a
    folder of the user's given as ``data.interim``, and with ``name=`` (empty) all of
    ``data/interim/``."""
    folder = resolve(str(OmegaConf.select(cfg, key)))
    if folder.is_dir() and any(folder.iterdir()) and not (folder / marker).is_file():
        raise ConfigError(f"{key}: {folder} is not empty and holds no {marker}, so this stage did "
                          "not write it; it would be replaced whole: give an empty or new folder")


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


def ingest_settings(cfg: DictConfig) -> dict:
    """What an ingest of ``data.path`` depends on: the folder and every reading option (as JSON
    holds them).  ``ingest`` records it; the stages reading ``data.interim`` compare."""
    opts = dataclasses.asdict(io.ReadOptions.from_cfg(data_options(cfg)))
    opts.pop("missing")      # internal: no data config key
    made = {"path": str(resolve(cfg.data.path)), **opts}
    if is_volumetric(cfg) and cfg.get("calibrate") is not None:
        # a volumetric dataset's parameter series depend on its calibration too (an outside
        # probe's ingest with a prior was evaluated without one: 33 targets, 25 rows, exit 0)
        c = OmegaConf.to_container(cfg.calibrate, resolve=True)
        made.update({f"calibrate.{k}": c.get(k) for k in ("outlier_z", "column_share",
                                                           "require_seen", "prior")})
    return json.loads(json.dumps(made, default=str))


def reference(cfg: DictConfig) -> str:
    """``data.reference`` as resolved by :func:`resolve_reference`; ``auto`` before the data are
    read (a library caller building from the config alone) is the contract's ``first_sample``."""
    given = str(cfg.data.reference)
    return "first_sample" if given == AUTO_REFERENCE else given


def resolve_reference(cfg: DictConfig, ds) -> str:
    """``data.reference=auto`` made ``none`` where a test or val campaign of ``ds`` continues
    another (its state is carried over, :mod:`thermocomp.core.continuation`), else ``first_sample``;
    said in one line.  An explicit ``first_sample`` there is warned about: each part restarts."""
    from ...core.continuation import predecessors

    links = predecessors(ds)
    scored = [c for c in ds.ids() if c in links and ds.manifest.loc[c, "split"] in ("test", "val")]
    given = cfg.data.reference
    if given == AUTO_REFERENCE:
        resolved = "none" if scored else "first_sample"
        why = (f"{scored[0]} continues {links[scored[0]]}: its state is carried over" if scored
               else "no test or val campaign continues another")
        say(f"data.reference=auto: {resolved} ({why})")
        with open_dict(cfg):
            cfg.data.reference = resolved
    elif given == "first_sample" and scored:
        logger.warning(f"data.reference=first_sample: {scored[0]} continues {links[scored[0]]}, "
                       "but each campaign restarts at its own first sample, no state carried "
                       "over (data.reference=none or auto carries it)")
    return cfg.data.reference


def load_ingested(cfg: DictConfig):
    """``data.interim`` as ``ingest`` left it, refused when it was ingested from another
    ``data.path`` or with other ``data.*`` reading options: a stage would otherwise score a
    stale dataset under this config's name (an ingest predating the record is read as it is)."""
    root = resolve(cfg.data.interim)
    ds = io.load_interim(root)
    made = ds.meta["ingest_report"].get("ingested_with")
    if made is not None:
        want = ingest_settings(cfg)
        # calibrate.*: recorded since a later version; an earlier ingest is read as it is
        key = next((k for k in want if made.get(k) != want[k]
                    and (k in made or not k.startswith("calibrate."))), None)
        if key is not None:
            name = key if key.startswith("calibrate.") else f"data.{key}"
            raise io.ContractError(
                f"it was ingested with {name}={made.get(key)!r}, not {want[key]!r}: run "
                "`thermocomp ingest` with this config first (or give another name= to keep both)",
                file=root / io.INGEST_REPORT)
    resolve_reference(cfg, ds)
    return ds


def check_declared(cfg: DictConfig, ds) -> None:
    """Every campaign of ``ds`` holds every column ``data.inputs``/``data.targets`` declare
    (before anything is fitted): the error names the odd campaign's file."""
    from ...core.frame import check_common_columns, resolve_columns

    targets = cfg.data.get("targets")
    inputs, targets = resolve_columns(ds.columns, list(cfg.data.inputs),
                                      None if targets is None else list(targets))
    check_common_columns(ds.campaigns, inputs + targets, {cid: ds.file_path(cid) for cid in ds.ids()})


def check_streamed_columns(ds, ids, columns, what: str) -> None:
    """Every campaign ``ids`` of ``ds`` holds every column ``what`` reads: else a ContractError
    naming the first campaign's file and column that lack."""
    for cid in ids:
        absent = [c for c in columns if c not in ds.campaigns[cid].columns]
        if absent:
            raise io.ContractError(f"test campaign {cid} lacks a column {what} reads",
                                   file=ds.file_path(cid), column=",".join(absent))


def warn_stream_mode(cfg: DictConfig, stage: str) -> None:
    """A deployed compensator predicts from the inputs alone (simulation): ``eval.mode`` is
    said not to apply, rather than silently dropped."""
    if str(cfg.eval.mode) != "simulation":
        logger.warning("%s: eval.mode=%s is not used: the deployed compensator streams its "
                       "correction from the inputs alone (simulation mode, no measured error)",
                       stage, cfg.eval.mode)


def read_streamed(cfg: DictConfig, test: bool = True):
    """``(dataset, train ids, test ids, missing cells per test campaign)`` of ``data.path`` as a
    stream sees it.

    Test campaigns are read as recorded (``missing="keep"``: a dropout streams as NaN);
    train campaigns as ``run`` reads them (gaps repaired within ``data.max_gap_samples`` /
    ``data.max_edge_samples``, else refused naming campaign, column and row), since the
    models and the sensor monitor are fitted on complete records.  ``test=False``: no
    test split needed (the stream comes from elsewhere).  A volumetric dataset is calibrated
    as ``run`` calibrates it: the streamed targets are its error parameters, every cycle
    identified (repaired as ``run`` repairs it).
    """
    from ...core.scoring.evaluation import require_split

    root = resolve(cfg.data.path)
    say(f"reading {root}")
    volumetric = volumetric_calibration(cfg)
    if volumetric is not None:    # its E_ columns are distances: stream the parameters, as `run` models them
        ds = volumetric[0]
        resolve_reference(cfg, ds)
        return ds, require_split(ds, "train"), require_split(ds, "test") if test else [], {}
    ds, report = io.read_dataset(root, data_options(cfg), missing="keep")
    resolve_reference(cfg, ds)
    train_ids = require_split(ds, "train")
    test_ids = require_split(ds, "test") if test else []
    hot = io.ReadOptions.from_cfg(data_options(cfg)).kelvin_threshold_c
    for cid in train_ids:
        df = ds.campaigns[cid]
        faulty = any(df[c].max() > hot for c in df.columns if c.startswith("T_"))
        if report["campaigns"][cid].get("missing") or faulty:   # read as `run` reads it
            try:
                table, _ = io.read_campaign(root / ds.manifest.loc[cid, "file"], data_options(cfg))
            except io.ContractError as exc:
                raise io.ContractError(f"train campaign {cid}: {exc.reason} (models and the sensor "
                                       "monitor are fitted on complete train records)",
                                       file=exc.file, column=exc.column, row=exc.row) from None
            ds.campaigns[cid] = table.to_pandas(split_blocks=True)
    missing = {c: report["campaigns"][c]["missing"] for c in test_ids
               if report["campaigns"][c].get("missing")}
    return ds, train_ids, test_ids, missing


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


def deploy_stream(cfg: DictConfig, comp: Compensator, train: dict, what: str = "the model"):
    """:meth:`StreamingCompensator.from_training` with ``promote.envelope`` (the plain stream
    every deployment starts from); a model that cannot stream is a ConfigError naming ``what``."""
    from ...apps.deploy import StreamingCompensator

    env = cfg.promote.envelope
    try:
        return StreamingCompensator.from_training(comp, train, float(env.margin), str(env.policy))
    except ValueError as exc:
        raise ConfigError(f"{what} cannot be deployed: {exc}") from None


def build_adaptive(cfg: DictConfig, streaming, train: dict):
    """The :class:`~thermocomp.apps.deploy.AdaptiveCompensator` of the ``monitor`` group around
    ``streaming``: POD, detector limits and correction guard fitted on ``train``."""
    from ...apps.deploy.adaptive import AdaptiveCompensator  # loaded by the stages that deploy, only

    m = cfg.monitor
    share = m.pod.fit_share
    pod = {"energy": float(m.pod.energy), "modes": m.pod.modes,
           "fit_band_c": None if share is None else float(share) * float(m.bands.warning_c),
           "window": int(m.window), "max_leverage": float(m.pod.max_leverage)}
    options = {"warning_c": float(m.bands.warning_c), "alarm_c": float(m.bands.alarm_c),
               "window": int(m.window), "confirm": int(m.confirm), "adaptive": bool(m.adaptive),
               "exclude_at": str(m.exclude_at), "spread_factor": float(m.bands.spread_factor),
               **OmegaConf.to_container(m.detectors)}
    try:
        return AdaptiveCompensator.from_training(
            streaming, train, monitor=options, pod=pod,
            guard=OmegaConf.to_container(m.guard), learned_bands=bool(m.bands.learned))
    except ValueError as exc:
        raise ConfigError(f"monitor: {exc}") from None


def lead_ins(comp: Compensator, ds, ids) -> dict:
    """``{campaign: lead-in}`` for the campaigns of ``ids`` that continue others: their stream
    is warmed on their predecessors (unscored) so that it predicts what ``run`` scores
    (:func:`thermocomp.core.continuation.carry_over`, :func:`~thermocomp.core.continuation.lead_in`);
    says which."""
    from ...core.continuation import carry_over, lead_in

    carried = {c: chain for c, chain in carry_over(comp, ds).items() if c in ids}
    if carried:
        say("stream warmed on the campaigns it continues (state carried over, unscored): "
            + carried_text(carried))
    return {c: lead_in(ds, chain) for c, chain in carried.items()}


def deployable(cfg: DictConfig, streaming, train: dict, ds=None):
    """What ``promote`` registers and ``replay`` streams: the adaptive compensator around
    ``streaming`` when ``monitor.adaptive`` (default), else ``streaming`` itself; it reads
    the lab's column names too (:func:`~thermocomp.apps.deploy.naming.lab_names`) and learns from
    reference measurements as ``adapt.*`` says (``adapt_``)."""
    from ...apps.deploy.adapt import from_config as adapt_from_config
    from ...apps.deploy.naming import lab_names

    deployed = build_adaptive(cfg, streaming, train) if bool(cfg.monitor.adaptive) else streaming
    deployed.lab_names_ = lab_names(cfg, ds)
    # served: every row that carries a measured error is a reference (no schedule)
    deployed.adapt_ = adapt_from_config(cfg.get("adapt"), len(deployed.targets_), scheduled=False)
    return deployed


def deployable_model(cfg: DictConfig, ds, train_ids, source, key: str) -> tuple[object, str, str]:
    """``(deployed compensator, source, model name)`` of ``source`` (the value of ``key``): the
    configured model fitted on ``train_ids`` (``None``), a model.pkl made deployable, or a pyfunc
    folder / ``models:/name@alias`` as registered (``replay``, ``connect``)."""
    if source is None:
        say(f"fitting {cfg.model.name} on {len(train_ids)} train campaigns")
        train = {c: ds.campaigns[c] for c in train_ids}
        comp, name, source = build_compensator(cfg, ds=ds).fit(train), str(cfg.model.name), "fitted"
    else:
        source = str(source)
        path = resolve(source) if not source.startswith("models:/") else None
        if path is None or (path / "MLmodel").is_file():
            from ...apps.deploy.pyfunc import load_deployed
            from ...apps.deploy.report import plain
            from ..tracking import connect

            if path is None:
                connect(cfg)     # only a registry model needs the store (track=false writes none)
            try:
                deployed = load_deployed(source, path)      # replayed as registered
            except io.ContractError:
                raise
            except Exception as exc:
                raise ConfigError(f"{key}={source}: cannot load it "
                                  f"({' '.join(str(exc).split())[:200]})") from None
            return deployed, source, model_family(plain(deployed).compensator)
        comp = load_model(path)
        name = model_family(comp)
        train = {c: ds.campaigns[c] for c in train_ids}
    return deployable(cfg, deploy_stream(cfg, comp, train), train, ds), source, name


def calibrated_dataset(cfg: DictConfig):
    """``volumetric.calibration.calibrate_folder`` of ``data.path`` with the ``calibrate.*``
    settings (the caller has checked them: :func:`check_calibrate`): what ``calibrate``
    writes and ``run`` models."""
    from ...apps.sim.scenario import single_threaded_blas
    from ...apps.volumetric.calibration import calibrate_folder

    c = cfg.calibrate
    with single_threaded_blas():      # 1430-wide matrices: threads on 2 busy cores only thrash
        return calibrate_folder(resolve(cfg.data.path), data_options(cfg), c.outlier_z,
                                c.column_share, c.get("require_seen"), calibration_prior(c))


def calibration_prior(c: DictConfig) -> dict | None:
    """``calibrate.prior`` as a plain mapping (its interpolations resolved), or None."""
    return None if c.get("prior") is None else OmegaConf.to_container(c.prior, resolve=True)


def volumetric_calibration(cfg: DictConfig):
    """:func:`calibrated_dataset` when ``data.path`` is a volumetric dataset (``volumetric.json``
    in it; ``calibrate.*`` checked by ``check_config``), else None: how ``ingest`` and ``run`` read one."""
    if not is_volumetric(cfg):
        return None
    say("volumetric dataset: calibrating the artefact distances into the error parameters")
    return calibrated_dataset(cfg)


def volumetric_source(cfg: DictConfig):
    """``(distance dataset, calibration)`` when ``data.path`` is a volumetric dataset, else None:
    what ``evaluate`` validates the parameter models against (``ingest`` calibrated the same
    folder into ``data.interim``; the calibration's model is fitted again, not its cycles)."""
    from ...apps.volumetric import ArtefactCalibration
    from ...apps.volumetric.series import check_columns, load_setup

    if not is_volumetric(cfg):
        return None
    root = resolve(cfg.data.path)
    setup = load_setup(root)
    raw, _ = io.read_dataset(root, data_options(cfg), missing="keep_errors")   # as calibrate reads it
    check_columns(raw, setup)
    from ...apps.volumetric.calibration import prior_sd

    return raw, ArtefactCalibration(setup, outlier_z=float(cfg.calibrate.outlier_z),
                                    prior_sd=prior_sd(setup.model, calibration_prior(cfg.calibrate))).fit()
