"""A q–z bed exported to OpenSees QzSimple2 springs (upliftlab.comparisons.opensees.qz).

References: the QzSimple2 backbone in closed form from OpenSees' source
(``SRC/material/uniaxial/PY/QzSimple2.cpp`` of OpenSees/OpenSees, ``revertToStart`` and
``getNearField``: far field c_far·q_ult/z50, near field rigid (10⁴ q_ult/z50) to elast·q_ult
then q = q_ult − (q_ult − q₀)[z_ref/(z_ref + z − z₀)]ⁿ with z_ref = c_ref·z50, closed gap
10³ q_ult/z50, in series; type 1 n = 1.2, elast = 0.22, c_ref = 0.5, c_far = 0.525; type 2
n = 5.5, elast = 0.36, c_ref = 9.29, c_far = 1.39), checked against OpenSees itself (openseespy
driving one material, within 1e-4 of q_ult); upliftlab's q–z backbone
(:func:`upliftlab.reduced.laws.qz.backbone_force`, bisection on its own closed form).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.opensees import opensees_spec, write_script
from upliftlab.comparisons.opensees.script import script_text
from upliftlab.comparisons.opensees.qz import (QZSIMPLE2_TYPES, QzSimple2Spring,
                                               qzsimple2_compression, qzsimple2_force,
                                               qzsimple2_springs)
from upliftlab.reduced import build_model
from upliftlab.reduced.laws.qz import QzShape, backbone_force
from upliftlab.scenes import scene_from_dict


def _scene(soil: str, **foundation):
    """Ewing's short-period wall (W = 202 kip) on 6 q–z springs (capacity 3 W, z50 0.2 in)."""
    f = {"support": "uplift", "half_width": 120.0, "layout": "winkler", "springs": 6,
         "vertical_period": 0.06, "law": "qz", "damping_ratio": 0.05, "capacity_multiple": 3.0,
         "z50": 0.2, "qz_soil": soil, **foundation}
    return scene_from_dict({
        "schema": 1, "units": "kip-in-s",
        "structure": {"weight": 202.0, "height": 336.0, "period": 0.15, "damping_ratio": 0.0,
                      "rotary_inertia": 7694.0},
        "foundation": f,
        "motion": {"type": "ricker", "amplitude": 0.5, "period": 0.3, "duration": 0.3}})


def _rows(scene):
    model = build_model(scene)
    return model.params[model.foundation_slice]


def test_the_published_constants_are_qzsimple2s():
    # QzSimple2.cpp, revertToStart (the types' zref, np, Elast, TFar_tang)
    fields = {k: (t.n, t.elast, t.c_ref, t.c_far) for k, t in QZSIMPLE2_TYPES.items()}
    assert fields == {1: (1.2, 0.22, 0.5, 0.525), 2: (5.5, 0.36, 9.29, 1.39)}


@pytest.mark.parametrize("soil, qz_type, beyond", [("sand", 2, 0.14), ("clay", 1, 0.39)])
def test_the_mapped_backbone_is_ours_in_the_elastic_range_and_differs_as_stated(soil, qz_type,
                                                                                  beyond):
    """Mapped spring by spring: the type of the soil's exponent, q_ult, the dashpot. In the
    elastic range of both (q ≤ 0.3 q_ult sand, 0.2 clay: z50 is set so that the initial
    stiffnesses agree) the forces agree to 1e-9 of q_ult; past it the backbones differ, by at
    most ``beyond``·q_ult at z from 2 to 100 elastic ranges (measured 0.134 q_ult on sand at
    10, 0.380 on clay at 10: QzSimple2's z_ref is c_ref·z50 of its own z50, upliftlab's the
    bed's), and both reach q_ult (within 7 % at 100 elastic ranges)."""
    rows = _rows(_scene(soil))
    springs = qzsimple2_springs(rows)
    assert len(springs) == len(rows) == 6
    for r, s in zip(rows, springs):
        assert (s.qz_type, s.qult, s.suction, s.c) == (qz_type, r["qult"], 0.0, r["c"])
        shape = QzShape(n=float(r["npow"]), elast=float(r["elast"]), emax=float(r["emax"]))
        z_elastic = r["elast"] * r["qult"] / r["k"]
        inside = np.linspace(0.05, 1.0, 8) * z_elastic
        ours = backbone_force(inside, r["k"], r["qult"], r["zref"], shape)
        np.testing.assert_allclose(qzsimple2_force(inside, s), ours, rtol=0,
                                   atol=1e-9 * r["qult"])
        far = np.array([2.0, 5.0, 10.0, 30.0, 100.0]) * z_elastic
        difference = backbone_force(far, r["k"], r["qult"], r["zref"], shape) - \
            qzsimple2_force(far, s)
        assert np.max(np.abs(difference)) <= beyond * r["qult"]
        assert np.max(np.abs(difference)) >= 0.5 * beyond * r["qult"]  # they do differ
        assert abs(difference[-1]) <= 0.07 * r["qult"]


def test_the_closed_form_is_what_opensees_computes():
    """openseespy drives one QzSimple2 (type 1 and 2, q_ult 101, z50 of a mapped spring) in
    compression (OpenSees' negative) in 400 steps to each z; its force equals the closed
    form's within 1e-4 q_ult (measured 2e-6 relative in z; the drag, 1e-12 of q_ult, left
    out of the closed form)."""
    from upliftlab.comparisons.opensees.model_script import import_opensees

    ops = import_opensees()
    for spring in (QzSimple2Spring(2, 101.0, 0.1466, 0.0, 0.0),
                   QzSimple2Spring(1, 101.0, 0.0554, 0.0, 0.0)):
        for z in np.array([0.2, 1.0, 3.0, 10.0, 40.0]) * spring.z50:
            ops.wipe()
            ops.uniaxialMaterial("QzSimple2", 1, *spring.args())
            ops.testUniaxialMaterial(1)
            for i in range(1, 401):
                ops.setStrain(-z * i / 400)
            q = -ops.getStress()
            assert float(qzsimple2_force(z, spring)) == pytest.approx(q, abs=1e-4 * spring.qult)
            assert float(qzsimple2_compression(q, spring)) == pytest.approx(z, rel=1e-4)
    ops.wipe()


def test_the_script_holds_the_qzsimple2_springs_as_numbers(tmp_path):
    """``upliftlab opensees`` of a q–z scene: model.json's QZ holds each spring's
    (type, q_ult, z50, suction, c) as numbers (the mapping's), the script (the package's
    module, unchanged: no scene text in it) creates QzSimple2 from them; a fitted exponent and a suction beyond QzSimple2's
    0.1 are refused in one line naming the field."""
    scene = _scene("sand", suction=0.05)
    spec = opensees_spec(scene)
    files = write_script(spec, tmp_path)
    numbers = json.loads(files.numbers.read_text())
    expected = [list(s.args()) for s in qzsimple2_springs(_rows(scene))]
    assert numbers["QZ"] == expected and all(q[3] == pytest.approx(0.05) for q in expected)
    text = files.script.read_text()
    assert '"QzSimple2"' in text and text == script_text()  # the module, unchanged
    assert any("QzSimple2" in note for note in numbers["NOTES"])
    with pytest.raises(InputError, match="foundation.qz_exponent = 3"):
        opensees_spec(_scene("sand", qz_exponent=3.0))
    with pytest.raises(InputError, match="foundation.suction = 0.2"):
        opensees_spec(_scene("sand", suction=0.2))


def test_the_comparison_plot_shows_the_difference(tmp_path):
    """The q–z wall run by both (OpenSees' subprocess on the exported QzSimple2 bed): the
    plot's left column is upliftlab minus OpenSees, equal to the histories' difference computed
    here (OpenSees interpolated onto upliftlab's times, np.interp) to 1e-12 of the peak; the
    overlaid curves are the optional second column; histories.png is written."""
    from upliftlab.comparisons.opensees import compare, write_comparison
    from upliftlab.comparisons.opensees.compare import comparison_plot, difference_panels

    c = compare(_scene("sand"), tmp_path / "run")
    r, h = c.response, c.opensees.histories
    panels = difference_panels(c)
    assert [p[0].split("\n")[0] for p in panels] == ["Δu [in]", "Δθ [mrad]",
                                                       "Δleftmost spring [in]"]
    expected = [r.u - np.interp(r.time, h["time"], h["u"]),
                1e3 * (r.theta - np.interp(r.time, h["time"], h["theta"])),
                r.left_spring_displacement - np.interp(r.time, h["time"],
                                                       h["left_spring_displacement"])]
    for (_, [(label, t, y)]), want in zip(panels, expected):
        assert label == "upliftlab − OpenSees" and np.array_equal(t, r.time)
        np.testing.assert_allclose(y, want, rtol=0, atol=1e-12 * np.max(np.abs(want)))
        assert np.max(np.abs(y)) > 0.0  # the two models differ (module docstring of .qz)
    import matplotlib.pyplot as plt

    both, alone = comparison_plot(c), comparison_plot(c, curves=False)
    assert both.axes[0].lines[0].get_ydata().tolist() == panels[0][1][0][2].tolist()
    assert len(both.axes) == 6 and len(alone.axes) == 3
    plt.close(both)
    plt.close(alone)
    written = write_comparison(c, tmp_path / "out", curves=False)
    assert (tmp_path / "out" / "histories.png") in written
