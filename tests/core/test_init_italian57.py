"""An Italian lab's export through `init` (session 57, benchmarks/bench_new_machines57.py).

The boring mill's files were refused ('Tempo [s]': "unit 's' is not a temperature's"); with the
time named, the ram's travel 'Corsa slittone W [mm]' was proposed as an error and the hall's air
'Aria capannone' as a plain temperature.
"""

from __future__ import annotations

import yaml

from thermocomp.core.io.roles import contract_columns
from thermocomp.shell.cli import main

HEADERS = ["Tempo [s]", "Slittone sopra [°C]", "Aria capannone [°C]", "Temperatura ambiente [°C]",
           "Errore Y [µm]", "Corsa slittone W [mm]", "Posizione X [mm]", "Giri mandrino [1/min]"]


def lab_file(path):
    """30 rows a minute apart, ';' and decimal commas: slow ramps, a travel in 5 mm steps."""
    rows = [";".join(HEADERS)]
    for i in range(30):
        temps = [f"{20 + 0.05 * i * k:.2f}".replace(".", ",") for k in (1, 2, 3)]
        rows.append(";".join([str(60 * i), *temps, f"{0.3 * i:.1f}".replace(".", ","),
                              str(5 * (i // 4)), str(100 * (i // 6)), "800"]))
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


def test_an_italian_export_gets_its_roles_from_init(tmp_path):
    path = lab_file(tmp_path / "Prova_01.csv")
    assert main(["init", str(path), "data.test_fraction=0.25", f"out={tmp_path / 'init'}"]) == 0
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "Prova_01.yaml").read_text())
    roles = config["roles"]
    assert roles["time"] == "auto"          # 'Tempo [s]' found as the time (it was refused)
    assert roles["error"] == ["Errore Y"]
    assert roles["state"] == ["Corsa slittone W", "Posizione X", "Giri mandrino"]
    assert roles["ambient"] == ["Aria capannone", "Temperatura ambiente"]


def test_run_reads_an_italian_time_and_travel_by_their_words():
    # a run given one role reads the other headers by their units and words, as init proposes
    assert contract_columns(["Tempo [s]", "T1 [°C]", "Errore Y [µm]", "Corsa slittone W [mm]"],
                            {"error": ["Errore Y"]}) == {"Tempo [s]": "time", "T1 [°C]": "T_T1",
                                    "Errore Y [µm]": "E_Errore_Y",
                                    "Corsa slittone W [mm]": "S_Corsa_slittone_W"}
