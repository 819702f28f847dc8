"""Hostile numbers: NaN, infinities and absurd sizes in any config knob, a signature file with
no end, lags longer than the data, another axis's error as an input, more IMFs than a signal
has.  Each is refused in one line (exit 2) before any work, or warned about; nothing is left
behind.

The meta-tests walk every config group's yaml: each number a user can set must be covered by a
rule that refuses NaN and ±inf (and, for a count, a size no machine can hold), checked by every
stage -- a knob without a rule, or checked only by its own stage, cannot come back unnoticed.
"""

from __future__ import annotations

import functools
import math
import shutil
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hydra import compose, initialize_config_dir
from hydra.errors import InstantiationException
from hydra.utils import instantiate
from omegaconf import OmegaConf

from conftest import refused
from thermocomp.base.errors import ThermocompError
from thermocomp.base.params import check_params
from thermocomp.base.paths import conf_dir
from thermocomp.shell.cli import _config_errors, main

# Documented as a value that switches a check off (docs/cli.md): accepted on purpose.
OFF_VALUES = {("calibrate.outlier_z", math.inf)}
HUGE = 10 ** 15          # a count no machine holds in memory nor loops over in a lifetime


def _options() -> list[list[str]]:
    """One override list per option of every config group (the default composition first)."""
    found = [[]]
    for group in sorted(p for p in Path(conf_dir()).iterdir() if p.is_dir() and p.name != "hydra"):
        found += [[f"{group.name}={option.stem}"] for option in sorted(group.glob("*.yaml"))]
    return found


def _numbers(node, prefix: str = ""):
    """``(dotted key, value)`` of every number, list of numbers or null in a plain config tree."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield from _numbers(value, f"{prefix}{key}.")
    elif isinstance(node, list):
        if node and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in node):
            yield prefix[:-1], node
    elif node is None or isinstance(node, (int, float)) and not isinstance(node, bool):
        yield prefix[:-1], node


@functools.cache
def _composed(overrides: tuple[str, ...]):
    """The config of ``overrides``; options that only pick what the defaults pick (``model=mlr``,
    19 of the 44) compose the defaults' config: one composition, not 20 (~0.2 s of CPU each)."""
    if overrides and all(_default_choices().get(o.split("=")[0]) == o.split("=")[1] for o in overrides):
        return _composed(())
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=[*overrides, "track=false"])


@functools.cache
def _default_choices() -> dict[str, str]:
    """The option each config group takes in the default composition (Hydra's runtime choices)."""
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=["track=false"], return_hydra_config=True)
    return dict(cfg.hydra.runtime.choices)


@functools.cache
def _knobs() -> dict[str, tuple[tuple[str, ...], object]]:
    """Every numeric config key -> (the overrides composing a config that has it, its value).

    Composed when a test first asks (27 compositions, ~5 s of CPU), not when the module is
    collected: every xdist worker collects every module, and only one runs these tests."""
    knobs = {}
    for overrides in _options():
        tree = OmegaConf.to_container(_composed(tuple(overrides)))
        tree.pop("hydra", None)
        for key, value in _numbers(tree):
            knobs.setdefault(key, (tuple(overrides), value))
    return knobs


def _accepted(overrides: tuple[str, ...], key: str, value) -> bool:
    """Whether the checks every stage runs before any work (``sim.*``: simulate's) let
    ``key=value`` through (set in the cached config for the call, then restored)."""
    cfg = _composed(overrides)
    before = OmegaConf.to_object(OmegaConf.select(cfg, key)) if isinstance(value, list) else \
        OmegaConf.select(cfg, key)      # a plain copy: update changes a list in place
    OmegaConf.update(cfg, key, value)
    try:
        _check(cfg, key)
    except _config_errors():        # what the CLI says in one line, exit 2
        return False
    finally:
        OmegaConf.update(cfg, key, before)
    return True


def _check(cfg, key: str) -> None:
    from thermocomp.shell.cli import _check_seed
    from thermocomp.shell.config.checks import check_config

    if not key.startswith("sim."):
        _check_seed(cfg)
        check_config(cfg, outputs=())
        return
    try:
        generator = instantiate(cfg.sim.generator)
    except InstantiationException as exc:      # the CLI says its cause's line
        raise exc.__cause__ if isinstance(exc.__cause__, ThermocompError) else exc
    check_params(generator)
    if ".effect_params." in key:     # an effect's parameters are checked when it is planted
        generator.effects = [key.split(".")[3]]
        generator.effects_list()


@functools.cache
def _default_accepted(overrides: tuple[str, ...]) -> bool:
    """The checks pass the composed defaults (else every hostile case would pass trivially)."""
    try:
        _check(_composed(overrides), "sim.generator.seed")
        _check(_composed(overrides), "")
    except _config_errors():
        return False
    return True


def _hostile(value) -> list:
    """NaN and ±inf for a real knob, one of them in a list; a huge count for an integer one."""
    if isinstance(value, list):
        return [[bad, *value[1:]] for bad in _hostile(value[0])]
    return [math.nan, math.inf, -math.inf]


@pytest.mark.parametrize("option", _options(), ids=lambda o: o[0] if o else "defaults")
def test_every_numeric_knob_refuses_non_finite_values_and_huge_counts(option):
    """Each number of conf/ refuses NaN and ±inf (an integer knob refuses them as not integers),
    and a count (a knob that refuses a half) refuses a size no machine holds.  Before, replay
    took ``promote.envelope.margin=nan`` and streamed with the clamp off.  One test per config
    group option (its defaults accepted), for the knobs that option's composition is the first to
    have: every value let through is named."""
    overrides = tuple(option)
    mine = {key: value for key, (found_in, value) in _knobs().items() if found_in == overrides}
    assert _default_accepted(overrides), f"{overrides}: the defaults are refused"
    accepted = [f"{key}={bad} is accepted" for key, value in sorted(mine.items())
                for bad in _let_through(overrides, key, value)]
    assert not accepted, "\n".join(accepted)


def _let_through(overrides: tuple[str, ...], key: str, value) -> list:
    """The hostile values of ``key`` the checks accept (none, as it should be)."""
    first = value[0] if isinstance(value, list) else value
    if value is None and _accepted(overrides, key, "x"):
        return []       # null, and takes a text: not a number (replay.model, data.targets, ...)
    through = []
    for bad in _hostile(value):
        shown = bad[0] if isinstance(bad, list) else bad
        if (key, shown) not in OFF_VALUES and _accepted(overrides, key, bad):
            through.append(bad)
    if isinstance(first, int) and not _accepted(overrides, key, _with(value, first + 0.5)) \
            and _accepted(overrides, key, _with(value, HUGE)):
        through.append(HUGE)
    return through


def _with(value, first):
    return [first, *value[1:]] if isinstance(value, list) else first


@pytest.mark.parametrize("stage, override, says", [
    # replay streamed with the clamp off (an outside probe: max correction 1,216 µm against 251)
    ("replay", "promote.envelope.margin=nan", "promote.envelope.margin=nan: must be a number >= 0"),
    ("monitor", "promote.envelope.margin=inf", "promote.envelope.margin=inf"),
    ("replay", "monitor.guard.margin=-inf", "monitor.guard.margin=-inf"),
    # OOM-killed at 24 GB; 211 s, then killed
    ("monitor", "monitor.window=1000000000", "monitor.window=1000000000: must be an integer >= 1"),
    ("design", "design.n_machines=1000000000", "design.n_machines=1000000000: must be an integer"),
    ("run", "model=arx_rf", "model.estimator.forest.n_estimators=1000000000000"),
])
def test_a_hostile_number_is_refused_in_one_line_by_the_stage_that_reads_it(tmp_path, capsys, stage,
                                                                            override, says):
    from test_hostile import FAST, make_dataset

    data, out = make_dataset(tmp_path / "ds"), tmp_path / "out"
    extra = ["model.estimator.forest.n_estimators=1000000000000"] if override == "model=arx_rf" else []
    refused([stage, f"data.path={data}", f"out={out}", *FAST, override, *extra], capsys, says)
    assert not out.exists()


@pytest.fixture(scope="module")
def signed_run(tmp_path_factory):
    """``(dataset, run folder)``: a FAST run on the hostile matrix's dataset, its model.pkl signed
    with a key of the test's own, made once; each case plants its signature on a copy of the
    folder (ci104e: each case made the same run)."""
    from test_hostile import FAST, make_dataset
    from thermocomp.base import signing

    root = tmp_path_factory.mktemp("signed_run")
    data = make_dataset(root / "ds")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv(signing.KEY_ENV, "k" * 40)
        assert main(["run", f"data.path={data}", f"out={root / 'run'}", *FAST]) == 0
    return data, root / "run"


@pytest.mark.parametrize("signature, says", [("/dev/zero", "not signed by this project"),
                                             ("huge", "model.pkl.sig is larger than a signature")])
def test_a_signature_with_no_end_is_refused_without_reading_it(tmp_path, capsys, monkeypatch,
                                                               signed_run, signature, says):
    """A ``model.pkl.sig`` that is ``/dev/zero`` was read until memory ran out (MemoryError,
    exit 1): a signature is read bounded, and a device is never read."""
    from test_hostile import FAST
    from thermocomp.base import signing
    monkeypatch.setenv(signing.KEY_ENV, "k" * 40)
    data = signed_run[0]
    shutil.copytree(signed_run[1], tmp_path / "run")
    model = tmp_path / "run" / "model.pkl"
    sig = signing.sig_path(model)
    sig.unlink()
    if signature == "huge":                  # a regular file: 8 MB of a valid line repeated
        sig.write_text(f"{signing.SCHEME} {'0' * 64}\n" * 100_000)
    else:
        sig.symlink_to(signature)
    refused(["replay", f"data.path={data}", f"replay.model={model}", f"out={tmp_path / 'out'}",
             *FAST], capsys, str(model), says, "refusing to unpickle it")
    assert not (tmp_path / "out").exists()


def test_an_arx_delay_as_long_as_a_campaign_is_refused_naming_it(tmp_path, capsys):
    """``delays=[100000]`` held every input at its campaign's first value and ended in 'ARX found
    no usable input' (a traceback, exit 1)."""
    from test_hostile import FAST, make_dataset

    data, out = make_dataset(tmp_path / "ds", rows=30), tmp_path / "out"
    common = ["run", f"data.path={data}", f"out={out}", *FAST, "model=arx"]
    refused([*common, "model.estimator.delays=[0,100000]"], capsys,
            "ARX.delays=[0, 100000]: each delay must be shorter than the shortest campaign",
            "30 samples")
    assert not out.exists()
    assert main([*common, "model.estimator.delays=[0,5]"]) == 0


def test_another_axis_error_as_an_input_is_refused_naming_it(tmp_path, capsys):
    """``data.inputs=[E_X,T_*]`` for E_Y fitted E_Y on E_X, measured in the test but not on a
    machine that is compensating: exit 0 without a word before."""
    from test_hostile import FAST, edit_csv, make_dataset

    data, out = make_dataset(tmp_path / "ds"), tmp_path / "out"
    for f in data.glob("K*.csv"):
        edit_csv(f, lambda df: df.insert(len(df.columns), "E_Y", 0.5 * df["E_X"]))
    refused(["run", f"data.path={data}", f"out={out}", *FAST, "data.inputs=[E_X,T_*]",
             "data.targets=[E_Y]"], capsys, "column 'E_X'", "takes a measured error as an input")
    refused(["run", f"data.path={data}", f"out={out}", *FAST, "data.inputs=[*]",
             "data.targets=[E_Y]"], capsys, "column 'E_X,E_Y'")
    assert not out.exists()


def _signals(n: int = 200) -> pd.DataFrame:
    """Noise (6 IMFs) and a sine on a ramp (2 IMFs)."""
    t = np.arange(n, dtype=float)
    return pd.DataFrame({"T_noisy": np.random.default_rng(0).normal(size=n),
                         "T_smooth": np.sin(t / 3) + t / 100})


def test_more_imfs_than_a_signal_has_are_said_and_than_any_has_refused():
    """Asking more IMFs than a signal has removed all of them, the trend alone left, without a
    word (an outside probe: n_imfs=1000 changed test E_Z 5.80 -> 8.47 µm)."""
    from thermocomp.base.errors import ParameterError
    from thermocomp.core.denoise import EMDDenoiser
    from thermocomp.core.denoise.emd import leading_imfs

    X = _signals()
    found = {c: len(leading_imfs(X[c].to_numpy(), 100)) for c in X}
    assert found["T_smooth"] < 4 <= found["T_noisy"]
    with pytest.warns(UserWarning, match=r"n_imfs=4: 1 of 2 input signals have fewer IMFs "
                                         r"\(T_smooth: \d\)"):
        EMDDenoiser(n_imfs=4).fit(X)
    with pytest.raises(ParameterError, match=f"no input signal has that many IMFs \\(at most "
                                             f"{found['T_noisy']}: T_noisy\\)"):
        EMDDenoiser(n_imfs=found["T_noisy"] + 1).fit(X)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        EMDDenoiser(n_imfs=min(found.values())).fit(X)         # every signal has that many


def test_an_imf_count_no_signal_can_have_is_refused_before_any_work(tmp_path, capsys):
    from test_hostile import FAST, make_dataset

    data, out = make_dataset(tmp_path / "ds"), tmp_path / "out"
    common = ["run", f"data.path={data}", f"out={out}", *FAST, "denoise=emd"]
    refused([*common, "denoise.denoiser.n_imfs=1000"], capsys,
            "denoise.denoiser.n_imfs=1000: must be an integer >= 1, at most 32")
    refused([*common, "denoise.denoiser.n_imfs=30"], capsys,
            "EMDDenoiser.n_imfs=30: no input signal has that many IMFs")
    assert not out.exists()


@pytest.mark.parametrize("overrides, says", [
    (["sim.generator.sample_period_s=0.0001"], "sim.generator: 24 campaigns of"),
    (["sim=long_record", "sim.generator.duration_days=100000"], "more than 10,000,000"),
    (["sim=fleet", "sim.generator.n_machines=10000"], "sim.generator.n_machines=10000: makes"),
])
def test_a_dataset_too_large_to_simulate_is_refused_before_simulating(tmp_path, capsys, overrides,
                                                                      says):
    """No single parameter's rule refuses a period of 1e-6 s or 1e5 days, yet together they
    would simulate until memory ran out: the sample count is estimated from the plans first."""
    data = tmp_path / "ds"
    refused(["simulate", f"data.path={data}", "track=false", *overrides], capsys, says)
    assert not data.exists()
