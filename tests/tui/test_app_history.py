"""Undo, redo and revert: every model edit can be taken back, and done again."""

from types import SimpleNamespace

import numpy as np
import pytest

import biceps.tui.app
from biceps.engine.config import load_config
from biceps.tui.history import KEPT_NODES, RUN_GAP, History
from biceps.tui.widgets.node_table import NodeTable


class Clock:
    """The app's clock, moved only by the test: whether length changes are one run (closer
    than RUN_GAP) must not depend on how fast a loaded machine hands the app its keys."""

    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now

    def advance(self, seconds: float) -> None:
        self.now += seconds


@pytest.fixture(autouse=True)
def clock(monkeypatch) -> Clock:
    clock = Clock()
    monkeypatch.setattr(biceps.tui.app, "monotonic", clock)
    return clock


async def test_a_deleted_node_comes_back_with_undo_and_goes_again_with_redo(biceps):
    async with biceps() as session:
        session.app.screen.query_one(NodeTable).move_cursor(row=7)
        await session.pilot.press("tab", "delete")
        assert session.app.scene.arm.muscle.node_count == 14
        assert any("Node 8 deleted; ctrl+z undoes it" in n.message for n in session.notes)
        await session.pilot.press("ctrl+z")
        assert session.app.scene.arm.muscle.node_count == 15
        assert session.app.scene.arm.muscle.radii[7] == 2.08
        assert not session.app.unsaved
        await session.pilot.press("ctrl+y")
        assert session.app.scene.arm.muscle.node_count == 14


async def test_undo_takes_back_length_changes_and_node_edits_one_by_one(biceps, config, clock):
    async with biceps() as session:
        app = session.app
        await session.pilot.press("C", "C")
        clock.advance(RUN_GAP)  # two steps, not one run of length changes
        await session.pilot.press("c", "tab", "slash")
        assert (app.scene.arm.length, app.scene.arm.muscle.node_count) == (30.9, 29)
        await session.pilot.press("ctrl+z")
        assert (app.scene.arm.length, app.scene.arm.muscle.node_count) == (30.9, 15)
        await session.pilot.press("ctrl+z")
        assert app.scene.arm.length == 31.0
        await session.pilot.press("ctrl+z")
        assert app.scene.arm is config.arm
        assert not app.unsaved
        await session.pilot.press("ctrl+z")
        assert session.notes[-1].message == "Nothing to undo"


async def test_a_held_key_is_one_step_to_undo(biceps, config):
    async with biceps() as session:
        await session.pilot.press(*"c" * 20)
        assert session.app.scene.arm.length == 31.0
        await session.pilot.press("ctrl+z")
        assert session.app.scene.arm is config.arm


async def test_the_view_is_not_undone(biceps):
    async with biceps() as session:
        await session.pilot.press("c", "right", "ctrl+z")
        assert session.app.scene.view.yaw == -20.0
        assert session.app.scene.arm.length == 33.0


async def test_revert_goes_back_to_the_saved_file_and_undo_comes_back(biceps, config_path):
    async with biceps() as session:
        app = session.app
        await session.pilot.press("C", "ctrl+s")
        await session.settle()
        await session.pilot.press("C", "tab", "n")
        assert app.unsaved
        await session.pilot.press("ctrl+r")
        assert not app.unsaved
        assert (app.scene.arm.length, app.scene.arm.muscle.node_count) == (32.0, 15)
        await session.pilot.press("ctrl+z")
        assert (app.scene.arm.length, app.scene.arm.muscle.node_count) == (31.0, 16)
        await session.pilot.press("ctrl+s")
        await session.settle()
        await session.pilot.press("ctrl+r")
        assert "Nothing to revert" in session.notes[-1].message
    assert load_config(config_path).arm.muscle.node_count == 16


async def test_opening_another_file_starts_a_new_history(biceps):
    from biceps.engine.config import BUNDLED

    async with biceps() as session:
        await session.pilot.press("c", "ctrl+s")
        await session.settle()
        await session.pilot.press("ctrl+o")
        for box, value in zip(session.app.screen.query("Input"), [str(BUNDLED / "toy.toml")]):
            box.value = value
        await session.pilot.press("enter", "ctrl+z")
        assert session.app.scene.arm.muscle.node_count == 4
        assert session.notes[-1].message == "Nothing to undo"


def test_a_run_of_length_changes_is_one_step_until_a_pause(config):
    history, arm = History(), config.arm
    shorter = arm.at_length(32.0)
    history.record(arm, "length", run=True, at=10.0)
    history.record(shorter, "length", run=True, at=10.0 + RUN_GAP / 2)
    history.record(arm.at_length(31.0), "length", run=True, at=10.0 + 2 * RUN_GAP)
    assert history.undo(arm.at_length(30.0)).arm.length == 31.0
    assert history.undo(arm.at_length(31.0)).arm is arm
    assert not history.can_undo and history.can_redo


def test_the_history_keeps_at_most_so_many_nodes_the_oldest_going_first(config):
    history, arm = History(), config.arm
    big = arm.with_muscle(arm.muscle.subdivided().subdivided().subdivided())  # 113 nodes
    steps = KEPT_NODES // big.muscle.node_count + 10
    for number in range(steps):
        history.record(big, f"edit {number}")
    undone = []
    while (step := history.undo(arm)) is not None:
        undone.append(step.what)
    assert len(undone) == KEPT_NODES // big.muscle.node_count
    assert undone[0] == f"edit {steps - 1}"


class _CountedArm:
    """An arm of ``nodes`` nodes that counts how often the history looks at its muscles."""

    looked = 0

    def __init__(self, nodes: int) -> None:
        self._muscles = (SimpleNamespace(node_count=nodes),)

    @property
    def muscles(self):
        _CountedArm.looked += 1
        return self._muscles


def test_an_edit_costs_the_same_however_long_the_history_is():
    # Each edit looks at its own arm alone, not at every step kept (which made 8,000 edits
    # quadratic), whether it is kept, undone, redone or dropped as the oldest.
    history, looks = History(), []
    for number in range(3 * KEPT_NODES // 1_000):
        before = _CountedArm.looked
        history.record(_CountedArm(1_000), f"edit {number}")
        if number % 7 == 0:
            history.redo(history.undo(_CountedArm(1_000)).arm)
        looks.append(_CountedArm.looked - before)
    assert max(looks) <= 4  # its record, an undo and a redo, the oldest step dropped
    kept = 0
    while history.undo(_CountedArm(1)) is not None:
        kept += 1
    assert kept == KEPT_NODES // 1_000


@pytest.mark.parametrize("key", ["ctrl+z", "ctrl+y"])
async def test_undo_and_redo_with_nothing_to_do_say_so(biceps, key):
    async with biceps() as session:
        before = session.app.scene
        await session.pilot.press(key)
        assert session.app.scene is before
        assert session.notes[-1].message.startswith("Nothing to")
        assert np.array_equal(before.arm.muscle.radii, session.app.scene.arm.muscle.radii)


async def test_a_key_at_a_limit_is_no_step_to_undo(biceps, clock):
    async with biceps() as session:
        await session.pilot.press(*["X"] * 4)  # to the straight arm, and against it
        straight = session.app.scene.arm.length
        clock.advance(RUN_GAP)
        await session.pilot.press("X", "ctrl+z")
        assert session.app.scene.arm.length == 33.0  # back past the run, not to itself
        assert straight > 33.0
