"""Runtime settings: a view, light or render setting outside its rules cannot be made, by
any path, and a file's tables validate into these values by the same rules."""

import math
from dataclasses import FrozenInstanceError, replace

import pytest
from hypothesis import given
from hypothesis import strategies as st
from pydantic import TypeAdapter, ValidationError

from biceps.engine.config import load_config
from biceps.engine.errors import ConfigError, SettingError
from biceps.engine.render import RASTERIZERS
from biceps.engine.scene import Scene
from biceps.engine.settings import IN_A_FILE, SHADINGS, RenderSettings, View
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

def in_a_file(kind, **table):
    """The setting ``kind`` that a file's table of these keys gives, as a file validates it."""
    return TypeAdapter(kind).validate_python(table, context=IN_A_FILE)



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
    with pytest.raises(ValidationError) as refusal:
        in_a_file(kind, **{field: value})
    assert refusal.value.errors()[0]["loc"][0] == field


@pytest.mark.parametrize("kind", [View, Light, RenderSettings])
def test_a_table_left_empty_is_the_default_setting(kind):
    assert in_a_file(kind) == kind()


def test_a_files_tables_are_the_settings_themselves(tmp_path):
    path = tmp_path / "set.toml"
    path.write_text("[muscle]\nlength = 33.0\nradius = [0.5, 2.0, 0.5]\ngrowth = [0, 1, 0]\n"
                    "[view]\nyaw = -25\noffset = [1, -2, 0.5]\n[light]\nshininess = 512\n"
                    "[render]\nshading = \"phong\"\nssaa = 4\n")
    config = load_config(path)
    assert config.view == View(yaw=-25.0, offset=(1.0, -2.0, 0.5))
    assert config.light == Light(shininess=512.0)
    assert config.render == RenderSettings(shading="phong", ssaa=4)
    assert replace(config.view, scale=2.0) == View(yaw=-25.0, offset=(1.0, -2.0, 0.5), scale=2.0)


def test_a_run_may_draw_overdraw_but_a_file_may_not_name_it(tmp_path):
    assert RenderSettings(shading="overdraw").shading == "overdraw"
    path = tmp_path / "overdraw.toml"
    path.write_text("[muscle]\nlength = 33.0\nradius = [0.5, 2.0, 0.5]\ngrowth = [0, 1, 0]\n"
                    "[render]\nshading = \"overdraw\"\n")
    with pytest.raises(ConfigError, match=":6: render.shading: Input should be 'gouraud' or "
                                          "'phong' \\(found 'overdraw'\\)"):
        load_config(path)


def test_an_unknown_setting_is_refused_by_name():
    with pytest.raises(SettingError, match="^view has no setting 'zoom': its settings are yaw, "):
        View(zoom=2.0)
    with pytest.raises(SettingError, match="^light has no setting 'colour'"):
        replace(Light(), colour="#ffffff")


@given(st.floats(), st.floats())
def test_the_file_and_the_view_agree_on_scale_and_fov(scale, fov):
    made = table_made = True
    try:
        View(scale=scale, fov=fov)
    except SettingError:
        made = False
    try:
        in_a_file(View, scale=scale, fov=fov)
    except ValidationError:
        table_made = False
    assert made == table_made
