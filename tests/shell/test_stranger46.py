"""Run as a stranger would, off the happy path (session 46): commands typed in a folder of one's
own, a model and a stream of another seed than the project's."""

from __future__ import annotations

from conftest import FAST, refused, thermocomp
from test_hostile import make_dataset


def test_a_relative_path_typed_in_another_folder_names_the_one_meant(tmp_path):
    make_dataset(tmp_path / "ds")          # ./ds here; relative paths are the project root's
    proc = thermocomp("replay", "data.path=ds", *FAST, f"out={tmp_path / 'out'}",
                      cwd=tmp_path, check=False)
    line = proc.stderr.strip().splitlines()[-1]
    assert proc.returncode == 2, proc.stderr
    assert "project root" in line and f"{tmp_path / 'ds'}" in line, line
    assert not (tmp_path / "out").exists()


def test_a_record_without_a_test_share_is_named_by_its_file_not_its_folder(tmp_path, capsys):
    ds = make_dataset(tmp_path / "ds")     # one campaign file of a dataset folder, read as a record
    line = refused(["run", f"data.path={ds / 'K01.csv'}", *FAST, f"out={tmp_path / 'out'}"],
                   capsys, "data.test_fraction")
    assert f"file {ds / 'K01.csv'}:" in line, line


def test_ati_on_one_train_campaign_says_it_fits_the_one_model(tmp_path):
    ds = make_dataset(tmp_path / "ds")     # K01 the only train campaign: no interval to choose
    proc = thermocomp("run", f"data.path={ds}", "ati=cmeans", "data.split_overrides={K02:test,K03:test}",
                      *FAST, f"out={tmp_path / 'out'}")
    assert "ATI: 1 training campaign(s) with 1 distinct ambient(s)" in proc.stderr, proc.stderr
    assert "the model ati=none fits" in proc.stderr, proc.stderr
