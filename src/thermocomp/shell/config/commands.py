"""The commands: what each does, reads and writes, and the config groups it composes.

Each command's root config (:func:`register`) is ``conf/config.yaml``'s defaults list cut to the
groups the command reads: ``compare`` composes no model, no monitor.  A key of a group a
command does not read is refused with the groups it does (``cli``).  The usage and each
command's ``--help`` are printed from :data:`COMMANDS`.  Light on purpose: ``--help`` imports it.
"""

from __future__ import annotations

import functools
from pathlib import Path
from typing import NamedTuple


class Command(NamedTuple):
    stage: str            # its function: ``module:function`` of shell/stages, imported on use
    summary: str          # its line in `thermocomp --help`
    what: str
    reads: str
    writes: str
    overrides: str        # its main overrides
    groups: tuple[str, ...]


# What reads a dataset composes: the modelling groups (an experiment sets several of them, and
# the default data.path is the scenario's dataset), calibrate and design (a volumetric dataset;
# calibrate.prior may be '${design.ranges}'), compare and promote (a sweep's table, its objective).
MODELLING = ("data", "sim", "denoise", "select", "model", "ati", "eval", "calibrate", "design",
             "compare", "promote", "experiment")
DEPLOYING = (*MODELLING, "monitor", "adapt")    # the deployed (adaptive) compensator, streamed

# Keys every root config holds (conf/common.yaml) that only these commands read.  Given to a
# command with a model key of its own (`replay.model`, ...) it is said to be ignored
# (`replay model_path=<pkl>` streamed a model fitted anew without a word); not refused, as a
# script may hand every command one list of overrides.
READ_ONLY_BY = {"model_path": ("select", "train", "evaluate")}
MODEL_KEYS = {c: f"{c}.model" for c in ("replay", "monitor", "export", "connect", "serve")}

COMMANDS = {
    "simulate": Command(
        "simulate:simulate",
        "write a dataset from the built-in digital twin (sim=<scenario>)",
        "write a dataset from the built-in digital twin", "conf/sim/<scenario>.yaml",
        "data.path (default data/raw/<scenario>/; -<digest> with a changed sim.generator) "
        "and <data.path>.truth.json",
        "sim=<scenario> seed=<int> data.path=<dir> \"sim.generator.effects=[door]\"", MODELLING),
    "init": Command(
        "init:init",
        "thermocomp init <file-or-folder>: what is detected, the data config that reads it",
        "detect a lab's file (or folder) and write the data config that reads it",
        "<file-or-folder> (data.path)", "<out>/conf/data/<name>.yaml; the `run` command to use",
        "thermocomp init lab.csv [data.roles.error=['ch*']] [data.sample_period_s=15] "
        "[data.test_fraction=0.1] [out=<dir>]", MODELLING),
    "rows": Command(
        "rows:rows",
        "thermocomp rows <file-or-folder>: its rows as stream.c and a served block read them",
        "a lab's file or folder, read with the data config, as the rows the exported code's "
        "stream.c and a served block read (contract names)",
        "<file-or-folder> (data.path) with the data config (data=<name> of init, data.*)",
        "the rows on stdout (CSV: time, T_/S_ columns, a blank line between campaigns)",
        "thermocomp rows EXPORT.csv 'hydra.searchpath=[file://<out>/conf]' data=<name> "
        "[rows.campaigns=[<id>]] [rows.errors=true] > rows.csv", ("data", "sim", "rows")),
    "ingest": Command(
        "ingest:ingest",
        "validate data.path, write Parquet + report to data.interim",
        "validate a dataset folder", "data.path",
        "data.interim (data/interim/<name>/: Parquet + ingest_report.json)",
        "data.path=<dir> data.delimiter=\";\" data.decimal=\",\" data.columns={T0:T_0} "
        "data.split_overrides={K01:test}", MODELLING),
    "denoise": Command(
        "denoise:denoise",
        "denoise the declared inputs (denoise=none|emd) -> data.processed + figures",
        "denoise the declared inputs", "data.interim",
        "data.processed (data/processed/<name>/), <out>/denoise/", "denoise=none|emd", MODELLING),
    "select": Command(
        "select:select",
        "choose the inputs per target (select=...) -> models/<name>/selection.json",
        "choose the inputs per target", "data.interim, data.processed",
        "models/<name>/selection.json, <out>/select/",
        "select=all|pearson|greedy_residual|cluster_grey data.targets=[E_Z]", MODELLING),
    "train": Command(
        "modelling:train",
        "fit the configured model on the train split",
        "fit the configured model on the train split",
        "data.interim (+ the denoise/select outputs when they match)",
        "model_path (models/<name>/model.pkl)", "model=mlr|pcr|arx|arx_rf|lstm|lagbank|hammerstein|auto "
        "select=... ati=none|cmeans denoise=none|emd", MODELLING),
    "evaluate": Command(
        "modelling:evaluate",
        "score it on train/test, write <out>/metrics.json and figures",
        "score the trained model on train/test", "data.interim, model_path",
        "<out>/metrics.json, <out>/headline/<target>.json, <out>/plots/ (PNG + CSV), "
        "<out>/volumetric/ (a volumetric dataset)",
        "eval.mode=simulation|one_step plots=summary|test|all|none", MODELLING),
    "diagnose": Command(
        "diagnose:diagnose",
        "closed loop: CV residual -> missing effect -> refit -> before/after (<out>/diagnosis.json)",
        "residual -> missing effect -> refit -> before/after", "data.path",
        "<out>/diagnosis.json, <out>/diagnosis_headline/<target>.json, <out>/diagnosis/",
        "model=... diagnose.targets=[E_Z] plots=none", (*DEPLOYING, "diagnose")),
    "run": Command(
        "modelling:run",
        "ingest .. evaluate in one process; -m for a sweep (one MLflow parent run)",
        "ingest .. evaluate in one process; -m for a sweep", "data.path",
        "<out>/: model.pkl, ingest_report.json, metrics.json, headline/, plots/ "
        "(data.group_by: metrics.json, fleet.csv, models/<group>.pkl)",
        "data.path=<dir> model=... select=... eval.mode=... out=<dir>; "
        "-m model=mlr,pcr select=all,pearson", MODELLING),
    "compare": Command(
        "compare:compare",
        "table of a sweep's child runs, best first (compare.sweep=, compare.sort_by=)",
        "table of a sweep's child runs, best first", "the sweep's MLflow runs",
        "compare.out (default: the sweep's folder): compare.csv, compare.md, compare.json",
        "compare.sweep=<dir|run id> compare.sort_by=val_rmse compare.target=E_Z",
        ("data", "sim", "eval", "compare")),  # data.path: no stage writes into it (eval: FAST lists)
    "promote": Command(
        "promote:promote",
        "register the best run's compensator; move @champion only if it is better",
        "register the best run's compensator, move @champion if better",
        "the sweep's MLflow runs, data.path (the stream is checked on its train campaigns)",
        "the MLflow model registry, <out>/promote.json",
        "promote.* (conf/promote/); monitor.adaptive=false registers the plain stream", DEPLOYING),
    "replay": Command(
        "replay:replay",
        "stream the test campaigns row by row through the deployable compensator (replay.json)",
        "stream the test campaigns row by row through the deployable compensator",
        "data.path and a fitted or registered model", "<out>/replay.json",
        "replay.model=<path|models:/name@alias> monitor.adaptive=false (the plain stream)",
        (*DEPLOYING, "replay")),
    "export": Command(
        "export:export",
        "the deployed compensator as code: json, C + stream.c, Structured Text (export.*)",
        "the deployed compensator as coefficients and code a CNC runs",
        "export.model (a model.pkl with data.path, a pyfunc folder, models:/name@alias)",
        "<out>/compensator.json (+ compensator.h/.c, stream.c | compensator.st)",
        "export.model=models:/thermocomp-compensator@champion export.format=c|st|json",
        (*DEPLOYING, "export")),
    "serve": Command(
        "serve:serve",
        "the registered compensator over HTTP (serve.model=, serve.port=; one worker)",
        "the registered compensator over HTTP (MLflow's scoring server, one worker)",
        "serve.model from the tracking store, a pyfunc folder, or a run's model.pkl (with data.path)",
        "nothing (answers POST /invocations)",
        "serve.model=models:/thermocomp-compensator@champion serve.port=5001 serve.host=127.0.0.1",
        (*DEPLOYING, "serve")),     # a run's model.pkl is made deployable on data.path's train split
    "twin": Command(
        "twin:twin",
        "a virtual machine over OPC UA serving the test campaigns (twin.port=, twin.speed=)",
        "a virtual machine tool over OPC UA serving the test campaigns of data.path",
        "data.path (its test campaigns)", "an OPC UA server (connect.nodes), <out>/twin.json",
        "twin.port=4840 twin.speed=10 twin.campaigns=[K03] twin.drops=[[20,15]] "
        "twin.restarts=[[80,10]]",
        (*DEPLOYING, "twin", "connect")),
    "connect": Command(
        "connect:connect",
        "the deployed compensator as an OPC UA client of a machine (connect.endpoint=)",
        "the deployed compensator as an OPC UA client: bounded offsets to a machine",
        "connect.model (null: fitted on data.path's train split) and connect.endpoint",
        "offsets on the machine's nodes, <out>/connect.json",
        "connect.endpoint=opc.tcp://127.0.0.1:4840 connect.model=models:/name@alias "
        "connect.hold_s=5 connect.decay_s=10 adapt.method=bias", (*DEPLOYING, "connect")),
    "monitor": Command(
        "monitor:monitor",
        "stream test campaigns (or stdin) through the fixed and the fault-tolerant\n"
        "             compensator: sensor events, RMSE of both (<out>/monitor.json)",
        "sensor surveillance (POD self-prediction) + fault-tolerant compensation, streamed",
        "data.path (or CSV rows on stdin: monitor.input=-) and a fitted model",
        "<out>/monitor.json, <out>/monitor/ (figures)",
        "monitor.adaptive=true monitor.bands.warning_c=0.4 monitor.pod.energy=0.99", DEPLOYING),
    "calibrate": Command(
        "calibrate:calibrate",
        "artefact distances of a volumetric dataset -> error parameter series (calibration.json)",
        "artefact distances -> geometric error parameters per measurement cycle",
        "data.path (a volumetric dataset: volumetric.json + E_<pose>_B<i>_B<j> columns)",
        "<out>/calibration.json, calibrate.dataset (default <out>/parameters/)",
        "calibrate.outlier_z=6 calibrate.column_share=0.5 calibrate.require_seen=[]", MODELLING),
    "design": Command(
        "design:design",
        "Monte Carlo study of artefact calibration strategies (<out>/design.json)",
        "Monte Carlo study of artefact calibration strategies (paper 001)",
        "data.path/volumetric.json when present (else the kinematic model defaults)",
        "<out>/design.json, <out>/design/ (figures)",
        "design.n_machines=200 design.n_jobs=-1 design.ranges.angular=6 design.machine.order=4",
        MODELLING),
}


def root_name(command: str) -> str:
    """The name of ``command``'s root config (in Hydra's ConfigStore, see :func:`register`)."""
    return f"thermocomp_{command}"


def register(command: str | None) -> None:
    """``command``'s root config in Hydra's ConfigStore, and no other command's (None: none):
    Hydra deep-copies the whole store at each compose, ~1.5 ms of CPU a root (all 19: a fifth
    of a compose)."""
    from hydra.core.config_store import ConfigStore

    from ...base.paths import conf_dir

    name, repo = command and f"{root_name(command)}.yaml", ConfigStore.instance().repo
    for other in [n for n in repo if n.startswith(root_name("")) and n != name]:
        del repo[other]
    if command is not None and name not in repo:
        ConfigStore.instance().store(name=root_name(command),
                                     node={"defaults": _root_defaults(str(conf_dir()), command)})


@functools.cache
def _root_defaults(conf: str, command: str) -> list:
    """``conf/config.yaml``'s defaults list (its options are the defaults) with only the groups
    ``command`` reads."""
    import yaml

    whole = yaml.safe_load((Path(conf) / "config.yaml").read_text())["defaults"]
    return [d for d in whole if not isinstance(d, dict) or next(iter(d)) in COMMANDS[command].groups
            or next(iter(d)).startswith("override hydra/")]


def groups_of(command: str) -> tuple[str, ...]:
    return COMMANDS[command].groups
