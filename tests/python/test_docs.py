"""docs/python.md's worked example runs as written."""
import os
import re
import subprocess

import pytest

from conftest import CLI, SOURCE


def test_the_worked_example_runs(tmp_path, monkeypatch):
    text = (SOURCE / "docs" / "python.md").read_text()
    section = text.split("## A worked example", 1)[1]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    # The example's RS.dcm: the example structure set as an RTSTRUCT.
    subprocess.run([CLI, "--quiet", "convert", str(SOURCE / "examples" / "two-rois.slices"),
                    "-o", str(tmp_path / "RS.dcm")], check=True)
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "docs/python.md", "exec"), {})
