"""docs/python.md's worked example, run as it stands (its python blocks in order, in a temporary
folder)."""
import os
import pathlib
import re

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"


def test_the_worked_example_runs(tmp_path, monkeypatch, capsys):
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S)
    assert blocks, "docs/python.md holds no python example"
    monkeypatch.chdir(tmp_path)
    exec(compile("\n".join(blocks), str(DOC), "exec"), {"__name__": "docs_example"})
    out = capsys.readouterr().out
    print(out)
    assert "SSIM" in out
    assert (tmp_path / "my_sheet.json").is_file() and (tmp_path / "photo.exr").is_file()
