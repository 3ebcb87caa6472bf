"""What certification asks of aeroelastic stability, as data, and the required speed it sets.

The regulations' speed factors and their sources (:data:`REGULATIONS`: CS/14 CFR 25.629(b)(1)
1.15 V_D, 14 CFR 23.629 1.2 V_D), which of them hold failure cases to 25.629(b)(2)
(:data:`PART25`, with the 1.15 V_C of (b)(2)(ii), :data:`FACTOR_VC_FAILURE`), the range of an
explicit factor, and :func:`required_speed` — the one place that turns V_D, a factor and a
regulation into the speed to clear and the rule that sets it.  With them the words a clearance
campaign speaks (:data:`AIRSPEEDS`, :data:`OPERATIONS`, :data:`STATES`, :data:`CASE_FACTORS`),
which a campaign file (:mod:`propwhirl.io.campaign_files`) and the campaign study
(:mod:`propwhirl.studies.campaign`) both check against.

A module of its own below the packages that use it (the analyses' margin, the studies'
clearance and campaign, the campaign files, the command line): it imports only
:mod:`propwhirl.validate` (docs/architecture.md, tests/test_layering.py).  SI units: speeds
[m/s], factors [-].
"""
from __future__ import annotations

from typing import Any, NamedTuple

from propwhirl import validate as v

#: The speed factor of CS/14 CFR 25.629(b)(1) [-]: no aeroelastic instability up to 1.15 V_D.
FACTOR_CS25 = 1.15
#: The speed factor of 14 CFR 23.629 and AC 23.629-1B [-]: free from flutter up to 1.2 V_D.
FACTOR_CFR23 = 1.2
#: The range of an explicit speed factor [-].
FACTOR_RANGE = (1.0, 3.0)
#: The factor on V_C of the failure cases' line in 25.629(b)(2)(ii) [-] (1.15 V_C).
FACTOR_VC_FAILURE = 1.15


class Regulation(NamedTuple):
    """A regulation's speed factor [-], its source (the words of the rule), the paragraph a
    required speed's rule names ("" for none) and whether its failure cases are held to the
    envelope of 25.629(b)(2)."""

    factor: float
    source: str
    paragraph: str = ""
    part25: bool = False


#: The regulations a campaign can name → :class:`Regulation` (``"explicit"``: a factor of its
#: own, in :data:`FACTOR_RANGE`).
REGULATIONS: dict[str, Regulation] = {
    "cs25": Regulation(FACTOR_CS25, "EASA CS 25.629(b)(1): aeroelastic stability for all speeds "
                       "up to the V_D/M_D envelope enlarged by 15 % in equivalent airspeed at "
                       "constant Mach number and at constant altitude", "25.629(b)(1)", True),
    "far25": Regulation(FACTOR_CS25, "14 CFR 25.629(b)(1) (the same words)", "25.629(b)(1)",
                        True),
    "far23": Regulation(FACTOR_CFR23, "14 CFR 23.629 (amendments up to 23-63; since amendment "
                        "23-64 the performance-based 14 CFR 23.2245 with its accepted means of "
                        "compliance) and FAA AC 23.629-1B: freedom from flutter shown by analysis "
                        "up to 1.2 V_D", "23.629"),
}
#: The name of a regulation given by its factor alone.
EXPLICIT = "explicit"
#: The regulations whose failure cases are held to the envelope of 25.629(b)(2).
PART25 = tuple(name for name, r in REGULATIONS.items() if r.part25)

#: What a damping requirement (g ≥ min_damping_g) can apply to: the total damping, or the
#: aerodynamic increment above each mode's damping at the lowest analysed speed; and to which
#: modes (:mod:`propwhirl.analysis.damping_requirement` judges it).
DAMPING_APPLIES_TO = ("total", "aerodynamic")
DAMPING_MODES = ("all", "critical")
#: The airspeeds V_D can be given as: equivalent or true airspeed.
AIRSPEEDS = ("EAS", "TAS")
#: Operations a campaign's case can switch a propeller to.
OPERATIONS = ("windmilling",)
#: States a case can put an installation in (:class:`propwhirl.model.systems.Installation`).
STATES = ("operating", "feathered", "stopped")
#: A case's factors and their ranges [-]: field → (low, high).
CASE_FACTORS: dict[str, tuple[float, float]] = {
    "mount_stiffness": (1e-3, 100.0), "mount_damping": (0.0, 100.0),
    "wing_damping": (0.0, 100.0), "rpm_factor": (0.1, 3.0)}


def regulation_factor(regulation: str, factor: float | None = None) -> float:
    """The speed factor [-] of `regulation` (a name of :data:`REGULATIONS`; or
    :data:`EXPLICIT` with `factor` in :data:`FACTOR_RANGE`); a `factor` given with a named
    regulation must be its own.

    Examples
    --------
    >>> from propwhirl.certification import regulation_factor
    >>> regulation_factor("cs25"), regulation_factor("far23"), regulation_factor("explicit", 1.3)
    (1.15, 1.2, 1.3)
    """
    if regulation == EXPLICIT:
        if factor is None:
            raise v.InputError("regulation 'explicit' needs a factor")
        return float(v.in_range("factor", factor, *FACTOR_RANGE))
    if regulation not in REGULATIONS:
        raise v.InputError(f"regulation = {v.short_repr(regulation)} is invalid: must be one of "
                           f"{', '.join(REGULATIONS)}, {EXPLICIT}")
    own = REGULATIONS[regulation].factor
    if factor is not None and float(factor) != own:
        raise v.InputError(f"factor = {factor!r} is invalid with regulation {regulation!r}, whose "
                           f"factor is {own:g}: give regulation = '{EXPLICIT}' for another factor")
    return own


def required_speed(V_D: Any, factor: Any = FACTOR_CS25, regulation: str = EXPLICIT, *,
                   failure: bool = False, V_line: float | None = None, line_part: str = "",
                   mach_limited: bool = False, vd_name: str = "V_D",
                   factor_name: str = "factor") -> tuple[float, str]:
    """The speed [m/s] an aircraft must be free of aeroelastic instability up to, and the rule
    that sets it.

    * not a failure case, or a regulation outside :data:`PART25` (14 CFR 23.629 and AC
      23.629-1B hold failure cases to the same 1.2 V_D): ``factor · V_D``, the rule
      "25.629(b)(1) 1.15 V_D", "23.629 1.2 V_D" or "1.25 V_D" (explicit);
    * a failure case under CS/14 CFR 25.629(b)(2): the greater of V_D (with its M_D limit,
      "25.629(b)(2)(i) V_D" or "... M_D") and the failure-case line of (b)(2)(ii) at that
      altitude, `V_line` (:func:`propwhirl.studies.flight_envelope.failure_line`; its
      `line_part` "1.15 V_C", "V_C-M_C line" or "M_C + 0.05" named); without V_C, V_D.

    Parameters
    ----------
    V_D : float
        The design dive speed [m/s] (> 0), as the analyses' speeds are (a true airspeed).
    factor : float
        The speed factor [-], in :data:`FACTOR_RANGE` (:data:`FACTOR_CS25` by default).
    regulation : str
        A name of :data:`REGULATIONS`, or :data:`EXPLICIT` (the rule then names no paragraph).
    failure : bool
        A failure condition of 25.629(d).
    V_line : float, optional
        The failure cases' line of 25.629(b)(2)(ii) [m/s, TAS] (None: no V_C given).
    line_part : str
        Which part of the line `V_line` is on.
    mach_limited : bool
        V_D is M_D · a(h) there.
    vd_name, factor_name : str
        How an error names V_D and the factor (e.g. the command line's ``--vd``).

    Returns
    -------
    speed : float
        The required speed [m/s].
    rule : str
        The rule that sets it.

    Raises
    ------
    InputError
        V_D not positive, or the factor outside :data:`FACTOR_RANGE`, in one line naming it.

    Examples
    --------
    >>> from propwhirl.certification import required_speed
    >>> required_speed(200.0, 1.2, "far23")
    (240.0, '23.629 1.2 V_D')
    >>> required_speed(100.0, 1.15, "cs25", failure=True, V_line=120.0, line_part="1.15 V_C")
    (120.0, '25.629(b)(2)(ii) 1.15 V_C')
    """
    v.positive(vd_name, V_D, "m/s")
    v.in_range(factor_name, factor, *FACTOR_RANGE)
    r = REGULATIONS.get(regulation)
    if r is None or not r.part25 or not failure:
        where = f"{r.paragraph} " if r is not None and r.paragraph else ""
        return float(factor) * float(V_D), f"{where}{float(factor):g} V_D"
    if V_line is not None and V_line > V_D:
        return float(V_line), f"25.629(b)(2)(ii) {line_part}"
    return float(V_D), "25.629(b)(2)(i) " + ("M_D" if mach_limited else "V_D")
