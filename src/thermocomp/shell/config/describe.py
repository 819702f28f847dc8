"""``thermocomp <command> --help keys [group]``: every key the command composes, one line each:
its default, its type and domain (the schema's :class:`Rule`, :mod:`.schema`) and what it does
(the comment beside it in its ``conf/`` file, where the default is)."""

from __future__ import annotations

import json
import re
import typing
from pathlib import Path

from omegaconf import DictConfig, ListConfig, OmegaConf

from ...base.paths import conf_dir
from .schema import Root, fields

_KEY_LINE = re.compile(r"^(\s*)([A-Za-z_][\w-]*):(.*)$")


def comments(path: Path) -> dict[str, str]:
    """``{dotted key: the comment on its line}`` of a YAML config file (its first line only)."""
    found, stack = {}, []
    for line in path.read_text().splitlines():
        m = _KEY_LINE.match(line)
        if not m:
            continue
        indent = len(m.group(1))
        while stack and stack[-1][0] >= indent:
            stack.pop()
        stack.append((indent, m.group(2)))
        _, hash_, comment = m.group(3).partition(" #")
        if hash_ and comment.strip():
            found[".".join(k for _, k in stack)] = comment.strip()
    return found


def _docs(choices: dict) -> dict[str, str]:
    """The comments of the files a config was composed from: ``common.yaml``, each group's option."""
    docs = comments(conf_dir() / "common.yaml")
    for group, option in choices.items():
        path = conf_dir() / group / f"{option}.yaml"
        if option is not None and not group.startswith("hydra") and path.is_file():
            docs.update({f"{group}.{k}": v for k, v in comments(path).items()})
    return docs


def _leaves(node, prefix: str = ""):
    if isinstance(node, DictConfig) and len(node):
        for k in node:
            if not str(k).startswith("_"):         # _target_, _partial_: how it is built
                yield from _leaves(node._get_node(k), f"{prefix}{k}.")
    else:
        yield prefix[:-1], node


def _type(annotation) -> str:
    """``int``, ``float | None``: a schema field's annotation as the user writes values."""
    args = typing.get_args(annotation)
    if args:
        return " | ".join("None" if a is type(None) else getattr(a, "__name__", str(a)) for a in args)
    return getattr(annotation, "__name__", str(annotation))


def _shown(node) -> str:
    """A default as written (``${...}`` unresolved)."""
    if isinstance(node, (DictConfig, ListConfig)):
        return json.dumps(OmegaConf.to_container(node), ensure_ascii=False)
    value = node._value()
    return "null" if value is None else json.dumps(value) if isinstance(value, bool) else str(value)


def describe(cfg: DictConfig, choices: dict, group: str | None = None) -> str:
    """One line per key of ``cfg`` (unresolved: ``${...}`` shown as written), under ``group``
    when given: ``key = default  (type: domain)  what it does``."""
    schema = dict(fields(Root))
    docs = _docs(choices)
    lines = []
    for key, node in _leaves(cfg):
        if group is not None and not key.startswith(f"{group}."):
            continue
        field = schema.get(key)
        kind = ""
        if field is not None:
            rule = field.metadata["rule"]
            kind = _type(field.type) + (f": {rule.says}" if rule is not None else "")
        line = f"  {key} = {_shown(node)}" + (f"  ({kind})" if kind else "")
        lines.append(line + (f"  {docs[key]}" if key in docs else ""))
    return "\n".join(lines)
