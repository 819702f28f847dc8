"""The exported C as the benches build and feed it: compiled as a control's build would
(warnings as errors), rows piped through ``stream.c``, and the pooled error after correction."""

from __future__ import annotations

import io
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd


def built(folder: Path, files: dict) -> Path:
    """``files`` (name -> text) written into ``folder`` and compiled: the ``stream`` program."""
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "compensator.c",
                    "stream.c", "-lm", "-o", "stream"], cwd=folder, check=True, capture_output=True)
    return folder / "stream"


def streamed(binary: Path, frame: pd.DataFrame) -> np.ndarray:
    """The corrections ``binary`` prints for the rows of ``frame`` (it must take them all)."""
    text = frame.to_csv(index=False, float_format="%.17g")
    run = subprocess.run([str(binary)], input=text, text=True, capture_output=True, check=True)
    return pd.read_csv(io.StringIO(run.stdout)).to_numpy(float)


def rmse(errors: list, corrections: list) -> np.ndarray:
    """Per target, the RMS of the errors after their corrections, pooled over the campaigns."""
    r = np.vstack([e + c for e, c in zip(errors, corrections)])
    return np.sqrt(np.mean(r ** 2, axis=0))


def deployed_on(data: Path, model: str, overrides: tuple = ()) -> tuple:
    """``data``'s record read as ``run`` reads it and ``model=<model>`` fitted on its train
    campaigns, deployed as ``promote`` deploys it (the stream warmed on the train record):
    ``(deployed, ds, test_ids)``; ``overrides``: more of the config's (``key=value``)."""
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
    from thermocomp.shell.source import read_streamed

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config",
                      overrides=[f"data.path={data}", "track=false", f"model={model}",
                                 *overrides])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {k: ds.campaigns[k] for k in train_ids}
    deployed = deployable(cfg, deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train),
                          train, ds)
    return deployed, ds, test_ids


def built_without_monitor(folder: Path, deployed) -> Path:
    """The exported C of ``deployed`` without its sensor monitor (the plain state space, the same
    driver), compiled: the ``stream`` program."""
    from thermocomp.apps.deploy.export import c, state_space
    from thermocomp.apps.deploy.export.driver import DRIVER

    plain = state_space(deployed)
    return built(folder, {"compensator.h": c.header(plain), "compensator.c": c.source(plain),
                          "stream.c": DRIVER})
