"""The cost of a compose (issue 35 item 7): Hydra deep-copies its whole ConfigStore at each
compose, so the store holds the root config of the command being composed and no other; it reads
every config file again, so a file of the project's conf/ is parsed once per text; a command reads
its overrides three times, so each is parsed once per text."""

from __future__ import annotations

import shutil

import pytest
from hydra.core.config_store import ConfigStore

from thermocomp.base.paths import conf_dir
from thermocomp.shell.config.commands import groups_of, root_name
from thermocomp.shell.config.overrides import compose

pytestmark = pytest.mark.usefixtures("plain_hydra")   # Hydra's own work is what is measured here

def _roots() -> list[str]:
    return sorted(name for name in ConfigStore.instance().repo if name.startswith(root_name("")))


def test_the_store_holds_only_the_root_of_the_command_composed():
    # the 19 roots stored at once were ~1.5 ms of CPU each in every compose's deepcopy
    some = ("model", "compare", "monitor", "replay")
    for command in ("run", "compare", "run", None, "replay"):
        cfg = compose(["track=false"], command)
        assert _roots() == ([f"{root_name(command)}.yaml"] if command else [])
        # each command still gets its own groups (None: the whole config, every group)
        assert {g for g in some if g in cfg} == {g for g in some if not command or g in groups_of(command)}
        assert cfg.hydra.job.config_name == (root_name(command) if command else "config")

def test_hydra_main_composes_the_root_of_its_own_command(capsys):
    # a Hydra flag goes through hydra.main, which finds the root by its name in the store
    from conftest import thermocomp

    compose(["track=false"], "run")
    out = thermocomp("compare", "--cfg", "job", "track=false").stdout
    assert "compare:" in out and "\nmodel:" not in out
    assert _roots() == [f"{root_name('compare')}.yaml"]


@pytest.fixture
def yaml_parses(monkeypatch) -> list:
    """Every YAML document parsed from now on (OmegaConf, Hydra's file sources, ours)."""
    import yaml

    seen, load = [], yaml.load

    def counted(stream, *args, **kwargs):
        seen.append(stream)
        return load(stream, *args, **kwargs)

    monkeypatch.setattr(yaml, "load", counted)
    return seen


def test_a_file_of_conf_is_parsed_once_per_text_and_an_edit_is_seen(tmp_path, monkeypatch, yaml_parses):
    # each compose parsed the ~15 files of conf/ it reads again: a fifth of its CPU
    project = tmp_path / "project"
    shutil.copytree(conf_dir(), project / "conf")
    for f in (project / "conf").rglob("*.yaml"):   # texts this process has not parsed yet
        f.write_text(f"{f.read_text()}\n# {tmp_path}\n")
    monkeypatch.setenv("THERMOCOMP_ROOT", str(project))
    modes = project / "conf" / "eval" / "default.yaml"
    parses, modes_seen = [], []
    for edit in (None, None, ("mode: simulation", "mode: one_step  ")):  # same size, same second
        if edit:
            modes.write_text(modes.read_text().replace(*edit))
        before = len(yaml_parses)
        modes_seen.append(compose(["track=false"], "run").eval.mode)
        parses.append(len(yaml_parses) - before)
    assert modes_seen == ["simulation", "simulation", "one_step"]
    assert parses[1] <= parses[0] - 10      # the ten files or more of conf/ not parsed again
    assert parses[2] == parses[1] + 1       # but the one edited
    # a config folder of the user's (hydra.searchpath) is read as Hydra reads it
    lab = tmp_path / "lab" / "data" / "lab.yaml"
    lab.parent.mkdir(parents=True)
    searched = [f"hydra.searchpath=[file://{lab.parents[1]}]", "data=lab", "track=false"]
    for sample_period in (15, 30):
        lab.write_text(f"defaults:\n  - default\n  - _self_\nsample_period_s: {sample_period}\n")
        assert compose(searched, "run").data.sample_period_s == sample_period


def test_a_command_parses_each_override_once(tmp_path, monkeypatch):
    # lenient, refuse and unread each parsed every override again with Hydra's grammar
    from conftest import thermocomp
    from thermocomp.shell.config import overrides

    parser, seen = overrides._parser(), []
    parse = parser.parse_override
    monkeypatch.setattr(parser, "parse_override", lambda arg: seen.append(arg) or parse(arg))
    args = ("run", f"data.path={tmp_path}/lab", f"out={tmp_path}/out", "eval.mode=sometimes",
            f"name=once-{tmp_path.name}", "track=false")
    parses = []
    for _ in range(2):
        proc = thermocomp(*args, check=False)
        assert proc.returncode == 2 and "eval.mode='sometimes'" in proc.stderr
        parses.append(len(seen))
        seen.clear()
    # each override once at most (some were parsed by other tests), then none: 15 and 15 before
    assert parses[0] <= len(args) - 1 and parses[1] == 0
