"""A stranger's paths off the happy path (audit87; ``benchmarks/bench_audit87.py`` writes the
full record): an export into a folder that holds another format's code of an earlier export."""

from __future__ import annotations

from test_export import _make_dataset, _trained
from thermocomp.shell.cli import main


def test_an_export_says_the_code_of_another_format_an_earlier_export_left_in_its_folder(
        tmp_path, capsys):
    # audit87: `export export.format=st` of a lagbank into the folder of an mlr's C export left
    # compensator.c / .h / stream.c of the mlr beside the lagbank's compensator.json and pack,
    # unsaid: `cc compensator.c stream.c` there built the earlier model
    data = _make_dataset(tmp_path / "data")
    common = [f"data.path={data}", "track=false", f"out={tmp_path / 'code'}"]
    mlr, lagbank = (_trained(data, tmp_path, m) for m in ("mlr", "lagbank"))
    assert main(["export", f"export.model={mlr}", "export.format=c", *common]) == 0
    assert "earlier export's code" not in capsys.readouterr().err
    assert main(["export", f"export.model={lagbank}", "export.format=st", *common]) == 0
    said = [line for line in capsys.readouterr().err.splitlines() if "earlier export's code" in line]
    assert len(said) == 1 and "warning" in said[0], said
    assert all(name in said[0] for name in ("compensator.c", "compensator.h", "stream.c")), said
    assert "compensator.st" not in said[0].split(" in ")[0], said
