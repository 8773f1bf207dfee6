"""Compiling femoat's kernels: the plumbing between the Python code and numba, in one room.

* :mod:`~femoat.compilation.sources`: which source files decide the compiled code (and a run's
  result) and their fingerprint: the one list read by the numba cache check, the ahead-of-time
  module's key and the suite's code version; hashed lazily, never at import.
* :mod:`~femoat.compilation.jit`: ``njit``, femoat's kernel decorator (numba is imported
  when a kernel is first compiled or called, not before).
* :mod:`~femoat.compilation.numba_cache`: drops numba's cached kernels compiled from other sources.
* :mod:`~femoat.compilation.exports`: the solver's entry points: the one list read by the JIT
  namespace, the ahead-of-time build and its loader.
* :mod:`~femoat.compilation.aot`: the ahead-of-time module's place, key and loader (no numba);
  :mod:`~femoat.compilation.aot_build` builds it (``femoat compile``).
* :mod:`~femoat.compilation.probe` and :mod:`~femoat.compilation.warmup`: a tiny run that
  compiles or loads every entry point, and the start-up it costs, paid before any timing.

The JIT path is first-class: the ahead-of-time module only saves a process numba's import.
"""
