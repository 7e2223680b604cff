"""The layers import one way only (docs/architecture.md); a violation fails here."""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "taxel"
STACK = ["mechanics", "transducers", "sensor", "reconstruction", "features", "active"]
SIDE = {"frames": set(), "io": {"mechanics", "transducers", "sensor", "frames"}}
LEAVES = {"viz", "report", "cli"}


def _allowed(layer: str) -> set[str]:
    if layer in STACK:
        below = set(STACK[: STACK.index(layer)])
        beside = {"frames"} if layer in ("features", "active") else set()
        if layer == "active":
            beside.add("io")  # the procedures save their tables and libraries
        return below | beside
    if layer in SIDE:
        return SIDE[layer]
    if layer == "viz":
        return set(STACK) | set(SIDE)
    if layer == "report":
        return set(STACK) | set(SIDE) | {"viz"}
    return set(STACK) | set(SIDE) | {"viz", "report"}  # cli


def _imported_layers(path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    layers = set()
    for node in ast.walk(tree):
        names = []
        if isinstance(node, ast.ImportFrom) and node.module:
            names = [node.module]
        elif isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        for name in names:
            parts = name.split(".")
            if parts[0] == "taxel" and len(parts) > 1 and not parts[1].startswith("_"):
                layers.add(parts[1])
    return layers


LAYERS = sorted(path.name for path in PACKAGE.iterdir() if (path / "__init__.py").exists())


def test_every_layer_is_known():
    assert set(LAYERS) <= set(STACK) | set(SIDE) | LEAVES


@pytest.mark.parametrize("layer", LAYERS)
def test_layer_imports_only_what_is_below_it(layer):
    allowed = _allowed(layer) | {layer}
    for path in (PACKAGE / layer).rglob("*.py"):
        wrong = _imported_layers(path) - allowed
        assert not wrong, f"{path.relative_to(PACKAGE)} imports {sorted(wrong)}"


def test_import_taxel_stays_light():
    import subprocess
    import sys

    code = "import sys, taxel, taxel.mechanics, taxel.sensor; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_modules_stay_small():
    # docs/architecture.md: about 450 lines at most; a module past 500 is split
    lengths = {
        str(path.relative_to(PACKAGE)): len(path.read_text().splitlines())
        for path in PACKAGE.rglob("*.py")
    }
    assert max(lengths.values()) > 100  # the walk found the package's modules
    assert {name: n for name, n in lengths.items() if n > 500} == {}
