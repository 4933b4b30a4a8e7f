"""Where each name of a robot is written and used: definitions, references, renaming,
completion, hover and outlines for URDF and xacro files, as an editor asks for them.

Places are 1-based lines and columns in characters (a Python string index plus one), a
span's end exclusive; paths are absolute. Texts are read through a
`~fishbot_urdf.workspace.Workspace`, so an editor's unsaved buffers are used, and scanned
leniently: a file in the middle of an edit answers what can be read of it. Nothing is
evaluated: a property's value is worked out only when it is arithmetic of numbers and other
properties.

- `Span` (path, line, column, end_line, end_column), `Symbol` (name, kind, span,
  selection, detail, children), `Completion` (label, kind, detail, documentation,
  insert_text);
- ``Index.of(workspace, result)``: the index of the robot a `~fishbot_urdf.lint.CheckResult`
  checked, kept in the workspace until a file it read changes; ``Index.of_file(workspace,
  path)`` for a file no robot checked (what it defines and uses itself). Then, at
  ``(path, line, column)``: ``definition`` -> spans, ``references(..., declaration=True)``
  -> spans, ``prepare_rename`` -> the span of the name or None, ``rename_refusal`` -> why the
  name there cannot be renamed or None, ``rename(..., new_name)``
  -> ``{path: [(span, new text), ...]}`` (raises `~fishbot_urdf.errors.ArgumentError`
  saying why not: a name built by an expression, an invalid or taken new name),
  ``completion`` -> completions, ``hover`` -> Markdown or None;
- ``symbols(workspace, path)``: the outline of one file.

Names: links and joints (``<link name>``, ``<joint name>``, a joint's parent and child,
``<gazebo reference>``, the joints of ``<transmission>`` and ``<ros2_control>``, ``<mimic>``,
the joints and frames of Gazebo plugins; a name a macro builds, ``${prefix}_link``, is
defined where the macro writes it, and a name handed to a macro as ``${param}`` is followed
to the call that gives it), materials, macros and their calls, macro parameters, properties
and ``${...}`` uses, arguments and ``$(arg ...)``, includes (``$(find pkg)`` resolved through
the workspace's packages).
"""

from __future__ import annotations

from .answers import Completion, Span, Symbol
from .index import Index
from .outline import symbols

__all__ = ["Completion", "Index", "Span", "Symbol", "symbols"]
