"""``njit`` that imports numba only when a kernel is first compiled or called from Python.

Importing numba and initialising its CPU target costs each process more than a whole paper run
(numba's own import, its registries, and the scipy.linalg import numba makes for BLAS; measured
in ``benchmarks/README.md``). femoat's kernels are decorated with :func:`njit` from this module
instead of numba's: the decorator only records the function, and numba is imported on the first call
from Python (or when another kernel that calls this one is compiled). A process that never runs
the solver (reading results, plotting, the command line's help) never imports numba.

Inside compiled code a :class:`Kernel` is exactly its numba dispatcher: numba is taught to
type it as one (``typeof`` is registered for :class:`Kernel` when numba is first imported
here), so kernels call kernels at full speed and numba's on-disk cache works as before.
"""

import functools
import sys

from femoat.compilation import machine_code

_registered = False
_checked = set()
_started = []
"""The kernels whose numba dispatcher this process has made (compiled or loaded from the
cache), in order."""

OPTIONS = {"_nrt": False, "no_cfunc_wrapper": True}
"""Compile options for every kernel. No kernel allocates, so numba's reference-counted runtime
is switched off: with it, every array passed between kernels (and every row view ``P[e]``)
costs an atomic increment and decrement, a large share of the solver's run time. No kernel is
handed to C code, so numba's C-callable wrapper (``cfunc``) is not built."""

INTERNAL = {"no_cpython_wrapper": True}
"""More options for a kernel declared ``njit(python=False)``, one that only compiled kernels
call: numba's wrapper converting Python arguments is not built. The kernels that take the
loop's bundles are declared so: the wrapper of such a kernel unboxes about a thousand values,
and LLVM optimizes and compiles it again in every kernel that links the kernel's code."""


def njit(*args, **options):
    """Like ``numba.njit`` (with or without options), compiled lazily; see the module docstring.
    One more option, ``python=False``: the kernel is called from compiled code only
    (:data:`INTERNAL`; a call from Python still works, through a copy of its own:
    :attr:`Kernel.python_dispatcher`)."""
    if args and callable(args[0]) and len(args) == 1 and not options:
        return Kernel(args[0], {})
    if args:
        raise TypeError("femoat.compilation.jit.njit takes keyword options only (e.g. cache=True)")
    return lambda func: Kernel(func, options)


class Kernel:
    """A Python function to be compiled by numba on first use."""

    def __init__(self, py_func, options):
        options = dict(options)
        python = options.pop("python", True)
        if python not in (True, False):
            raise TypeError(f"python = {python!r}: use True (the default) or False (a kernel "
                            "that only compiled kernels call)")
        self.py_func = py_func
        self.options = options
        self.python = python
        self._dispatcher = None
        self._python_dispatcher = None
        functools.update_wrapper(self, py_func)

    @property
    def dispatcher(self):
        """The numba dispatcher that compiled kernels call (numba is imported and this function
        registered on first use); without the Python-argument wrapper when declared
        ``python=False`` (:data:`INTERNAL`)."""
        if self._dispatcher is None:
            _register()
            _fresh_cache(self.py_func)
            import numba

            internal = {} if self.python else INTERNAL
            self._dispatcher = numba.njit(**{**OPTIONS, **internal, **self.options})(
                self.py_func)
            if self.options.get("inline", "never") == "never":
                _compile_for_types(self._dispatcher)
            _load_without_refresh(self._dispatcher)
            machine_code.defer(self._dispatcher)
            _started.append(self)
        return self._dispatcher

    @property
    def python_dispatcher(self):
        """The numba dispatcher of a call from Python: :attr:`dispatcher`, or for a kernel
        declared ``python=False`` a dispatcher of its own, with the wrapper, over a copy of the
        function named ``<name>__python``: its own index in numba's on-disk cache, so that it
        never loads the code of :attr:`dispatcher`, which has no entry from Python."""
        if self.python:
            return self.dispatcher
        if self._python_dispatcher is None:
            _register()
            _fresh_cache(self.py_func)
            import numba

            self._python_dispatcher = numba.njit(**{**OPTIONS, **self.options})(
                _python_copy(self.py_func))
            _load_without_refresh(self._python_dispatcher)
            machine_code.defer(self._python_dispatcher)
            _started.append(self)
        return self._python_dispatcher

    @property
    def targetoptions(self):
        """numba's compile options of this kernel: numba's inliner reads them (and ``py_func``)
        from a callee, so ``njit(inline="always")`` works between femoat kernels too."""
        return self.dispatcher.targetoptions

    def __call__(self, *args):
        return self.python_dispatcher(*args)

    def retarget(self, py_func):
        """Make this kernel compile ``py_func`` instead (its name and arguments the same), as
        long as numba has not compiled any kernel of this process yet (:func:`started`): every
        kernel that calls this one then compiles the new function, since numba reads a callee
        only when it compiles its caller. How :func:`femoat.bearings.registry.select` leaves
        bearing kinds out of the loop."""
        if started():
            raise RuntimeError(f"{self!r}: cannot be retargeted once numba has compiled a kernel "
                               "of this process (do it first, in a new process).")
        self.py_func = py_func
        self.__wrapped__ = py_func

    def __repr__(self):
        return f"<femoat kernel {self.py_func.__module__}.{self.py_func.__qualname__}>"


def _python_copy(func):
    """``func`` under the name ``<qualname>__python``: the same code, globals and defaults (numba
    names a function's cache index, and its compiled symbols, after the qualified name)."""
    import types

    copy = types.FunctionType(func.__code__, func.__globals__, func.__name__,
                              func.__defaults__, func.__closure__)
    copy.__kwdefaults__ = func.__kwdefaults__
    copy.__qualname__ = f"{func.__qualname__}__python"
    copy.__module__ = func.__module__
    copy.__doc__ = func.__doc__
    return copy


def _compile_for_types(dispatcher):
    """Make a kernel called from compiled code compile one version per argument *types*, not
    one per constant: numba types a constant argument as a literal (``_series(p, s, 0, ...)``:
    ``Literal[int](0)``) and compiles the callee anew for each literal value and for the
    variable, each a whole pipeline (the triple pendulum's series solve was compiled three times).
    The callee compiled for the plain types serves every call (a literal converts to its type);
    the arithmetic is the same, only the branches on such an argument are taken at run time."""
    from numba.core.types import unliteral

    resolve = dispatcher.get_call_template

    def get_call_template(args, kws):
        return resolve(tuple(unliteral(a) for a in args),
                       {k: unliteral(v) for k, v in kws.items()})

    dispatcher.get_call_template = get_call_template


def started():
    """Whether this process has made any kernel's numba dispatcher (compiled or loaded one):
    from then on the compiled loop's callees are fixed."""
    return bool(_started)


def _fresh_cache(func):
    """Before numba first compiles or loads a kernel of a module, drop that module's cached
    kernels if any kernel source changed since (numba itself checks only the module's own file,
    and neither the kernels it inlines from others nor the compile options set here)."""
    module_file = getattr(sys.modules.get(func.__module__), "__file__", None)
    if module_file is None or module_file in _checked:
        return
    _checked.add(module_file)
    from femoat.compilation.numba_cache import drop_stale_cache
    from femoat.compilation.sources import fingerprint

    drop_stale_cache(module_file, fingerprint("kernels"))


def _load_without_refresh(dispatcher):
    """Load ``dispatcher``'s cache entries without numba's context refresh
    (:mod:`femoat.compilation.cache_load`) and save them under a lock between processes
    (:func:`femoat.compilation.numba_cache.locked_saves`); neither decides what a kernel
    compiles to (they are not kernel sources)."""
    from femoat.compilation import cache_load, numba_cache

    cache_load.without_refresh(dispatcher)
    numba_cache.locked_saves(dispatcher)


def _register():
    global _registered
    if _registered:
        return
    from numba.core.typing.typeof import typeof_impl

    from femoat.compilation import (cache_load, call_types, error_markup, flags, inlining,
                                    ir_builder, liveness, ssa)

    machine_code.install()
    cache_load.install()
    error_markup.install()
    ir_builder.install()
    inlining.install()
    ssa.install()
    liveness.install()
    flags.install()
    call_types.install()

    @typeof_impl.register(Kernel)
    def _typeof_kernel(value, context):
        return typeof_impl(value.dispatcher, context)

    _registered = True
