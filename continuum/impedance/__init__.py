"""The footing's dynamic impedance in the frequency domain (:mod:`.analysis`, with the
perfectly matched layer of :mod:`.pml`), checked against references independent of the FE
code: the exact half-plane (:mod:`.halfplane`) and Gazetas' formulas (:mod:`.gazetas`);
:mod:`.output` summarises and draws it."""
