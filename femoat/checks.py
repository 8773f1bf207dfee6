"""Validation of physical parameters, shared by the contact laws and the materials: every
message names the parameter, its unit and the accepted range."""

import math


def finite(name, value, unit):
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
        raise ValueError(f"{name} = {value!r} {unit}: must be a finite number.")


def positive(name, value, unit):
    finite(name, value, unit)
    if value <= 0.0:
        raise ValueError(f"{name} = {value!r} {unit}: must be > 0.")


def positive_or_inf(name, value, unit):
    if not isinstance(value, (int, float)) or isinstance(value, bool) or math.isnan(value):
        raise ValueError(f"{name} = {value!r} {unit}: must be a number > 0 (math.inf allowed).")
    if value <= 0.0:
        raise ValueError(f"{name} = {value!r} {unit}: must be > 0 (math.inf allowed).")


def in_range(name, value, unit, lo, hi, lo_open=False, hi_open=False):
    finite(name, value, unit)
    low_bad = value <= lo if lo_open else value < lo
    high_bad = value >= hi if hi_open else value > hi
    if low_bad or high_bad:
        left = "(" if lo_open else "["
        right = ")" if hi_open else "]"
        raise ValueError(f"{name} = {value!r} {unit}: must lie in {left}{lo}, {hi}{right}.")


def non_negative(name, value, unit):
    finite(name, value, unit)
    if value < 0.0:
        raise ValueError(f"{name} = {value!r} {unit}: must be >= 0.")


def flag(name, value):
    if not isinstance(value, bool):
        raise ValueError(f"{name} = {value!r}: must be True or False.")


def restitution(e):
    """A coefficient of restitution e in (0, 1], the argument of every closed form."""
    if not (isinstance(e, (int, float)) and math.isfinite(e) and 0 < e <= 1):
        raise ValueError(f"e = {e!r} is invalid: the coefficient of restitution must be in (0, 1].")
