"""The command line's overrides: composed with Hydra, refused in one line where Hydra would
take them or say why in many.

Hydra parses every override (its ``OverridesParser``) and composes the command's root config
(:mod:`.commands`); what is here is what Hydra cannot do: the README's values its grammar
rejects (:func:`lenient`), what it accepts but no stage would read as meant (:func:`refuse`), a
sweep's jobs composed before any runs (:func:`check_jobs`) and its errors said in one line with
the closest option or key, or the groups a command reads (:func:`explain`).  Each refusal is a
:class:`~thermocomp.base.errors.ConfigError` (the CLI's one line, exit 2).
"""

from __future__ import annotations

import difflib
import functools
import itertools
import os
import re

from ...base.errors import ConfigError, closest, config_file_form
from ...base.extras import missing
from ...base.paths import conf_dir, resolve
from .commands import MODEL_KEYS, READ_ONLY_BY, groups_of, register, root_name

# Objects built from `_target_`: `~key` of an argument leaves the constructor's default.
BUILT = ("model.estimator", "ati.estimator", "denoise.denoiser", "select.selector", "sim.generator")
# Config nodes that are free-form maps: `key={...}` adds keys there (Hydra wants `++key={...}`).
FREE_MAPS = ("data.columns", "data.units", "data.split_overrides", "data.derive", "data.bits",
             "sim.generator.effect_params",
             "design.studies", "model.candidate_defaults")
# Another primary config or config folder would escape the check of what Hydra builds.
CONFIG_FLAGS = ("-cp", "--config-path", "-cn", "--config-name", "-cd", "--config-dir")
# Hydra's own folders, read from the current directory by Hydra; thermocomp roots them.
ROOTED_FOLDERS = ("hydra.sweep.dir", "hydra.run.dir")
SEARCHPATH = "hydra.searchpath"
MAX_CHECKED_JOBS = 100   # jobs of a grid sweep composed up front (~0.1-0.3 s each)


def config_errors() -> tuple[type, ...]:
    """What a config Hydra cannot compose or a check refuses raises."""
    from hydra.errors import HydraException
    from omegaconf.errors import OmegaConfBaseException

    from ...base.errors import ThermocompError

    return (ThermocompError, HydraException, OmegaConfBaseException)


def compose(overrides: list[str], command: str | None = None):
    """``command``'s root config (None: the whole ``conf/config.yaml``) with its ``hydra`` node."""
    from hydra import compose as hydra_compose
    from hydra import initialize_config_dir

    register(command)
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3",
                               job_name="thermocomp"):
        return hydra_compose(config_name=root_name(command) if command else "config",
                             overrides=overrides, return_hydra_config=True)


def compose_checked(overrides: list[str], command: str):
    """:func:`compose`; a config Hydra cannot compose is a ConfigError saying why in one line."""
    try:
        return compose(overrides, command)
    except config_errors() as exc:     # explained outside: the explanation composes too
        error = exc
    raise ConfigError(explain(error, command)) from error


def group_options(key: str) -> list[str] | None:
    """The options of config group ``key`` (``conf/<key>/*.yaml``), None if it is no group."""
    folder = conf_dir() / key.replace(".", "/")
    return sorted(f.stem for f in folder.glob("*.yaml")) if folder.is_dir() else None


def _under(key: str, nodes, itself: bool = False) -> bool:
    """Whether ``key`` lies under one of ``nodes`` (``itself``: or is one)."""
    return any(key.startswith(f"{n}.") or itself and key == n for n in nodes)


@functools.cache
def _parser():
    from hydra.core.override_parser.overrides_parser import OverridesParser

    return OverridesParser.create()


@functools.lru_cache(maxsize=4096)
def parse(arg: str):
    """Hydra's parse of one override; None for a flag or what Hydra rejects (composing says why).
    Once per text and process: a command reads its overrides three times (:func:`lenient`,
    :func:`refuse`, :func:`unread`), ~0.3 ms each (Hydra's ANTLR grammar); what it returns is
    only read."""
    if arg.startswith("-"):
        return None
    try:
        return _parser().parse_override(arg)
    except Exception:
        return None


def lenient(args: list[str]) -> list[str]:
    """The overrides as thermocomp reads them, spelled for Hydra.

    ``key=value`` that Hydra's grammar rejects (``data.delimiter=;``, ``data.decimal=,``
    as bash passes ``";"`` and ``","``) is retried with the value quoted; ``key={...}`` on a
    free-form map (:data:`FREE_MAPS`) becomes ``++key={...}`` (add keys); ``+key=``/``++key=``
    of a plain key loses its ``+``: a stage reads only the keys its config has, so Hydra refuses
    one it lacks (``+`` adds keys to a free map, an object built from ``_target_``
    (:data:`BUILT`), the defaults list (a group) and ``hydra.*``).  Nothing else is rewritten,
    so a typo still fails.
    """
    from hydra.core.override_parser.types import OverrideType

    out = []
    for arg in args:
        key, eq, value = arg.partition("=")
        o = parse(arg)
        if arg.startswith("-") or not eq:
            out.append(arg)
        elif key in FREE_MAPS and value.startswith("{"):
            out.append(f"++{arg}")
        elif o is None:
            plain = not any(c in value for c in "[]{}()'\"") and not value.endswith("\\")
            out.append(f"{key}='{value}'" if plain else arg)
        elif (o.type in (OverrideType.ADD, OverrideType.FORCE_ADD) and group_options(o.key_or_group)
              is None and not _under(o.key_or_group, ("hydra", *FREE_MAPS, *BUILT), itself=True)):
            out.append(arg.lstrip("+"))
        else:
            out.append(arg)
    return out


def rooted_override(arg: str) -> str:
    """``arg`` with Hydra's own relative folders rooted at the project root, as every relative
    path thermocomp takes is (outputs.md): ``hydra.sweep.dir`` / ``hydra.run.dir`` and each
    ``file://`` entry of ``hydra.searchpath``.  Hydra reads them from the current directory, so a
    sweep started elsewhere wrote its jobs there (and its sweep.json here), and a lab's
    ``hydra.searchpath=[file://conf_lab]`` typed in a subfolder was not found (audit88)."""
    from hydra.core.override_parser.types import Quote, QuotedString

    o = parse(arg)
    if o is None or o.key_or_group not in (*ROOTED_FOLDERS, SEARCHPATH):
        return arg
    value = o.value()       # a sweep over folders (a,b) is left to Hydra, as typed
    if o.key_or_group in ROOTED_FOLDERS:
        rooted = _rooted(value) if isinstance(value, str) else value
    elif isinstance(value, list):
        rooted = [f"file://{_rooted(e[len('file://'):])}"
                  if isinstance(e, str) and e.startswith("file://") else e for e in value]
    else:
        rooted = value
    if rooted == value:
        return arg
    quoted = [QuotedString(text=str(e), quote=Quote.single).with_quotes()
              for e in (rooted if isinstance(rooted, list) else [rooted])]
    key = arg.partition("=")[0]                 # as typed, with its + or ++
    return f"{key}=[{','.join(quoted)}]" if isinstance(rooted, list) else f"{key}={quoted[0]}"


def _rooted(path: str) -> str:
    """``path`` under the project root where it is relative; an absolute one, ``~/...`` and
    one an interpolation builds (``${root:...}``, ``${oc.env:...}``) as given."""
    if path.startswith("${") or os.path.isabs(os.path.expanduser(path)):
        return path
    return str(resolve(path))


def refuse(args: list[str]) -> None:
    """What Hydra accepts but no stage would read as meant, refused before anything is composed:
    another config folder, a group set to ``null`` or removed with ``~`` (Hydra's ValueError or
    OmegaConf's 'not in struct' name no key), a swept group option that does not exist (Hydra:
    many lines, exit 1)."""
    from hydra.core.override_parser.types import OverrideType

    flag = next((a.split("=")[0] for a in args if a.split("=")[0] in CONFIG_FLAGS), None)
    if flag:
        raise ConfigError(f"{flag}: thermocomp composes conf/ of its project; add config "
                          "folders with hydra.searchpath=[file://<dir>]")
    sweeping = any(a in ("-m", "--multirun") for a in args)
    elsewhere = any(a.startswith("hydra.searchpath") for a in args)   # options from elsewhere
    for arg, o in ((a, parse(a)) for a in args):
        key = o.key_or_group if o else ""
        if o is not None and o.type == OverrideType.DEL and not _under(key, (*FREE_MAPS, *BUILT)):
            raise ConfigError(f"~{key}: thermocomp reads every key and group of its config; set "
                              f"it instead ({key}=...)")
        options = o and group_options(key)
        if not options:
            continue
        if not o.is_sweep_override() and o.value() is None:
            raise ConfigError(f"{key}=null: the config group {key!r} needs one of its options "
                              f"({', '.join(options)})")
        unknown = [v for v in (sweeping and not elsewhere and _swept(o)) or () if v not in options]
        if unknown:
            raise ConfigError(f"unknown {key} {unknown[0]!r} in the sweep {arg}; options: "
                              f"{', '.join(options)}")


def unread(args: list[str], command: str) -> list[str]:
    """Why each override of ``args`` that ``command`` ignores is ignored, where the command has a
    key of its own for what the user likely meant (:data:`~.commands.READ_ONLY_BY`)."""
    out = []
    for o in filter(None, map(parse, args)):
        readers = READ_ONLY_BY.get(o.key_or_group)
        if readers and command not in readers and command in MODEL_KEYS:
            out.append(f"{o.key_or_group} is not read by thermocomp {command} (only by "
                       f"{', '.join(readers)}): {MODEL_KEYS[command]}=<path> names the model it uses")
    return out


def _swept(o) -> list[str] | None:
    """The values of a sweep override; None if it is none or a search dimension (interval)."""
    try:
        return list(o.sweep_string_iterator()) if o.is_sweep_override() else None
    except Exception:
        return None


def check_jobs(args: list[str], command: str):
    """A sweep's jobs composed before any runs, so that a bad override is one line naming the
    job: Hydra composes each job in its launcher, and one it cannot compose (a key only some of
    the swept models have) ended the whole sweep with its multi-line message, exit 1, no job
    run.  One job per combination of the swept groups when a key is set inside one of them,
    else the first job (each swept key at its first value).  A search sweeper's dimensions are
    left out, and what fails then is Hydra's to say.  The first job's config, or None."""
    from hydra.errors import OverrideParseException

    overrides = [(a, parse(a)) for a in args if "=" in a and not a.startswith("-")]
    fixed = [a for a, o in overrides if o is None or not o.is_sweep_override()]
    groups, searched = {}, False
    for arg, o in overrides:
        values = _swept(o) if o is not None and o.is_sweep_override() else []
        searched = searched or values is None
        if values and group_options(o.key_or_group) is not None:
            groups[o.key_or_group] = [f"{o.get_key_element()}={v}" for v in values]
        elif values:
            fixed.append(f"{o.get_key_element()}={values[0]}")
    inside = [a.lstrip("+~").split("=", 1)[0] for a in fixed]
    if not any(_under(k, [g.replace("/", ".")]) for k in inside for g in groups):
        groups = {g: v[:1] for g, v in groups.items()}
    first = None
    for job in itertools.islice(itertools.product(*groups.values()), MAX_CHECKED_JOBS):
        try:
            cfg = compose([*fixed, *job], command)
        except config_errors() as exc:
            if (searched or isinstance(exc, OverrideParseException)) and not missing(exc):
                return None            # a search dimension left out, a value re-spelled here
            error = exc
            break
        first = cfg if first is None else first
    else:
        return first
    raise ConfigError(f"sweep job {' '.join(job)}: " * bool(job) + explain(error, command)) from error


def explain(exc: BaseException, command: str | None = None) -> str:
    """Hydra's message in one line, with the closest option or key when the user made a typo,
    or the groups ``command`` reads when the key is of another."""
    from hydra.errors import MissingConfigException

    if missing(exc):                     # a launcher config its plugin (an extra) registers
        return str(missing(exc))
    msg = " ".join(str(exc).split())
    if isinstance(exc, MissingConfigException) and exc.missing_cfg_file and exc.options:
        group, _, option = exc.missing_cfg_file.rpartition("/")
        ranked = sorted(exc.options, key=lambda o: -difflib.SequenceMatcher(None, option, o).ratio())
        return f"unknown {group} {option!r}; options, closest first: {', '.join(ranked)}"
    m = re.match(r"Could not override '([^']+)'", msg)
    if not m:
        return _quoted_hint(exc, msg)
    key = m.group(1)
    unread = _unread_group(key, command)
    if unread:
        return unread
    close = _fix_key(key, _whole_config())
    unread = close and _unread_group(close, command)
    if unread:   # the closest key is of a group the command does not read: no fix to offer here
        return f"unknown config key {key!r}; the closest, {unread}"
    hint = f"; did you mean {close!r}?" if close else ""
    free = [m for m in FREE_MAPS if key.startswith(f"{m}.")]
    if free and not close:   # an entry the scenario's own config leaves out: how to add it
        hint = f"; {free[0]} is a free-form map: add an entry with '+{key}=...'"
    cause = " ".join(str(exc.__cause__).split("full_key")[0].split()) if exc.__cause__ else msg
    return f"unknown config key {key!r}{hint} (Could not override {key!r}: {cause})"


def _quoted_hint(exc: BaseException, msg: str) -> str:
    """Hydra's parse error for an override whose value a lab's header word makes unreadable
    unquoted (a letter beyond ASCII, ``Tür``; spaces with brackets or parentheses, ``Verlagerung
    X [um]``), with the override quoted as Hydra reads it, when that parses: Hydra's message
    named only the grammar page (and ``mismatched input '['`` not even the override).  A map's
    key beyond ASCII (``data.columns={Spindel [°C]: ...}``) is read by no quoting (quoted, the
    map is a string): the config file is named instead."""
    from hydra.core.override_parser.overrides_parser import OverridesParser
    from hydra.errors import OverrideParseException

    override = getattr(exc, "override", None)
    if not isinstance(exc, OverrideParseException) or not override or "=" not in override:
        return msg
    key, value = override.split("=", 1)
    if value.isascii() and " " not in value:     # a typo (``model=mlr[``), not a header word
        return msg
    if value.startswith("{"):    # quoted, a map is one string; its keys are read unquoted only
        section, _, entry = key.lstrip("+").partition(".")
        pairs = (pair.partition(":") for pair in value.strip("{}").split(","))
        yaml = ", ".join(f"'{k.strip().strip(chr(39) + chr(34))}': {v.strip()}" if sep else k
                         for k, sep, v in pairs)      # (a key the user quoted: quoted once)
        letters = "beyond ASCII" if not value.isascii() else "with spaces or brackets"
        return (f"{msg}; a map's key {letters} is not read on the command line, quoted or "
                f"not (Hydra's grammar): write the entry into a config file, "
                f"{config_file_form(section, f'{entry}: {{{yaml}}}')}")

    def quoted(v: str) -> str:
        plain = v.isascii() and not any(c in v for c in " []()")
        return v if plain or v[:1] in "'\"" else "'" + v + "'"

    fixed = (f"[{','.join(quoted(v.strip()) for v in value[1:-1].split(','))}]"
             if value.startswith("[") and value.endswith("]") else quoted(value.strip()))
    try:
        OverridesParser.create().parse_overrides([f"{key}={fixed}"])
    except OverrideParseException:
        return msg
    why = ("a value with a letter beyond ASCII" if not value.isascii()
           else "a value with spaces, brackets or parentheses")
    return (f"{msg}; {why} is read only quoted: \"{key}={fixed}\" (the double quotes for "
            "the shell)")


def _fix_key(key: str, config: dict) -> str | None:
    """``key`` with its first unknown segment replaced by the closest existing one, or None."""
    node, done = config, []
    parts = key.split(".")
    for i, part in enumerate(parts):
        if not isinstance(node, dict):
            return None
        if part not in node:
            close = closest(part, [str(k) for k in node])
            return ".".join([*done, close[0], *parts[i + 1:]]) if close else None
        node, done = node[part], [*done, part]
    return None


def _whole_config() -> dict:
    """``conf/config.yaml`` as composed (every group, unresolved): where a typo's hint is found,
    whatever group it is of."""
    return _composed_whole(str(conf_dir()))


@functools.cache
def _composed_whole(conf: str) -> dict:     # once per process and project
    from omegaconf import OmegaConf

    whole = OmegaConf.to_container(compose([]), resolve=False)
    return {k: v for k, v in whole.items() if k != "hydra"}


def _unread_group(key: str, command: str | None) -> str | None:
    """Why ``key`` is not in ``command``'s config when it is a key (or the choice) of a group
    the command does not compose (its root config, :mod:`.commands`), else None."""
    group = key.replace("/", ".").split(".")[0]
    if command is None or group in groups_of(command) or group_options(group) is None:
        return None
    node = _whole_config()
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None                  # not a key of the group either: a typo, hinted
        node = node[part]
    return (f"{key}: thermocomp {command} does not read the {group} group (it composes "
            f"{', '.join(groups_of(command))})")
