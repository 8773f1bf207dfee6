"""A kernel's machine code and Python wrapper built when Python first calls it, not before.

numba compiles every function it types to machine code at once and builds, beside it, the
wrapper that converts Python arguments (``NativeLowering``: ``create_cpython_wrapper``, then
``get_executable``, which optimizes the library's module as a whole and compiles it into the
JIT engine). For a kernel that only other kernels call, the machine code and the wrapper are
thrown away: a caller links the kernel's LLVM module (``add_linking_library``) into its own,
optimizes it again with the caller's code and compiles it there. femoat's loop calls about 170
such kernels, so a cold compile spent a fifth of its time on code nobody ran.

Here a kernel compiled while numba types one of its callers (and not because Python called it)
stops after LLVM's function passes: its library is finalized without the module passes and
without entering the JIT engine, the wrapper is not built, and its entry point is a
:class:`LazyEntry`, the key under which numba's lowering finds the kernel's code for its
callers. The module passes (inlining across functions among them) run where the module is
linked, in each caller, as they did there before. numba's on-disk cache keeps such a kernel as
its module (:data:`KIND`, no object code). The first call from Python makes what numba would
have made: a library holding the wrapper and the kernel's module, finalized (linked, optimized
as a whole, compiled to machine code), numba's ``cfunc`` over it, the dispatcher's overload and
its on-disk cache entry replaced by that ordinary one (:func:`materialize`).

What a caller computes is unchanged (LLVM's optimizations keep IEEE arithmetic; the solver's
fingerprints are equal to the bit either way); its machine code may differ, since its module
passes now meet the callees' code before rather than after theirs.

Installed with femoat's other numba replacements (:mod:`femoat.compilation.jit`), on the numba
versions whose ``codegen``, ``cpu``, ``lowering`` and ``dispatcher`` modules were read and
tested (:data:`NUMBA_VERSIONS`); ``FEMOAT_LAZY_MACHINE_CODE=0`` compiles every kernel at once
as numba does (the replacements stay installed, so that a deferred cache entry still loads; it
is then built at once). Not deferred: an object-mode block lifted from a kernel. A deferred
kernel that mutual recursion calls through numba's run-time linker enters the JIT engine as it
is (:func:`_link_recursion`), where the linker finds it.
"""

import threading
import weakref

from femoat.compilation import numba_version

NUMBA_VERSIONS = ((0, 68), (0, 68))
"""The first and last numba minor versions whose code-library, lowering and dispatcher code
this module was read and tested against (both ends included)."""

KIND = "femoat-module-without-machine-code"
"""numba's serialization kind (``CodeLibrary._unserialize``) of a cache entry without machine
code (the library's LLVM module after the function passes, as bitcode), and the first item of
its index key (:func:`_deferred_key`)."""

_installed = []
_state = threading.local()


def install():
    """Teach numba the library without machine code (once a process): its finalizing, its
    entry point, its cache entry. Returns whether it is installed (False on an unknown numba).
    Which compiles produce such libraries is decided per dispatcher (:func:`defer`)."""
    if _installed:
        return True
    if not numba_version.supported(NUMBA_VERSIONS):
        return False
    from numba.core import codegen, cpu, lowering

    library = codegen.CPUCodeLibrary
    for cls, name, replacement in (
            (library, "_optimize_final_module", _optimize_final_module),
            (library, "_finalize_final_module", _finalize_final_module),
            (library, "serialize_using_object_code", _serialize),
            (codegen.JITCPUCodegen, "set_env", _set_env),
            (cpu.CPUContext, "get_executable", _get_executable),
            (lowering.BaseLower, "lower", _lower),
            (lowering.BaseLower, "create_cpython_wrapper", _create_cpython_wrapper)):
        replacement.__wrapped__ = getattr(cls, name)
        setattr(cls, name, replacement)
    _unserialize.__wrapped__ = library._unserialize.__func__
    library._unserialize = classmethod(_unserialize)
    _installed.append(True)
    return True


def enabled():
    """Whether kernels compiled for their callers skip machine code in this process."""
    return bool(_installed) and numba_version.wanted("FEMOAT_LAZY_MACHINE_CODE", NUMBA_VERSIONS)


def defer(dispatcher):
    """Make ``dispatcher`` (a femoat kernel's numba dispatcher) build machine code only for a
    call from Python: compiled (or loaded from the cache) while numba types a caller, it stops
    at its module. Its cache entries without machine code are kept under an index key of their
    own (:func:`_deferred_key`), which no other dispatcher reads. When not :func:`enabled`, a
    deferred cache entry is built as soon as it is loaded (one with a Python wrapper to build).
    No-op unless :func:`install` ran."""
    if not _installed:
        return dispatcher
    deferring = enabled()
    compile_ = dispatcher.compile
    compile_for_args = dispatcher._compile_for_args
    add_overload = dispatcher.add_overload
    cache = dispatcher._cache
    load_overload, save_overload = cache.load_overload, cache.save_overload

    def compile(sig):
        requests = _stack("requests")
        for_python = bool(requests) and requests[-1] is dispatcher
        modes = _stack("modes")
        requests.append(None)  # what this compile compiles in turn is for its callers
        modes.append((dispatcher.py_func, deferring and not for_python))
        try:
            entry = compile_(sig)
        finally:
            modes.pop()
            requests.pop()
        if isinstance(entry, LazyEntry) and (
                for_python or (not deferring and entry.release_gil is not None)):
            entry = materialize(dispatcher, entry)
        return entry

    def _compile_for_args(*args, **kws):
        requests = _stack("requests")
        requests.append(dispatcher)
        try:
            return compile_for_args(*args, **kws)
        finally:
            requests.pop()

    def _add_overload(cres):
        if isinstance(cres.entry_point, LazyEntry):  # nothing Python can call yet
            dispatcher.overloads[tuple(cres.signature.args)] = cres
        else:
            add_overload(cres)

    def _load_overload(sig, target_context):
        found = load_overload(sig, target_context)
        return found if found is not None else load_overload(_deferred_key(sig), target_context)

    def _save_overload(sig, data):
        deferred = isinstance(data.entry_point, LazyEntry)
        return save_overload(_deferred_key(sig) if deferred else sig, data)

    dispatcher.compile = compile
    dispatcher._compile_for_args = _compile_for_args
    dispatcher.add_overload = _add_overload
    cache.load_overload = _load_overload
    cache.save_overload = _save_overload
    return dispatcher


def compile_for_python(dispatcher, sig):
    """Compile ``dispatcher`` (a :func:`defer`-wrapped dispatcher) for the argument types
    ``sig`` as a call from Python would: machine code and wrapper at once, no deferred entry
    (or load it from numba's cache). Returns the entry point."""
    requests = _stack("requests")
    requests.append(dispatcher)
    try:
        return dispatcher.compile(sig)
    finally:
        requests.pop()


def _deferred_key(sig):
    """The signature under which numba's cache index keeps a deferred entry of ``sig`` (the
    argument types): never a signature numba itself asks for, so a dispatcher that cannot load
    such an entry (one :func:`defer` did not wrap, or a process without :func:`install`) never
    finds it and compiles as usual."""
    return (KIND, *sig)


class LazyEntry:
    """The entry point of a kernel compiled without machine code: the key under which numba's
    lowering finds the kernel's code (``insert_user_function``). Not callable: a call from
    Python reaches the dispatcher's ``compile``, which builds it first (:func:`materialize`);
    numba's dispatcher never holds it in its table of compiled code."""

    __slots__ = ("library", "fndesc", "environment", "release_gil", "__weakref__")

    def __init__(self, library, fndesc, environment, release_gil):
        self.library = library
        self.fndesc = fndesc
        self.environment = environment
        self.release_gil = release_gil

    def __repr__(self):
        return f"<kernel {self.fndesc.qualname} without machine code>"


def materialize(dispatcher, entry):
    """Build a deferred overload of ``dispatcher`` (``entry``, its :class:`LazyEntry`) as numba
    would have built it: the Python wrapper and the kernel's module in one library, optimized
    and compiled to machine code; numba's ``cfunc`` over it becomes the overload's entry point,
    in the dispatcher, in numba's lowering and in the on-disk cache. Returns the ``cfunc``."""
    if entry.release_gil is None:
        raise TypeError(f"{dispatcher.py_func.__qualname__} is compiled without numba's Python "
                        "wrapper (no_cpython_wrapper=True; a femoat kernel declared "
                        "python=False): call its python_dispatcher from Python")
    from numba.core.compiler_lock import global_compiler_lock

    with global_compiler_lock:
        args = tuple(entry.fndesc.argtypes)
        cres = dispatcher.overloads[args]
        if cres.entry_point is not entry:  # built meanwhile (another thread's call)
            return cres.entry_point
        context = cres.target_context
        context.refresh()  # numba lowers on a refreshed context; cache_load's load skips it
        library = context.codegen().create_library(entry.library.name)
        library.enable_object_caching()
        context.create_cpython_wrapper(library, entry.fndesc, entry.environment, None,
                                       release_gil=entry.release_gil)
        library.add_linking_library(entry.library)
        cfunc = _get_executable.__wrapped__(context, library, entry.fndesc, entry.environment)
        _set_environments(library)
        context.insert_user_function(cfunc, entry.fndesc, [library])
        built = cres._replace(entry_point=cfunc, library=library)
        dispatcher.overloads[args] = built
        dispatcher._insert([a._code for a in args], cfunc, built.objectmode)
        dispatcher._cache.save_overload(args, built)  # numba's cache key: the argument types
    return cfunc


def _stack(name):
    stack = getattr(_state, name, None)
    if stack is None:
        stack = []
        setattr(_state, name, stack)
    return stack


def _deferred(func):
    """Whether the function ``func`` being lowered now is a deferred compile (:func:`defer`):
    the kernel itself, not an object-mode block lifted from it (same function identity)."""
    modes = getattr(_state, "modes", None)
    return bool(modes) and modes[-1][0] is func and modes[-1][1]


# numba's methods, replaced (each calls numba's own unless the library is deferred)

def _lower(self):
    if (self.generator_info is None and self.fndesc.native
            and _deferred(self.func_ir.func_id.func)):
        self.library._femoat_release_gil = None  # deferred; no wrapper asked for yet
    return _lower.__wrapped__(self)


def _create_cpython_wrapper(self, release_gil=False):
    if hasattr(self.library, "_femoat_release_gil"):
        self.library._femoat_release_gil = release_gil  # built by materialize, if ever
        return None
    return _create_cpython_wrapper.__wrapped__(self, release_gil)


def _optimize_final_module(self):
    if not hasattr(self, "_femoat_release_gil"):
        return _optimize_final_module.__wrapped__(self)
    return None  # the module passes run where the module is linked: in each caller


def _finalize_final_module(self):
    if not hasattr(self, "_femoat_release_gil"):
        return _finalize_final_module.__wrapped__(self)
    # numba's, less entering the JIT engine and compiling to machine code
    self._finalize_dynamic_globals()
    self._verify_declare_only_symbols()
    self._finalized = True
    return None


def _get_executable(self, library, fndesc, env):
    if not hasattr(library, "_femoat_release_gil"):
        cfunc = _get_executable.__wrapped__(self, library, fndesc, env)
        _set_environments(library)
        return cfunc
    library._ensure_finalized()
    _link_recursion(library, fndesc)
    return LazyEntry(library, fndesc, env, library._femoat_release_gil)


_needed = set()
"""Symbols that a deferred library calls through numba's run-time linker (a recursive call:
``.numba.unresolved$<symbol>``), not yet defined in the JIT engine."""
_deferred_libraries = weakref.WeakValueDictionary()
"""{a deferred kernel's symbol: its library}."""


def _link_recursion(library, fndesc):
    """Mutual recursion: a kernel typed inside its own compile is called through numba's
    run-time linker (a pointer it fills when a module defining the symbol enters the JIT
    engine). A deferred library never enters it, so the library defining such a symbol is put
    there (compiled as it is, without its wrapper), whichever of the two is finalized first."""
    prefix = ".numba.unresolved$"
    for gv in library._final_module.global_variables:
        if gv.name.startswith(prefix):
            symbol = gv.name[len(prefix):]
            target = _deferred_libraries.get(symbol)
            if target is not None:
                _enter_engine(target)
            else:
                _needed.add(symbol)
    _deferred_libraries[fndesc.mangled_name] = library
    if fndesc.mangled_name in _needed:
        _needed.discard(fndesc.mangled_name)
        _enter_engine(library)


def _enter_engine(library):
    """Compile a deferred library into the JIT engine as numba's finalizing would, less the
    object-code cache hooks (its cache entry keeps no machine code)."""
    if getattr(library, "_femoat_in_engine", False):
        return
    library._femoat_in_engine = True
    library._codegen._add_module(library._final_module)
    library._finalize_specific()


def _set_env(self, env_name, env):
    if self._engine.get_global_value_address(env_name):
        return _set_env.__wrapped__(self, env_name, env)
    return None  # in a deferred library's module only: set when it is built


def _set_environments(library):
    """Point the environment variables of the callees in ``library`` at their environments,
    as numba does for a library loaded from its cache (``CompileResult._rebuild``): a deferred
    callee's own module, where numba's ``get_executable`` would have set them, is not in the
    JIT engine."""
    if not _installed:
        return
    from numba.core.environment import lookup_environment

    for gv in library._final_module.global_variables:
        if gv.name.startswith("_ZN08NumbaEnv"):
            env = lookup_environment(gv.name)
            if env is not None:
                library.codegen.set_env(gv.name, env)


def _serialize(self):
    if not hasattr(self, "_femoat_release_gil"):
        return _serialize.__wrapped__(self)
    self._ensure_finalized()
    return (self.name, KIND, (self._final_module.as_bitcode(), self._femoat_release_gil))


def _unserialize(cls, codegen, state):
    name, kind, data = state
    if kind != KIND:
        return _unserialize.__wrapped__(cls, codegen, state)
    import llvmlite.binding as ll

    bitcode, release_gil = data
    self = codegen.create_library(name)
    self._femoat_release_gil = release_gil
    self._final_module = ll.parse_bitcode(bitcode)
    self._finalize_final_module()
    return self
