"""What a run is called and what it records, from the schema (:mod:`.schema`): the config
groups and keys that name every run (``names``), those that never do (``reports``: where things
go, how much is reported), the params every run logs (``logged``)."""

from __future__ import annotations

import dataclasses
import re

from omegaconf import DictConfig

from .schema import Root


def _entries(schema: type = Root, prefix: str = ""):
    """``(dotted name, metadata)`` of every key and group of ``schema``, a group before its keys."""
    for f in dataclasses.fields(schema):
        yield f"{prefix}{f.name}", f.metadata
        if f.default_factory is not dataclasses.MISSING:
            yield from _entries(f.default_factory, f"{prefix}{f.name}.")


_GROUPED = {name for name, f in ((f.name, f) for f in dataclasses.fields(Root))
            if f.default_factory is not dataclasses.MISSING}
# Config groups in the order they name a run, each with the option left out (None: none is).
NAMING_GROUPS = tuple((name, meta["unnamed"]) for name, meta in _entries()
                      if name in _GROUPED and meta["names"])
# Keys that name a run whenever set (the groups' choices above, the seed, eval.mode).
NAMING_KEYS = tuple(name for name, meta in _entries() if meta["names"] and name not in _GROUPED)
# Overrides that say where things go or how much is reported, not what is fitted: a key there
# or under one never names a run (nor does Hydra's own node).
REPORTING = ("hydra", *(name for name, meta in _entries() if meta["reports"]))
# Config leaves always logged as params (when present); plus every overridden key.
PARAM_KEYS = tuple(name for name, meta in _entries() if meta.get("logged"))
_HYPER = ("model.estimator.", "select.selector.")    # the fitted model's own parameters


def _reporting(key: str) -> bool:
    return any(key == r or key.startswith((f"{r}.", f"{r}/")) for r in REPORTING)


def task_overrides() -> list[str] | None:
    """The command line's overrides of this job (Hydra's ``overrides.task``), or None."""
    from hydra.core.hydra_config import HydraConfig

    if not HydraConfig.initialized():
        return None
    try:
        return [str(o) for o in HydraConfig.get().overrides.task]
    except Exception:  # a Hydra config without overrides (composed by hand)
        return None


def _split(override: str) -> tuple[str, str]:
    key, _, value = override.partition("=")
    return key.lstrip("+~"), value


def _short(value: str) -> str:
    """A value as a run-name token: no brackets, quotes, spaces, slashes."""
    value = re.sub(r"[\[\]{}()'\" ]", "", value)
    value = value.lower() if value in ("True", "False") else value   # a sweep writes `False`
    return re.sub(r"[/\\:]+", "_", value).strip("_") or "none"


def run_name(cfg: DictConfig, overrides: list[str] | None = None) -> str:
    """A short, stable name of what ran, from what differs from the defaults.

    The model, the non-default selector, ATI and denoiser, ``eval.mode``, the
    seed when set, then every other override that changes what is fitted
    (``leaf=value``): ``mlr-pearson-seed1``, ``arx-cmeans-one_step``,
    ``mlr-inputs=T_1``.  A ``name`` other than ``default`` prefixes it (``weak/mlr``).
    """
    parts = []
    for group, default in NAMING_GROUPS:
        value = (cfg.get(group) or {}).get("name")
        if value is not None and value != default:
            parts.append(str(value))
    mode = (cfg.get("eval") or {}).get("mode")
    if mode not in (None, "simulation"):
        parts.append(str(mode))
    keys = {_split(o)[0] for o in overrides or ()}
    if "seed" in keys or cfg.get("seed", 0) != 0:
        parts.append(f"seed{cfg.get('seed')}")
    named = {g for g, _ in NAMING_GROUPS} | set(NAMING_KEYS)
    for o in overrides or ():
        key, value = _split(o)
        if key in named or _reporting(key):
            continue
        leaf = key.rsplit(".", 1)[-1]
        if o.startswith("~"):
            parts.append(f"no-{leaf}")
        elif "." not in key:               # a config group (sim=..., experiment=...): its choice
            parts.append(_short(value))
        else:
            parts.append(f"{leaf}={_short(value)}")
    name = "-".join(parts) or "default"
    if cfg.get("name") not in (None, "default"):
        name = f"{cfg.get('name')}/{name}"
    return name[:250]


def sweep_name(overrides: list[str], name: str = "default") -> str:
    """A sweep's parent run name from what it sweeps: ``sweep/model=mlr,pcr-seed=range0,3``."""
    swept = [(k, v) for k, v in map(_split, overrides)
             if ("," in v or v.startswith(("range(", "choice(", "glob("))) and not _reporting(k)]
    parts = [f"{k.rsplit('.', 1)[-1]}={_short(v)}" for k, v in swept]
    prefix = "sweep" if name in (None, "default") else f"sweep/{name}"
    return (f"{prefix}/{'-'.join(parts)}" if parts else prefix)[:250]


def run_params(container: dict, overrides: list[str] | None = None,
               given_model: bool = False) -> dict:
    """The params worth comparing runs by (not all ~130 leaves; ``config.yaml`` has them):
    :data:`PARAM_KEYS`, the model's and selector's own parameters, every overridden key.
    ``given_model``: a stage streaming a saved model (``replay.model``, ``monitor.model``) logs
    none of the config's ``model.*`` / ``select.*``: it never fitted them (its tags name the model)."""
    flat = {k: v for k, v in _flat_params(container).items()
            if not k.rsplit(".", 1)[-1].startswith("_")}          # no _target_ & co
    if given_model:
        flat = {k: v for k, v in flat.items() if not k.startswith(("model.", "select."))}
    keys = [k for k in PARAM_KEYS if k in flat] + [k for k in flat if k.startswith(_HYPER)]
    for o in overrides or ():
        key = _split(o)[0]
        if key.startswith(("hydra", "tracking_uri", "experiment_name", "track")):
            continue
        if f"{key}.name" in flat:           # a config group choice: its name, not its leaves
            keys.append(f"{key}.name")
        else:
            keys += [k for k in flat if k == key or k.startswith(key + ".")]
    out = {}
    for k in dict.fromkeys(keys):      # a lab's column name as a key: 'data.columns.dZ [µm]'
        out.setdefault(_UNSAFE.sub("_", k), flat[k])
    return out


# what MLflow allows in a param name; anything else (brackets, °, µ) became an exception that
# ended the run with a traceback
_UNSAFE = re.compile(r"[^A-Za-z0-9_\-. :/]")




def _flat_params(d, prefix=""):
    out = {}
    for k, v in d.items():
        key = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, dict):
            out.update(_flat_params(v, key))
        else:
            out[key] = str(v)[:500]
    return out
