"""numba's typing of a call to one of its functions, resolved once per argument types.

Each time numba's type inference meets a call to a function it types by templates (an
operator, a math or NumPy function, a function written with ``@overload``), it asks the
function's type for the call's signature (``types.Function.get_call_type``), which tries the
templates one by one. The same question comes again and again: every call site of every
kernel, and each site again on every round of the inference until the types settle: nearly
every question of a cold compile is a repeat (counted in docs/startup.md).

:func:`get_call_type` answers a repeat from a memo keyed by everything numba's answer depends
on: the function's type, the typing context and target, the argument types (literal values
included) and the compile flags in force (an ``@overload`` is compiled under them). Along with
the signature it keeps, and puts back on a repeat, what resolving the call leaves behind for
lowering: the implementation key of the signature and, for templates that compile an
implementation, the compiled overload and the inlining information stored under the
signature's argument types (those that resolving it set): after a repeat, numba's state is what
resolving it again would have left. A call that fails is not memoized (it is resolved, and
fails, each time). ``tests/test_call_types.py`` checks answers and that state against numba's own.

Installed by :func:`install` when femoat first imports numba (:mod:`femoat.compilation.jit`),
on the numba versions whose ``types.functions`` module was read and tested
(:data:`NUMBA_VERSIONS`); ``FEMOAT_CALL_TYPES_MEMO=0`` leaves numba's own.
"""

from femoat.compilation import numba_version

NUMBA_VERSIONS = ((0, 68), (0, 68))
"""The first and last numba minor versions whose ``BaseFunction.get_call_type`` this module was
read and tested against (both ends included)."""

_installed = []
_memo = {}
_STATE = ("_compiled_overloads", "_inline_overloads")
"""The template attributes keyed by a signature's argument types that resolving a call sets."""


def install():
    """Make numba's ``BaseFunction.get_call_type`` :func:`get_call_type` (once a process).
    Returns whether it is installed (False on an unknown numba, or with
    ``FEMOAT_CALL_TYPES_MEMO=0``)."""
    if _installed:
        return True
    if not numba_version.wanted("FEMOAT_CALL_TYPES_MEMO", NUMBA_VERSIONS):
        return False
    from numba.core.types.functions import BaseFunction

    get_call_type.__wrapped__ = BaseFunction.get_call_type
    BaseFunction.get_call_type = get_call_type
    _installed.append(True)
    return True


def clear():
    """Forget every memoized answer (numba's own caches are untouched)."""
    _memo.clear()


def get_call_type(self, context, args, kws):
    """The signature of a call of the function type ``self`` with argument types ``args`` and
    keyword argument types ``kws``: numba's ``BaseFunction.get_call_type``, from the memo when
    the same call was resolved before under the same flags."""
    key = _key(self, context, args, kws)
    if key is None:
        return get_call_type.__wrapped__(self, context, args, kws)
    known = _memo.get(key)
    if known is not None:
        sig, impl_key, state = known
        self._impl_keys[sig.args] = impl_key
        for table, entry in state:
            table[sig.args] = entry
        return sig
    tables = _tables(self)
    before = [dict(table) for table in tables]
    sig = get_call_type.__wrapped__(self, context, args, kws)
    if sig is not None:
        state = tuple((table, table[sig.args]) for table, old in zip(tables, before)
                      if sig.args in table and table[sig.args] is not old.get(sig.args))
        _memo[key] = (sig, self._impl_keys[sig.args], state)
    return sig


def _key(function, context, args, kws):
    """The memo's key of a call, or None when a part of it cannot be hashed (never memoized)."""
    from numba.core.target_extension import get_local_target
    from numba.core.targetconfig import ConfigStack

    flags = ConfigStack.top_or_none()
    try:
        key = (function, context, get_local_target(context), tuple(args),
               tuple(sorted(kws.items())),
               None if flags is None else _frozen(flags))
        hash(key)
    except TypeError:
        return None
    return key


def _frozen(flags):
    """The options set on ``flags`` (the others are their class's defaults), by name, as a
    hashable tuple with the flags' class: equal tuples, equal flags. An option whose value
    cannot be hashed (numba's option objects: fastmath, inline, parallel) by its type and
    ``repr``, which shows every field."""
    frozen = [type(flags)]
    for name, value in sorted(flags._values.items(), key=lambda item: item[0]):
        try:
            hash(value)
        except TypeError:
            value = (type(value).__qualname__, repr(value))
        frozen.append((name, value))
    return tuple(frozen)


def _tables(function):
    """The templates' per-signature tables of ``function`` that resolving a call fills."""
    tables = []
    for template in function.templates:
        for name in _STATE:
            table = getattr(template, name, None)
            if isinstance(table, dict) and all(table is not t for t in tables):
                tables.append(table)
    return tables
