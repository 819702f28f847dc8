"""The cost of a compose (issue 35 item 7): Hydra deep-copies its whole ConfigStore at each
compose, so the store holds the root config of the command being composed and no other."""

from __future__ import annotations

from hydra.core.config_store import ConfigStore

from thermocomp.shell.config.commands import groups_of, root_name
from thermocomp.shell.config.overrides import compose


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

