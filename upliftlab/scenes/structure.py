"""The structure and the foundation of a scene: their records and how they are read from the
scene's ``[structure]`` and ``[foundation]`` tables (the foundation's law: :mod:`.laws`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .. import bounds, checks
from ..checks import InputError
from .laws import LAWS, ElasticLaw, LawContext, LawRecord, read_law
from .table import MISSING, Table, choice, in_range, numbers
from ..units import UnitSystem

__all__ = ["KINEMATICS", "SUPPORTS", "LAYOUTS", "LAWS", "IMPACT_MASSES", "MAX_SPRINGS", "Story",
           "Structure", "Foundation", "read_structure", "read_foundation"]

SUPPORTS = ("uplift", "bonded", "fixed")
LAYOUTS = ("winkler", "edges", "equivalent", "end_stiffened", "custom")
IMPACT_MASSES = ("point", "tributary")
KINEMATICS = ("small", "exact")


@dataclass(frozen=True)
class Story:
    """One story of a shear building: a lumped mass on a story spring.

    ``weight`` (force) at ``height`` (length, above the base centre O); ``stiffness`` of the story
    spring below it (force/length); ``yield_force`` (force; inf = elastic) with a bilinear
    ``post_yield_ratio``; ``damping_ratio`` of its parallel dashpot, as a fraction of critical
    for the fixed-base first mode (None: the structure's ratio).
    """

    weight: float
    height: float
    stiffness: float
    yield_force: float = math.inf
    post_yield_ratio: float = 0.0
    damping_ratio: float | None = None


@dataclass(frozen=True)
class Structure:
    """The superstructure (Ewing eqs. 6–8): one story (SDOF) or a shear building (MDOF).

    ``rotary_inertia`` is I₀, the mass moment of inertia of the rocking base body about O
    (mass·length²), excluding the story masses, which enter through their lateral DOFs.
    ``vertical_weight`` (force) is carried by the foundation and gives the vertical mass.
    ``rigid`` ties every story to the base rotation (u = 0). ``p_delta`` adds the P-Δ effect of
    the story weights: about the rocking base and on the story drifts. ``kinematics`` is
    ``small`` (the paper's small rotations) or ``exact``: the base rotates about the edge it
    leans towards, every mass moves on its exact path and gravity acts on the exact
    configuration (P-Δ exact, so ``p_delta`` is true).
    """

    stories: tuple[Story, ...]
    damping_ratio: float
    rotary_inertia: float
    vertical_weight: float
    rigid: bool = False
    p_delta: bool = False
    kinematics: str = "small"

    @property
    def weight(self) -> float:
        return sum(s.weight for s in self.stories)

    @property
    def height(self) -> float:
        """Height of the top mass (length)."""
        return self.stories[-1].height


def _story(table: Table, sdof: bool, units: UnitSystem) -> Story:
    weight = table.get("weight", bounds.checker("force", units))
    height = table.get("height", bounds.checker("length", units))
    if table.has("stiffness") and table.has("period"):
        raise InputError(f"{table.path}: give stiffness or period, not both")
    if table.has("period") and sdof:
        period = table.get("period", bounds.checker("period", units))
        stiffness = (weight / units.gravity) * (2.0 * math.pi / period) ** 2
    else:
        stiffness = table.get("stiffness", bounds.checker("stiffness", units))
    yield_force = table.get("yield_force", lambda n, v: _force_or_inf(n, v, units), math.inf)
    ratio = table.get("post_yield_ratio", in_range(0.0, 1.0, high_open=True), 0.0)
    damping = None if sdof else table.get("damping_ratio", in_range(0.0, 1.0), None)
    return Story(weight, height, stiffness, yield_force, ratio, damping)


def _force_or_inf(name: str, value, units: UnitSystem) -> float:
    """A force within the physical range, or inf (no yield)."""
    value = checks.positive(name, value, allow_inf=True)
    return value if math.isinf(value) else bounds.check(name, value, "force", units)


def read_structure(data, units: UnitSystem) -> Structure:
    """The :class:`Structure` of a ``[structure]`` table (one story, or ``[[structure.story]]``)."""
    table = Table(data, "structure")
    if table.has("story"):
        stories_data = table.get("story")
        if not isinstance(stories_data, list) or not stories_data:
            raise InputError("structure.story: expected a list of story tables")
        stories = []
        for i, item in enumerate(stories_data):
            sub = Table(item, f"structure.story.{i}")
            stories.append(_story(sub, sdof=False, units=units))
            sub.done()
        stories = tuple(stories)
    else:
        stories = (_story(table, sdof=True, units=units),)
    heights = [s.height for s in stories]
    for i in range(1, len(heights)):
        if heights[i] <= heights[i - 1]:
            raise InputError(f"structure.story.{i}.height = {heights[i]:g}: must exceed the "
                             f"story below ({heights[i - 1]:g})")
    rigid = table.get("rigid", checks.boolean, False)
    kinematics = table.get("kinematics", choice(KINEMATICS), "small")
    p_delta = table.get("p_delta", checks.boolean, kinematics == "exact")
    if kinematics == "exact" and not p_delta:
        raise InputError("structure.p_delta = false with structure.kinematics = 'exact': exact "
                         "kinematics carries the weight's P-Δ exactly; valid: true (or remove it)")
    structure = Structure(
        stories=stories,
        damping_ratio=table.get("damping_ratio", in_range(0.0, 1.0), 0.0),
        rotary_inertia=table.get("rotary_inertia", bounds.checker("rotary_inertia", units)),
        vertical_weight=table.get("vertical_weight", bounds.checker("force", units),
                                  sum(s.weight for s in stories)),
        rigid=rigid,
        p_delta=p_delta,
        kinematics=kinematics,
    )
    table.done()
    if kinematics == "exact" and structure.vertical_weight < structure.weight * (1 - 1e-12):
        raise InputError(f"structure.vertical_weight = {structure.vertical_weight:g}: with exact "
                         f"kinematics the story weights ride on the base; valid range is >= "
                         f"their sum {structure.weight:g}")
    return structure


@dataclass(frozen=True)
class Foundation:
    """The foundation under the base (Ewing eqs. 3, 9; Figs. 1, 6).

    ``support``: ``uplift`` (compression-only springs), ``bonded`` (springs also carry tension)
    or ``fixed`` (θ and V locked). ``half_width`` b (length). ``layout`` and ``springs`` (N) place
    the springs; ``stiffness`` is their total K_v (force/length). ``law`` is the springs' law:
    its record (:mod:`.laws`: :class:`~.laws.ElasticLaw`, :class:`~.laws.ElastoplasticLaw`,
    :class:`~.laws.QzLaw`), named by ``law.name`` and holding that law's own keys of the table
    (a yield multiple, a capacity, z50, …). Dashpots in
    parallel carry ``damping_ratio`` of critical for the bonded vertical mode. ``restitution`` ε
    < 1 adds Ewing's impact damper with c* = ``impact_multiple`` · c_cr. ``impact_mass``: the
    mass behind a landing spring in c_cr and Δz — ``point`` (the paper's eq. 17: the structure's
    effective mass at the spring's position, so each landing spring removes (1 − ε²) of that
    mass's closing energy and a bed of N springs removes N times as much) or ``tributary``
    (that mass times the spring's share k_i/K_v of the bed, so the energy removed per landing
    of the whole base does not grow with N). ``dashpots`` (force·s/length, one per spring:
    from −b to +b, or in the order of ``positions`` for a custom layout; None: from
    ``damping_ratio``) sets every spring's dashpot instead, e.g. the radiation dashpots of a
    soil's impedance distributed over the bed.

    ``sway_stiffness`` (force/length; None: no sway, Ewing's model) puts a horizontal spring
    under the base, with a parallel dashpot ``sway_damping`` (force·s/length; None: none) and,
    with ``sliding_friction`` μ (None: no sliding), a slider in series with the spring that
    carries at most μ W (W the structure's ``vertical_weight``, the weight the foundation
    carries at rest): the base then has the continuum footing's three DOFs (horizontal,
    vertical, rotation).
    """

    support: str
    half_width: float
    layout: str
    springs: int
    stiffness: float
    law: LawRecord = ElasticLaw()
    damping_ratio: float = 0.0
    restitution: float = 1.0
    impact_multiple: float = 10.0
    impact_mass: str = "point"
    end_stiffness_ratio: float = 1.0
    end_length: float = 0.0
    positions: tuple[float, ...] = ()
    stiffnesses: tuple[float, ...] = ()
    dashpots: tuple[float, ...] | None = None
    sway_stiffness: float | None = None
    sway_damping: float | None = None
    sliding_friction: float | None = None

    @property
    def width(self) -> float:
        """Full base width B = 2b (length)."""
        return 2.0 * self.half_width

    @property
    def sways(self) -> bool:
        """True when the base has a horizontal spring (its sway DOF)."""
        return self.sway_stiffness is not None

    def __getattr__(self, name: str):
        """A law's key asked of the foundation (``foundation.z50``) is an error that says where
        it is: in ``foundation.law`` if the law has it, else in another law only."""
        readers = [law.name for law in LAWS.values() if name in law.keys()]
        if not readers or name.startswith("_"):
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        law = self.law.name
        where = (f"its law's record holds it: foundation.law.{name}" if law in readers else
                 f"it belongs to law {' or '.join(map(repr, readers))}, and this "
                 f"foundation's law is {law!r}")
        raise AttributeError(f"foundation.{name}: a key of the foundation's law, not a field of "
                             f"Foundation; {where}")


#: Most springs a foundation may have: a bed finer than b/50000 resolves nothing more, and its
#: histories outgrow any memory (the run's memory is estimated by :mod:`upliftlab.budget`).
MAX_SPRINGS = 100_000


def _spring_count(name: str, value) -> int:
    count = checks.integer_at_least(name, value, 2)
    if count > MAX_SPRINGS:
        shown = f"{count:.3g}" if count > 10**12 else str(count)
        raise InputError(f"{name} = {shown}: valid range is [2, {MAX_SPRINGS}]")
    return count


def read_foundation(data, vertical_mass: float, units: UnitSystem) -> Foundation:
    """The :class:`Foundation` of a ``[foundation]`` table; ``vertical_mass`` turns a
    ``vertical_period`` into a stiffness."""
    table = Table(data, "foundation")
    support = table.get("support", choice(SUPPORTS), "uplift")
    half_width = table.get("half_width", bounds.checker("length", units))
    layout = table.get("layout", choice(LAYOUTS), "winkler")
    positions, stiffnesses = (), ()
    if layout == "custom":
        positions = table.get("positions", numbers)
        stiffnesses = table.get("stiffnesses", numbers)
        if len(positions) != len(stiffnesses):
            raise InputError(f"foundation.stiffnesses has {len(stiffnesses)} entries but "
                             f"foundation.positions has {len(positions)}: give one per spring")
        for i, (x, k) in enumerate(zip(positions, stiffnesses)):
            checks.in_range(f"foundation.positions[{i}]", x, -half_width, half_width)
            bounds.check(f"foundation.stiffnesses[{i}]", k, "stiffness", units)
        springs, stiffness = len(positions), float(sum(stiffnesses))
        _spring_count("foundation.springs (number of custom positions)", springs)
        given = table.get("springs", None, springs)
        if given != springs:
            raise InputError(f"foundation.springs = {given!r}: a custom layout has one spring "
                             f"per position ({springs}); set it to {springs} or remove it")
        for key in ("stiffness", "vertical_period"):
            if table.get(key, None, None) is not None:
                raise InputError(f"foundation.{key}: a custom layout takes its stiffness from "
                                 f"foundation.stiffnesses; remove foundation.{key} "
                                 f"(--set foundation.{key}= removes a key)")
    else:
        default_n = 2 if layout in ("edges", "equivalent") else MISSING
        springs = table.get("springs", _spring_count, default_n)
        if layout in ("edges", "equivalent") and springs != 2:
            raise InputError(f"foundation.springs = {springs}: layout {layout!r} has exactly 2 "
                             "springs; set foundation.springs = 2 or remove it")
        if table.has("stiffness") and table.has("vertical_period"):
            raise InputError("foundation: give stiffness or vertical_period, not both")
        if table.has("vertical_period"):
            period = table.get("vertical_period", bounds.checker("period", units))
            stiffness = vertical_mass * (2.0 * math.pi / period) ** 2
        else:
            stiffness = table.get("stiffness", bounds.checker("stiffness", units))
    end_ratio, end_length = 1.0, 0.0
    if layout == "end_stiffened":
        end_ratio = table.get("end_stiffness_ratio", in_range(1.0, 1e6))
        end_length = table.get("end_length", in_range(0.0, 1.0, low_open=True, high_open=True))
    damping_ratio = table.get("damping_ratio", in_range(0.0, 2.0), 0.0)
    dashpots = _dashpots(table, springs, damping_ratio, units)
    sway_stiffness, sway_damping, friction = _sway(table, units)
    law = read_law(table, LawContext(support, springs, units))
    foundation = Foundation(
        support=support,
        half_width=half_width,
        layout=layout,
        springs=springs,
        stiffness=stiffness,
        law=law,
        damping_ratio=damping_ratio,
        restitution=table.get("restitution", in_range(0.0, 1.0), 1.0),
        impact_multiple=table.get("impact_multiple", in_range(0.1, 1e4), 10.0),
        impact_mass=table.get("impact_mass", choice(IMPACT_MASSES), "point"),
        end_stiffness_ratio=end_ratio,
        end_length=end_length,
        positions=positions,
        stiffnesses=stiffnesses,
        dashpots=dashpots,
        sway_stiffness=sway_stiffness,
        sway_damping=sway_damping,
        sliding_friction=friction,
    )
    table.done()
    law.check(foundation)
    return foundation


#: Largest sliding friction coefficient μ: beyond it the base never slides in any record.
MAX_FRICTION = 10.0


def _dashpots(table: Table, springs: int, damping_ratio: float,
              units: UnitSystem) -> tuple[float, ...] | None:
    """``foundation.dashpots``: one dashpot per spring (force·s/length), or None."""
    if not table.has("dashpots"):
        return None
    dashpots = table.get("dashpots", numbers)
    if len(dashpots) != springs:
        raise InputError(f"foundation.dashpots has {len(dashpots)} entries: give one per spring "
                         f"({springs})")
    for i, c in enumerate(dashpots):
        bounds.check(f"foundation.dashpots[{i}]", c, "dashpot", units)
    if damping_ratio > 0.0:
        raise InputError(f"foundation.damping_ratio = {damping_ratio:g} with foundation.dashpots:"
                         " give one of them; valid: 0 (or remove it)")
    return dashpots


def _sway(table: Table, units: UnitSystem):
    """(sway_stiffness, sway_damping, sliding_friction) of ``[foundation]``: all None without
    a sway spring, whose other keys are then refused (they would do nothing)."""
    if not table.has("sway_stiffness"):
        for key in ("sway_damping", "sliding_friction"):
            if table.has(key):
                raise InputError(f"foundation.{key} without foundation.sway_stiffness: it acts "
                                 "on the sway spring; give foundation.sway_stiffness too")
        return None, None, None
    stiffness = table.get("sway_stiffness", bounds.checker("stiffness", units))
    damping = table.get("sway_damping", bounds.checker("dashpot", units), None)
    friction = table.get("sliding_friction", in_range(0.0, MAX_FRICTION, low_open=True), None)
    return stiffness, damping, friction
