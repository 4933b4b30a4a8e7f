"""How names are offered back: the closest of several, and listings with the names most
like the one asked for first."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fishbot_urdf.wording import closest, did_you_mean, listing, ranked

FISHBOT_LINKS = [
    "back_caster_link",
    "base_footprint",
    "base_link",
    "camera_link",
    "front_caster_link",
    "imu_link",
    "laser_cylinder_link",
    "laser_link",
    "left_wheel_link",
    "right_wheel_link",
]


@pytest.mark.parametrize(
    ("name", "candidates", "found"),
    [
        # A ROS suffix more or less, or another one.
        ("imu", FISHBOT_LINKS, "imu_link"),
        ("left_wheel", FISHBOT_LINKS, "left_wheel_link"),
        ("base", FISHBOT_LINKS, "base_link"),
        ("imu_frame", FISHBOT_LINKS, "imu_link"),
        ("camera_link", ["camera", "camera_optical"], "camera"),
        ("imu_frame", ["imx_link", "laser_link"], "imx_link"),  # a misspelling, another suffix
        # Misspellings: a letter changed, left out, put in, two swapped; case.
        ("base_lnk", FISHBOT_LINKS, "base_link"),
        ("lft_wheel_link", FISHBOT_LINKS, "left_wheel_link"),
        ("front_castor_link", FISHBOT_LINKS, "front_caster_link"),
        ("Base_Link", FISHBOT_LINKS, "base_link"),
        ("radus", ["radius", "length"], "radius"),
        ("wiht_arm", ["with_arm", "use_camera"], "with_arm"),
        ("base_urdf.xacro", ["base.urdf.xacro", "robot.urdf.xacro"], "base.urdf.xacro"),
        ("inertia-mismach", ["inertia-mismatch", "mesh-units"], "inertia-mismatch"),
        ("velocty", ["position", "velocity", "effort"], "velocity"),
        # What shares only a word with it, or differs in the word that matters, is not.
        ("wheel_radius", ["wheel_name", "wheel_length"], None),
        ("wheel_radius", ["wheel_name", "wheel_radus"], "wheel_radus"),
        ("right_wheel_joint", ["left_wheel_joint", "camera_joint"], None),
        ("base_link", ["laser_link"], None),
        ("ghost_joint", ["camera_joint"], None),
    ],
)
def test_the_closest_name(name: str, candidates: list[str], found: str | None) -> None:
    assert closest(name, candidates) == found


def test_did_you_mean_words_it() -> None:
    assert did_you_mean("imu", FISHBOT_LINKS) == "did you mean 'imu_link'? "
    assert did_you_mean("wheel_radius", ["wheel_name"]) == ""


def test_a_listing_puts_the_names_like_the_one_asked_for_first_and_counts_the_rest() -> None:
    assert listing(FISHBOT_LINKS) == (
        "back_caster_link, base_footprint, base_link, camera_link, front_caster_link, "
        "imu_link, laser_cylinder_link, laser_link, ... (2 more)"
    )
    assert listing(FISHBOT_LINKS, 4, near="left_wheel") == (
        "left_wheel_link, right_wheel_link, back_caster_link, base_footprint, ... (6 more)"
    )
    assert ranked("laser", FISHBOT_LINKS) == ["laser_link", "laser_cylinder_link"]
    assert listing(["b", "a"], near="zzz") == "a, b"


_NAMES = st.text(alphabet="abcde_", max_size=8)


@settings(max_examples=300, deadline=None)
@given(_NAMES, st.lists(_NAMES, max_size=12))
def test_the_closest_name_is_a_candidate_whatever_their_order(
    name: str, candidates: list[str]
) -> None:
    found = closest(name, candidates)
    assert found is None or found in candidates
    assert closest(name, list(reversed(candidates))) == found
    if found is not None:
        assert ranked(name, candidates)[0] == found


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet="abcdefgh", min_size=4, max_size=12), st.data())
def test_one_edit_finds_the_name(name: str, data: st.DataObject) -> None:
    i = data.draw(st.integers(0, len(name) - 2))
    edited = data.draw(
        st.sampled_from(
            [
                name[:i] + name[i + 1 :],  # left out
                name[:i] + "z" + name[i:],  # put in
                name[:i] + "z" + name[i + 1 :],  # changed
                name[:i] + name[i + 1] + name[i] + name[i + 2 :],  # swapped
            ]
        )
    )
    assert closest(edited, [name, "something_else_entirely"]) == name
    assert closest(name + "_link", [name]) == name


def _osa(a: str, b: str) -> int:
    """Optimal string alignment distance, every cell counted (what the matcher bounds)."""
    d = [[i + j if i * j == 0 else 0 for j in range(len(b) + 1)] for i in range(len(a) + 1)]
    for i in range(1, len(a) + 1):
        for j in range(1, len(b) + 1):
            d[i][j] = min(
                d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])
            )
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                d[i][j] = min(d[i][j], d[i - 2][j - 2] + 1)
    return d[len(a)][len(b)]


def _stem(name: str) -> str:
    low = name.lower()
    for suffix in ("_link", "_joint", "_frame", "-link", "-joint", "-frame"):
        if low.endswith(suffix) and len(low) > len(suffix):
            return low[: -len(suffix)]
    return low


def _reference(name: str, candidates: list[str]) -> str | None:
    found = []
    for c in set(candidates):
        gap = abs(len(c) - len(name))
        if c.lower() == name.lower():
            found.append((0, 0, gap, c))
        elif _stem(c) == _stem(name):
            found.append((1, 0, gap, c))
        else:
            allowed = max(1, max(len(_stem(name)), len(_stem(c))) // 4)
            edits = min(_osa(name.lower(), c.lower()), _osa(_stem(name), _stem(c)))
            if edits <= allowed:
                found.append((2, edits, gap, c))
    return min(found)[3] if found else None


_PARTS = st.sampled_from(["imu", "imx", "base", "bsae", "wheel", "whel", "_link", "_frame", "_"])


@settings(max_examples=500, deadline=None)
@given(
    st.lists(_PARTS, min_size=1, max_size=4).map("".join),
    st.lists(st.lists(_PARTS, min_size=1, max_size=4).map("".join), max_size=10),
)
def test_what_the_matcher_turns_down_unseen_it_would_have_turned_down_seen(
    name: str, candidates: list[str]
) -> None:
    # The length and letter bounds, and the edits counted only so far, change no answer.
    assert closest(name, candidates) == _reference(name, candidates)
