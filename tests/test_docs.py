"""docs/cli.md and docs/data-format.md cover what the code has; no doc links outside the repo."""

from __future__ import annotations

import io
import json
import re
import shutil

import pandas as pd
import pytest
import yaml

from conftest import ROOT, thermocomp
from thermocomp.shell.cli import main
from thermocomp.shell.config import overrides
from thermocomp.shell.stages import STAGES

CLI = (ROOT / "docs" / "cli.md").read_text()
DATA_FORMAT = (ROOT / "docs" / "data-format.md").read_text()
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]   # measured/ too


def _documented(key: str, text: str) -> bool:
    """``key`` is a code span of its own (`` `key` ``, `` `key=<v>` ``), a part of a dotted path
    in one (`` `targets.<t>.key` ``), or a key of a JSON block: not any word in any code span."""
    if f'"{key}":' in text:
        return True
    prose = re.sub(r"```.*?```", "", text, flags=re.S)
    return any(key in re.split(r"[.\[\]]", span.split("=", 1)[0])
               for span in re.findall(r"`([^`\n]+)`", prose) if " " not in span.split("=", 1)[0])


def test_a_key_is_documented_as_a_key_not_as_a_word_of_a_code_span():
    doc = 'see `thermocomp run model=mlr`, `val_rmse`, `a.<t>.train`, `out=<dir>`\n```\n{"gap": 1}\n```'
    assert [k for k in ("train", "out", "val_rmse", "gap") if not _documented(k, doc)] == []
    assert [k for k in ("run", "model", "mlr", "rmse", "dir") if _documented(k, doc)] == []


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


def test_every_monitor_config_key_is_in_the_cli_reference():
    def leaves(d: dict, prefix: str) -> list[str]:
        return [k for key, v in d.items()
                for k in (leaves(v, f"{prefix}{key}.") if isinstance(v, dict) else [prefix + key])]

    keys = leaves(yaml.safe_load((ROOT / "conf" / "monitor" / "default.yaml").read_text()), "monitor.")
    missing = [k for k in keys if f"| `{k}` |" not in CLI]
    assert keys and not missing, f"docs/cli.md lacks the monitor config keys {missing}"


@pytest.mark.slow
def test_every_key_of_a_real_monitor_json_is_in_the_cli_reference(default_dataset, tmp_path, monkeypatch):
    # a dropout on one test campaign: `missing`, the dropout and guard events too
    data = tmp_path / "ds"
    shutil.copytree(default_dataset, data)
    index = pd.read_csv(data / "campaigns.csv")
    test = data / index.loc[index["split"] == "test", "file"].iloc[0]
    df = pd.read_csv(test)
    sensor = next(c for c in df.columns if c.startswith("T_") and not c.startswith("T_amb"))
    df.loc[len(df) // 2:, sensor] = None
    df.to_csv(test, index=False)
    thermocomp("monitor", f"data.path={data}", "track=false", f"out={tmp_path / 'mon'}")
    report = json.loads((tmp_path / "mon" / "monitor.json").read_text())
    # stdin, judged only: a time that goes back and a +50 °C jump reach the guard
    df.loc[len(df) // 2:, sensor] = pd.read_csv(default_dataset / test.name)[sensor] + 50.0
    df.loc[5, "time"] = df.loc[3, "time"]
    # in this process (the keys are the subject; a piped stdin as a process reads it is
    # docs/monitoring.md's page, tests/test_readme.py): no interpreter's ~2.5 s of imports
    monkeypatch.setattr("sys.stdin", io.StringIO(df.to_csv(index=False)))
    proc = thermocomp("monitor", "monitor.input=-", "track=false", "monitor.adaptive=false",
                      f"data.path={data}", f"out={tmp_path / 'in'}", "plots=none", check=False)
    assert proc.returncode == 0, proc.stderr
    stdin = json.loads((tmp_path / "in" / "monitor.json").read_text())
    events = report["events"] + stdin["events"]
    assert report["missing"] and {"time", None} <= {e["sensor"] for e in events}
    keys = {
        "monitor.json": set(report) | set(stdin),
        "monitor.json sensors.<s>": {k for k in _keys(report["sensors"][sensor], 2)
                                     if not k.startswith("E_")},   # per target
        "monitor.json targets.<t>": set(next(iter(report["targets"].values()))),
        "monitor.json events": {k for e in events for k in e},
        "monitor.json pod, bands": set(report["pod"]) | set(report["bands"]),
    }
    for name, found in keys.items():
        missing = sorted(k for k in found if not _documented(k, CLI))
        assert not missing, f"docs/cli.md lacks keys of {name}: {missing}"
    states = {e[k] for e in events for k in ("from", "to")}
    assert not [s for s in states if f"`{s}`" not in CLI]
    figures = sorted(p.name for p in (tmp_path / "mon" / "monitor").iterdir())
    assert figures and not [f for f in figures if f"`{f}`" not in CLI]


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


def _heading_anchors(text: str) -> set[str]:
    """The ids Python-Markdown's toc gives a page's headings (code spans and link targets
    dropped, punctuation removed, spaces joined by '-')."""
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    ids = set()
    for title in re.findall(r"^#{1,6} (.+)$", text, flags=re.M):
        title = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", title.replace("`", ""))
        title = title.encode("ascii", "ignore").decode()
        ids.add(re.sub(r"[-\s]+", "-", re.sub(r"[^\w\s-]", "", title).strip().lower()))
    return ids


@pytest.mark.parametrize("guide", ["models.md", "to-the-machine.md"])
def test_a_guide_page_links_its_measurement_record_by_heading(guide):
    # the guide keeps what a user needs; each section's history is one link away, in
    # docs/measured/<page>, and every such link lands on a heading there
    text = (ROOT / "docs" / guide).read_text()
    record = ROOT / "docs" / "measured" / guide
    links = [t for t in _links(text) if t.startswith(f"measured/{guide}#")]
    assert record.exists() and len(links) >= 5, f"docs/{guide} links no sections of {record.name}"
    ids = _heading_anchors(record.read_text())
    assert not [t for t in links if t.split("#", 1)[1] not in ids]
    nav = yaml.safe_load((ROOT / "mkdocs.yml").read_text())["nav"]
    assert f"measured/{guide}" in json.dumps(nav), "the record is not in mkdocs.yml's nav"


def test_the_link_check_sees_links_and_skips_code():
    text = "see [a](docs/a.md) and ![b](x.png#y)\n`[c](nope.md)`\n```\n[d](nope2.md)\n```\n"
    assert _links(text) == ["docs/a.md", "x.png#y"]


# The contracts are fixed: docs/cli.md and docs/data-format.md copy them word for word above
# their rule, and extend them only below it.  A clone has no ../shared/spec, so the copies are
# held to the digests of the contracts as given; where the originals are at hand, to them too.
CONTRACTS = {"cli.md": ("# Command-line contract", "# Extensions in thermocomp", "CLI.md",
                        "5b0f8c533d30f00d"),
             "data-format.md": ("# Data contract", "\n---\n", "DATA_FORMAT.md", "a6090a68b0508abf")}


def _contract_text(text: str) -> str:
    return "\n".join(line.rstrip() for line in text.strip().splitlines()).strip("-\n ")


@pytest.mark.parametrize("doc", sorted(CONTRACTS))
def test_the_contract_part_of_the_docs_is_word_for_word(doc):
    import hashlib

    start, end, original, digest = CONTRACTS[doc]
    text = (ROOT / "docs" / doc).read_text()
    copy = _contract_text(text[text.index(start):text.index(end, text.index(start))])
    spec = ROOT.parent / "shared" / "spec" / original
    if spec.is_file():
        assert copy == _contract_text(spec.read_text()), f"docs/{doc} departs from {original}"
    assert hashlib.sha256(copy.encode()).hexdigest()[:len(digest)] == digest, (
        f"docs/{doc}: the contract part changed (extensions go below the rule)")


@pytest.mark.parametrize("page", ["README.md", "docs/install.md"])
def test_every_extra_of_pyproject_is_in_the_extras_table(page):
    # a newcomer picks extras from these tables: one left out is a feature they never find
    # (README's lacked excel, tdms and matlab while its `all` row said "every extra above")
    import tomllib
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    rows = set(re.findall(r"^\| `([\w-]+)` \|", (ROOT / page).read_text(), re.M))
    missing = sorted(set(extras) - {"test"} - rows)
    assert not missing, f"{page}'s extras table lacks {missing}"



# audit88: the groups whose options are the project's own (a lab's `data=<name>`, a scenario
# `sim=<name>`, `experiment=diagnosed` are written by `init`, the user or `diagnose`), and the
# options the docs name as refused on purpose
OWN_GROUPS = sorted(p.name for p in (ROOT / "conf").iterdir()
                    if p.is_dir() and p.name not in ("hydra", "data", "sim", "experiment"))
REFUSED_EXAMPLES = {"null", "nosuch"}
CHOICE = re.compile(r"(?:^|(?<=[\s`'\"]))(%s)=([\w|,]+)" % "|".join(OWN_GROUPS), re.M)


def _choices() -> list[tuple[str, str, str]]:
    """Every ``group=option`` the docs name (``a,b``: a sweep; ``a|b``: a list of the options):
    (where, group, what follows the ``=``)."""
    found = []
    for doc in DOCS:
        text = doc.read_text()
        for m in CHOICE.finditer(text):
            found.append((f"{doc.relative_to(ROOT)}:{text[:m.start()].count(chr(10)) + 1}", m[1], m[2]))
    return found


def test_a_group_option_the_docs_name_is_one_the_group_has():
    # data-format.md said `adapt=bias` (exit 2, "unknown adapt 'bias'"): the key is adapt.method
    found = _choices()
    assert len(found) > 100
    wrong = [(where, f"{group}={option}") for where, group, value in found
             for option in re.split(r"[|,]", value)
             if option not in overrides.group_options(group) and option not in REFUSED_EXAMPLES]
    assert not wrong, f"options no conf/<group>/ has: {wrong}"


def test_a_list_of_a_groups_options_names_them_all():
    # outputs.md's `model=mlr|pcr|arx|arx_rf|lstm` left out lagbank, hammerstein and auto
    lists = [(where, group, set(value.split("|"))) for where, group, value in _choices() if "|" in value]
    assert lists
    short = [(where, sorted(set(overrides.group_options(group)) - options))
             for where, group, options in lists if set(overrides.group_options(group)) - options]
    assert not short, f"a list of a group's options leaves some out: {short}"


def test_the_synopsis_of_the_commands_names_every_stage():
    # outputs.md's "one subcommand per stage" left out `init` and `rows`
    block = re.search(r"a synopsis.*?```bash\n(.*?)```", (ROOT / "docs" / "outputs.md").read_text(), re.S)[1]
    missing = [s for s in STAGES if not re.search(rf"^thermocomp (\w+ \| )*{s}\b", block, re.M)]
    assert not missing, f"docs/outputs.md's synopsis lacks {missing}"


def test_the_cli_references_example_of_a_group_not_read_is_what_the_command_says(capsys):
    # it quoted `thermocomp serve model=arx` refused, where serve reads the model group
    example = re.search(r"\(`thermocomp (\w+) ([^`]+)`: `([^`]+)`", CLI)
    assert main([example[1], *example[2].split()]) == 2
    said = " ".join(capsys.readouterr().err.split())
    assert f"thermocomp: error: {' '.join(example[3].split())}" in said, said


def test_the_layout_names_every_layer_and_package_of_the_source():
    # layout.md described a flat src/thermocomp/ (stats, iso10791, evaluation, plots, deploy ...
    # side by side), not the four layers the code has: no base/, core/, apps/, shell/ in it
    import thermocomp

    text = (ROOT / "docs" / "layout.md").read_text()
    src = ROOT / "src" / "thermocomp"
    missing = [f"{layer}/" for layer in thermocomp.__layers__ if f"{layer}/" not in text]
    missing += [f"{layer}/{p.name}" for layer in thermocomp.__layers__ for p in (src / layer).iterdir()
                if (p / "__init__.py").is_file() and not re.search(rf"\b{p.name}\b", text)]
    assert not missing, f"docs/layout.md does not name {missing}"


def test_the_home_page_links_every_page_of_the_site():
    # index.md's table left out measured/monitoring.md and measured/diagnose.md, both in the nav
    from test_readme import pages

    home = (ROOT / "docs" / "index.md").read_text()
    linked = {(ROOT / "docs" / t.split("#")[0]).resolve() for t in _links(home)}
    missing = [str(p.relative_to(ROOT)) for p in pages()[1:]
               if p.name != "index.md" and p.resolve() not in linked]
    assert not missing, f"docs/index.md does not link {missing}"


def test_the_make_targets_said_to_install_every_extra_do():
    # install.md said `make run` calls `make install`; it installs the core alone ($(CORE))
    makefile = (ROOT / "Makefile").read_text()
    installing = set(re.findall(r"^([\w-]+):[^=\n]*\$\(STAMP\)", makefile, re.M))
    install = (ROOT / "docs" / "install.md").read_text()
    said = re.search(r"`make install` \(which (.*?)\s+call\)", install, re.S)[1]
    named = set(re.findall(r"`make ([\w-]+)`", said))
    assert named and named <= installing, f"install.md: {sorted(named - installing)} do not run make install"


def test_every_flag_of_the_command_is_in_the_cli_reference():
    # cli.md, "every command, override group, output file and key", named no -q, -v, --version
    from thermocomp.shell.cli import LOG_FLAGS

    flags = [*LOG_FLAGS, "--version", "-V", "--help", "-h"]
    missing = [f for f in flags if f"`{f}`" not in CLI and f"`thermocomp {f}`" not in CLI]
    assert not missing, f"docs/cli.md lacks the flags {missing}"


def test_an_error_parameters_figure_the_docs_give_is_in_its_unit():
    """audit96b: volumetric.md gave `E_ZY2` (a straightness, µm) as "1.01 → 1.55 µm/m", the figures
    of its run on seed 0 in µm.  Each "`E_..` ... a → b <unit>" in a page names the parameter's
    unit (:func:`thermocomp.core.metrics.unit`).  Fails on 324eb8b2."""
    from thermocomp.core.metrics import unit

    pattern = re.compile(r"`(E_[A-Z]{2}\d)`[^`.;]*?\d+(?:\.\d+)? → \d+(?:\.\d+)? (µm/m|µm)\b")
    wrong = [(doc.name, name, said) for doc in DOCS
             for name, said in pattern.findall(doc.read_text(encoding="utf-8")) if said != unit(name)]
    assert wrong == []


# audit107b: the keys the docs set (`monitor.guard.margin=100`, `connect.nodes.sample=null`), beside
# the group options above: a key a page sets that no config has is refused (exit 2) as written
KEY_GROUPS = sorted(p.name for p in (ROOT / "conf").iterdir() if p.is_dir() and p.name != "hydra")
SET_KEY = re.compile(r"(?:^|(?<=[\s`'\"\[(]))((?:%s)\.[A-Za-z_][\w.]*)=" % "|".join(KEY_GROUPS), re.M)


def _has_key(node, parts: list[str]) -> bool:
    """``parts`` is a path of ``node``, or of an entry a config leaves free (below a null or an
    empty map: a scenario's ``effect_params.<name>``), or runs into a placeholder (``<t>``)."""
    for part in parts:
        if "<" in part or node is None:
            return True
        if not isinstance(node, dict):
            return False                      # below a value
        if part not in node:
            return not node                   # an empty map's entries are free
        node = node[part]
    return True


def _unknown_keys(text: str, whole: dict) -> list[str]:
    """The ``group.key=`` of ``text``'s code spans and blocks that neither the whole config nor
    any option of the group (``conf/<group>/*.yaml``) has, nor a free map (``FREE_MAPS``, whose
    entries a user adds: ``sim.generator.effect_params.<effect>.<key>``) takes."""
    from thermocomp.shell.config.overrides import FREE_MAPS

    code = re.findall(r"```.*?```", text, flags=re.S)
    code += re.findall(r"`([^`\n]+)`", re.sub(r"```.*?```", "", text, flags=re.S))
    unknown = []
    for key in dict.fromkeys(k for span in code for k in SET_KEY.findall(span)):
        if key.startswith(tuple(f"{m}." for m in FREE_MAPS)):
            continue
        group, *rest = key.split(".")
        options = [yaml.safe_load(f.read_text()) or {} for f in (ROOT / "conf" / group).rglob("*.yaml")]
        if not _has_key(whole, key.split(".")) and not any(_has_key(o, rest) for o in options):
            unknown.append(key)
    return unknown


def test_a_key_the_docs_set_is_one_a_config_has():
    from thermocomp.shell.config.overrides import _whole_config

    whole = _whole_config()
    planted = ("`thermocomp monitor monitor.guard.margin=100 monitor.gaurd.margin=1`\n```bash\nthermocomp "
               "simulate sim.generator.effect_params.door.rate_per_h=2 model.estimator.max_inputs=3\n```")
    assert _unknown_keys(planted, whole) == ["monitor.gaurd.margin"]
    pages = [p for p in DOCS if "measured" not in p.parts]      # the record keeps its days' keys
    assert sum(len(SET_KEY.findall(p.read_text())) for p in pages) > 100
    unknown = {p.name: keys for p in pages if (keys := _unknown_keys(p.read_text(), whole))}
    assert unknown == {}, f"keys no config has: {unknown}"
