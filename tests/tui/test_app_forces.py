"""Forces in the app: the muscles asked for an activation or to hold a weight, their numbers
in the side panel, their tension and colour in the picture, the torque plot."""

import re
import shutil

import numpy as np
import pytest
from textual.content import Content

from biceps.configs import FOLDER
from biceps.engine.config import load_config
from biceps.engine.hold import hold_arm
from biceps.tui.commands import KeyCommands
from biceps.tui.widgets.forces import Forces
from biceps.tui.widgets.node_table import NodeTable
from biceps.tui.widgets.plots import CURVE_POINTS, Plots
from biceps.tui.widgets.stats import Stats

from test_app_nodes import _text


@pytest.fixture
def elbow(tmp_path):
    path = tmp_path / "elbow.toml"
    shutil.copy(FOLDER / "elbow.toml", path)
    return load_config(path)


async def settled(session):
    """Wait for the muscles' effort to be worked out for the newest pose, and shown."""
    app = session.app
    for _ in range(1000):
        workers = [worker for worker in app.workers if worker.group == "effort"]
        if workers:
            await app.workers.wait_for_complete(workers)
        await session.pilot.pause()
        if not app._effort_busy:  # an answer for an older pose asks again for the newest
            break
    else:
        raise AssertionError("the effort never caught up with the pose")
    await session.settle()


async def test_activation_keys_ask_every_muscle_and_the_panel_shows_what_they_do(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        panel = app.screen.query_one(Forces)
        assert not panel.has_class("-shown") and app.scene.activations == ()
        await pilot.press(*">" * 5)
        await settled(session)
        assert app.scene.activation == 0.5
        assert app.scene.activations == (0.5,) * 6
        assert panel.has_class("-shown") and panel.border_title == "all at activation 0.50"
        text = _text(panel.content)
        for muscle in app.effort.muscles:
            assert muscle.name in text and f"{muscle.torque:+.2f}" in text
        assert f"net {app.effort.torque:+.2f}" in " ".join(text.split())
        await pilot.press(*"<" * 5)
        await settled(session)
        assert app.scene.activation == 0.0 and app.scene.activations == ()
        assert app.effort is None and not panel.has_class("-shown")
        assert not app.unsaved  # asking the muscles to work is no edit
        assert session.warnings == []


async def test_a_weight_in_the_hand_is_held_with_the_least_effort(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        await pilot.press(*"}" * 5)
        await settled(session)
        assert app.scene.mass == 5.0
        arm = app.scene.arm
        expected = hold_arm(arm, app.config.force_parameters(), arm.flexion, 5.0)
        assert app.scene.activations == pytest.approx(
            [muscle.activation for muscle in expected.muscles], abs=1e-12)
        assert app.effort.torque == pytest.approx(app.effort.load.torque, abs=1e-8)
        panel = app.screen.query_one(Forces)
        assert panel.border_title == "holding 5 kg"
        assert panel.border_subtitle == f"load {app.effort.load.torque:.2f} N m"
        # The weight is held again at every pose the elbow is moved to, the last of a run
        # of keys too.
        await pilot.press("C", *"c" * 10)
        await settled(session)
        assert app.effort.load.flexion == pytest.approx(app.scene.arm.flexion)
        assert app.effort.torque == pytest.approx(app.effort.load.torque, abs=1e-8)
        await pilot.press(*"{" * 5)
        await settled(session)
        assert app.scene.mass == 0.0 and app.effort is None


async def test_at_80_by_24_every_side_panel_keeps_rows_of_its_own(biceps, elbow):
    async with biceps(size=(80, 24), on=elbow) as session:
        app, pilot = session.app, session.pilot
        await pilot.press("h")  # the side panel is folded away at 80 columns
        await session.settle()
        stats, nodes = app.screen.query_one(Stats), app.screen.query_one(NodeTable)
        full = stats.region.height
        await pilot.press(*"}" * 5)
        await settled(session)
        side = app.screen.query_one("#side").region
        panel = app.screen.query_one(Forces)
        assert panel.has_class("-shown")
        # its border, a heading, six muscles and the net torque; the load in the border
        assert panel.region.height == 10 and side.contains_region(panel.region)
        assert "load 13.15 N m" in str(panel.border_subtitle)
        # the numbers brief (a name, a length, a flexion, a volume), and says so
        assert stats.region.height == 6 < full and side.contains_region(stats.region)
        assert "volume" in _text(stats.content) and "more" in str(stats.border_subtitle)
        # the node table: its border, its heading and four nodes
        assert nodes.region.height == 7 and side.contains_region(nodes.region)
        await pilot.resize_terminal(80, 50)
        await session.settle()
        assert stats.region.height == full and stats.border_subtitle is None
        await pilot.resize_terminal(80, 24)
        await pilot.press(*"{" * 5)  # the forces gone, the numbers whole again
        await settled(session)
        assert stats.region.height == full and not panel.display


async def test_with_the_plots_the_numbers_shrink_to_leave_the_node_table_rows(biceps, elbow):
    async with biceps(size=(150, 45), on=elbow) as session:
        app, pilot = session.app, session.pilot
        await pilot.press(*"}" * 5)
        await settled(session)
        stats, nodes = app.screen.query_one(Stats), app.screen.query_one(NodeTable)
        assert stats.border_subtitle is None  # 44 rows for the side panel: room for all
        await pilot.press("p")  # the plots take 40 % of the rows
        await session.settle()
        assert stats.border_subtitle is not None and nodes.region.height >= 10
        await pilot.press("p")
        await session.settle()
        assert stats.border_subtitle is None


async def test_a_weight_too_heavy_is_refused_with_the_strongest_torque(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        await pilot.press(*"}" * 40)
        await settled(session)
        assert any("the strongest the muscles can hold there is" in warning
                   for warning in session.warnings)
        forces = app.screen.query_one(Forces)
        said = Content.from_markup(forces.border_subtitle).plain
        assert re.fullmatch(r"too heavy: max [0-9.]+ kg", said)
        # Whole in the border: Textual keeps a corner, a line and a space each side of it.
        assert len(said) <= forces.outer_size.width - 6
        flexors = [muscle.activation for muscle in app.effort.muscles if muscle.moment_arm > 0]
        assert flexors == [1.0, 1.0, 1.0]  # at their strongest, shown so


async def test_the_keys_stop_at_their_bounds_and_say_so(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        await session.pilot.press("<", "{")
        assert session.app.scene.activation == 0.0 and session.app.scene.mass == 0.0
        assert "Every muscle is at rest already: activation 0" in session.warnings
        assert "The hand holds nothing already" in session.warnings
        await session.pilot.press(*">" * 11)
        assert session.app.scene.activation == 1.0
        assert "Every muscle is fully active already: activation 1" in session.warnings


async def test_a_muscle_without_parameters_says_what_to_give(biceps, tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text((FOLDER / "biceps.toml").read_text().replace(
        "[muscle]\n", '[muscle]\nname = "mine"\n', 1))
    async with biceps(on=load_config(path)) as session:
        await session.pilot.press(">")
        assert session.app.scene.activation == 0.0
        assert any("give them in a [forces.mine] table" in warning
                   for warning in session.warnings)


async def test_b_colours_by_activation_and_the_active_bellies_are_tensed(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        await pilot.press("b", "b")
        assert app.scene.render.colour_by == "activation"
        await pilot.press(*">" * 10)
        await settled(session)
        assert app.scene.activations == (1.0,) * 6
        from biceps.engine.scene_renderer import SceneRenderer

        picture = SceneRenderer().render(app.scene, 160, 90).astype(int)
        red = (picture[..., 0] > 150) & (picture[..., 1] < 60) & (picture[..., 2] < 60)
        assert red.sum() > 100  # fully active bellies, red
        await pilot.press("b")
        assert app.scene.render.colour_by == "muscle"
        assert session.warnings == []


async def test_the_torque_plot_shows_once_the_muscles_work(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        await pilot.press("p")
        plots = app.screen.query_one(Plots)
        panel = plots.query_one("#torque")
        assert not panel.has_class("-shown")
        await pilot.press(*"}" * 3)
        await settled(session)
        assert panel.has_class("-shown") and panel.display
        strongest = plots._strongest
        assert strongest.shape == (CURVE_POINTS,) and strongest.max() > 30.0
        await pilot.press("c")
        await settled(session)
        assert plots._strongest is strongest  # a contraction only moves the mark
        await pilot.press(*"{" * 3)
        await settled(session)
        assert not panel.has_class("-shown") and not panel.display
        assert session.warnings == []


async def test_the_palette_offers_the_forces_keys(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        offered = {hit.text async for hit in KeyCommands(session.app.screen).discover()}
        assert {"Activate", "Relax", "Weight", "Lighter weight"} <= offered
        await session.run_command("weight")
        await settled(session)
        assert session.app.scene.mass == 1.0
        assert np.all(np.array(session.app.scene.activations) >= 0.01)


def test_effort_changes_stop_at_their_bounds_in_round_steps():
    from biceps.engine.errors import RefusedChange
    from biceps.engine.scene import Scene
    from biceps.tui.changes import effort_changed

    scene = Scene.of(load_config(FOLDER / "elbow.toml"))
    for _ in range(3):
        scene = effort_changed(scene, activation=0.1)
    assert scene.activation == 0.3  # not 0.30000000000000004
    scene = effort_changed(scene, activation=5.0)
    assert scene.activation == 1.0
    with pytest.raises(RefusedChange, match="fully active already"):
        effort_changed(scene, activation=0.1)
    scene = effort_changed(scene, mass=2.0)
    assert (scene.activation, scene.mass) == (1.0, 2.0)
    with pytest.raises(RefusedChange, match="holds nothing already"):
        effort_changed(effort_changed(scene, mass=-5.0), mass=-1.0)


async def test_the_forces_are_worked_out_once_a_pose_not_once_a_frame(biceps, elbow, monkeypatch):
    import biceps.tui.app as app_module

    asked, original = [], app_module.effort
    monkeypatch.setattr(app_module, "effort",
                        lambda arm, *rest: asked.append(arm) or original(arm, *rest))
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        await pilot.press(*"}" * 2)
        await settled(session)
        before = len(asked)
        await pilot.press(*["right"] * 10, "up")  # turns: the same pose, new frames
        await settled(session)
        assert len(asked) == before and app.effort is not None
        await pilot.press("c")  # a new pose: asked once more
        await settled(session)
        assert len(asked) == before + 1 and asked[-1] is app.scene.arm
