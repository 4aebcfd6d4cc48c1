"""The README's Python session runs as written: its ```python block is a doctest (trycmd runs
only the `console` blocks)."""

import doctest
import os
import pathlib
import re

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def python_blocks():
    text = README.read_text(encoding="utf-8")
    section = text.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```python\n(.*?)```", section, flags=re.S)


def test_the_readme_python_session_runs_as_written(tmp_path):
    blocks = python_blocks()
    assert blocks, "the README's Python section has a ```python block"
    cwd = os.getcwd()
    os.chdir(tmp_path)  # the session writes its pictures here
    try:
        for i, code in enumerate(blocks):
            test = doctest.DocTestParser().get_doctest(code, {}, f"README-{i}", str(README), 0)
            assert len(test.examples) >= 10
            runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
            runner.run(test)
            assert runner.failures == 0, f"{runner.failures} README example(s) failed"
        assert (tmp_path / "bode.png").read_bytes().startswith(b"\x89PNG")
    finally:
        os.chdir(cwd)
