"""`fishbot sim`: the robot dropped on a floor and driven, or held, in MuJoCo, and what went
wrong said as a learner would see it in Gazebo."""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Sequence
from typing import Literal

import click

from .. import simulation
from ..analysis import Analysis
from ..catalog.gazebo import DIFF_DRIVE_SIZE, DIFF_DRIVE_WHEELS
from ..catalog.joints import WHEEL_AXIS
from ..config import Config
from ..diagnostics import escape_controls
from ..errors import FishbotUrdfError, RobotError, ToolNotFoundError
from ..lint import CheckResult, check_again
from ..simulation import Outcome, quiet_mujoco, simulate
from ._checking import check_input, nearest_config, posable_input, posing, posing_errors
from ._common import (
    EXIT_INVALID,
    EXIT_OK,
    base_options,
    emit_findings,
    format_option,
    limit_options,
    not_installed,
    package_option,
    packages_option,
    status_of,
    stop_on,
    to_stdout,
    xacro_args,
)

_FASTEST, _TURNIEST = 20.0, 50.0  # m/s, rad/s: beyond what a robot described in URDF drives


class _Drive(click.ParamType):  # type: ignore[type-arg]
    """``V,OMEGA``: a speed (m/s) and a turn rate (rad/s)."""

    name = "V,OMEGA"

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> tuple[float, float]:
        if isinstance(value, tuple):
            return (float(value[0]), float(value[1]))
        parts = str(value).split(",")
        try:
            speed, turn = (float(p) for p in parts)
        except ValueError:
            self.fail(f"{value!r} is not V,OMEGA: two numbers, as 0.5,1.0", param, ctx)
        if not (abs(speed) <= _FASTEST and abs(turn) <= _TURNIEST):
            self.fail(
                f"{value!r}: a speed of at most {_FASTEST:g} m/s and a turn rate of at most "
                f"{_TURNIEST:g} rad/s, either way",
                param,
                ctx,
            )
        return speed, turn


@click.command()
@click.argument("file", type=click.Path(allow_dash=True))
@click.argument("args", nargs=-1, metavar="[name:=value]...")
@click.option(
    "--drive",
    type=_Drive(),
    default="0.5,1.0",
    show_default=True,
    help="The straight run's speed (m/s) and the turn's rate (rad/s, positive to the left), "
    "as linear.x and angular.z of the Twist teleop_twist_keyboard sends.",
)
@click.option(
    "--seconds",
    type=click.FloatRange(min=0, min_open=True, max=600),
    default=2.0,
    show_default=True,
    help="How long each drive (or the hold) lasts once the command is reached (simulated s).",
)
@base_options(
    "Hold the robot by its root link (the default for a robot without wheels).",
    "Drop the robot on the floor (the default for a wheeled robot).",
)
@click.option(
    "--view",
    is_flag=True,
    help="Run the robot live on the page of `fishbot view`, driven by the arrow keys, "
    "until Ctrl-C, in place of the trial.",
)
@click.option(
    "--host", default="127.0.0.1", show_default=True, help="With --view: where to serve the page."
)
@click.option(
    "--port",
    default=8080,
    show_default=True,
    type=click.IntRange(0, 65535),
    help="With --view: the port (0: any free one).",
)
@format_option(("text", "json"), "text: what was measured, as a table; json: the same.")
@package_option()
@limit_options()
def sim(
    file: str,
    args: Sequence[str],
    drive: tuple[float, float],
    seconds: float,
    base: str | None,
    view: bool,
    host: str,
    port: int,
    fmt: str,
    package_items: Sequence[str],
) -> None:
    """Drop FILE (URDF or xacro) on a floor in MuJoCo and drive it, or hold it, and say what
    went wrong, as a learner would check it in Gazebo: no ROS, no Gazebo, no display.

    A robot with a differential drive (its Gazebo plugin's wheels, or two continuous wheel
    joints) is dropped on the floor, left to settle for 1 s, driven straight, stopped, and
    turned on the spot, each at the --drive command (ramped over 0.5 s) for --seconds; its
    wheels are turned as the plugin turns them, from the separation and radius it is
    told. Measured: each wheel centre's height against its radius, the speed against the
    command and against the wheels' turning times their radius, the turn rate, and which
    links touch the floor. Any other robot is held by its root link, each joint at 0 (or
    at the limit nearer 0), by a servo limited to its <limit effort>; measured: how far each
    joint sags. Every run watches for a blow-up, tipping over, shapes deep in the floor,
    and links whose collision shapes overlap at the start.

    What went wrong is printed as check prints findings (sim-sank, sim-speed, sim-turn,
    sim-wheel-off-floor, sim-body-on-floor, sim-caster-drag, sim-tipped, sim-exploded,
    sim-penetration, sim-sag, sim-self-contact; `fishbot rules sim-speed` explains one),
    with the line to fix and the cause where the robot's files show it; a body MuJoCo
    refuses is an mjcf-refused error and nothing is simulated. The table of what was
    measured goes to standard output (--format json: the same, with the findings). Needs
    the sim extra: pip install 'fishbot-urdf[sim]'. Exit status: 0 the robot did what it
    was told, 1 something went wrong (an error finding), 2 a file could not be read,
    mujoco is not installed, or the command line is wrong.

    With --view, the robot runs live in real time on the page of `fishbot view` (prints
    the URL; Ctrl-C stops), in a square room 3 m wide: Up and Down step its speed by
    0.1 m/s, Left and Right its turn rate by 0.5 rad/s, space or k stops (or the page's
    buttons), each wheel turned as its drive plugin turns it, ramped over 0.5 s. The
    Sensors checkbox shows each lidar's rays to what they hit, cast at the sensor's
    <update_rate> from its <range> min to max. A robot without a drive is held by its
    root link. --drive, --seconds, the bases and --format are for the trial. Needs the
    view extra too: pip install 'fishbot-urdf[view]'.

    \b
    Examples:
      fishbot sim robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot sim robot.urdf.xacro --drive 0.2,0.5 --seconds 5
      fishbot sim arm.urdf --format json
      fishbot sim humanoid.urdf --floating-base
      fishbot sim robot.urdf.xacro --view --port 8081
    """
    if file == "-" and args:
        raise click.UsageError("name:=value arguments are for a .xacro file, not standard input")
    values = xacro_args(args)
    config = nearest_config(file)
    packages = packages_option(package_items)
    if fmt == "json":  # the robot's errors in the report too, and nothing on stderr
        result = _json_input(file, values, packages, config)
    else:
        result = posable_input(file, values, packages, config=config)
    assert result.analysis is not None
    if view:
        _live(result.analysis, host, port)
    speed, turn = drive
    chosen: Literal["auto", "fixed", "floating"] = (
        "fixed" if base == "fixed" else "floating" if base == "floating" else "auto"
    )
    try:
        quiet_mujoco()  # its warnings are the findings' to say (and no log file is written)
        outcome = simulate(result.analysis, seconds=seconds, speed=speed, turn=turn, base=chosen)
    except ToolNotFoundError as exc:  # mujoco: the setup's fault, not the robot's
        emit_findings([not_installed(exc, "fishbot sim", "the simulation")])
        sys.exit(status_of(exc))
    except FishbotUrdfError as exc:
        stop_on(exc)
    # what the check says of the drive first (it names the cause the simulation shows), then
    # what the simulation found that it did not say
    drive_rules = [rule.id for rule in _DRIVE_RULES if config.applies(rule.id)]
    said = list(check_again(result, config.updated(select=drive_rules))) if drive_rules else []
    places = {(d.rule, d.path, d.line) for d in said}
    findings = said + [
        d
        for d in outcome.findings
        if config.applies(d.rule) and (d.rule, d.path, d.line) not in places
    ]
    if fmt == "json":  # the findings are in it, as check --format json has them
        to_stdout((json.dumps(_json(outcome, findings), indent=2) + "\n").encode("utf-8"))
    else:
        to_stdout(_table(outcome, speed, turn).encode("utf-8"))
        emit_findings(findings)
    sys.exit(EXIT_INVALID if any(d.is_error for d in findings) else EXIT_OK)


def _json_input(
    file: str, values: dict[str, str], packages: dict[str, str], config: Config
) -> CheckResult:
    """FILE read and checked as `posable_input` does, for --format json: a robot whose tree
    is in doubt is a report of its errors, with no trial (exit 1)."""
    try:
        result = check_input(file, values, packages, posing(config))
    except FishbotUrdfError as exc:
        stop_on(exc)
    blocking = posing_errors(result.diagnostics)
    if result.analysis is not None and not blocking:
        return result
    report = {
        "robot": result.robot.name if result.robot is not None else None,
        "trial": None,
        "seconds": 0.0,
        "steps": 0,
        "ok": False,
        "measures": [],
        "findings": [d.to_dict() for d in blocking],
    }
    to_stdout((json.dumps(report, indent=2) + "\n").encode("utf-8"))
    sys.exit(EXIT_INVALID)


def _live(analysis: Analysis, host: str, port: int) -> None:
    """Serve the robot live until Ctrl-C (never returns)."""
    try:
        shown = simulation.stream(analysis, host=host, port=port)
    except ToolNotFoundError as exc:  # mujoco or viser: the setup's fault, not the robot's
        needs = "the simulation" if exc.tool == "mujoco" else "the viewer"
        emit_findings([not_installed(exc, "fishbot sim", needs)])
        sys.exit(status_of(exc))
    except RobotError as exc:  # mjcf-refused: the bodies MuJoCo would refuse, located
        emit_findings(list(exc.diagnostics))
        sys.exit(EXIT_INVALID)
    except FishbotUrdfError as exc:  # cannot serve there, MuJoCo refuses the robot
        stop_on(exc)
    try:
        if shown.live.drive is None:
            _say(
                f"fishbot sim: {analysis.robot.name} has no differential drive: it is held "
                "by its root link, and the keys move nothing"
            )
        _say(f"fishbot sim: {shown.url} (Ctrl-C stops)")
        while True:
            time.sleep(3600)
    finally:
        shown.close()


def _say(line: str) -> None:
    """A line on stdout, as every command writes there (a closed stdout is an error)."""
    to_stdout(f"{escape_controls(line)}\n".encode("utf-8", "surrogateescape"))


_DRIVE_RULES = (WHEEL_AXIS, DIFF_DRIVE_WHEELS, DIFF_DRIVE_SIZE)
"""The check's rules on a drive, which say what the simulation will show, and why (a drive
naming no joint of the robot is the simulation's own finding)."""
_DONE = {
    "drive": "dropped on the floor, driven straight at {speed:g} m/s, turned at {turn:g} rad/s",
    "hold": "held by its root link, each joint by its servo",
    "drop": "dropped on the floor, each joint held by its servo",
}


def _table(outcome: Outcome, speed: float, turn: float) -> str:
    done = _DONE[outcome.trial].format(speed=speed, turn=turn)
    if outcome.stopped:
        return f"{outcome.robot}: not simulated: {outcome.stopped}\n"
    lines = [f"{outcome.robot}: {done} ({outcome.seconds:.2f} s simulated, {outcome.steps} steps)"]
    rows = []
    for m in outcome.measures:
        expected = "" if m.expected is None else f"{_number(m.expected)} {m.unit}"
        if m.most is not None:
            expected = f"at most {_number(m.most)} {m.unit}"
        rows.append(
            (m.name, m.about, f"{_number(m.value)} {m.unit}", expected, "ok" if m.ok else "FAIL")
        )
    if rows:
        header = ("measured", "on", "value", "expected", "")
        widths = [max(len(r[i]) for r in [header, *rows]) for i in range(5)]
        for row in [header, *rows]:
            lines.append("  " + "  ".join(c.ljust(w) for c, w in zip(row, widths, strict=True)))
    status = "did what it was told" if outcome.ok else "went wrong: see the findings"
    lines.append(f"{outcome.robot}: {status}")
    return "\n".join(line.rstrip() for line in lines) + "\n"


def _number(value: float) -> str:
    return f"{value:.4g}"


def _json(outcome: Outcome, findings: list) -> dict:  # type: ignore[type-arg]
    return {
        "robot": outcome.robot,
        "trial": outcome.trial,
        "seconds": outcome.seconds,
        "steps": outcome.steps,
        "ok": not any(d.is_error for d in findings),
        "measures": [m.to_dict() for m in outcome.measures],
        "findings": [d.to_dict() for d in findings],
    }
