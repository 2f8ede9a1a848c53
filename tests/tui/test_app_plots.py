"""The plot panel: shown and hidden by a key, and following every change at once."""

import numpy as np
import pytest
from textual_plotext import PlotextPlot

from biceps.engine.config import load_config
from biceps.engine.sweep import flexion_range
from biceps.engine.sweep import sweep as sweep_of_engine
from biceps.tui.widgets.plots import Plots
from biceps.tui.widgets.viewport import Viewport


# The order a plot against flexion draws its lines in: arm26's, the model's, the mark.
ARM26, MODEL, NOW = range(3)


def _lines(session, plot_id: str):
    """What the plot draws: its lines as (x, y) lists, where its vertical marks are, and its
    axes' limits."""
    monitor = session.app.screen.query_one(f"#{plot_id}", PlotextPlot).plt.monitor
    return list(zip(monitor.x, monitor.y)), monitor.vcoord[0], monitor.ylim


async def test_p_shows_the_plots_under_the_picture_and_hides_them_again(biceps):
    async with biceps(size=(100, 30)) as session:
        plots = session.app.screen.query_one(Plots)
        viewport = session.app.screen.query_one(Viewport)
        alone = viewport.size.height
        assert not plots.display or plots.size.height == 0
        await session.pilot.press("p")
        await session.settle()
        assert plots.has_class("-shown") and plots.size.height >= 10
        assert viewport.size.height < alone
        assert plots.region.y > viewport.region.y
        await session.pilot.press("p")
        await session.settle()
        assert viewport.size.height == alone


async def test_the_profile_and_the_mark_follow_a_contraction_at_once(biceps):
    async with biceps() as session:
        await session.pilot.press("p", "C", "C")
        await session.pilot.pause()
        arm = session.app.scene.arm
        muscle = arm.muscle
        (rest, now), _, _ = _lines(session, "profile")
        assert now == (muscle.positions.tolist(), muscle.radii.tolist())
        assert rest[1] == muscle.reference_radii.tolist()
        straight = arm.skeleton.length_at(0.0)
        for plot, now in (("length", arm.length - straight), ("moment-arm", arm.moment_arm)):
            curves, marks, _ = _lines(session, plot)
            assert marks == [arm.flexion]
            flexions, values = curves[MODEL]
            assert flexions[0] == 0.0 and flexions[-1] == 130.0
            assert curves[NOW] == ([arm.flexion], [pytest.approx(now)])
            assert curves[ARM26][0] == flexions
        curves, _, _ = _lines(session, "length")
        least, most = arm.skeleton.length_range()
        assert (curves[MODEL][1][0], curves[MODEL][1][-1]) == pytest.approx((0.0, least - most))
        # arm26's BIClong, from 424.5754 mm straight to 340.7173 mm at 130 degrees
        assert curves[ARM26][1][-1] == pytest.approx((340.7173 - 424.5754) / 10)
        curves, _, _ = _lines(session, "moment-arm")
        assert curves[ARM26][1][0] == pytest.approx(0.93799)
        curves, _, _ = _lines(session, "girth")
        assert curves[1] == ([arm.flexion], [muscle.girth])


async def test_the_axes_stay_put_while_the_muscle_contracts(biceps):
    async with biceps() as session:
        await session.pilot.press("p")
        await session.pilot.pause()
        plots = ("profile", "length", "moment-arm", "girth")
        before = [_lines(session, plot)[2] for plot in plots]
        await session.pilot.press("C", "C", "C")
        await session.pilot.pause()
        assert [_lines(session, plot)[2] for plot in plots] == before


async def test_an_edited_node_sweeps_the_curves_again(biceps):
    async with biceps() as session:
        await session.pilot.press("p")
        await session.pilot.pause()
        girth_before = _lines(session, "girth")[0][0][1]
        await session.pilot.press("tab", "n")  # a node after the first, halfway to the next
        await session.pilot.pause()
        arm = session.app.scene.arm
        assert arm.muscle.node_count == 16
        girth_after = _lines(session, "girth")[0][0][1]
        assert girth_after != girth_before
        least, most = flexion_range(arm)
        assert girth_after[-1] == pytest.approx(arm.at_flexion(most).muscle.girth)
        (rest, now), _, _ = _lines(session, "profile")
        assert len(now[0]) == 16 and np.allclose(rest[1], now[1])  # the edit is the new rest


async def test_a_terminal_too_small_for_the_layout_hides_the_plots_too(biceps):
    async with biceps(size=(100, 30)) as session:
        await session.pilot.press("p")
        await session.pilot.resize_terminal(50, 12)
        await session.settle()
        plots = session.app.screen.query_one(Plots)
        assert plots.has_class("-shown") and plots.region.height == 0
        await session.pilot.resize_terminal(100, 30)
        await session.settle()
        assert plots.region.height >= 10


async def test_limits_that_leave_one_length_plot_one_point(biceps, config_path):
    text = config_path.read_text().replace("length = 33.0", "length = 30.0")
    config_path.write_text(text.replace("# min_length = 28.0", "min_length = 30.0")
                           .replace("# max_length = 35.0", "max_length = 30.0"))
    async with biceps(on=load_config(config_path)) as session:
        await session.pilot.press("p", "c")
        await session.settle()
        curves, marks, _ = _lines(session, "length")
        assert curves[MODEL] == ([session.app.scene.arm.flexion], [0.0])
        assert any("shortest" in warning for warning in session.warnings)


async def test_hidden_plots_cost_nothing_and_show_the_latest_arm_when_opened(biceps,
                                                                              monkeypatch):
    swept = []

    def counting(arm, flexions):
        swept.append(arm)
        return sweep_of_engine(arm, flexions)

    monkeypatch.setattr("biceps.tui.widgets.plots.sweep", counting)
    async with biceps() as session:
        await session.pilot.press("tab", "n", "C")  # an edit and a contraction, plots hidden
        await session.settle()
        assert swept == []
        await session.pilot.press("p")
        assert swept[-1].muscle.node_count == 16  # drawn for the arm as it now is
