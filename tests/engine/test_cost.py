"""What a model, a picture and an animation may cost: each bound refused with the limit and
the figure, and a hair inside it allowed."""

import pytest

from biceps.engine.bounds import (ANIMATION_BYTES, LAYING, MESH_VERTICES, MUSCLES, NODES,
                                  PICTURE_BYTES)
from biceps.engine.cost import (check_frames, check_model, check_picture, model_problem,
                                picture_bytes)
from biceps.engine.errors import BicepsError, RefusedChange


@pytest.mark.parametrize("nodes, segments, over, words", [
    ([3] * (MUSCLES + 1), 48, "muscles", f"{MUSCLES + 1:,} muscles; a model has at most "
                                         f"{MUSCLES}"),
    ([NODES // 2 + 1] * 2, 3, "nodes", f"{NODES + 2:,} nodes; a model has at most {NODES:,}"),
    ([1_000], 1_001, "segments", "1,000 nodes at 1,001 segments round each make 1,001,000 "
                                 "vertices; at most 1,000,000 are drawn: give at most 1,000 "
                                 "segments"),
    ([LAYING // 6 // 6 + 1] * 6, 48, "nodes", f"6 muscles of {6 * (LAYING // 36 + 1):,} "
                                              "nodes together, each laid round the others: "
                                              f"6 muscles may have at most {LAYING // 6:,}"),
])
def test_a_model_over_a_bound_is_refused_with_the_limit_and_its_figure(nodes, segments, over,
                                                                       words):
    problem = model_problem(nodes, segments)
    assert problem[0] == over and problem[1].startswith(words)
    with pytest.raises(RefusedChange, match=words[:40]):
        check_model(nodes, segments)


@pytest.mark.parametrize("nodes, segments", [
    ([3] * MUSCLES, 1024), ([LAYING // 4] * 2, MESH_VERTICES // NODES), ([1_000], 1_000),
    ([NODES], 48),
])
def test_a_model_at_its_bounds_is_allowed(nodes, segments):
    assert model_problem(nodes, segments) is None


def test_a_picture_s_memory_is_its_samples_and_the_picture_averaged_down():
    assert picture_bytes(10, 20, 1) == 10 * 20 * 7
    assert picture_bytes(10, 20, 3) == 10 * 20 * (9 * 7 + 3)


@pytest.mark.parametrize("width, height, ssaa, allowed", [
    (8192, 8192, 1, True), (8192, 8192, 2, False), (4096, 4096, 3, True), (4096, 4096, 4, False),
])
def test_a_picture_larger_than_its_memory_bound_is_refused(width, height, ssaa, allowed):
    assert (picture_bytes(width, height, ssaa) <= PICTURE_BYTES) == allowed
    if allowed:
        check_picture(width, height, ssaa)
        return
    with pytest.raises(BicepsError, match=f"a picture of {width}x{height} with {ssaa}x{ssaa} "
                                          "supersampling needs .* GiB of memory, more than "
                                          "the 1.50 GiB allowed"):
        check_picture(width, height, ssaa)


def test_an_animation_s_frames_are_bounded_by_the_memory_their_encoding_takes():
    most = ANIMATION_BYTES // (640 * 360 * 7)
    check_frames(most, 640, 360)
    with pytest.raises(BicepsError, match=f"{most + 1:,} different frames of 640x360 need "
                                          f".* GiB of memory to encode, more than the 1.50 "
                                          f"GiB allowed: at this size at most {most:,}"):
        check_frames(most + 1, 640, 360)
