"""``taxel demo --out``: a folder that cannot be made is one line naming --out, before any work."""

import errno
from pathlib import Path

from taxel.cli import main


def _must_not_run(*args, **kwargs):
    raise AssertionError("the demo ran before its --out was checked")


def test_a_parent_that_cannot_be_made_names_the_flag(tmp_path, capsys, monkeypatch):
    # (as a user without rights on the parent folder sees it: mkdir fails on the parent)
    monkeypatch.setattr("taxel.report.run_demo", _must_not_run)
    locked = tmp_path / "locked"

    def refused(self, *args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied", str(locked))

    monkeypatch.setattr(Path, "mkdir", refused)
    out = locked / "sub" / "report"
    assert main(["demo", "--out", str(out), "--no-progress"]) == 2
    assert capsys.readouterr().err == (
        f"taxel demo: error: --out {out} cannot be made (Permission denied: {locked})\n"
    )
