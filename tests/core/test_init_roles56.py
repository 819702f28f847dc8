"""`thermocomp init` on a file of contract names and one lab's header (session 56)."""

from __future__ import annotations

import re

import yaml

from thermocomp.shell.cli import main


def test_init_reads_a_lab_temperature_header_beside_contract_names(tmp_path, capsys):
    # no role was proposed (the error is E_X, the temperature has no unit that says a role),
    # so the headers were read without roles and 'Spindelkopf [°C]' refused as unmapped
    path = tmp_path / "lab.csv"
    path.write_text("time,Spindelkopf [°C],T_bed,E_X\n" + "".join(
        f"{60 * i},{20 + 0.1 * i:.2f},{21 + 0.02 * i:.2f},{0.3 * i:.1f}\n" for i in range(30)),
        encoding="utf-8")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "lab.yaml").read_text())
    assert config["roles"]["error"] == ["E_X"]
    assert re.search(r"Spindelkopf \[°C\] +temperature +T_Spindelkopf\n", capsys.readouterr().out)
