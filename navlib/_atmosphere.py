"""Unchecked cores of :mod:`navlib.atmosphere`: the ISA troposphere (ICAO Doc 7488) and its constants.

The checked public functions live in :mod:`navlib.atmosphere`, which also publishes the constants; a function of
another module that has already checked its heights and reference pressure (e.g.
:func:`navlib.sensors.simulate_barometer`) calls the core here, so that nothing is checked twice on one call.
Heights are geopotential metres within the troposphere (:data:`H_MIN` to :data:`H_MAX`), pressures Pa (> 0).
"""

from __future__ import annotations

from ._typing import Array

P0, T0, LAPSE, R_AIR = 101325.0, 288.15, 0.0065, 287.05287  # published as navlib.atmosphere's, with their units
G0 = 9.80665  # the ISA's g0 (m/s^2): standard gravity, navlib.units.G0
H_MIN, H_MAX = -1000.0, 11000.0  # heights (m) where the ISA troposphere holds
EXPONENT = R_AIR * LAPSE / G0  # R L / g0 = 0.190263: p / p0 = (1 - L h / T0)^(1 / EXPONENT)
P_11KM = P0 * (1 - LAPSE * H_MAX / T0) ** (1 / EXPONENT)  # tropopause pressure (Pa) for p0 = P0: 22632.04


def isa_pressure(h: Array, p0: float | Array) -> Array:
    """ISA pressure (Pa) at heights ``h`` (m) with sea-level pressure ``p0`` (Pa)."""
    return p0 * (1 - LAPSE * h / T0) ** (1 / EXPONENT)


def isa_altitude(p: Array, p0: float | Array) -> Array:
    """ISA geopotential altitude (m) of pressures ``p`` (Pa) with sea-level pressure ``p0`` (Pa)."""
    return T0 / LAPSE * (1 - (p / p0) ** EXPONENT)
