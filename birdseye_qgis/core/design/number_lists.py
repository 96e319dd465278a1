"""The comma-separated number lists the platform-design tools take (altitudes, pose sigmas, sKLD cut-offs).

Shared by the Processing parameters and the sensor-bound calculator dock, so both accept and refuse the
same text with the same message.
"""
from __future__ import annotations

import math

from ..errors import InputError
from .sensor_bound import AXES, SIGMA_UNITS

SIGMAS_HINT = "x, y, z in metres; roll, pitch, yaw in degrees"


def format_number_list(values) -> str:
    """``[10.0, 20.0]`` → ``"10,20"``: the comma-separated form the list parameters take."""
    return ",".join(f"{float(v):g}" for v in values)


def parse_number_list(text, name: str, hint: str) -> list[float]:
    """Comma-separated numbers (spaces and ';' accepted as well); ``name`` prefixes every message.

    Raises ``InputError`` naming the offending item and what was expected (``hint``).
    """
    items = [item for item in str(text or "").replace(";", ",").replace(" ", ",").split(",") if item]
    if not items:
        raise InputError(f"{name}: no values given — expected comma-separated {hint}")
    values = []
    for position, item in enumerate(items, start=1):
        try:
            value = float(item)
        except ValueError:
            raise InputError(f"{name}: item {position} '{item}' is not a number — expected "
                             f"comma-separated {hint}") from None
        if not math.isfinite(value):
            raise InputError(f"{name}: item {position} '{item}' is not a finite number")
        values.append(value)
    return values


def _parse_positive_list(text, name: str, expected: str, refusal: str) -> list[float]:
    """:func:`parse_number_list`, each value > 0; ``refusal`` says why a value is not, with ``{value}`` in it."""
    values = parse_number_list(text, name, expected)
    for value in values:
        if value <= 0:
            raise InputError(f"{name}: " + refusal.format(value=f"{value:g}"))
    return values


def parse_altitudes(text, name: str = "ALTITUDES") -> list[float]:
    """Altitudes above the ground (m), each > 0."""
    return _parse_positive_list(text, name, "altitudes above the ground in metres, e.g. 10,20",
                                "altitude {value} m is not above the ground — every altitude must be greater "
                                "than 0 m")


def parse_sigmas(text, name: str = "SIGMAS") -> list[float]:
    """The six pose sigmas (x, y, z in m; roll, pitch, yaw in degrees), each ≥ 0."""
    sigmas = parse_number_list(text, name, f"pose sigmas ({SIGMAS_HINT})")
    if len(sigmas) != len(AXES):
        raise InputError(f"{name}: expected {len(AXES)} sigmas ({SIGMAS_HINT}), got {len(sigmas)}")
    for axis, unit, sigma in zip(AXES, SIGMA_UNITS, sigmas):
        if sigma < 0:
            raise InputError(f"{name}: the {axis} sigma is negative ({sigma:g} {unit}) — sigmas are "
                             "standard deviations and must be 0 or more")
    return sigmas


def parse_skld_cutoffs(text, name: str = "SKLD_CUTOFFS") -> list[float]:
    """Symmetric KL divergence cut-offs (nats), each > 0."""
    return _parse_positive_list(text, name, "sKLD cut-offs in nats, e.g. 0.01",
                                "cut-off {value} is not a divergence — every sKLD cut-off must be greater than "
                                "0 nats")
