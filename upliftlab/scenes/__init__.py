"""Scenes: TOML files that describe a structure, its foundation, a motion and an analysis.

A scene is read, merged with one of its ``[cases.X]`` tables, patched with ``--set`` overrides
(dotted TOML keys), and validated into immutable dataclasses. Unknown keys are errors, and every
error names the field, the value and the valid range before any work starts.

The same scene runs in the reduced model and (with ``[soil]`` and ``[continuum]``) in the
continuum model. Units are declared by ``units`` and g follows from them.

The records and their readers live in :mod:`upliftlab.scenes.structure` (structure,
foundation), :mod:`upliftlab.scenes.motion` (motion, analysis, :func:`build_motion`) and
:mod:`upliftlab.scenes.soil` (soil, continuum); :mod:`upliftlab.scenes.table` reads a table key
by key; :mod:`upliftlab.scenes.overrides` merges cases and applies ``--set`` overrides;
:mod:`upliftlab.scenes.edit` derives a scene's own table, digest and provenance from its fields.
Every public name of those modules is importable from here.
"""

from __future__ import annotations

import copy
import hashlib
import json
import os
import tomllib
from dataclasses import InitVar, dataclass, field, replace
from importlib import resources
from pathlib import Path

from .. import checks
from ..checks import InputError
from ..motions import Motion
from ..paths import NO_SUCH_FILE, REGULAR_FILE, file_kind, path_component
from .motion import (DEFAULT_ENERGY_TOLERANCE, DEFAULT_MAX_MEMORY,  # noqa: F401
                     DEFAULT_MAX_STEPS, DEFAULT_RTOL, INTEGRATORS, MAX_SCALE, MOTION_TYPES,
                     Analysis, MotionSpec, build_motion, read_analysis, read_motion)
from .overrides import (apply_override, apply_overrides, check_case_override, merge_case,
                        override_key)
from .soil import (DYNAMICS, ELEMENTS, INTERFACES, MAX_ELEMENTS_ACROSS,  # noqa: F401
                   SOIL_MODELS, ContinuumOptions, Soil, read_continuum, read_soil)
from .laws import (ElasticLaw, ElastoplasticLaw, LawRecord, QzLaw,  # noqa: F401
                   check_overrides, curved_law)
from .structure import (IMPACT_MASSES, KINEMATICS, LAWS, LAYOUTS,  # noqa: F401
                        MAX_SPRINGS, SUPPORTS, Foundation, Story, Structure, read_foundation,
                        read_structure)
from .frozen import freeze
from .table import SCHEMA_VERSION, Table, check_values, string
from ..units import UnitSystem, unit_system  # noqa: F401

__all__ = [
    "SCHEMA_VERSION",
    "Story",
    "Structure",
    "Foundation",
    "MotionSpec",
    "Analysis",
    "Soil",
    "ContinuumOptions",
    "Scene",
    "load_scene",
    "scene_from_dict",
    "find_scene",
    "packaged_scenes",
    "apply_override",
    "build_motion",
]



@dataclass(frozen=True)
class Scene:
    """A validated scene. ``data`` is the merged table it came from (for provenance), a
    read-only copy (:mod:`upliftlab.scenes.frozen`): changing it raises ``TypeError``.

    The fields are the scene; ``data``, :attr:`digest` and :attr:`table` describe them. A scene
    made otherwise than by :func:`scene_from_dict` (``dataclasses.replace``, or the typed
    :meth:`replace`) is validated again from its fields, with the same checks and messages as
    a file; if its fields no longer match ``data``, ``data`` becomes the fields' own table and
    the changes are added to ``overrides``, so that the provenance of a run always describes
    the scene that ran (:mod:`upliftlab.scenes.edit`).
    """

    title: str
    units: UnitSystem
    structure: Structure
    foundation: Foundation
    motion: MotionSpec
    analysis: Analysis
    soil: Soil | None = None
    continuum: ContinuumOptions | None = None
    description: str = ""
    reference: str = ""
    cases: tuple[str, ...] = ()
    case: str | None = None
    source: str = ""
    overrides: tuple[str, ...] = ()
    data: dict = field(default_factory=dict, repr=False, compare=False)
    validated: InitVar[bool] = False

    def __post_init__(self, validated: bool) -> None:
        if not validated:
            from .edit import revalidate
            revalidate(self, scene_from_dict)
        # read-only and the scene's own copy: provenance records what ran (:mod:`.frozen`)
        object.__setattr__(self, "data", freeze(self.data))

    @property
    def g(self) -> float:
        """Acceleration of gravity in the scene's units (length/s²)."""
        return self.units.gravity

    @property
    def name(self) -> str:
        stem = Path(self.source).stem if self.source else "scene"
        return f"{stem}-{self.case}" if self.case else stem

    @property
    def table(self) -> dict:
        """The scene's own table, derived from its fields: every value explicit (defaults
        and derived stiffnesses included), in the scene's units; validating it gives back
        this scene."""
        from .edit import scene_table
        return scene_table(self)

    @property
    def digest(self) -> str:
        """SHA-256 of :attr:`table`: equal digests mean equal inputs, however the scene was
        written or changed."""
        text = json.dumps(self.table, sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()

    def build_motion(self) -> Motion:
        return build_motion(self.motion)

    def with_overrides(self, *overrides: str) -> Scene:
        """This scene with more ``key=value`` overrides (dotted TOML keys)."""
        data = copy.deepcopy(self.data)
        apply_overrides(data, overrides)
        return scene_from_dict(data, source=self.source, case=self.case,
                               overrides=self.overrides + tuple(overrides), merged=True)

    def replace(self, table: str, **fields) -> Scene:
        """This scene with ``fields`` of one record changed, validated as a file would be:
        ``scene.replace("foundation", springs=40)``. ``table`` is ``structure``, ``story``
        (the one story of an SDOF; ``story.1`` for a story of a building), ``foundation``,
        ``motion``, ``analysis``, ``soil`` or ``continuum``; each field is a field of that
        record, in the scene's units. The change is recorded in ``overrides``."""
        from .edit import replace_fields
        return replace_fields(self, table, fields)


def scene_from_dict(data: dict, *, source: str = "", case: str | None = None,
                    overrides: tuple[str, ...] = (), merged: bool = False,
                    motion: str | None = None) -> Scene:
    """Validate a scene table (as parsed from TOML) into a :class:`Scene`.

    Unless ``merged``, the ``[cases.<case>]`` table is merged in, the motion replaced by the
    record ``motion`` (a name on UPLIFTLAB_MOTIONS or a path) if given, and ``overrides``
    applied, in that order.
    """
    check_values(data)  # before the deep copy: a file nested thousands deep is refused here
    data = copy.deepcopy(data)
    if source:  # the file's name names the results: one plain path component
        path_component(Path(source).stem, "scene file name")
    if not merged:
        in_cases = [o for o in overrides if override_key(o).split(".")[0] == "cases"]
        for item in in_cases:  # edit the case table itself, before it is merged
            check_case_override(item, case, data.get("cases"))
            apply_override(data, item)
        cases_table = data.get("cases", {})
        data = merge_case(data, case)
        if motion is not None:
            data["motion"] = {"type": "record", "name": str(motion)}
        apply_overrides(data, [o for o in overrides if o not in in_cases])
        check_values(data)  # what the overrides brought in
    cases_table = data.get("cases", {}) if merged else cases_table
    table = Table(data, "")
    schema = table.get("schema", lambda n, v: checks.integer_at_least(n, v, 1))
    if schema != SCHEMA_VERSION:
        raise InputError(f"schema = {schema}: this upliftlab reads schema {SCHEMA_VERSION}")
    units = unit_system(table.get("units", string))
    g = units.gravity
    structure = read_structure(table.get("structure"), units)
    vertical_mass = structure.vertical_weight / g
    scene = Scene(
        title=table.get("title", text, ""),
        description=table.get("description", text, ""),
        reference=table.get("reference", text, ""),
        units=units,
        structure=structure,
        foundation=read_foundation(table.get("foundation"), vertical_mass, units),
        motion=read_motion(table.get("motion"), units),
        analysis=_analysis_for(read_analysis(table.get("analysis", None, {}), units),
                               data.get("analysis"), data.get("foundation")),
        soil=read_soil(table.get("soil"), units) if table.has("soil") else None,
        continuum=read_continuum(table.get("continuum")) if table.has("continuum") else None,
        cases=tuple(cases_table) if isinstance(cases_table, dict) else (),
        case=case,
        source=source,
        overrides=tuple(overrides),
        data=data,
        validated=True,
    )
    table.get("cases", None, None)
    table.done()
    _check_consistency(scene)
    return scene


#: The integrator a scene with curved springs (q–z) takes when it names none (the default, the
#: event stepper, tabulates piecewise-affine laws and refuses a curved law).
QZ_INTEGRATOR = "rk4"


def text(name: str, value) -> str:
    """``value`` if it is a string of text: no control character but tab and line breaks. A
    scene's title, description and reference are written into every result (netCDF refuses a
    NUL in a string, after the run) and printed on the terminal (an escape sequence there
    would act on it)."""
    value = string(name, value)
    for position, character in enumerate(value):
        if (ord(character) < 32 and character not in "\t\n\r") or ord(character) == 127:
            raise InputError(f"{name}: control character {character!r} at position {position}; "
                             "a scene's text holds printable characters, tabs and line breaks")
    return value


def _analysis_for(analysis: Analysis, analysis_data, foundation_data) -> Analysis:
    """The analysis of a scene with its foundation in view: a bed of a curved law
    (:attr:`~.laws.LawRecord.curved`, q–z) that names no integrator gets
    :data:`QZ_INTEGRATOR`; one that names the event stepper is refused."""
    name = foundation_data.get("law") if isinstance(foundation_data, dict) else None
    law = curved_law(name)
    if law is None:
        return analysis
    given = analysis_data.get("integrator") if isinstance(analysis_data, dict) else None
    if given is None:
        return replace(analysis, integrator=QZ_INTEGRATOR)
    if given == "events":
        raise InputError(f"analysis.integrator = 'events' with foundation.law = {name!r}: the "
                         f"event stepper tabulates piecewise-affine laws and {law.curved}; "
                         "valid: 'rk4', 'abm4', 'newmark', 'hht'")
    return analysis


def _check_consistency(scene: Scene) -> None:
    s, f = scene.structure, scene.foundation
    check_overrides(f.law, scene.overrides)
    if s.rigid and f.support == "fixed" and not f.sways:
        raise InputError("structure.rigid = true with foundation.support = 'fixed': "
                         "a rigid structure on a fixed base has no motion")
    if f.sways and s.kinematics == "exact":
        raise InputError("foundation.sway_stiffness with structure.kinematics = 'exact': exact "
                         "kinematics pivots the base on its edge without sliding; valid: 'small'")
    if f.sways and not s.rigid and not s.vertical_weight > s.weight * (1.0 + 1e-9):
        raise InputError(f"structure.vertical_weight = {s.vertical_weight:g} with "
                         "foundation.sway_stiffness: a flexible structure's swaying base needs "
                         "a mass of its own (the foundation's weight); valid range is > the "
                         f"story weights, {s.weight:g}")
    if s.rotary_inertia == 0.0 and not s.rigid and f.support != "fixed":
        raise InputError("structure.rotary_inertia = 0: the rocking base needs a mass moment of "
                         "inertia > 0 (mass·length²) unless structure.rigid = true")


def packaged_scenes() -> dict[str, Path]:
    """The scene files shipped with upliftlab, by name (in a source checkout imported as it is,
    the ``scenes/`` folder beside the package)."""
    try:
        root = resources.files("upliftlab.scene_files")
    except ModuleNotFoundError:
        root = Path(__file__).resolve().parent.parent / "scenes"
    return {Path(p.name).stem: Path(str(p)) for p in root.iterdir() if p.name.endswith(".toml")}


#: Largest scene file read (bytes).
MAX_SCENE_BYTES = 16 * 2**20


def _is_path(text: str) -> bool:
    """Whether a scene argument is a path (it has a folder part, or ends in ``.toml``) rather
    than the name of a packaged scene."""
    return os.sep in text or (os.altsep or os.sep) in text or text.lower().endswith(".toml") \
        or text.startswith("~")


def find_scene(name_or_path: str) -> Path:
    """A scene file given by a path, used as given (a path that names no file is refused, never
    replaced by a packaged scene of the same name), or the packaged scene of that name."""
    path = Path(name_or_path).expanduser()
    kind = file_kind(path, f"scene {name_or_path!r}")  # not opened: a named pipe would block
    if kind == REGULAR_FILE:
        return path
    if _is_path(name_or_path):
        what = kind if kind == NO_SUCH_FILE else f"{kind}, not a scene file"
        raise InputError(f"scene {name_or_path!r}: {what}; a path is used as given (a packaged "
                         "scene is named without folder or .toml, see `upliftlab scenes`)")
    scenes = packaged_scenes()
    if name_or_path in scenes:
        return scenes[name_or_path]
    raise InputError(f"scene {name_or_path!r}: no such file, and no packaged scene of that name "
                     f"(packaged: {', '.join(sorted(scenes))})")


def load_scene(name_or_path: str, case: str | None = None,
               overrides: tuple[str, ...] | list[str] = (), motion: str | None = None) -> Scene:
    """Read, merge, override and validate a scene file (see :func:`scene_from_dict`)."""
    path = find_scene(str(name_or_path))
    try:
        size = path.stat().st_size
        if size > MAX_SCENE_BYTES:
            raise InputError(f"scene {str(path)!r}: {size / 2**20:.0f} MiB; a scene file may "
                             f"hold at most {MAX_SCENE_BYTES // 2**20} MiB of TOML")
        data = tomllib.loads(path.read_bytes().decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise InputError(f"scene {str(path)!r}: not UTF-8 text (byte {exc.start}); a scene is "
                         "a TOML file") from None
    except OSError as exc:
        raise InputError(f"scene {str(path)!r}: cannot read it ({exc.strerror})") from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"scene {str(path)!r}: not valid TOML ({exc})") from None
    except RecursionError:
        raise InputError(f"scene {str(path)!r}: tables or lists nested too deeply to read; a "
                         "scene file nests at most a few levels") from None
    return scene_from_dict(data, source=str(path), case=case, overrides=tuple(overrides),
                           motion=motion)
