"""A scene's table and digest do not depend on how its foundation's law is held: every packaged
scene and case, and a set of overrides that name every law and every variant of one (the q–z
law with z50 or with z_ref and a fitted shape, on a uniform or an end-stiffened bed; the
elasto-plastic law by yield multiple, bearing capacity or given yield forces, the last on a
custom layout given out of order; a bonded bed; a sway spring; given dashpots), has the digest
it had when the foundation held every law's fields.

Reference: digests recorded with the code before the law records, run in a separate process
from main's checkout at commit c9b5a8b (a flat ``Foundation`` of 27 fields whose table writer
skipped the fields of the other laws): an independent implementation of the same table. A
digest is the SHA-256 of the scene's whole table (:attr:`upliftlab.scenes.Scene.digest`):
equal digests mean equal tables, key by key and value by value.
"""

import pytest

from upliftlab.scenes import load_scene, scene_from_dict

#: (scene, case) -> digest, every packaged scene and case.
PACKAGED = {
    ("long_period_elcentro", None):
        "a3b486da67856f21eca37ecae68cc7c5b239c84299f7b3590df79438a2e87871",
    ("long_period_elcentro", "A"):
        "43becab27bd55109708e459b05f831b6ea8cbf801112f30f8b0a6a528bcb8ace",
    ("long_period_elcentro", "B"):
        "21c6a1bbc6a6554d072c51e3e7628a9c4f0a88fe4dbe1b49343fc73fd4af979a",
    ("long_period_elcentro", "C"):
        "a3b486da67856f21eca37ecae68cc7c5b239c84299f7b3590df79438a2e87871",
    ("long_period_elcentro", "fixed"):
        "49ef5a1f5662f62bd3ece931d16460a5300f134851ee15fdc45500a1f22ac497",
    ("long_period_free", None):
        "74ad9f3e0c04b834b322cb44941bbc4dec14f5601be8becc17a6c70b47c7e292",
    ("long_period_free", "A"):
        "46ddee3bb14443f13eb31af4377fb9ff28f05252cbead12998849e72212b0184",
    ("long_period_free", "B"):
        "c6d3641ad98dadf2c15b1e1ed841cf2eabd154082011ee642d138f298795eab3",
    ("long_period_free", "C"):
        "74ad9f3e0c04b834b322cb44941bbc4dec14f5601be8becc17a6c70b47c7e292",
    ("short_period_elcentro", None):
        "adb0735bea1b123b2997fc181ed8ea0d55b668c8127fc5bc76be06d814be081c",
    ("short_period_elcentro", "A"):
        "9ebb285d6147d9d3ee67536e36c6185c95ca17fd391d5142ef2ca78690993021",
    ("short_period_elcentro", "B"):
        "ddf294a803ec8969017fcfa78561a5e549a2be00fb581d28e4c9e0aecab6330a",
    ("short_period_elcentro", "C"):
        "adb0735bea1b123b2997fc181ed8ea0d55b668c8127fc5bc76be06d814be081c",
    ("short_period_elcentro", "fixed"):
        "cf31fa1476b022ac764d18e8c102aa8b79e0a3a2ba459dc7a79102117d9d579a",
    ("short_period_free", None):
        "7b1b07b41f1c2f8f446bfb1520bd2a83ea28cc34ec058f759154c00e052d7350",
    ("short_period_free", "A"):
        "72843c37ff5dfe2775ffe6e4fef53df8c806beea1669909b2afca2ab043a42ba",
    ("short_period_free", "B"):
        "b2ae176af9fadac993cba8cc9a2daccde53d537210b14ef10f288d1a10d384bc",
    ("short_period_free", "C"):
        "7b1b07b41f1c2f8f446bfb1520bd2a83ea28cc34ec058f759154c00e052d7350",
    ("strip_footing_clay", None):
        "ce16ddd936fabf48e17b81664125fa07d84c1fb82f8f60320d1a9a3b6e4d3001",
    ("three_story_frame", None):
        "937738433bd6fc515c696044f2db5277a0b8d3b27528fe29f63244136bd21852",
    ("three_story_frame", "fixed"):
        "f2b42bb2fc5637b0e0fa9ff47b52d0b450d4874bea01a4486fd7e813469064d4",
    ("wall_elcentro", None):
        "08fffa5ce1a54fe44ce8fc9e15224c915f0b96d7750d4390d7bbfe94d03ef30a",
    ("wall_elcentro", "e07"):
        "dd09b5136cf9d5ab9da3e9943dad5b6f0bada18db521618da5bf7c180515bae3",
    ("wall_elcentro", "e10"):
        "08fffa5ce1a54fe44ce8fc9e15224c915f0b96d7750d4390d7bbfe94d03ef30a",
    ("wall_elcentro", "fixed"):
        "4e34fd2ed1f1ef31074b7c0c860f93e279615f59ef8aa15b96e5e62a80431d3f",
    ("wall_free", None):
        "fede03eadfc4d29c6d88ea38e473d3de52fb1f3a9a8270c00aca5a043aada642",
    ("wall_free", "e07"):
        "1d7244d42811852a2ef94cd158955ecf6110e9fa95db2dca27f019effff19ea9",
    ("wall_free", "e10"):
        "fede03eadfc4d29c6d88ea38e473d3de52fb1f3a9a8270c00aca5a043aada642",
}

QZ = ["foundation.law='qz'", "foundation.capacity_multiple=3.0", "foundation.z50=0.5"]

#: label -> (scene, case, overrides, digest).
VARIANTS = {
    "qz_z50": ("short_period_free", "B", QZ,
               "9f0bb75aa0e506f4590b99055e885b9d73ab62f3e4eaa4e73076ec642d3a5483"),
    "qz_zref_sand": ("short_period_free", "B", [
        "foundation.law='qz'", "foundation.capacity_multiple=4.0", "foundation.qz_zref=0.05",
        "foundation.suction=0.05", "foundation.qz_soil='sand'", "foundation.qz_exponent=3.0",
        "foundation.qz_elastic_range=0.4"],
        "c7e54f2410385e5bb4d05f69e53f330235b13c645d07b48c419f97f6ca009366"),
    "qz_end_stiffened": ("short_period_free", "B", QZ + [
        "foundation.layout='end_stiffened'", "foundation.end_stiffness_ratio=2.0",
        "foundation.end_length=0.25", "foundation.damping_ratio=0.05"],
        "c1dc2f1461099611541b6f6cd4e0e18c2106e9f1cd26f084786e65701087f590"),
    "ep_capacity": ("short_period_free", "B", ["foundation.yield_multiple=",
                                               "foundation.capacity_multiple=2.5"],
                    "80ff75bdcda4f6b71211039fe18515344ffe1c49dcb1931e43ef3bd113a1fe32"),
    "ep_yield_forces": ("short_period_free", "C", [
        "foundation.yield_multiple=", "foundation.yield_forces=[" + ",".join(["30.0"] * 12) + "]"],
        "4f031556f82a310512dc413582b5f3f8d4b6e1c1d2c34b25f94b36218378dc06"),
    "ep_yield_multiple": ("short_period_free", "B", ["foundation.yield_multiple=4.0"],
                          "71987556cefef6d21f7e6bd1ff0c7af46485ea734228ed61fa234a7e4c403f46"),
    "bonded": ("short_period_free", "A", ["foundation.support='bonded'"],
               "1cff8c45c95b8980feb2b8aa2af4061da27706a1fa320ecc05e0bc83d29ee3ea"),
    "custom_yield_forces": ("short_period_free", "B", [
        "foundation.layout='custom'", "foundation.positions=[120.0, -40.0, 40.0, -120.0]",
        "foundation.stiffnesses=[1000.0, 2000.0, 2000.0, 1000.0]", "foundation.springs=",
        "foundation.vertical_period=", "foundation.yield_multiple=",
        "foundation.yield_forces=[40.0, 80.0, 80.0, 40.0]"],
        "02a95389eb2d05035cef760b7b31454f6e9f884909a238d2b5562232c5d9582a"),
    "wall_elastoplastic": ("wall_free", "e07", ["foundation.law='elastoplastic'"],
                           "3e018efd95f9d0640e877e904832b05ae087b131a6d4aba1fbfa2bcbd0b81935"),
    "sway": ("short_period_free", "C", ["structure.vertical_weight=272.0",
                                        "foundation.sway_stiffness=5000.0",
                                        "foundation.sway_damping=10.0",
                                        "foundation.sliding_friction=0.5"],
             "b791d6b7b6dd19878d8b0d7c6179bdad3cb165773fc2397787a357ec9a6216f1"),
    "dashpots": ("wall_free", None, ["foundation.dashpots=[" + ",".join(["1.5"] * 12) + "]"],
                 "798c1879294ebfe2ee92735d9d32b568ddc23a7de6298c871fb350c2f3e3b37a"),
}


@pytest.mark.parametrize("name, case", list(PACKAGED))
def test_every_packaged_scene_and_case_keeps_its_digest(name, case):
    scene = load_scene(name, case=case)
    assert scene.digest == PACKAGED[name, case]
    again = scene_from_dict(scene.table, merged=True)  # the table gives back the same scene
    assert again.foundation == scene.foundation and again.digest == scene.digest


@pytest.mark.parametrize("label", list(VARIANTS))
def test_every_law_and_variant_keeps_its_digest(label):
    name, case, overrides, digest = VARIANTS[label]
    scene = load_scene(name, case=case, overrides=overrides)
    assert scene.digest == digest
    again = scene_from_dict(scene.table, merged=True)
    assert again.foundation == scene.foundation and again.digest == digest
