"""docs/cli.md and docs/data-format.md cover what the code has; no doc links outside the repo."""

from __future__ import annotations

import json
import re

import pytest
import yaml

from conftest import ROOT, thermocomp
from thermocomp.stages import STAGES

CLI = (ROOT / "docs" / "cli.md").read_text()
DATA_FORMAT = (ROOT / "docs" / "data-format.md").read_text()
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def _documented(key: str, text: str) -> bool:
    """``key`` appears as code (`` `key` ``, a dotted path with it) or as a key of a JSON block."""
    k = re.escape(key)
    return re.search(rf'`[^`\n]*\b{k}\b[^`\n]*`|"{k}":', text) is not None


def test_every_stage_is_in_the_cli_reference():
    missing = [s for s in STAGES if f"`thermocomp {s}" not in CLI]
    assert not missing, f"docs/cli.md lacks the commands {missing}"


def test_every_data_config_key_is_in_the_data_format_reference():
    keys = yaml.safe_load((ROOT / "conf" / "data" / "default.yaml").read_text())
    missing = [k for k in keys if f"| `{k}` |" not in DATA_FORMAT]
    assert not missing, f"docs/data-format.md lacks the data config keys {missing}"


def test_every_config_group_is_in_the_cli_reference():
    groups = [p.name for p in (ROOT / "conf").iterdir() if p.is_dir() and p.name != "hydra"]
    missing = [g for g in groups if f"| `{g}` |" not in CLI]
    assert not missing, f"docs/cli.md lacks the override groups {missing}"
    options = [p.stem for g in groups for p in (ROOT / "conf" / g).glob("*.yaml")]
    assert not [o for o in options if f"`{o}`" not in CLI]


def _keys(d: dict, depth: int) -> set[str]:
    out = set(d)
    if depth > 1:
        for v in d.values():
            if isinstance(v, dict):
                out |= _keys(v, depth - 1)
    return out


@pytest.mark.slow
def test_every_key_of_a_real_metrics_and_replay_json_is_in_the_cli_reference(default_dataset, tmp_path):
    common = [f"data.path={default_dataset}", "track=false"]
    thermocomp("run", *common, f"out={tmp_path / 'run'}", "plots=none", "name=docs-test")
    thermocomp("replay", *common, f"out={tmp_path / 'replay'}", "name=docs-test")
    metrics = json.loads((tmp_path / "run" / "metrics.json").read_text())
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())
    ingest = json.loads((tmp_path / "run" / "ingest_report.json").read_text())
    target = next(iter(metrics["targets"]))
    keys = {
        "metrics.json": set(metrics),
        "metrics.json targets.<t>": _keys(metrics["targets"][target], 2),
        "replay.json": set(replay) | set(replay["targets"][target]),
        "ingest_report.json": set(ingest) | set(next(iter(ingest["campaigns"].values()))),
    }
    for name, found in keys.items():
        found = {k for k in found if not k.startswith(("K", "E_"))}   # campaign ids, targets
        missing = sorted(k for k in found if not _documented(k, CLI))
        assert not missing, f"docs/cli.md lacks keys of {name}: {missing}"


LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def _links(text: str) -> list[str]:
    """Markdown link targets outside code blocks and code spans."""
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    text = re.sub(r"`[^`\n]*`", "", text)
    return LINK.findall(text)


@pytest.mark.parametrize("doc", DOCS, ids=lambda p: p.name)
def test_links_resolve_inside_the_repository(doc):
    for target in _links(doc.read_text()):
        if target.startswith(("http://", "https://", "mailto:", "#")):
            continue
        assert "shared/" not in target, f"{doc.name} links {target}: a clone has no ../shared"
        path = (doc.parent / target.split("#", 1)[0]).resolve()
        assert path.exists(), f"{doc.name} links {target}, which does not exist"
        assert ROOT in path.parents, f"{doc.name} links {target}, outside the repository"


def test_the_link_check_sees_links_and_skips_code():
    text = "see [a](docs/a.md) and ![b](x.png#y)\n`[c](nope.md)`\n```\n[d](nope2.md)\n```\n"
    assert _links(text) == ["docs/a.md", "x.png#y"]
