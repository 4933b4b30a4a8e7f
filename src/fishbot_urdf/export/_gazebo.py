"""The robot's ``<gazebo>`` blocks as sdformat's URDF converter carries them into SDF: the
settings it knows (material, friction, gravity, joint physics, ...) turned into SDF
elements, everything else copied as it is; a lumped link's blocks moved to the link it is
lumped into, its sensors re-posed there and plugins' ``bodyName``/``frameName`` naming it
renamed, with offsets."""

from __future__ import annotations

from collections.abc import Callable, Iterable

from ..analysis.sdformat import FLAGS, IGNORED, NUMBERS, stod, stoi
from ..errors import ConversionError
from ..location import Location
from ..spatial import urdfdom_angles
from ._elements import LUMP, number, short, vector3
from ._lumping import IDENTITY, Placement, compose, quaternion, then
from ._reader import Element, Node, copy

__all__ = ["Extension", "Extensions"]

_ZERO = (0.0, 0.0, 0.0)


def _number(setting: Element, text: str, reference: str) -> float:
    value = stod(text)
    if value is None:
        raise _refused(setting, text, reference)
    return value


def _refused(setting: Element, text: str, reference: str) -> ConversionError:
    block = f"<gazebo reference={reference!r}>" if reference else "<gazebo>"
    where = setting.where
    return ConversionError(
        f"{block}: <{setting.tag}> is {text!r}, not a number: sdformat's converter stops on it",
        target="sdf",
        subject=reference or None,
        path=where.path if where is not None else None,
        line=where.line if where is not None else None,
        column=where.column if where is not None else None,
    )


def _key_value(element: Element) -> str:
    """A setting's text as the converter reads it: its ``value`` attribute, else its text."""
    value = element.get("value")
    if value is None:
        value = element.text if element.text is not None and not element.children else ""
    return value.strip()


def _text(value: float | bool | str) -> str:
    """A setting as the converter writes it: a text as it is, a whole number (maxContacts)
    in digits, a number as its other numbers."""
    if isinstance(value, str):
        return value
    return str(value) if isinstance(value, int) else number(value)


def _flag(text: str) -> bool:
    return text.lower() in ("true", "yes") or text == "1"


def _pose(text: str) -> Placement | None:
    """A ``<pose>`` text as gz::math's stream reads it (6 numbers), or None."""
    tokens = text.split()
    try:
        values = [float(t) for t in tokens[:6]]
    except ValueError:
        return None
    if len(values) < 6:
        return None
    return Placement(
        (values[0], values[1], values[2]), quaternion((values[3], values[4], values[5]))
    )


class Extension:
    """One ``<gazebo>`` block as the converter holds it: its settings, its blobs (the
    elements it copies), and the transform of the fixed joints lumped between the link it
    named and the one it is on now."""

    def __init__(self, reference: str, block: Element) -> None:
        self.reference = reference
        self.old = reference if block.children else ""  # the converter's oldLinkName
        self.material = ""
        self.settings: dict[str, float | bool | str] = {}
        self.where: dict[str, Location | None] = {}  # where each setting is written
        self.collisions: list[Element] = []
        self.visuals: list[Element] = []
        self.blobs: list[Element] = []
        self.reduction = Placement(_ZERO, IDENTITY)
        self.kept: dict[int, str] = {}  # a re-posed sensor's first pose, by blob index
        for child in block.children:
            tag = child.tag
            if tag == "material":
                self.material = _key_value(child)
            elif tag in ("collision", "visual"):
                (self.collisions if tag == "collision" else self.visuals).extend(
                    c.clone() for c in child.children
                )
            elif tag in FLAGS:
                self.settings[tag] = _flag(_key_value(child))
            elif tag == "cfmDamping":
                self.settings["implicitSpringDamper"] = _flag(_key_value(child))
            elif tag == "turnGravityOff":
                self.settings["gravity"] = _key_value(child).lower() in ("false", "no", "0")
            elif tag in NUMBERS:
                self.settings[tag] = _number(child, _key_value(child), reference)
                self.where[tag] = child.where
            elif tag == "maxContacts":
                whole = stoi(_key_value(child))
                if whole is None:
                    raise _refused(child, _key_value(child), reference)
                self.settings[tag] = whole
                self.where[tag] = child.where
            elif tag == "fdir1":
                self.settings[tag] = _key_value(child)
                self.where[tag] = child.where
            elif tag not in IGNORED:
                self.blobs.append(child.clone())

    def repose(self) -> None:
        """Sensors' and projectors' poses in the link the block is on now."""
        for index, blob in enumerate(self.blobs):
            if blob.tag not in ("sensor", "projector"):
                continue
            old = blob.find("pose")
            text = "0 0 0 0 0 0"
            if old is not None:
                if old.get("relative_to") is not None:
                    continue
                if index in self.kept:
                    text = self.kept[index]
                elif old.text is not None:
                    text = old.text
                else:
                    continue
                blob.remove(old)
            self.kept.setdefault(index, text)
            given = _pose(text)
            if given is None:
                continue
            placed = compose(self.reduction, given)
            blob.append(Element("pose", short((*placed.xyz, *urdfdom_angles(placed.rotation)))))

    def rename(self, link: str, parent: str, joint: Placement) -> None:
        """Plugins' ``bodyName`` and ``frameName`` that name ``link`` name ``parent``, their
        offsets carried through ``joint``."""
        for blob in self.blobs:
            if blob.tag != "plugin":
                continue
            for tag in ("bodyName", "frameName"):
                named = blob.find(tag)
                if named is None or _key_value(named) != link:
                    continue
                blob.remove(named)
                blob.append(Element(tag, parent))
                xyz, rotation = self.reduction
                offset = blob.find("xyzOffset")
                if offset is not None:
                    xyz = vector3(_key_value(offset))
                    blob.remove(offset)
                turn = blob.find("rpyOffset")
                if turn is not None:
                    rotation = quaternion(vector3(_key_value(turn)))
                    blob.remove(turn)
                corrected = blob.find("ignition::corrected_offsets")
                if corrected is not None:
                    blob.remove(corrected)
                placed = then(joint, Placement(xyz, rotation))
                blob.append(Element("xyzOffset", short(placed.xyz)))
                blob.append(Element("rpyOffset", short(urdfdom_angles(placed.rotation))))
                blob.append(Element("ignition::corrected_offsets", "1"))


class Extensions:
    """Every ``<gazebo>`` block by the name it is on (the model's under ""), as lumping
    moves them."""

    def __init__(
        self, blocks: Iterable[tuple[str, Node, Callable[[Node], Location | None]]]
    ) -> None:
        self.on: dict[str, list[Extension]] = {}
        for reference, element, place in blocks:
            self.on.setdefault(reference, []).append(Extension(reference, copy(element, place)))

    def lump(self, link: str, parent: str, joint: Placement) -> None:
        """``link``'s blocks moved onto ``parent``, welded at ``joint`` (its frame in the
        parent's), and every plugin that names it renamed."""
        moved = self.on.get(link)
        if moved is not None:
            for extension in moved:
                extension.reduction = then(joint, extension.reduction)
                extension.repose()
            self.on.setdefault(parent, []).extend(moved)
            self.on[link] = []
        for reference in sorted(self.on, key=lambda name: name.encode("utf-8")):
            for extension in self.on[reference]:
                extension.rename(link, parent, joint)

    def link(self, element: Element, name: str) -> None:
        """The link's settings and blobs, after its inertial, collisions and visuals."""
        for extension in self.on.get(name, ()):
            settings = extension.settings
            if "gravity" in settings:
                element.put("gravity", "true" if settings["gravity"] else "false")
            if "dampingFactor" in settings:
                factor = number(float(settings["dampingFactor"]))
                linear, angular = Element("linear", factor), Element("angular", factor)
                linear.where = angular.where = extension.where.get("dampingFactor")
                element.append(Element("velocity_decay", children=[linear, angular]))
            if "selfCollide" in settings:
                element.put("self_collide", "1" if settings["selfCollide"] else "0")
            element.children += [blob.clone() for blob in extension.blobs]

    def _mine(self, extension: Extension, shape: str, name: str, suffix: str) -> bool:
        """Whether the converter gives ``extension`` to the shape named ``shape`` of link
        ``name``: a block on the link to its own shapes, a lumped link's to the shapes
        lumped from it that it named after itself."""
        if name == extension.old:
            return LUMP not in shape
        return f"{LUMP}{extension.old}{suffix}" in shape

    def collision(self, element: Element, link: str) -> None:
        """A collision's surface settings and blobs."""
        name = element.get("name") or ""
        surface = element.find("surface")
        contact = contact_ode = friction = friction_ode = None
        for extension in self.on.get(link, ()):
            if not self._mine(extension, name, link, "_collision"):
                continue
            for blob in extension.collisions:
                if blob.tag != "surface":
                    element.append(blob.clone())
                    continue
                if surface is not None:
                    element.remove(surface)
                surface = element.append(blob.clone())
                contact = surface.find("contact")
                if contact is not None:
                    contact_ode = contact.find("ode")
                friction = surface.find("friction")
                if friction is not None:
                    friction_ode = friction.find("ode")
            if surface is None:
                surface = element.append(Element("surface"))
            if contact is None:
                contact = surface.find("contact") or surface.append(Element("contact"))
            if contact_ode is None:
                contact_ode = contact.find("ode") or contact.append(Element("ode"))
            if friction is None:
                friction = surface.find("friction") or surface.append(Element("friction"))
            if friction_ode is None:
                friction_ode = friction.find("ode") or friction.append(Element("ode"))
            settings = extension.settings
            for key, into, tag in (
                ("mu1", friction_ode, "mu"),
                ("mu2", friction_ode, "mu2"),
                ("fdir1", friction_ode, "fdir1"),
                ("kp", contact_ode, "kp"),
                ("kd", contact_ode, "kd"),
                ("maxVel", contact_ode, "max_vel"),
                ("minDepth", contact_ode, "min_depth"),
                ("laserRetro", element, "laser_retro"),
                ("maxContacts", element, "max_contacts"),
            ):
                value = settings.get(key)
                if value is not None and value != "":
                    into.put(tag, _text(value), extension.where.get(key))

    def visual(self, element: Element, link: str) -> None:
        """A visual's material script and blobs."""
        name = element.get("name") or ""
        material = element.find("material")
        script = None
        for extension in self.on.get(link, ()):
            if not self._mine(extension, name, link, "_visual"):
                continue
            for blob in extension.visuals:
                if blob.tag != "material":
                    element.append(blob.clone())
                    continue
                if material is not None:
                    element.remove(material)
                material = element.append(blob.clone())
                script = material.find("script")
            if extension.material:
                if material is None:
                    material = element.append(Element("material"))
                if script is None:
                    script = material.find("script") or material.append(Element("script"))
                script.put("name", extension.material)
                script.put("uri", "file://media/materials/scripts/gazebo.material")

    def joint(self, element: Element, name: str) -> None:
        """A joint's physics settings and blobs."""
        for extension in self.on.get(name, ()):
            physics = element.find("physics") or Element("physics")
            ode = physics.find("ode") or Element("ode")
            limit = ode.find("limit") or Element("limit")
            axis = element.find("axis") or Element("axis")
            dynamics = axis.find("dynamics") or Element("dynamics")
            settings = extension.settings
            for key, into, tag in (
                ("stopCfm", limit, "cfm"),
                ("stopErp", limit, "erp"),
                ("springReference", dynamics, "spring_reference"),
                ("springStiffness", dynamics, "spring_stiffness"),
            ):
                if key in settings:
                    into.put(tag, number(float(settings[key])), extension.where.get(key))
            if "provideFeedback" in settings:
                feedback = "true" if settings["provideFeedback"] else "false"
                physics.put("provide_feedback", feedback)
                ode.put("provide_feedback", feedback)
            if "implicitSpringDamper" in settings:
                implicit = "true" if settings["implicitSpringDamper"] else "false"
                ode.put("implicit_spring_damper", implicit)
                ode.put("cfm_damping", implicit)
            if "fudgeFactor" in settings:
                ode.put(
                    "fudge_factor",
                    number(float(settings["fudgeFactor"])),
                    extension.where.get("fudgeFactor"),
                )
            for parent, child in (
                (axis, dynamics),
                (element, axis),
                (ode, limit),
                (physics, ode),
                (element, physics),
            ):
                if all(c is not child for c in parent.children):
                    parent.append(child)
            element.children += [blob.clone() for blob in extension.blobs]

    def model(self, element: Element) -> None:
        """The model's ``static`` and blobs, after its links and joints."""
        for extension in self.on.get("", ()):
            element.put("static", "true" if extension.settings.get("static") else "false")
            element.children += [blob.clone() for blob in extension.blobs]
