"""What the stages build from the config: the compensator, its denoiser, what is deployed
(``model=auto``'s candidates from :mod:`thermocomp.shell.config.candidates`)."""

from __future__ import annotations

from dataclasses import replace

from omegaconf import DictConfig, OmegaConf
from sklearn.base import clone

from ..base.errors import ConfigError, ContractError, ThermocompError, listed
from ..base.log import logger, say
from ..base.params import check_params, check_values, subset
from ..base.paths import resolve
from ..core.compensator import Compensator
from ..core.continuation import fit_joined
from ..core.models.auto import as_chosen
from ..core.scoring.auto_validation import val_split_scores
from .build import build
from .config import rules
from .config.candidates import build_candidates, is_auto
from .model_store import load_model, model_family
from .source import is_volumetric, reference, slashed_time
from .store import is_registered_model


def auto_scheme(cfg: DictConfig, ds) -> dict:
    """``{"scheme": ...}``: validate as the test split of ``ds`` is held out, unless
    ``model.estimator.scheme`` names one (``{}`` without a dataset)."""
    if ds is None or cfg.model.estimator.get("scheme", "auto") != "auto":
        return {}
    from ..core.scoring.evaluation import holdout_scheme

    return {"scheme": holdout_scheme(ds)}


def build_compensator(cfg: DictConfig, ati: bool = True, ds=None, search: bool = True) -> Compensator:
    """The configured compensator; ``ati=False`` leaves out the ATI wrapper (``ati=cmeans``).
    ``ds``: the dataset it will be fitted on, whose split ``model=auto`` validates like (and,
    with ``model.diagnosed=true`` and ``search``, whose train split the closed loop searches for
    the ``diagnosed`` candidate: :func:`diagnosed_candidate`)."""
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
    if is_auto(cfg) and search and ds is not None and cfg.model.get("diagnosed", False):
        comp.estimator.set_params(candidates={**comp.estimator.candidates,
                                              **diagnosed_candidate(cfg, ds, comp)})
    if is_auto(cfg) and ds is not None and ds.ids("val"):   # chosen on the val split, as validated
        comp.estimator.set_params(val_scores=val_split_scores(comp, ds))
    return comp


def validation_template(cfg: DictConfig, fitted: Compensator, ds) -> Compensator:
    """What a run's validation refits per fold: the configured compensator, with the family
    model=auto chose per target in ``fitted`` (:func:`~.auto.as_chosen`; its ``diagnosed``
    candidate taken from ``fitted``, not searched again); validated like the test split of
    ``ds`` unless a val split scores ``fitted`` itself."""
    return as_chosen(build_compensator(cfg, ds=None if ds.ids("val") else ds, search=False), fitted)


def search_options(dcfg):
    """``diagnose.*`` -> SearchOptions (the ``diagnose`` stage's and ``model.diagnosed``'s); a
    value outside its rule is a ConfigError (exit 2).  Every stage checks
    ``rules.DIAGNOSE_RULES``; the families are the closed loop's (``targets`` is also checked
    against the modelled targets)."""
    from ..apps.diagnose import outputs
    from ..apps.diagnose.features import KINDS

    check_values(dcfg, {**rules.DIAGNOSE_RULES, "families": subset(KINDS)}, "diagnose")
    return outputs.search_options(OmegaConf.to_container(dcfg, resolve=True))


def diagnosed_candidate(cfg: DictConfig, ds, comp: Compensator) -> dict:
    """``{"diagnosed": ForTargets}`` (no model for a target where nothing is accepted; its
    ``about``: :func:`accepted_entry` per target, for ``metrics.json``): per target, MLR with the
    effects and penalty the closed loop accepts on the train split of ``ds``
    (:func:`~thermocomp.apps.diagnose.search_train`, ``diagnose``'s own search and acceptance
    test with its ``diagnose.*`` keys, on ``comp`` -- this run's data, inputs and reference --
    with MLR), validated and voted by auto's folds like any candidate (``model.diagnosed``;
    autodiag99: mt9888 E_X 10.28 -> 3.22 µm).  Sensors the search finds faulty stay in (a
    candidate cannot change the inputs).  The search costs 1.6-78 s per record; ``run`` composes
    no ``diagnose`` group, so it searches with ``conf/diagnose/default.yaml``."""
    from ..apps.diagnose import AugmentedRegressor, search_train
    from ..base.paths import conf_dir
    from ..core.io.own_headers import lab_names
    from ..core.models.auto import BASELINE
    from ..core.models.base import ForTargets
    from .build import load_node
    from .config.candidates import family_estimator

    if ds.ids("val"):
        raise ConfigError("model.diagnosed=true: the val split scores auto's candidates on every "
                          "target alike; the diagnosed candidate is per target (use the folds: "
                          "no val campaigns in the manifest, or model.diagnosed=false)")
    mlr = family_estimator(cfg, BASELINE)
    template = clone(comp).set_params(estimator=mlr)       # ``comp`` (auto) as model=mlr
    # diagnose's keys: the command's own where it composes them, else conf/diagnose/default.yaml
    dcfg = cfg.get("diagnose") or load_node(conf_dir() / "diagnose" / "default.yaml",
                                            cfg.get("seed", 0), "model.diagnosed")
    searched = search_train(ds, template, search_options(dcfg), str(cfg.eval.mode))
    by_target, about = {}, {}
    for target, result in searched.found.items():
        effects = [e.to_dict() for e in result.effects if e.transform != "remove"]
        if effects:
            by_target[target] = AugmentedRegressor(clone(mlr), effects, comp.reference,
                                                   result.alpha or None)
        about[target] = accepted_entry(result, searched.designs[target]["min_p"], lab_names(cfg, ds))
        say(f"model.diagnosed: {target}: "
            + (", ".join(e.title for e in result.effects if e.transform != "remove") or "nothing")
            + " accepted on the train split")
    # kept where nothing is accepted too: metrics.json says so (effects99)
    return {"diagnosed": ForTargets(by_target, about)}


def accepted_entry(result, min_p: float, lab: dict) -> dict:
    """``targets.<t>.auto.diagnosed`` of ``metrics.json`` (effects99): the effects the search
    accepted for one target (``result``, a SearchResult), in acceptance order, named with the
    lab's headers where the record has them (``lab``: ``lab_names``), each with its acceptance
    p (family-wise over its round, as ``diagnosis.json``'s ``p_value_family``) and its own
    sign-flip p; the penalty on the effect features (``alpha``, None: least squares) and the
    smallest p the design's test can give (``min_p``, as ``diagnose`` reports it)."""
    from ..apps.deploy.naming import raw_names

    def named(column):
        return None if column is None else (raw_names(lab, column) or [column])[0]

    accepted = [{"effect": replace(ev.effect, column=named(ev.effect.column),
                                   other=named(ev.effect.other)).title,
                 "p": ev.p_family, "p_value": ev.p_value}
                for ev in result.accepted if ev.effect.transform != "remove"]
    return {"accepted": accepted, "alpha": result.alpha if accepted else None, "min_p": min_p}


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
    check_params(denoiser, "denoise.denoiser")
    return denoiser


def warn_stream_mode(cfg: DictConfig, stage: str) -> None:
    """A deployed compensator predicts from the inputs alone (simulation): ``eval.mode`` is
    said not to apply, rather than silently dropped."""
    if str(cfg.eval.mode) != "simulation":
        logger.warning("%s: eval.mode=%s is not used: the deployed compensator streams its "
                       "correction from the inputs alone (simulation mode, no measured error)",
                       stage, cfg.eval.mode)


def deploy_stream(cfg: DictConfig, comp: Compensator, train: dict, what: str = "the model"):
    """:meth:`StreamingCompensator.from_training` with ``promote.envelope`` (the plain stream
    every deployment starts from); a model that cannot stream is a ConfigError naming ``what``."""
    from ..apps.deploy import StreamingCompensator

    env = cfg.promote.envelope
    try:
        return StreamingCompensator.from_training(comp, train, float(env.margin), str(env.policy),
                                                  bool(env.get("pattern", True)),
                                                  bool(env.get("per_target", False)))
    except ValueError as exc:
        raise ConfigError(f"{what} cannot be deployed: {exc}") from None


def build_adaptive(cfg: DictConfig, streaming, train: dict, ds=None):
    """The :class:`~thermocomp.apps.deploy.AdaptiveCompensator` of the ``monitor`` group around
    ``streaming``: POD, detector limits and correction guard fitted on ``train``, its files that
    continue one another joined as the model was fitted on them (``ds`` given: stranger65, a
    lab's day files of one record were each referenced to their own first sample in the POD and
    the guard, while the stream, warmed on the train days, read the test day against the first
    day's: a healthy bed sensor excluded for the whole test day, replay 3.82 / 1.73 µm against
    run's 3.39 / 1.32)."""
    from ..apps.deploy.adaptive import AdaptiveCompensator  # loaded by the stages that deploy, only
    from ..core.continuation import continue_inside, fit_campaigns

    reference = getattr(streaming.compensator, "reference", "first_sample")
    if ds is not None and reference == "none" and continue_inside(ds, list(train)):
        train = fit_campaigns(ds, train, list(train), reference)

    m = cfg.monitor
    share = m.pod.fit_share
    pod = {"energy": float(m.pod.energy), "modes": m.pod.modes,
           "fit_band_c": None if share is None else float(share) * float(m.bands.warning_c),
           "window": int(m.window), "max_leverage": float(m.pod.max_leverage)}
    options = {"warning_c": float(m.bands.warning_c), "alarm_c": float(m.bands.alarm_c),
               "window": int(m.window), "confirm": int(m.confirm), "adaptive": bool(m.adaptive),
               "exclude_at": str(m.exclude_at), "spread_factor": float(m.bands.spread_factor),
               "new_state": bool(m.new_state.enabled), "new_state_others": int(m.new_state.others),
               **OmegaConf.to_container(m.detectors)}
    try:
        return AdaptiveCompensator.from_training(
            streaming, train, monitor=options, pod=pod,
            guard=OmegaConf.to_container(m.guard), learned_bands=bool(m.bands.learned),
            fallbacks=str(m.get("fallbacks", "unobservable")))
    except ValueError as exc:
        raise ConfigError(f"monitor: {exc}") from None


def deployable(cfg: DictConfig, streaming, train: dict, ds=None):
    """What ``promote`` registers and ``replay`` streams: the adaptive compensator around
    ``streaming`` when ``monitor.adaptive`` (default), else ``streaming`` itself; it reads
    the lab's column names too (:func:`~thermocomp.core.io.own_headers.lab_names`) and learns from
    reference measurements as ``adapt.*`` says (``adapt_``)."""
    from ..apps.deploy.adapt import from_config as adapt_from_config
    from ..apps.deploy.naming import lab_units, raw_names
    from ..core.context import TIME
    from ..core.io.bits import parsed as parsed_bits
    from ..core.io.derived import parsed as parsed_derive
    from ..core.io.own_headers import lab_names

    deployed = build_adaptive(cfg, streaming, train, ds) if bool(cfg.monitor.adaptive) else streaming
    deployed.lab_names_ = lab_names(cfg, ds)
    deployed.lab_units_ = lab_units(ds)    # (the exported stream.c converts these headers)
    deployed.derived_ = parsed_derive(cfg.data.get("derive"))   # a reference's derived targets
    deployed.bits_ = parsed_bits(cfg.data.get("bits"))   # a served block's status word (bits85)
    deployed.slashed_ = slashed_time(cfg, ds)     # a served block's dates read in its order
    deployed.pause_s_ = pause_seconds(cfg, ds)    # a served session's runs, as stream.c's (audit106)
    # (dep108d) plain seconds of the day carried past midnight, as stream.c's TC_DAY_SECONDS
    deployed.day_seconds_ = day_seconds(cfg, ds, raw_names(deployed.lab_names_, TIME))
    deployed.missing_values_ = [str(m) for m in cfg.data.get("missing_values") or ()]   # (-9999)
    # served: every row that carries a measured error is a reference (no schedule)
    deployed.adapt_ = adapt_from_config(cfg.get("adapt"), len(deployed.targets_), scheduled=False)
    return deployed


def pause_seconds(cfg: DictConfig, ds, deployed=None) -> float:
    """``TC_PAUSE_S`` and a served model's ``pause_s_``: with ``data.runs_at_pauses``, the step of
    the time after which the reader starts the next run (:func:`.runs.pause_blocks`: PAUSE_PERIODS
    of the record's period), so that the lab's file of appended tests streams each as the campaign
    it was scored as; without the record read (a registered model), the ``deployed`` model's own
    (audit106: it travels with the model, as its lab's names do); 0 without it."""
    if ds is None:
        return float(getattr(deployed, "pause_s_", 0.0) or 0.0)
    if not cfg.data.get("runs_at_pauses"):
        return 0.0
    from ..core.context import TIME
    from ..core.io.rates import PAUSE_PERIODS
    from ..core.timerule import median_step

    first = next(iter(ds.campaigns.values()))
    return PAUSE_PERIODS * float(median_step(first[TIME].to_numpy(float)) or 0.0)


def day_seconds(cfg: DictConfig, ds, time_headers: list, deployed=None) -> bool:
    """``TC_DAY_SECONDS`` and a served model's ``day_seconds_``: the ``deployed`` model's own (the
    C reads the time as the model serves it, rev109); else ``data.time=of_day``, the record's
    time read as seconds since midnight, a day added as it passed (data89b), or its lab headers
    (a record that never passed midnight; a model pickled before dep108d) say it is the time of
    day; ``stream.c`` and (dep108d) the served model then read plain seconds so (lead91: the C
    took midnight's step back for a clock set back, one period on, and a run after a pause
    across midnight for the run before it; dep108d: served, 2.16 um off)."""
    from ..core.io.timestamps import OF_DAY_KIND, names_day_seconds

    if (said := getattr(deployed, "day_seconds_", None)) is not None:
        return bool(said)
    return str(cfg.data.get("time")) == OF_DAY_KIND or bool(
        ds is not None and ds.meta.get("seconds_of_day")) or names_day_seconds(time_headers)


def is_registered(source) -> bool:
    """Whether a model source (``replay.model``, ``serve.model`` ...) is loaded as registered, a
    pyfunc folder or ``models:/name@alias``, with no data; else it is a model.pkl made deployable
    on the train split (or, ``None``, the configured model fitted there)."""
    return source is not None and (is_registered_model(source)
                                   or (resolve(str(source)) / "MLmodel").is_file())


def deployable_model(cfg: DictConfig, ds, train_ids, source, key: str,
                     loaded=None) -> tuple[object, str, str]:
    """``(deployed compensator, source, model name)`` of ``source`` (the value of ``key``): the
    configured model fitted on ``train_ids`` (``None``), a model.pkl made deployable (``loaded``:
    its compensator, already unpickled by the caller), or a pyfunc folder /
    ``models:/name@alias`` as registered (:func:`is_registered`: ``ds`` is not read)."""
    if source is None:
        say(f"fitting {cfg.model.name} on {len(train_ids)} train campaigns")
        train = {c: ds.campaigns[c] for c in train_ids}
        # fitted as run fits it: train files that continue one another joined
        comp = fit_joined(build_compensator(cfg, ds=ds), ds, train_ids)
        name, source = str(cfg.model.name), "fitted"
        what = "the model"
    else:
        source = str(source)
        if is_registered(source):
            return _registered(cfg, source, None if is_registered_model(source) else resolve(source),
                               key)
        comp = loaded if loaded is not None else load_model(resolve(source))
        name, what = model_family(comp), f"{key}={source}"
        train = {c: ds.campaigns[c] for c in train_ids}
        return deployable(cfg, loaded_stream(cfg, ds, train, comp, what), train, ds), source, name
    return deployable(cfg, deploy_stream(cfg, comp, train, what), train, ds), source, name


def loaded_stream(cfg: DictConfig, ds, train: dict, comp, what: str):
    """The plain stream of a loaded model.pkl made deployable on ``train``, checked in one order
    by every stage given one (``deployable_model``: replay, serve, export, connect; ``monitor``):
    a name an earlier rule derived, then another record's model (said first: names97, monitor
    named a campaign's file where replay said "fitted on another record"), then a train
    campaign lacking an input, by its file."""
    check_model_names(cfg, ds, comp, what)
    foreign = other_record(cfg, ds, comp, what)     # another record's model: say so first
    if not foreign:
        check_model_columns_in(ds, train, comp, what)
    try:
        return deploy_stream(cfg, comp, train, what)
    except ConfigError as exc:
        raise ConfigError(foreign or str(exc)) from None


def other_record(cfg: DictConfig, ds, comp, what: str) -> str:
    """Why a model.pkl cannot be deployed on ``data.path`` where the record lacks every column of
    some it reads: it was fitted on another record (audit96b: ``serve
    serve.model=reports/fl_thermal/model.pkl`` read the default dataset and advised leaving
    ``T_t1`` out of data.inputs); "" where each is in some campaign (a fault of the record).
    Each is named as its lab wrote it where the model carries the lab's names (``lab_names_``,
    a model.pkl of ``run``: names97, ``'t1(°C)' (read as T_t1)``)."""
    from ..core.io.own_headers import named_one

    wanted = [*getattr(comp, "inputs_", ()), *getattr(comp, "targets_", ())]
    absent = [c for c in wanted if c not in ds.columns]
    if not absent:
        return ""
    lab = getattr(comp, "lab_names_", None) or {}
    absent = [named_one(c, lab) if lab.get(c) else c for c in absent]
    return (f"{what} cannot be deployed on data.path={cfg.data.path}: the record has none of "
            f"{listed(absent, 4)}, which the model reads. It was fitted on another record, and a "
            "model.pkl is made deployable on the train split of data.path: give the data config "
            "its run read (data=<name> or data.path=..., as for that run)")


def check_model_names(cfg: DictConfig, ds, comp, what: str) -> None:
    """(data95) A model fitted under a name an earlier rule derived from a lab's header
    (``T_Temp_Luft``, now ``T_Luft``) is refused saying the name now and how to keep the old
    (it was refused as a column the train campaigns lack, the new name unsaid)."""
    from ..core.io.roles import former_said

    absent = [c for c in getattr(comp, "inputs_", ()) if c not in ds.columns]
    said = former_said(absent, ds.meta.get("column_map") or {}, cfg.data.path)
    if said:
        raise ContractError(f"{what}: {said}", file=cfg.data.path)


def check_model_columns_in(ds, train: dict, comp, what: str) -> None:
    """Every train campaign holds every input a loaded model reads (what its stream's envelope is
    built from): else refused naming the odd campaign's file (badin96: the stream's own check,
    :meth:`StreamingCompensator.from_training`'s, named the campaign's id alone)."""
    from ..core.frame import check_common_columns

    headers = {name: raw for raw, name in (ds.meta.get("column_map") or {}).items()}
    try:
        check_common_columns(train, list(getattr(comp, "inputs_", ())),
                             {cid: ds.file_path(cid) for cid in train}, headers)
    except ContractError as exc:
        raise ContractError(f"{what} cannot be deployed: {exc.reason}", file=exc.file,
                            column=exc.column) from None


def _registered(cfg: DictConfig, source: str, path, key: str) -> tuple[object, str, str]:
    """A pyfunc folder or ``models:/name@alias`` loaded as registered."""
    from ..apps.deploy.pyfunc import load_deployed
    from ..apps.deploy.report import plain
    from .tracking import connect

    if path is None:
        connect(cfg, existing=True)   # only a registry model needs the store, read (none created)
    try:
        deployed = load_deployed(source, path)      # replayed as registered
    except ThermocompError:
        raise
    except Exception as exc:
        raise ConfigError(f"{key}={source}: cannot load it "
                          f"({' '.join(str(exc).split())[:200]})") from None
    return deployed, source, model_family(plain(deployed).compensator)


def registered_first(cfg: DictConfig, source, key: str) -> tuple[DictConfig, tuple | None]:
    """``(cfg, loaded)``: a registered ``source`` (:func:`is_registered`; ``key`` where it was
    given) loaded by :func:`deployable_model` before the record is read, and ``cfg`` reading its
    status words as it declares them (:func:`with_model_bits`); ``(cfg, None)`` for any other."""
    if not is_registered(source):
        return cfg, None
    loaded = deployable_model(cfg, None, [], source, key)
    return with_model_bits(cfg, loaded[0], f"{key}={source}"), loaded


def with_model_bits(cfg: DictConfig, deployed, key: str) -> DictConfig:
    """``cfg`` reading the record as the registered model ``deployed`` (``key``: where it was
    given) was fitted: its PLC status words decoded by the declaration it carries (``bits_``,
    bits85) where ``data.bits`` is not given (data86: ``replay`` and ``export`` refused, "give
    data.bits=..."); a ``data.bits`` given that declares otherwise is refused naming both."""
    from ..core.io.bits import parsed as parsed_bits

    carried = getattr(deployed, "bits_", None) or {}
    given = parsed_bits(cfg.data.get("bits"))
    if not carried or given == carried:
        return cfg
    if given:
        raise ConfigError(f"data.bits={_bits_text(given)} is not the declaration {key} was "
                          f"fitted with, data.bits={_bits_text(carried)}: a status word is read "
                          "as the model reads it; leave data.bits out (the model's is read) or "
                          "give the model's")
    say(f"data.bits: the PLC status word(s) decoded as {key} declares them, "
        f"{_bits_text(carried)}")
    cfg = cfg.copy()
    OmegaConf.update(cfg, "data.bits", {w: {int(b): n for b, n in named.items()}
                                        for w, named in carried.items()}, force_add=True)
    return cfg


def _bits_text(bits: dict) -> str:
    return "{" + "; ".join(f"{w}: {{{', '.join(f'{b}: {n}' for b, n in named.items())}}}"
                           for w, named in bits.items()) + "}"
