"""The colours of what sdformat's converter makes of the links: one for each link of the
Gazebo model (those lumped into it share it), and a dark ghost for a link it leaves out;
and the words the viewer labels such links with."""

from __future__ import annotations

from ..analysis.gazebo import Lumping

__all__ = ["DROPPED", "PALETTE", "notes", "tints"]

PALETTE = (
    (0.12, 0.47, 0.71, 1.0),  # blue
    (0.17, 0.63, 0.17, 1.0),  # green
    (0.55, 0.34, 0.29, 1.0),  # brown
    (0.89, 0.47, 0.76, 1.0),  # pink
    (0.74, 0.74, 0.13, 1.0),  # olive
    (0.09, 0.75, 0.81, 1.0),  # cyan
    (0.5, 0.5, 0.5, 1.0),  # grey
)
"""The Gazebo links' colours, in the order the converter meets them from the root (and
round again past the last): no red, orange or purple, which the mass, the lidars and the
cameras are drawn in."""
DROPPED = (0.1, 0.1, 0.1, 0.4)
"""A link the converter leaves out: dark and seen through."""


def tints(lumping: Lumping) -> dict[str, tuple[float, float, float, float]]:
    """Each link's colour by what it becomes in Gazebo: the colour of the Gazebo link it is
    (or is lumped into), or :data:`DROPPED`."""
    lost = lumping.lost()
    kept = dict.fromkeys(
        landing.link for name, landing in lumping.landings.items() if name not in lost
    )
    colours = {link: PALETTE[i % len(PALETTE)] for i, link in enumerate(kept)}
    return {
        name: DROPPED if name in lost else colours.get(landing.link, DROPPED)
        for name, landing in lumping.landings.items()
    }


def notes(lumping: Lumping) -> dict[str, str]:
    """What a person is told of each link sdformat's converter does not keep as it is: the
    link it is lumped into, or that it is left out, and why."""
    said: dict[str, str] = {}
    for name, landing in lumping.landings.items():
        if landing.link != name:
            said[name] = f"{name} \u2192 {landing.link} (lumped)"
    for stop, lost in lumping.dropped.items():
        for name in lost:
            why = "no mass" if name == stop else f"{stop} has no mass"
            said[name] = f"{name}: left out ({why})"
    return said
