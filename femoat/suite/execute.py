"""Run a suite: in-process, on a local Dask cluster, or on an existing one; resumable.

* The output folder holds ``suite.json`` (the definition and its hash), ``runs/part-*.parquet``
  (one part per finished batch) and ``histories/`` (the runs ``[run] histories`` asks for).
* **Resume**: rerunning the same suite into the same folder skips every run already stored.
  A folder holding another suite (a different hash: the definition, its records or femoat's
  version changed) is refused, so old and new rows never mix: choose another ``--out`` or pass
  ``--overwrite`` to delete the old results.
* Runs go to workers in batches (``[run] batch_size``); a hunt-and-fill trace is one task (it is
  sequential). A batch whose task fails as a whole (a run that kills its worker three times)
  is rerun one run per task, and the run that still fails is stored with status 'error'.
  Each finished task's rows are written at once, so an interruption (Ctrl-C, a killed worker
  or client) loses at most the tasks in flight.
* The client compiles the solver's kernels into numba's on-disk cache before any worker starts
  (once per install: :func:`femoat.startup.warmup.warm_up`), so that the workers load them
  from the cache instead of each compiling them.
* On a remote cluster every worker needs femoat installed and the suite's AT2 files at the same
  path (their samples are checked against the definition).
"""

import contextlib
import json
import math
import shutil
import sys
import time
from pathlib import Path

from femoat.suite import runs as rn
from femoat.suite import table as tb
from femoat.suite.huntfill import Outcome, hunt_fill
from femoat.suite.progress import Progress


class _Incomplete(Exception):
    pass


def prepare(suite, out, overwrite=False):
    """Create or check the output folder ``out`` for ``suite``; write suite.json atomically."""
    from femoat.atomic import write_text

    out = Path(out)
    meta_path = out / "suite.json"
    if meta_path.is_file():
        old = json.loads(meta_path.read_text(encoding="utf-8")).get("suite_hash")
        if old != suite.hash:
            if not overwrite:
                raise ValueError(
                    f"{out} holds the results of another suite (hash {old}; this one is "
                    f"{suite.hash}: the definition, its records or femoat changed). Use --out "
                    "with a new folder, or --overwrite to delete the old results.")
            for sub in ("runs", "histories"):
                shutil.rmtree(out / sub, ignore_errors=True)
    elif (out / "runs").is_dir() and any((out / "runs").iterdir()) and not overwrite:
        raise ValueError(f"{out}/runs holds files but no suite.json; use another --out or "
                         "--overwrite.")
    write_text(meta_path, json.dumps(suite.metadata(), indent=1, default=str) + "\n")


def pending(suite, out):
    """The work left: ``(tasks, units)``, the tasks a list of :class:`~femoat.suite.runs.Batch`
    or of :class:`~femoat.suite.runs.Trace`, the units the runs (traces) they hold."""
    stored = tb.stored_runs(out, () if suite.scaling.hunt is None else suite.walls)
    if suite.scaling.hunt is None:
        todo = [s for s in rn.plan(suite) if s.run_id not in stored]
        size = suite.batch_size or default_batch_size(len(todo))
        return [rn.Batch(tuple(todo[i:i + size])) for i in range(0, len(todo), size)], len(todo)
    by_trace = {}
    for rid, run in stored.items():
        by_trace.setdefault((run.record, run.variation), {})[rid] = Outcome(not run.survived,
                                                                            run.hits)
    tasks = []
    for r, v in rn.traces(suite):
        mine = by_trace.get(rn.trace_key(suite, r, v), {})
        if not _trace_complete(suite, r, v, mine):
            tasks.append(rn.Trace(r, v, mine))
    return tasks, len(tasks)


def _trace_complete(suite, r, v, stored):
    def oracle(im):
        rid = rn.run_id(suite, r, v, im)
        if rid not in stored:
            raise _Incomplete
        return stored[rid]

    try:
        hunt_fill(oracle, **rn.hunt_settings(suite))
    except _Incomplete:
        return False
    return True


def default_batch_size(n_runs, workers=2):
    """At most 48 runs per task (0.4-1 s: a run takes 8-20 ms, less when it stops at collapse),
    and at least 4 tasks per worker."""
    return max(1, min(48, math.ceil(n_runs / (4 * workers))))


def run_suite(suite, out, workers=None, scheduler=None, scheduler_file=None, serial=False,
              overwrite=False, stream=None):
    """Run what is left of ``suite`` into ``out``; return a summary dict.

    workers : int or None  local worker processes (default: one per core), single-threaded
    scheduler / scheduler_file : address or file of an existing Dask scheduler
    serial : bool  run in this process (no Dask)
    """
    stream = stream or sys.stderr
    out = Path(out)
    prepare(suite, out, overwrite)
    tasks, total = pending(suite, out)
    unit = "runs" if suite.scaling.hunt is None else "traces"
    bearings = select_kinds(suite)
    summary = dict(out=str(out), suite_hash=suite.hash, todo=total, unit=unit, runs=0,
                   collapses=0, failures=0, failed_tasks=0, kernels=_kernels(stream),
                   bearings=list(bearings))
    if not tasks:
        stream.write(f"femoat suite: nothing to do, every run is stored in {out}\n")
        return summary
    progress = Progress(total, unit, stream)
    try:
        if serial:
            for task in tasks:
                _finish(suite, out, task, task.run(suite, out), progress)
        else:
            _on_dask(suite, out, tasks, progress, summary, workers, scheduler, scheduler_file,
                     bearings)
    finally:
        progress.close()
    elapsed = time.perf_counter() - progress.start
    summary.update(runs=progress.runs, collapses=progress.collapses, failures=progress.failures,
                   elapsed=elapsed, runs_per_second=progress.runs / elapsed if elapsed else 0.0)
    return summary


def select_kinds(suite):
    """Compile this process's loop for the bearing kinds ``suite``'s models need
    (:mod:`femoat.startup.bearing_kinds`: the pendulum alone, or every kind); returns their
    scenario keys, which the workers choose too."""
    from femoat.startup.bearing_kinds import select_for

    return select_for(rn.models(suite))


def _kernels(stream):
    """Compile the solver's kernels into numba's cache (or load them) in the client, before any
    worker starts; say so when it is the first time."""
    from femoat.startup.warmup import warm_up

    cpu = warm_up()
    if cpu > 10.0:
        stream.write(f"femoat suite: compiled the solver's kernels in {cpu:.0f} s of CPU (once "
                     "per install: later processes and every worker load them from numba's "
                     "cache)\n")
    return "jit"


def _load_kernels(bearings):
    """In a worker: load (or compile) the solver's kernels for the bearing kinds ``bearings``
    (the client's choice); return how many signatures this process compiled itself rather than
    loading them from numba's cache."""
    from femoat.bearings import registry
    from femoat.compilation.exports import EXPORTS
    from femoat.startup.warmup import warm_up
    from femoat.integration.solve import kernels

    registry.select(bearings)
    warm_up()
    k = kernels()
    return sum(sum(getattr(k, name).dispatcher.stats.cache_misses.values()) for name in EXPORTS)


def _finish(suite, out, task, rows, progress):
    if rows:
        tb.write_part(rows, suite, out)
    progress.update(rows, units=task.units)


LOCAL_WORKER_CONFIG = {
    # our own local workers go without Dask's statistical profiler (it samples every thread's
    # stack every 10 ms, holding the GIL, beside runs of a few ms), and with a slower event-loop
    # tick (20 ms: a blocked-loop check) and memory monitor (100 ms): on a small machine the
    # workers' background threads otherwise take CPU from the runs
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.memory.monitor-interval": "1s",
}


def _ignore_sigint():
    import signal
    import threading

    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)


def _ignore_sigint_plugin():
    """A worker plugin: Ctrl-C on the terminal reaches every process of its group; the local
    workers ignore it (the client stops them), so it prints no worker tracebacks."""
    from distributed.diagnostics.plugin import WorkerPlugin

    class IgnoreSigint(WorkerPlugin):
        name = "femoat-ignore-sigint"

        def setup(self, worker):
            _ignore_sigint()

    return IgnoreSigint()


@contextlib.contextmanager
def _sigint_ignored():
    """SIGINT ignored while local workers start: a spawned process inherits the ignored signal
    (Python keeps SIGINT ignored when its parent ignored it), so Ctrl-C then stops only us."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)


@contextlib.contextmanager
def local_cluster(workers=None):
    """A local Dask cluster of ``workers`` single-threaded worker processes (default: one per
    core), started once for one suite or several in a row (a study's suites share it, and so
    its start and its workers' loaded kernels): yields the scheduler's address for
    :func:`run_suite`'s ``scheduler``; closed on exit."""
    import logging
    import os

    import dask
    from dask.distributed import Client, LocalCluster

    n = workers or os.cpu_count() or 1
    # (workers' own log lines at shutdown, e.g. a heartbeat to a scheduler already gone, are
    # noise: a failing run reaches us through its future)
    with dask.config.set(LOCAL_WORKER_CONFIG), _sigint_ignored():
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.CRITICAL)
    try:
        with Client(cluster) as client:
            client.register_plugin(_ignore_sigint_plugin())  # and a worker restarted later
        yield cluster.scheduler_address
    finally:
        cluster.close()


def _on_dask(suite, out, tasks, progress, summary, workers, scheduler, scheduler_file, bearings):
    with contextlib.ExitStack() as stack:
        if not (scheduler or scheduler_file):
            scheduler = stack.enter_context(local_cluster(workers))
        _on_client(suite, out, tasks, progress, summary, scheduler, scheduler_file, bearings)


def _on_client(suite, out, tasks, progress, summary, scheduler, scheduler_file, bearings):
    from dask.distributed import Client, as_completed

    if scheduler:
        client = Client(scheduler)
    else:
        client = Client(scheduler_file=str(scheduler_file))
    futures = {}
    try:
        # per worker: the kernels loaded (from the cache the client just wrote) and how many
        # signatures it had to compile itself (0 when the cache served it)
        summary["worker_compiles"] = sorted(client.run(_load_kernels, bearings).values())
        shared = client.scatter(suite, broadcast=True)
        client.run(rn.warm, suite)  # per worker: models built, record set loaded, once
        progress.restart()
        absolute = str(Path(out).resolve())

        def submit(task):
            f = client.submit(task.run, shared, absolute, pure=False)
            futures[f] = task
            return f

        pending_futures = as_completed([submit(task) for task in tasks])
        for f in pending_futures:
            task = futures.pop(f)  # dropping the future frees its result on the cluster
            try:
                rows = f.result()
            except Exception as exc:  # noqa: BLE001 - e.g. a run that kills its worker
                if isinstance(task, rn.Batch) and len(task.specs) > 1:
                    # run the batch's runs one by one, so that only the culprit is lost
                    for s in task.specs:
                        pending_futures.add(submit(rn.Batch((s,))))
                    continue
                if isinstance(task, rn.Batch):
                    rows = [rn.failed_row(suite, task.specs[0], exc)]
                else:
                    summary["failed_tasks"] += 1
                    progress.stream.write(f"\nfemoat suite: a hunt-and-fill trace failed "
                                          f"({type(exc).__name__}: {exc}); its runs are not "
                                          "stored: rerun to retry it\n")
                    continue
            _finish(suite, out, task, rows, progress)
    except KeyboardInterrupt:
        _quiet_distributed()
        raise
    finally:
        for f in futures:
            f.cancel()
        client.close()


def _quiet_distributed():
    """Silence every ``distributed`` logger of this process (a local cluster's scheduler runs
    here): on Ctrl-C the futures are cancelled while the workers die with the same signal, and
    the scheduler logs each cancel it can no longer send as CRITICAL, with a traceback (seen on
    a loaded machine); the CLI's one line says what happened."""
    import logging

    names = ["distributed"] + [n for n in logging.root.manager.loggerDict
                               if n.startswith("distributed.")]
    for name in names:
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)
