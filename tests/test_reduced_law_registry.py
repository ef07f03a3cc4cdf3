"""The foundation laws plug in through their registries (upliftlab.scenes.laws for what a scene
says, upliftlab.reduced.laws for what the reduced model makes of it), so that a law is its
module, its registration and its tests.

A toy law, written here in one module as a plug-in would be — a linear spring law, its record,
its builder and the elasto-plastic springs' compiled forms with Fy = ∞ — is registered and runs
a scene end to end. Reference: the same scene on the elastic law, whose builder solves the bonded
bed's equilibrium, while the toy's sets the closed form of a symmetric bed, F0_i = W k_i / Σ k
(the same springs, so the two runs agree to the round-off of F0: 1e-9 of each history's
largest value).
"""

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.reduced import build_model, run
from upliftlab.reduced import laws as reduced_laws
from upliftlab.reduced.laws import SPRING_DTYPE, Law
from upliftlab.reduced.laws.elastoplastic import BONDED, UPLIFT, support_kind
from upliftlab.scenes import laws as scene_laws
from upliftlab.scenes import load_scene
from upliftlab.scenes.laws import LawRecord

TOL = 1e-9  # of each history's largest value: the round-off of F0 through a free vibration


@dataclass(frozen=True, eq=False, kw_only=True)
class LinearLaw(LawRecord):
    """A toy law: linear compression-only springs, with no key of its own."""

    name: ClassVar[str] = "linear"


def linear_springs(law, bed, table):
    """F0 of a symmetric bed in closed form, no yield: the elastic law's springs."""
    k = bed.layout.stiffnesses
    table["kind"] = support_kind(bed.support)
    table["f0"] = bed.weight * k / k.sum()
    table["fy"] = np.inf
    return table, 0.0


LINEAR = Law(record=LinearLaw, springs=linear_springs, kinds=(UPLIFT, BONDED))

SCENE = """schema = 1
units = "kip-in-s"
[structure]
weight = 200.0
height = 288.0
stiffness = 500.0
damping_ratio = 0.02
rotary_inertia = 1750.0
[foundation]
support = "uplift"
half_width = 72.0
layout = "winkler"
springs = 12
stiffness = 6000.0
law = "{law}"
damping_ratio = 0.05
[motion]
type = "free"
velocity = 20.0
duration = 1.0
"""


@pytest.fixture
def linear():
    reduced_laws.register(LINEAR)
    yield LINEAR
    del reduced_laws.LAWS["linear"], scene_laws.LAWS["linear"]


def _scene(tmp_path, law):
    path = tmp_path / f"{law}.toml"
    path.write_text(SCENE.format(law=law))
    return load_scene(str(path))


def test_a_registered_law_runs_a_scene_end_to_end(linear, tmp_path):
    scene = _scene(tmp_path, "linear")
    assert scene.foundation.law == LinearLaw() and scene.foundation.law.name == "linear"
    assert scene.table["foundation"]["law"] == "linear"
    ours, elastic = run(scene), run(_scene(tmp_path, "elastic"))
    assert ours.q.shape == elastic.q.shape and ours.q.shape[0] > 100
    assert np.abs(elastic.theta).max() > 1e-4  # the base rocks: springs separate and land
    for name in ("q", "qd", "force", "energy"):
        a, b = getattr(ours, name), getattr(elastic, name)
        np.testing.assert_allclose(a, b, rtol=0, atol=TOL * np.abs(b).max())
    np.testing.assert_array_equal(ours.mode, elastic.mode)


def test_a_registered_law_refuses_the_keys_of_other_laws(linear, tmp_path):
    path = tmp_path / "linear.toml"
    path.write_text(SCENE.format(law="linear").replace('law = "linear"\n',
                                                       'law = "linear"\nz50 = 0.5\n'))
    with pytest.raises(InputError, match=r"^foundation.z50 is read only with foundation.law = "
                                         r"'qz' \(law is 'linear'\)"):
        load_scene(str(path))
    with pytest.raises(InputError, match=r"^foundation.law = 'plastic': must be one of .*"
                                         r"'linear'"):
        load_scene(str(path), overrides=["foundation.law='plastic'", "foundation.z50="])


def test_the_two_registries_name_the_same_laws_with_the_same_records():
    # Reference: each registry on its own; a law read by scenes must be one the model builds.
    assert list(scene_laws.LAWS) == list(reduced_laws.LAWS) == ["elastic", "elastoplastic", "qz",
                                                                "macro"]
    for name, law in reduced_laws.LAWS.items():
        assert law.record is scene_laws.LAWS[name] and law.name == name
        assert {n for n, _ in law.columns} <= set(SPRING_DTYPE.names)
        # a law is springs (a builder and kinds) or one element on the base, never both
        assert (law.springs is None) == (law.element is not None) == (not law.kinds)
    # a law with a state at rest has kinds of its own (its start would touch no other law's)
    for law in reduced_laws.LAWS.values():
        if law.start is not None:
            others = {k for o in reduced_laws.LAWS.values() if o is not law for k in o.kinds}
            assert not others & set(law.kinds)
    assert reduced_laws.curved_kinds() == reduced_laws.LAWS["qz"].kinds


def test_a_law_that_the_model_does_not_have_is_refused_before_any_work(tmp_path):
    scene_laws.register(LinearLaw)
    try:
        scene = _scene(tmp_path, "linear")
        with pytest.raises(InputError, match=r"^foundation.law = 'linear': the reduced model "
                                             r"has no such law"):
            build_model(scene)
    finally:
        del scene_laws.LAWS["linear"]


def test_a_law_record_is_not_its_name():
    # Reference: the flat records before the law records compared foundation.law with a name;
    # such a comparison would now be quietly false, so it is refused.
    law = scene_laws.QzLaw(capacity_multiple=3.0, z50=0.2)
    assert law.name == "qz" and law == scene_laws.QzLaw(capacity_multiple=3.0, z50=0.2)
    assert law != scene_laws.QzLaw(capacity_multiple=3.0, z50=0.3)
    with pytest.raises(TypeError, match="compare foundation.law.name"):
        law == "qz"  # noqa: B015


def test_a_law_key_asked_of_the_foundation_says_where_it_is():
    # Reference: the records' fields (ElasticLaw has yield_multiple only; z50 is QzLaw's).
    foundation = load_scene("short_period_free", case="A").foundation
    assert foundation.law.name == "elastic" and foundation.law.yield_multiple == 3.0
    with pytest.raises(AttributeError, match=r"^foundation.z50: .* belongs to law 'qz', and "
                                             r"this foundation's law is 'elastic'$"):
        foundation.z50  # noqa: B018
    with pytest.raises(AttributeError, match=r"its law's record holds it: "
                                             r"foundation.law.yield_multiple$"):
        foundation.yield_multiple  # noqa: B018
    assert not hasattr(foundation, "capacity_multiple")
    with pytest.raises(AttributeError, match=r"has no attribute 'colour'"):
        foundation.colour  # noqa: B018


def test_the_qz_records_soil_names_are_the_backbones():
    # Reference: the reduced law's backbone shapes (reduced/laws/qz/backbone.py), which the
    # scene's record names without importing the model.
    from upliftlab.reduced.laws.qz import QZ_SOILS
    assert scene_laws.QZ_SOIL_NAMES == tuple(QZ_SOILS)
