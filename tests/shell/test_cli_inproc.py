"""conftest's ``thermocomp()`` runs a command in the test's process: what the console script
gives (exit status, stdout, stderr), and the process as it was afterwards, whatever test
comes next."""

from __future__ import annotations

import logging
import os
import sys

from conftest import thermocomp

TINY = ("track=false", "sim.generator.n_campaigns=3", "sim.generator.duration_h=[1.0,1.0]")


def _state() -> dict:
    from hydra.core.global_hydra import GlobalHydra
    from hydra.core.hydra_config import HydraConfig

    root, ours = logging.getLogger(), logging.getLogger("thermocomp")
    return {"cwd": os.getcwd(), "argv": sys.argv[:], "env": dict(os.environ),
            "root": (root.handlers[:], root.level), "thermocomp": (ours.handlers[:], ours.level,
                                                                   ours.propagate),
            "hydra": (GlobalHydra.instance().is_initialized(), HydraConfig.initialized())}


def test_a_command_in_process_leaves_the_process_as_it_found_it(tmp_path):
    before = _state()
    proc = thermocomp("-v", "simulate", f"data.path={tmp_path / 'ds'}", *TINY, cwd=tmp_path,
                      env={"THERMOCOMP_TEST_MARK": "1"})
    assert proc.returncode == 0 and "wrote 3 campaigns" in proc.stderr
    assert (tmp_path / "ds" / "campaigns.csv").is_file()
    assert _state() == before       # pytest's log capture handlers on the root logger among it


def test_in_process_and_console_script_refuse_alike(tmp_path):
    args = ("simulate", f"data.path={tmp_path / 'ds'}", *TINY, "sim.generator.n_campaigns=-1")
    inside = thermocomp(*args, check=False)
    outside = thermocomp(*args, check=False, subprocess=True)
    assert inside.returncode == outside.returncode == 2
    errors = [[ln for ln in p.stderr.splitlines() if ln.startswith("thermocomp: error")]
              for p in (inside, outside)]
    assert len(errors[0]) == 1 and errors[0] == errors[1], (inside.stderr, outside.stderr)
    assert not (tmp_path / "ds").exists()
