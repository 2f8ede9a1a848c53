"""Runtime settings: a view, light or render setting outside its rules cannot be made, by
any path, and the file's tables agree with the values on every default and bound."""

import math
from dataclasses import FrozenInstanceError, replace

import pytest
from hypothesis import given
from hypothesis import strategies as st
from pydantic import ValidationError

from biceps.engine.config import LightTable, RenderTable, ViewTable
from biceps.engine.errors import SettingError
from biceps.engine.render import RASTERIZERS
from biceps.engine.scene import Scene
from biceps.engine.settings import SHADINGS, RenderSettings, View
from biceps.engine.transforms import Light

INF, NAN = math.inf, math.nan
POINT = "three finite numbers (x, y, z) from -1e+08 to 1e+08 cm"
GRAPHICS = "'halfblocks', 'auto', 'kitty', 'sixel', 'iterm', 'sextants' or 'quadrants'"

# (field, a value it refuses, what the message must say is allowed)
VIEW_REFUSES = [
    ("scale", 0.0, "a finite number from 0.01 to 100"),
    ("scale", -3.0, "a finite number from 0.01 to 100"),
    ("scale", INF, "a finite number from 0.01 to 100"),
    ("scale", True, "a finite number from 0.01 to 100"),
    ("scale", "2", "a finite number from 0.01 to 100"),
    ("scale", 1e300, "a finite number from 0.01 to 100"),
    ("fov", 500.0, "a finite number above 1 and below 170 degrees"),
    ("fov", 170.0, "a finite number above 1 and below 170 degrees"),
    ("fov", 1.0, "a finite number above 1 and below 170 degrees"),
    ("fov", NAN, "a finite number above 1 and below 170 degrees"),
    ("yaw", NAN, "a finite number from -360 to 360 degrees"),
    ("pitch", INF, "a finite number from -360 to 360 degrees"),
    ("roll", -INF, "a finite number from -360 to 360 degrees"),
    ("yaw", 1e308, "a finite number from -360 to 360 degrees"),  # its sine: an accident
    ("roll", -360.5, "a finite number from -360 to 360 degrees"),
    ("offset", (0.0, 0.0), POINT),
    ("offset", (0.0, 0.0, NAN), POINT),
    ("offset", "abc", POINT),
    ("offset", (1e308, 0.0, 0.0), POINT),
]
LIGHT_REFUSES = [
    ("position", (0.0, 0.0, INF), POINT),
    ("position", (NAN, 0.0, 0.0), POINT),
    ("position", (1.0, 2.0), POINT),
    ("position", (1.0, 2.0, 3.0, 4.0), POINT),
    ("position", (0.0, 1e308, 0.0), POINT),
    ("position", (0.0, 0.0, -1.0000001e8), POINT),
    ("ambient", -0.1, "a finite number from 0 to 1"),
    ("diffuse", 1.5, "a finite number from 0 to 1"),
    ("specular", NAN, "a finite number from 0 to 1"),
    ("shininess", 0.5, "a finite number from 1 to 512"),
    ("shininess", 600.0, "a finite number from 1 to 512"),
]
RENDER_REFUSES = [
    ("ssaa", 0, "a whole number from 1 to 4"),
    ("ssaa", 5, "a whole number from 1 to 4"),
    ("ssaa", 2.0, "a whole number from 1 to 4"),
    ("ssaa", True, "a whole number from 1 to 4"),
    ("segments", 2, "a whole number from 3 to 1024"),
    ("segments", 1025, "a whole number from 3 to 1024"),
    ("shading", "flat", "'gouraud', 'phong' or 'overdraw'"),
    ("shading", None, "'gouraud', 'phong' or 'overdraw'"),
    ("muscle_colour", "red", "a colour written #rrggbb"),
    ("bone_colour", "#12345", "a colour written #rrggbb"),
    ("background", "#12161c\n", "a colour written #rrggbb"),
    ("background", "#gg0000", "a colour written #rrggbb"),
    ("graphics", "png", GRAPHICS),
    ("graphics", None, GRAPHICS),
    ("colors", "16", "'auto', 'truecolor' or '256'"),
]
REFUSALS = ([(View, "view", *case) for case in VIEW_REFUSES]
            + [(Light, "light", *case) for case in LIGHT_REFUSES]
            + [(RenderSettings, "render", *case) for case in RENDER_REFUSES])
TABLES = {View: ViewTable, Light: LightTable, RenderSettings: RenderTable}
MADE_BY = {View: ViewTable.view, Light: LightTable.light,
           RenderSettings: RenderTable.render_settings}



@pytest.mark.parametrize("kind, owner, field, value, allowed", REFUSALS)
def test_a_setting_outside_its_rules_cannot_be_made(kind, owner, field, value, allowed):
    with pytest.raises(SettingError) as refusal:
        kind(**{field: value})
    assert str(refusal.value) == f"{owner}.{field} is {value!r}: it must be {allowed}"


@pytest.mark.parametrize("kind, owner, field, value, allowed", REFUSALS)
def test_replacing_a_field_checks_it_too(kind, owner, field, value, allowed):
    with pytest.raises(SettingError, match=f"^{owner}.{field} is "):
        replace(kind(), **{field: value})


def test_a_setting_may_name_every_shading_the_renderer_draws_and_no_other():
    assert set(SHADINGS) == set(RASTERIZERS)


def test_the_defaults_are_settings():
    assert (View().fov, Light().shininess, RenderSettings().ssaa) == (35.0, 24.0, 1)


def test_a_setting_is_frozen():
    with pytest.raises(FrozenInstanceError):
        View().scale = -3.0


def test_equal_settings_compare_equal_however_written():
    assert View(scale=2, offset=[1, 2, 3]) == View(scale=2.0, offset=(1.0, 2.0, 3.0))
    assert Light(position=[1, 2, 3]).position == (1.0, 2.0, 3.0)


@given(st.floats())
def test_a_scale_is_made_exactly_when_it_is_from_a_hundredth_to_a_hundred(scale):
    allowed = 0.01 <= scale <= 100
    try:
        View(scale=scale)
    except SettingError:
        assert not allowed
    else:
        assert allowed


@given(st.floats())
def test_a_field_of_view_is_made_exactly_when_it_is_between_1_and_170_degrees(fov):
    allowed = 1 < fov < 170
    try:
        View(fov=fov)
    except SettingError:
        assert not allowed
    else:
        assert allowed


@pytest.mark.parametrize("kind, owner, field, value, allowed", REFUSALS)
def test_a_scene_cannot_be_made_with_a_setting_outside_its_rules(config, kind, owner, field,
                                                                 value, allowed):
    defaults = {"view": View(), "light": Light(), "render": RenderSettings()}
    with pytest.raises(SettingError, match=f"^{owner}.{field} is "):
        Scene(config.arm, **{**defaults, owner: kind(**{field: value})})


@pytest.mark.parametrize("kind, owner, field, value, allowed", REFUSALS)
def test_a_scene_refuses_a_change_to_a_setting_outside_its_rules(config, kind, owner, field,
                                                                 value, allowed):
    scene = Scene.of(config)
    change = {"view": scene.with_view, "light": scene.with_light, "render": scene.with_render}
    with pytest.raises(SettingError, match=f"^{owner}.{field} is "):
        change[owner](**{field: value})
    assert scene == Scene.of(config)


def test_the_fov_and_scale_of_the_issue_are_refused(config):
    scene = Scene.of(config)
    with pytest.raises(SettingError, match="view.scale is -3"):
        scene.with_view(fov=500, scale=-3)
    with pytest.raises(SettingError, match="view.fov is 500"):
        scene.with_view(fov=500)


@pytest.mark.parametrize("kind, owner, field, value, allowed", REFUSALS)
def test_the_file_refuses_what_the_setting_refuses(kind, owner, field, value, allowed):
    with pytest.raises(ValidationError):
        TABLES[kind](**{field: value})


@pytest.mark.parametrize("kind", TABLES)
def test_a_table_left_empty_is_the_default_setting(kind):
    assert TABLES[kind]().model_dump() == TABLES[kind].of(kind()).model_dump()
    assert MADE_BY[kind](TABLES[kind]()) == kind()


@pytest.mark.parametrize("setting", [
    View(yaw=-25.0, scale=1.3, offset=(1.0, -2.0, 0.5), fov=60.0),
    Light(position=(-80.0, 40.0, 60.0), shininess=512.0),
    RenderSettings(segments=3, shading="phong", ssaa=4, background="#000000", graphics="sixel"),
])
def test_a_setting_comes_back_from_its_table_unchanged(setting):
    table = TABLES[type(setting)].of(setting)
    assert MADE_BY[type(setting)](table) == setting


@given(st.floats(), st.floats())
def test_the_file_and_the_view_agree_on_scale_and_fov(scale, fov):
    made = table_made = True
    try:
        View(scale=scale, fov=fov)
    except SettingError:
        made = False
    try:
        ViewTable(scale=scale, fov=fov)
    except ValidationError:
        table_made = False
    assert made == table_made
