"""`thermocomp.core.io.export`: a lab-format copy of a dataset reads back, through the data config
alone, to the same numbers (the README's own-data recipe relies on it)."""

import numpy as np
import pytest

from thermocomp.core.io import read_dataset
from thermocomp.core.io.export import export_foreign, main, sample_period


def test_lab_export_reads_back_through_the_data_config(default_dataset, tmp_path):
    dest = export_foreign(default_dataset, tmp_path / "lab",
                          {"T_nose": "T0", "T_amb": "T1", "E_Z": "delta L"})
    first = (dest / "K01.csv").read_text().splitlines()
    assert first[0] == "T0;T1;delta L" and "," in first[1] and ";" in first[1]
    period = sample_period(default_dataset)
    lab, _ = read_dataset(dest, {"columns": {"T0": "T_0", "T1": "T_1", "delta L": "E_L"},
                                 "sample_period_s": period, "delimiter": ";", "decimal": ",",
                                 "reference": "none"})
    src, _ = read_dataset(default_dataset, {"reference": "none"})
    assert lab.ids() == src.ids() and lab.ids("test") == src.ids("test")
    for cid in src.ids():
        a, b = lab.campaigns[cid], src.campaigns[cid]
        np.testing.assert_allclose(a["E_L"], b["E_Z"])
        np.testing.assert_allclose(a["T_0"], b["T_nose"])
        np.testing.assert_allclose(a["time"], np.arange(len(b)) * period)


def test_export_names_a_missing_column(default_dataset, tmp_path):
    with pytest.raises(ValueError, match="T_nowhere"):
        export_foreign(default_dataset, tmp_path / "lab", {"T_nowhere": "T0"})
    assert not (tmp_path / "lab").exists()
    with pytest.raises(SystemExit):
        main([str(default_dataset), str(tmp_path / "x"), "T_nose"])


def test_the_command_says_bad_input_in_one_line_and_exits_2(tmp_path, capsys):
    # a missing folder printed an 18-line traceback, exit 1
    assert main([str(tmp_path / "nowhere"), str(tmp_path / "lab"), "E_X=delta L"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "nowhere" in err[0] and "campaigns.csv" in err[0], err
    assert not (tmp_path / "lab").exists()
