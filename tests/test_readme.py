"""The README's five-minute tour runs as written."""

import re
from pathlib import Path

README = Path(__file__).resolve().parents[1] / "README.md"


def test_python_blocks_of_the_readme_run_in_order():
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)
    assert len(blocks) >= 3
    namespace: dict = {}
    for block in blocks:
        exec(compile(block, str(README), "exec"), namespace)
    assert namespace["frame"].raw.dtype.name == "uint8"
    assert abs(namespace["reading"].normal_force - 12.0) < 1e-9


def test_readme_opens_with_the_two_commands():
    text = README.read_text()
    commands = re.search(r"```sh\n(.*?)```", text, flags=re.S).group(1)
    assert [line.split()[0:2] for line in commands.strip().splitlines()] == [
        ["make", "demo"],
        ["make", "test"],
    ]
