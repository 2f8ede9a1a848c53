"""Textual's private parts are used in one module, tui/textual_private.py, and the app works
without them (BICEPS_TEXTUAL_PRIVATE=0)."""

from __future__ import annotations

import ast
import importlib
import os
import subprocess
import sys
from pathlib import Path

import pytest

from biceps.tui import textual_private

ROOT = Path(__file__).resolve().parents[1]
SEAM = ROOT / "tui" / "textual_private.py"
SOURCES = sorted(path for folder in ("biceps", "engine", "terminal", "tui")
                 for path in (ROOT / folder).rglob("*.py") if path != SEAM)

# Private attributes of Textual's objects, by name: what the app used before it had the seam
# (tui/textual_private.py's list of what it checks), so that none comes back elsewhere.
PRIVATE_NAMES = {
    "_driver", "_compositor", "_styles_cache", "_batch_count", "_display",
    "_sync_available", "_repaint_regions", "_handle_exception", "_parse_extended_key",
    "_gather_commands", "_GATHER_COMMANDS_GROUP", "_on_click", "_suggestion",
    "_exception", "_return_code", "_notifications", "_bindings_ready",
}
# What reads the frames of a traceback, whose locals are Textual's own code as it stands
# (how the app knows an error for a closing palette's).
FRAME_NAMES = {"tb_frame", "f_locals"}


def _textual_class(module: ast.Module, name: str) -> type | None:
    """The Textual class that ``name`` was imported as in ``module``, if it is one."""
    for node in module.body:
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("textual"):
            for alias in node.names:
                if (alias.asname or alias.name) == name:
                    found = getattr(importlib.import_module(node.module), alias.name, None)
                    return found if isinstance(found, type) else None
    return None


def private_uses(path: Path) -> list[str]:
    """Each use of a private part of Textual in the source at ``path``, as ``line: what``."""
    module = ast.parse(path.read_text(), str(path))
    found = []
    for node in ast.walk(module):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            names = [node.module or ""] if isinstance(node, ast.ImportFrom) else [
                alias.name for alias in node.names]
            found += [f"{node.lineno}: import {name}" for name in names
                      if name.split(".")[0] == "textual"
                      and any(part.startswith("_") for part in name.split("."))]
        elif isinstance(node, ast.Attribute) and node.attr in PRIVATE_NAMES | FRAME_NAMES:
            found.append(f"{node.lineno}: .{node.attr}")
        elif (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
              and node.value.id == "Strip" and node.attr in ("__init__", "__slots__")):
            found.append(f"{node.lineno}: Strip.{node.attr}")
        elif isinstance(node, (ast.Assign, ast.AugAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            found += [f"{node.lineno}: {ast.unparse(target)} =" for target in targets
                      if ast.unparse(target).startswith("textual.")]
        elif isinstance(node, ast.ClassDef):
            # A method overriding one of a Textual base's private ones.
            bases = [base for base in (_textual_class(module, ast.unparse(b).split("[")[0])
                                       for b in node.bases) if base is not None]
            found += [f"{item.lineno}: {node.name}.{item.name} overrides Textual's"
                      for item in node.body
                      if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef))
                      and item.name.startswith("_") and not item.name.startswith("__")
                      and any(hasattr(base, item.name) for base in bases)]
    return found


def test_textual_s_private_parts_are_used_in_one_module_only():
    uses = {str(path.relative_to(ROOT)): private_uses(path) for path in SOURCES}
    assert {path: found for path, found in uses.items() if found} == {}


def test_the_check_finds_what_the_seam_uses():
    found = "\n".join(private_uses(SEAM))
    for use in ("import textual._compositor", "._driver", "._compositor", "._styles_cache",
                "._batch_count", "._sync_available", "._repaint_regions",
                "Strip.__init__", "textual.constants.COLOR_SYSTEM =",
                "AppHooks._display overrides", "AppHooks._handle_exception overrides",
                ".tb_frame", ".f_locals"):
        assert use in found


def test_no_private_id_of_textual_s_is_used():
    # Textual names its own widgets "--something" (the palette "--command-palette"): one
    # reused, mounted beside Textual's, is DuplicateIds.
    ids = [f"{path.relative_to(ROOT)}:{number}" for path in SOURCES
           for number, line in enumerate(path.read_text().splitlines(), 1)
           if '"--' in line and "id=" in line]
    assert ids == []


def test_this_textual_has_all_the_app_uses():
    # The pin (textual>=8.2.7,<9) allows only Textuals with them.
    assert textual_private._missing() == []


@pytest.mark.parametrize("version, known", [
    ("8.2.6", False), ("8.2.7", True), ("8.3.0", True), ("9.0.0", False), ("8.10.1rc1", True),
])
def test_only_versions_whose_internals_are_known_are_taken_for_the_private_path(version, known):
    parsed = textual_private._version(version)
    assert (textual_private.OLDEST <= parsed < textual_private.BEYOND) is known


@pytest.mark.parametrize("value, path", [("0", "public"), ("1", "private"), (None, "private")])
def test_the_switch_chooses_the_path_and_doctor_says_which(value, path):
    env = {key: item for key, item in os.environ.items() if key != textual_private.SWITCH}
    if value is not None:
        env[textual_private.SWITCH] = value
    code = ("from biceps.tui import textual_private as p; "
            "print(p.ENABLED); print(p.describe())")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, check=True).stdout.splitlines()
    assert out[0] == str(path == "private")
    assert out[1].startswith(f"the {path} path")
