"""``hydra/sweeper=optuna``: Optuna proposes each job of a sweep from the scores of the last.

The config keys and the override syntax are those of the former hydra-optuna-sweeper plugin
(which pins Optuna 2.10): ``hydra.sweeper.params`` or sweep overrides, where
``choice(a,b)`` is categorical, ``range(a,b[,step])`` integers ``a..b`` *inclusive*,
``interval(a,b)`` a float and ``tag(log, interval(a,b))`` on a log
scale; ``n_trials`` jobs in batches of ``n_jobs``; the best trial written to
``<sweep dir>/optimization_results.yaml`` (``best_params``, ``best_value``).  Optuna is
imported only when a sweep starts, so Hydra's plugin scan needs nothing of the extra.
"""

import logging
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

from hydra.core.config_store import ConfigStore
from hydra.core.override_parser.overrides_parser import OverridesParser
from hydra.core.override_parser.types import Override, Transformer
from hydra.core.plugins import Plugins
from hydra.plugins.sweeper import Sweeper
from hydra.types import HydraContext, TaskFunction
from omegaconf import MISSING, DictConfig, OmegaConf

log = logging.getLogger(__name__)


@dataclass
class SamplerConf:
    _target_: str = "optuna.samplers.TPESampler"
    seed: Optional[int] = None


@dataclass
class OptunaSweeperConf:
    _target_: str = "hydra_plugins.thermocomp_optuna.optuna_sweeper.OptunaSweeper"
    defaults: List[Any] = field(default_factory=lambda: [{"sampler": "tpe"}])
    sampler: Any = MISSING              # hydra/sweeper/sampler=tpe (default) | random | nsgaii | grid
    direction: str = "minimize"        # or maximize
    storage: Optional[str] = None      # an Optuna storage URL: a study that outlives the sweep
    study_name: Optional[str] = None
    n_trials: int = 20
    n_jobs: int = 2                    # trials launched at once (one launcher batch)
    max_failure_rate: float = 0.0      # failed trials beyond this share of a batch end the sweep
    params: Optional[Dict[str, str]] = None


_store = ConfigStore.instance()
_store.store(group="hydra/sweeper", name="optuna", node=OptunaSweeperConf, provider="thermocomp")
# (CmaEsSampler needs the cmaes package: hydra.sweeper.sampler._target_=optuna.samplers.CmaEsSampler)
for _name, _sampler in {"tpe": "TPESampler", "random": "RandomSampler", "nsgaii": "NSGAIISampler"}.items():
    _store.store(group="hydra/sweeper/sampler", name=_name, provider="thermocomp",
                 node=SamplerConf(_target_=f"optuna.samplers.{_sampler}"))
_store.store(group="hydra/sweeper/sampler", name="grid", provider="thermocomp",   # the search space
             node={"_target_": "optuna.samplers.GridSampler", "_partial_": True})  # comes at sweep


def distribution(override: Override):
    """The Optuna distribution of a sweep override, or its value as a string when fixed."""
    from optuna.distributions import CategoricalDistribution, FloatDistribution, IntDistribution

    if not override.is_sweep_override():
        return override.get_value_element_as_str()
    if override.is_choice_sweep() or (override.is_range_sweep() and override.value().shuffle):
        return CategoricalDistribution(list(override.sweep_iterator(transformer=Transformer.encode)))
    value = override.value()
    if override.is_range_sweep():        # inclusive of stop, as the former plugin read it
        if any(isinstance(v, float) for v in (value.start, value.stop, value.step)):
            return FloatDistribution(value.start, value.stop, step=value.step)
        return IntDistribution(int(value.start), int(value.stop), step=int(value.step))
    if override.is_interval_sweep():    # Hydra reads both ends as floats: integers are range()
        return FloatDistribution(value.start, value.end, log="log" in value.tags)
    raise ValueError(f"{override.input_line}: not a search dimension Optuna knows")


def _grid_values(dist) -> list:
    from optuna.distributions import CategoricalDistribution

    if isinstance(dist, CategoricalDistribution):
        return list(dist.choices)
    if dist.step is None:
        raise ValueError("the grid sampler needs choice() or range() dimensions, not interval()")
    n = int(round((dist.high - dist.low) / dist.step)) + 1
    return [dist.low + i * dist.step for i in range(n)]


class OptunaSweeper(Sweeper):
    """Hydra sweeper: ``n_trials`` jobs proposed by an Optuna study, each job's return value
    (:class:`thermocomp.shell.callbacks.SweepObjective`: the validation score) its objective."""

    def __init__(self, sampler, direction="minimize", storage=None, study_name=None, n_trials=20,
                 n_jobs=2, max_failure_rate=0.0, params=None):
        if not 0.0 <= max_failure_rate <= 1.0:
            raise ValueError(f"hydra.sweeper.max_failure_rate={max_failure_rate}: not in [0, 1]")
        self.sampler, self.direction, self.storage = sampler, str(direction), storage
        self.study_name, self.n_trials, self.n_jobs = study_name, int(n_trials), max(1, int(n_jobs))
        self.max_failure_rate, self.params = max_failure_rate, params or {}

    def setup(self, *, hydra_context: HydraContext, task_function: TaskFunction,
              config: DictConfig) -> None:
        from thermocomp.base.extras import require

        require("optuna")   # the [scale] extra: one line naming it, not a traceback
        self.config, self.job_idx = config, 0
        self.launcher = Plugins.instance().instantiate_launcher(
            config=config, hydra_context=hydra_context, task_function=task_function)

    def _space(self, arguments):
        lines = [f"{k}={v}" for k, v in self.params.items()] + list(arguments)
        space, fixed = {}, {}
        for override in OverridesParser.create().parse_overrides(lines):
            dist = distribution(override)
            (fixed if isinstance(dist, str) else space)[override.get_key_element()] = dist
        return {k: v for k, v in space.items() if k not in fixed}, fixed

    def sweep(self, arguments):
        import functools
        import math

        import optuna

        space, fixed = self._space(arguments)
        sampler, n_trials = self.sampler, self.n_trials
        if isinstance(sampler, functools.partial):      # the grid: its values from the space
            grid = {name: _grid_values(dist) for name, dist in space.items()}
            sampler = sampler(grid)
            n_trials = min(n_trials, int(math.prod(len(v) for v in grid.values())))
        study = optuna.create_study(study_name=self.study_name, storage=self.storage,
                                    sampler=sampler, direction=self.direction, load_if_exists=True)
        to_go = n_trials
        while to_go > 0:
            trials = [study.ask(space) for _ in range(min(to_go, self.n_jobs))]
            overrides = [tuple(f"{k}={v}" for k, v in {**t.params, **fixed}.items()) for t in trials]
            returns = self.launcher.launch(overrides, initial_job_idx=self.job_idx)
            self.job_idx += len(returns)
            failures = 0
            for trial, ret in zip(trials, returns):
                try:
                    value = float(ret.return_value)   # a failed job raises its error here
                except Exception as exc:
                    log.warning("trial %d failed: %s", trial.number, exc)
                    study.tell(trial, state=optuna.trial.TrialState.FAIL)
                    failures += 1
                    continue
                study.tell(trial, value)          # NaN (no validation figure): a failed trial
            if failures / len(returns) > self.max_failure_rate:
                raise RuntimeError(f"{failures} of {len(returns)} trials failed "
                                   f"(hydra.sweeper.max_failure_rate={self.max_failure_rate})")
            to_go -= len(returns)
        best = study.best_trial
        log.info("best value %s with %s", best.value, best.params)
        OmegaConf.save(OmegaConf.create({"name": "optuna", "best_params": best.params,
                                         "best_value": best.value}),
                       f"{self.config.hydra.sweep.dir}/optimization_results.yaml")
