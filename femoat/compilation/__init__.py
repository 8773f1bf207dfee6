"""Compiling femoat's kernels: the plumbing between the Python code and numba, in one room.

* :mod:`~femoat.compilation.sources`: which source files decide the compiled code (and a run's
  result) and their fingerprint: the one list read by the numba cache check and the suite's
  code version; hashed lazily, never at import.
* :mod:`~femoat.compilation.jit`: ``njit``, femoat's kernel decorator (numba is imported
  when a kernel is first compiled or called, not before).
* :mod:`~femoat.compilation.numba_cache`: drops numba's cached kernels compiled from other sources.
* :mod:`~femoat.compilation.exports`: the solver's entry points, the namespace
  :func:`femoat.integration.solve.kernels` hands to the solver.
* :mod:`~femoat.compilation.inlining`, :mod:`~femoat.compilation.ssa`,
  :mod:`~femoat.compilation.liveness`, :mod:`~femoat.compilation.call_types` and
  :mod:`~femoat.compilation.flags`: numba's inliner, SSA reconstruction, liveness analysis,
  call typing and compile flags made to cost what the code costs (the same IR, built once,
  walked where it names a variable; live sets once per loop; a call's types resolved once);
  installed with the first kernel, on the numba version they were read against, each with a
  switch that leaves numba's own (both decided in :mod:`~femoat.compilation.numba_version`).

* :mod:`~femoat.compilation.machine_code`: a kernel compiled for its callers stops at its
  LLVM module (what its callers link and optimize); its machine code and Python wrapper are
  built when Python first calls it.
* :mod:`~femoat.compilation.error_markup` and :mod:`~femoat.compilation.ir_builder`: numba's
  error messages marked up without wrapping the streams, llvmlite's builder positioned before
  a terminator without a search (the same strings and positions).
* :mod:`~femoat.compilation.cache_load`: a kernel loaded from numba's cache without numba's
  refresh of its whole target context (which imports scipy.linalg, among others).
* :mod:`~femoat.compilation.compile_plan`: a cold first run compiles the loop while a helper
  process (:mod:`femoat.startup.compile_helper`) compiles its callees from a recorded plan
  into numba's cache; :func:`~femoat.compilation.numba_cache.locked_saves` serializes the
  processes' saves.

The tiny run that compiles (or loads) every entry point before timing, which runs the solver, is
one layer above it: :mod:`femoat.startup`.

numba's JIT with its on-disk cache is the only path: a process that finds the cache loads the
kernels in about a second; there is no ahead-of-time module (``numba.pycc`` is deprecated
upstream, and the second it saved per process did not pay for its build: docs/startup.md).
"""
