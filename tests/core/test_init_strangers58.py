"""A Spanish and a French lab's exports through `init` (session 58,
benchmarks/bench_new_machines58.py).

The 5-axis centre's one long file (a run column ``Ensayo``, tabs, decimal commas, a day-first
wall clock ``01/07/2026 13:22:42``, the tilt ``Eje A [°]``) put in a folder was refused: "a
folder whose one file is its one campaign has none to hold out" (it holds 12 runs), then "day or
month first?" (its rows from 13/07 say day first), then "'Eje A [°]': unit '°' is not a
temperature's".  The laser's folder of French files (``15/06/2026 06:00:00``: no month 15) was
refused "day or month first?" too, and its ``Air atelier`` (as the Spanish ``Aire nave``) was
proposed as a plain temperature.
"""

from __future__ import annotations

import pytest
import yaml

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.roles import contract_columns
from thermocomp.shell.cli import main

HEADERS = ["Ensayo", "Fecha y hora", "Cuna [°C]", "Motor eje A [°C]", "Aire nave [°C]",
           "Error X [µm]"]


def long_file(path, days=(1, 13), rows=20, sep="\t", angle=False, iso=False):
    """One run a day (``days`` of July 2026), ``rows`` a minute apart from 08:00, the run's
    number first; decimal commas; the wall clock day first (``iso``: ISO 8601); ``angle``: the
    tilt ``Eje A [°]`` last."""
    lines = [sep.join(HEADERS + ["Eje A [°]"] * angle)]
    for run, day in enumerate(days):
        for i in range(rows):
            cells = [f"{20 + 0.05 * i * k + run:.2f}".replace(".", ",") for k in (1, 2, 0.2)]
            stamp = f"2026-07-{day:02d}T08:{i:02d}:00" if iso else f"{day:02d}/07/2026 08:{i:02d}:00"
            lines.append(sep.join([str(run + 1), stamp, *cells, f"{0.2 * i:.1f}".replace(".", ","),
                                   *[str(15 * (i // 5))] * angle]))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_an_angle_is_a_state_unless_its_name_says_a_temperature():
    assert contract_columns(["time", "T1 [°C]", "Error X [µm]", "Eje A [°]", "Tilt (deg)"],
                            {"error": ["Error X"]}) == {
        "time": "time", "T1 [°C]": "T_T1", "Error X [µm]": "E_Error_X", "Eje A [°]": "S_Eje_A",
        "Tilt (deg)": "S_Tilt"}
    with pytest.raises(ContractError, match="unit '°' is not a temperature's"):
        contract_columns(["time", "Temperatura mesa [°]", "Error X [µm]"], {"error": ["Error X"]})


def test_a_slashed_date_with_a_day_past_12_is_read_day_first(tmp_path):
    path = long_file(tmp_path / "releve.csv", days=(15,), sep=";")
    ds, report = read_dataset(path, {"roles": {"error": ["Error X"], "campaign": "Ensayo"},
                                     "delimiter": ";", "decimal": ","})
    (cid,) = ds.ids()
    assert report["campaigns"][cid]["time_origin"] == "2026-07-15T08:00:00"
    assert ds.campaigns[cid]["time"].iloc[-1] == 19 * 60.0


def test_init_reads_a_folders_lone_long_file_as_the_record_of_its_runs(tmp_path, capsys):
    folder = tmp_path / "trunnion"
    long_file(folder / "datos_ensayos.csv", iso=True)
    out = tmp_path / "init"
    assert main(["init", str(folder), "data.test_fraction=0.5", f"out={out}"]) == 0
    assert "one file and no campaigns.csv: read as the record datos_ensayos.csv" in \
        capsys.readouterr().out
    config = yaml.safe_load((out / "conf/data/datos_ensayos.yaml").read_text(encoding="utf-8"))
    assert config["path"] == str(folder / "datos_ensayos.csv")
    assert config["roles"]["campaign"] == "Ensayo"
    ds, _ = read_dataset(config["path"], {k: v for k, v in config.items() if k != "defaults"})
    assert ds.ids() == ["Ensayo_1", "Ensayo_2"]
    assert list(ds.manifest["split"]) == ["train", "test"]


def test_init_writes_the_date_order_a_later_row_says(tmp_path, capsys):
    # 01/07 either order, 13/07 day first: the whole file read so, and every file of a folder
    path = long_file(tmp_path / "datos.csv")
    out = tmp_path / "init"
    assert main(["init", str(path), "data.test_fraction=0.5", f"out={out}"]) == 0
    assert "read as data.time='%d/%m/%Y %H:%M:%S'" in capsys.readouterr().out
    config = yaml.safe_load((out / "conf/data/datos.yaml").read_text(encoding="utf-8"))
    assert config["time"] == "%d/%m/%Y %H:%M:%S"
    ds, report = read_dataset(path, {k: v for k, v in config.items() if k != "defaults"})
    assert report["campaigns"]["Ensayo_2"]["time_origin"] == "2026-07-13T08:00:00"


def test_a_french_workshops_air_is_the_ambient(tmp_path):
    path = long_file(tmp_path / "releve.csv", days=(15, 16), sep=";", iso=True)
    path.write_text(path.read_text(encoding="utf-8").replace("Aire nave", "Air atelier"),
                    encoding="utf-8")
    out = tmp_path / "init"
    assert main(["init", str(path), "data.test_fraction=0.5", f"out={out}"]) == 0
    config = yaml.safe_load((out / "conf/data/releve.yaml").read_text(encoding="utf-8"))
    assert config["roles"]["ambient"] == ["Air atelier"]


def test_a_spanish_run_column_of_labels_is_the_campaign(tmp_path):
    # 'Ensayo' E01, E02: text labels under a header that must say "run" (it was proposed ignore)
    path = long_file(tmp_path / "datos.csv", iso=True)
    lines = path.read_text(encoding="utf-8").splitlines()
    path.write_text("\n".join([lines[0], *(f"E0{ln.split(chr(9), 1)[0]}\t{ln.split(chr(9), 1)[1]}"
                                           for ln in lines[1:])]) + "\n", encoding="utf-8")
    out = tmp_path / "init"
    assert main(["init", str(path), "data.test_fraction=0.5", f"out={out}"]) == 0
    config = yaml.safe_load((out / "conf/data/datos.yaml").read_text(encoding="utf-8"))
    assert config["roles"]["campaign"] == "Ensayo"
