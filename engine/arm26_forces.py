"""arm26's numbers for forces, in one place: the six elbow muscles' Hill-type parameters, the
forearm's mass and centre of mass, and gravity.

Source: OpenSim's arm26 model (``shared/data/arm26.osim``; Holzbaur, Murray and Delp, Ann
Biomed Eng 33, 2005, adapted by the OpenSim team), each muscle a ``Thelen2003Muscle`` whose
curves follow Thelen, J Biomech Eng 125, 2003 (see ``engine/hill.py``). The file gives
lengths in metres and angles in radians; here they are in cm and degrees, as the project's
configurations are: ``optimal_fiber_length`` 0.1157 m is 11.57 cm, and the triceps' long
head's ``pennation_angle_at_optimal`` 0.20943951 rad is 12 degrees (to the file's 8 digits),
its lateral and medial heads' 0.15707963 rad 9 degrees. ``minimum_activation`` is not in the
file: it is OpenSim's default for the muscle, 0.01, which arm26's ``min_control`` matches.
``tests/engine/test_arm26_forces.py`` checks every value against what OpenSim reads from
the file (``benchmarks/arm26_forces.py``).

A configuration may override any of them, muscle by muscle (``[forces.NAME]``, see
``engine/config.py``); a muscle not named after one of arm26's six has none by default,
except the unnamed muscle of a single-muscle file, whose skeleton is fitted to BIClong.
"""

from __future__ import annotations

from biceps.engine.hill import HillParameters

CURVES = dict(tendon_strain=0.033, passive_strain=0.6, active_shape=0.5, passive_shape=4.0,
              minimum_activation=0.01)
"""Thelen 2003's curves as arm26 shapes them for all six (FmaxTendonStrain, FmaxMuscleStrain,
KshapeActive, KshapePassive), and OpenSim's minimum activation."""

PARAMETERS: dict[str, HillParameters] = {
    # name: maximum isometric force (N), optimal fibre length (cm), tendon slack length
    # (cm), pennation at the optimal fibre length (degrees)
    "BIClong": HillParameters(624.3, 11.57, 27.23, 0.0, **CURVES),
    "BICshort": HillParameters(435.56, 13.21, 19.23, 0.0, **CURVES),
    "BRA": HillParameters(987.26, 8.58, 5.35, 0.0, **CURVES),
    "TRIlong": HillParameters(798.52, 13.4, 14.3, 12.0, **CURVES),
    "TRIlat": HillParameters(624.3, 11.38, 9.8, 9.0, **CURVES),
    "TRImed": HillParameters(624.3, 11.38, 9.08, 9.0, **CURVES),
}
"""arm26's six, by their names in arm26 and in ``configs/elbow.toml``."""

UNNAMED = "BIClong"
"""Whose parameters a single-muscle file's unnamed muscle (``muscle``) takes: the default
skeleton's attachments are fitted to arm26's BIClong (``engine/skeleton.py``)."""

FOREARM_MASS = 1.534315
"""kg: arm26's ``r_ulna_radius_hand``, the forearm and hand as one body."""

FOREARM_CENTRE = 18.1479
"""cm from the elbow's centre along the forearm's axis to that body's centre of mass (arm26:
``mass_center`` 0 -0.181479 0 in the body's frame, whose origin is the elbow joint's)."""

GRAVITY = 9.8066
"""m/s^2, arm26's ``gravity`` (0 -9.8066 0)."""


def default_parameters(name: str) -> HillParameters | None:
    """arm26's parameters for the muscle called ``name`` in a configuration, if it has any."""
    return PARAMETERS.get(UNNAMED if name == "muscle" else name)
