"""A live simulation streamed to the browser viewer (`fishbot sim --view`): the page of
`fishbot view`, its robot posed by MuJoCo, driven by the page's keys, its lidars' scans
drawn as they are cast."""

from __future__ import annotations

from dataclasses import dataclass

from ..analysis import Analysis, of
from ..drawing.teleop import Teleop
from ..drawing.viewer import Viewer
from ..model import Robot
from ._live import ROOM, WALL_THICKNESS, Live

__all__ = ["Stream", "stream"]


@dataclass(frozen=True, slots=True)
class Stream:
    """A simulation on a page, running until `close`.

    Attributes:
        live: The simulation.
        viewer: The page's server.
        teleop: What steps the simulation and drives it from the page.
    """

    live: Live
    viewer: Viewer
    teleop: Teleop

    @property
    def url(self) -> str:
        """Where the page is served."""
        return self.viewer.url

    def close(self) -> None:
        """Stop the simulation and the server."""
        self.teleop.close()
        self.viewer.close()


def stream(
    robot: Robot | Analysis, *, host: str = "127.0.0.1", port: int = 8080, walls: bool = True
) -> Stream:
    """Simulate ``robot`` live (see `Live`) and serve it on the viewer's page at ``host``
    and ``port`` (0: any free port).

    Raises:
        ToolNotFoundError: mujoco or viser is not installed.
        ServeError: ``host`` and ``port`` cannot be served on.
        RobotError: A body MuJoCo would refuse (its ``mjcf-refused`` findings).
        ConversionError: MuJoCo refuses the model.
    """
    analysis = of(robot)
    live = Live(analysis, walls=walls)
    viewer = Viewer(lambda: (analysis, ()), host=host, port=port, live=True)
    try:
        viewer.place(live.poses())
        teleop = Teleop(
            viewer, live, obstacles=live.obstacles, ground=ROOM + 2 * WALL_THICKNESS + 1.0
        )
    except BaseException:
        viewer.close()
        raise
    return Stream(live, viewer, teleop)
