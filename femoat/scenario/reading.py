"""Typed reads of a scenario's tables, and the defaults they fall back on.

A value of the wrong type is a ValueError that names the table and the key (and shows an
example); a table's object then checks the ranges itself (its message names the parameter,
prefixed with the table by :func:`naming`). Defaults are read from the objects the tables build
(:func:`field_default`, :func:`parameter_default`), never written here a second time.
"""

import contextlib
import dataclasses
import inspect
import math
import tomllib
from pathlib import Path


# ---- defaults, read from the objects the tables build ----------------------------------------

def field_default(cls, name):
    """The default of dataclass ``cls``'s field ``name`` (its default factory called)."""
    field = {f.name: f for f in dataclasses.fields(cls)}[name]
    if field.default_factory is not dataclasses.MISSING:
        return field.default_factory()
    if field.default is dataclasses.MISSING:
        raise TypeError(f"{cls.__name__}.{name} has no default")
    return field.default


def field_defaults(cls, leave_out=()):
    """``{field: default}`` of the fields of dataclass ``cls`` that have a default, without
    ``leave_out`` and without those whose default is None (TOML has no null: a key left out is
    the None)."""
    out = {}
    for f in dataclasses.fields(cls):
        has = f.default is not dataclasses.MISSING or f.default_factory is not dataclasses.MISSING
        if has and f.name not in leave_out:
            value = field_default(cls, f.name)
            if value is not None:
                out[f.name] = value
    return out


def parameter_default(function, name):
    """The default of ``function``'s parameter ``name``."""
    default = inspect.signature(function).parameters[name].default
    if default is inspect.Parameter.empty:
        raise TypeError(f"{function.__qualname__}({name}) has no default")
    return default


def one_of(choices):
    """"'a', 'b' or 'c'": the choices of a key, quoted as in the file."""
    quoted = [repr(c) for c in choices]
    return quoted[0] if len(quoted) == 1 else f"{', '.join(quoted[:-1])} or {quoted[-1]}"


# ---- typed reads ------------------------------------------------------------------------------

def check_keys(table, allowed, where):
    """A ValueError naming the unknown keys of ``table`` (and the allowed ones)."""
    unknown = set(table) - set(allowed)
    if unknown:
        raise ValueError(f"{where}: unknown key(s) {sorted(unknown)}; allowed: "
                         f"{sorted(allowed)}.")


def subtable(d, key, where):
    """The table ``d[key]`` (a copy; empty when absent)."""
    value = d.get(key, {})
    if not isinstance(value, dict):
        raise ValueError(f"{where} {key} = {value!r}: expected a table ([{key}] with key = value "
                         "lines).")
    return dict(value)


def is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def number(d, key, default, where, unit=""):
    value = d.get(key, default)
    if not is_number(value):
        example = f", e.g. {key} = {default!r}" if default is not None else ""
        raise ValueError(f"{where} {key} = {value!r}: expected a finite number"
                         f"{f' [{unit}]' if unit else ''}{example}.")
    return float(value)


def integer(d, key, default, where):
    value = d.get(key, default)
    if not (isinstance(value, int) and not isinstance(value, bool)):
        raise ValueError(f"{where} {key} = {value!r}: expected a whole number, e.g. "
                         f"{key} = {default!r}.")
    return value


def flag(d, key, default, where):
    value = d.get(key, default)
    if not isinstance(value, bool):
        raise ValueError(f"{where} {key} = {value!r}: expected true or false.")
    return value


def text(d, key, default, where):
    value = d.get(key, default)
    if not isinstance(value, str):
        raise ValueError(f"{where} {key} = {value!r}: expected a string in quotes, e.g. "
                         f"{key} = {default!r}.")
    return value


def numbers(d, key, default, where, unit):
    value = d.get(key, default)
    if not (isinstance(value, (list, tuple)) and all(is_number(v) for v in value)):
        raise ValueError(f"{where} {key} = {value!r}: expected a list of finite numbers [{unit}], "
                         f"e.g. {key} = {list(default)!r}.")
    return tuple(float(v) for v in value)


@contextlib.contextmanager
def naming(where):
    """Prefix the table to a ValueError raised by the objects a table builds (their messages name
    the parameter, e.g. "gap = -1.0 must be ..."; a file reader's error names its file), its
    fix phrased in the file's keys (:data:`FILE_WORDS`)."""
    from femoat.ground_motions import RecordFormatError

    try:
        yield
    except RecordFormatError:
        raise
    except (ValueError, OverflowError) as exc:  # OverflowError: int(inf) in a check
        if isinstance(exc, ValueError) and str(exc).startswith("["):  # already names its table
            raise
        raise ValueError(f"{where} {in_file_words(str(exc))}") from None


FILE_WORDS = {
    "(read_at2_pair(..., pad=True))": "(pad = true in [motion])",
    "Integrator(method='newmark')": "method = \"newmark\" in [solver]",
}
"""A Python call a library message names as its fix: the scenario file's key that does it."""


def in_file_words(message):
    """``message`` with each fix of :data:`FILE_WORDS` in the file's words."""
    for python, key in FILE_WORDS.items():
        message = message.replace(python, key)
    return message


def numeric_table(table, cls, where):
    """``cls(**table)`` for a table of numbers whose keys are ``cls``'s fields (the fields left
    out take ``cls``'s defaults)."""
    allowed = {f.name for f in dataclasses.fields(cls)}
    check_keys(table, allowed, where)
    whole = {f.name for f in dataclasses.fields(cls) if f.type in (int, "int")}
    for key, value in table.items():  # ranges (and whether inf is allowed) are cls's to check
        if not isinstance(value, (int, float)) or isinstance(value, bool) or math.isnan(value):
            raise ValueError(f"{where} {key} = {value!r}: expected a number.")
        if key in whole and not isinstance(value, int):
            raise ValueError(f"{where} {key} = {value!r}: expected a whole number.")
    try:
        with naming(where):
            return cls(**table)
    except TypeError as exc:  # a required parameter missing
        raise ValueError(f"{where}: {exc}; allowed keys: {sorted(allowed)}.") from None


# ---- files ------------------------------------------------------------------------------------

def resolve(path, base_dir):
    """``path`` relative to the scenario file's folder ``base_dir`` (unless absolute)."""
    p = Path(path)
    return p if p.is_absolute() else Path(base_dir) / p


def read_toml(path, kind):
    """The parsed TOML document of the ``kind`` file ``path`` (e.g. "scenario", "suite").

    Raises FileNotFoundError, or ValueError naming the file when it is not UTF-8 TOML.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{kind} file {path} does not exist.")
    try:
        return tomllib.loads(path.read_bytes().decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not UTF-8 text (byte {exc.start}); a {kind} file is TOML "
                         "text.") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML ({exc}).") from None
