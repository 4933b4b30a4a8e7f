"""The rules of `fishbot sim`: what went wrong when the robot was dropped on a floor and
driven, or held, in MuJoCo, as a learner would see it go wrong in Gazebo.

Data only: the simulation that reports them is `fishbot_urdf.simulation`. Their examples
run `fishbot sim` on small robots: ``cart.urdf`` is a box on two wheels and a caster, with
a differential drive plugin, that drives as it is told.
"""

from __future__ import annotations

from ..diagnostics import Consumer, Family, Rule, Severity

E, W = Severity.ERROR, Severity.WARNING
_SIMULATORS = (Consumer.GAZEBO, Consumer.MUJOCO)
_GOOD = """\
fishbot sim cart.urdf
"""


def _example(file: str, comment: str) -> str:
    return f"# {file}: {comment}\nfishbot sim {file}\n"


SIM_EXPLODED = Rule(
    "sim-exploded",
    E,
    Family.SIMULATION,
    summary="The simulation blew up: a position or speed became infinite or not a number.",
    explanation="A simulator steps the robot's motion a few hundred times a second; a link "
    "far lighter than the links it is joined to, an inertia a thousand times too small for "
    "its mass, or shapes that start deep inside each other make a step throw it further than "
    "the last, until the numbers overflow. In Gazebo the robot jitters, then flies off or "
    "vanishes. `fishbot sim` stops at the first such step and says when it came. Give each "
    "link the mass and inertia of its part (`fishbot inertia --fill`).",
    bad=_example("spinner.urdf", "wheels of 200 g whose inertia is 1e-11 kg*m^2"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
SIM_SANK = Rule(
    "sim-sank",
    E,
    Family.SIMULATION,
    summary="A wheel's centre came lower than its radius above the floor: the wheel does not "
    "roll on the circle its description says.",
    explanation="A wheel's collision cylinder is what the simulator rolls on, and URDF's "
    "cylinders lie along their link's z axis: a wheel turning about y needs "
    '`rpy="1.5708 0 0"` on its collision\'s origin. Left out, the wheel turns a coin end over '
    "end: it rolls on its rims and flat sides, the robot bumps up and down and drives at the "
    "wrong speed. A wheel sunk into the floor under its load comes low too. `fishbot sim` "
    "drops the robot on a floor, drives it, and measures how low each wheel's centre comes "
    "against its radius. Turn the collision cylinders about the axle.",
    bad=_example("coins.urdf", "the wheels' collision cylinders lie along z"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
SIM_PENETRATION = Rule(
    "sim-penetration",
    W,
    Family.SIMULATION,
    summary="A collision shape sank into the floor by more than a centimetre.",
    explanation="A simulator lets shapes in contact overlap a little; a deep overlap means "
    "the contact cannot hold the weight on it: a body far heavier than the wheels it stands "
    "on presses them into the floor, and in Gazebo the robot sinks into the ground plane and "
    "jitters. Give the links the masses they have.",
    bad=_example("anvil.urdf", "a body of 100 t on wheels of 200 g"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
SIM_TIPPED = Rule(
    "sim-tipped",
    E,
    Family.SIMULATION,
    summary="The robot tipped over: its base leaned more than 30 degrees.",
    explanation="A robot falls over when its centre of mass leaves the area its contacts "
    "span: wheels and casters too close together, a mass placed high or far out, or an "
    "inertial written in the wrong frame. In Gazebo it topples as soon as it is spawned or "
    "when it starts to drive. Check where each link's mass is (`fishbot view` shows it), and "
    "put the casters where they hold the body up.",
    bad=_example("tall.urdf", "a 2 m mast of 10 kg on a body of 1 kg with no casters"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
SIM_WHEEL_OFF_FLOOR = Rule(
    "sim-wheel-off-floor",
    E,
    Family.SIMULATION,
    summary="A driven wheel never, or hardly ever, touches the floor.",
    explanation="A wheel in the air turns and moves nothing: the robot stands still or turns "
    "in circles while its odometry says it drives. Casters placed below the wheels' contact "
    "plane lift the wheels off the floor, and so do wheels placed too high on the body. "
    "`fishbot sim` counts the steps on which each driven wheel touches the floor. Place the "
    "casters' lowest point at the wheels' (the wheel joint's height less the wheel radius).",
    bad=_example("stilts.urdf", "the caster reaches 1 cm below the wheels"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
SIM_BODY_ON_FLOOR = Rule(
    "sim-body-on-floor",
    E,
    Family.SIMULATION,
    summary="A part of the robot that is neither a wheel nor a caster rests on the floor.",
    explanation="A body that touches the floor drags along it: the robot drives slower than "
    "it is told, or not at all, and turns about the point it scrapes. Wheels too small for "
    "the body, placed too high, or a body too heavy for its wheels' contacts let it down. "
    "Give the robot wheels that hold the body above the floor.",
    bad=_example("sledge.urdf", "the body's box reaches 2 cm below the wheels"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
SIM_CASTER_DRAG = Rule(
    "sim-caster-drag",
    W,
    Family.SIMULATION,
    summary="A caster drags on the floor instead of rolling: it holds the robot back.",
    explanation="A caster is often a ball fixed to the body: it cannot roll, so it slides, "
    "and Gazebo gives it the friction of any link (1, unless its `<gazebo reference>` says "
    "`<mu1>`). A sliding caster with friction brakes the robot and turns it off its course. "
    "Give the caster `<mu1>0</mu1>` and `<mu2>0</mu2>` in its `<gazebo reference>`, or a "
    "continuous joint to roll on.",
    bad=_example("braked.urdf", "a fixed ball caster with Gazebo's default friction"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
SIM_SPEED = Rule(
    "sim-speed",
    E,
    Family.SIMULATION,
    summary="Driven straight, the robot moved at a speed other than it was told, or other "
    "than its wheels' turning says.",
    explanation="A differential drive turns each wheel at the commanded speed over the wheel "
    "radius it is told; the robot moves at that turning times the radius it rolls on. A "
    "plugin told the wrong radius, wheels that slip or spin in the air, and a body that drags "
    "make the robot slower or faster than commanded, and the odometry wrong. `fishbot sim` "
    "drives the robot straight and compares its speed with the command and with its wheels' "
    "turning times their radius; it names the cause it can see.",
    bad=_example("slow.urdf", "the plugin is told the wheel diameter as the radius"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
SIM_TURN = Rule(
    "sim-turn",
    E,
    Family.SIMULATION,
    summary="Turned on the spot, the robot turned at a rate other than it was told, or the "
    "other way.",
    explanation="To turn, a differential drive runs its wheels at opposite speeds from the "
    "separation it is told. With the left and right wheels swapped, the robot turns right "
    "when told to turn left; with the wrong separation, or casters that brake, it turns at "
    "the wrong rate. `fishbot sim` turns the robot on the spot and compares its turn rate "
    "with the command, and with the rate its wheels' speeds and separation give.",
    bad=_example("mirrored.urdf", "the plugin's left_joint is the wheel on the right"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
SIM_SAG = Rule(
    "sim-sag",
    E,
    Family.SIMULATION,
    summary="A joint held by its servo sagged under gravity: its effort limit cannot hold "
    "the links it carries.",
    explanation="`fishbot sim` holds a robot without wheels at a configuration within its "
    "joint limits, by its root, as an arm stands on its table, with a position servo on "
    "each joint limited to its `<limit effort>`. A joint whose effort limit is below the "
    "torque gravity puts on it sags, as it does in Gazebo under ros2_control, and a real "
    "motor of that rating cannot hold the pose. Give the joint its motor's effort, or the "
    "links their real masses.",
    bad=_example("weak_arm.urdf", "a 1 m arm of 5 kg on a joint of 1 N*m"),
    good="fishbot sim arm.urdf\n",
    consumers=_SIMULATORS,
    language="shell",
)
SIM_SELF_CONTACT = Rule(
    "sim-self-contact",
    W,
    Family.SIMULATION,
    summary="Two links' collision shapes overlap at the configuration the robot is held or "
    "driven at.",
    explanation="MuJoCo collides a robot's links with each other, except a link with its "
    "parent, and so does Gazebo for links whose `<self_collide>` is on: collision shapes that "
    "overlap at rest then push the links apart, and the robot shakes or jumps as soon as the "
    "simulation starts. `fishbot sim` says which overlap where the robot starts, then lets "
    "them pass through each other, as Gazebo does by default. Shrink the collision shapes to "
    "the parts they stand for.",
    bad=_example("crowded.urdf", "the two wheels, 2 cm apart, overlap"),
    good=_GOOD,
    consumers=_SIMULATORS,
    language="shell",
)
