"""Dask workers for the long runs (a Monte Carlo of 10^9 draws, a sweep of 10^9 sets):
a local cluster of processes by default, with no set-up, or the cluster whose
scheduler is at an address. The work is cut into tasks whose answers do not depend on
where they run, so one worker, two or a cluster give the one-process answer.
"""

from __future__ import annotations

import socket
import sys
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from rigidimpact.errors import InputError

__all__ = ["dask_client", "gathered", "guided", "local_or_here", "REPAYS"]

# The work below which local workers do not repay their start, counted in the work's own
# units (never in seconds: the same command says the same thing on every machine).
# Starting two local workers and feeding them costs about 1 s on a 2-core machine
# (importing Dask here 0.4 to 0.55 s, the cluster with its two workers forked from this
# process 0.2 to 0.5 s, closing it 0.03 s), measured so, each pair in turn: the
# barbell's rebound with 3 x 10^7 draws took 3.3 and 4.5 s in one process against 3.6
# and 4.1 s on two workers, 5 x 10^7 4.4 and 5.6 against 4.3 and 5.3 s, 10^8 5.9 and
# 5.9 against 5.2 and 4.9 s; the compliant cradle's 100 solves 5.9 s against 5.5 s
# twice, 300 solves 14.4 against 11.1 and 11.7 s. A closed form's draws and sets cost
# alike (its fused kernel, 1e7 to 2e7 a second); a solve (a scene with no closed form)
# costs 1e3 to 1e5 times more.
REPAYS = {"draws": 10**8, "sets": 10**8, "solves": 200}


def local_or_here(work: int, kind: str, workers: int | None,
                  scheduler: str | None) -> tuple[int | None, str | None]:
    """The workers to start for `work` units of `kind` (``"draws"``, ``"sets"`` or
    ``"solves"``) and a note to print: where local workers were asked for (`workers`,
    no `scheduler`) for less work than :data:`REPAYS` says repays their start, none
    (the command runs in its own process, with the same numbers) and the note saying
    so; otherwise `workers` unchanged and no note. A `scheduler`'s workers are already
    running: they are always used.

    Examples
    --------
    >>> local_or_here(10**6, "draws", 2, None)[0] is None
    True
    >>> local_or_here(10**9, "draws", 2, None)
    (2, None)
    >>> local_or_here(10, "solves", 2, "tcp://10.0.0.1:8786")  # a running cluster's
    (2, None)
    """
    least = REPAYS[kind]
    if workers is None or scheduler is not None or work >= least:
        return workers, None
    return None, (f"--workers {workers}: {work:,} {kind} are fewer than the {least:,} "
                  "from which local Dask workers are started (starting them costs about "
                  "1 s on a 2-core machine); run in this process instead, with the same "
                  "numbers")


def guided(count: int, workers: int, least: int = 1) -> list[tuple[int, int]]:
    """[start, stop) runs covering range(count) in order, one Dask task each, for
    `workers` workers that take the next run as they free: each run a ``2 * workers``-th
    part of what is left (at least `least`), so the runs shrink as the work ends.

    Equal runs leave a worker idle at the end for up to a run's time whenever the other
    was slowed (by this process deriving beside them, or by the machine): two workers
    drawing the dropped barbell's 10^9 draws in eight equal runs of 3 to 4 s finished
    1.1 s apart. Shrinking runs (guided self-scheduling, Polychronopoulos and Kuck,
    IEEE Trans. Comput. 36, 1987) end within a small run of each other, for a few more
    tasks: 1,000 units on two workers in 22 runs instead of 8.

    Examples
    --------
    Two workers: a quarter of what is left each time, rounded up (20, then 15, 11, 8,
    6, 4, 3, 2 and 1 left).

    >>> guided(20, 2)
    [(0, 5), (5, 9), (9, 12), (12, 14), (14, 16), (16, 17), (17, 18), (18, 19), (19, 20)]
    >>> guided(20, 2, least=3)
    [(0, 5), (5, 9), (9, 12), (12, 15), (15, 18), (18, 20)]
    >>> len(guided(1000, 2)), guided(0, 2)
    (22, [])
    """
    runs, start, parts = [], 0, 2 * max(1, workers)
    while start < count:
        stop = min(count, start + max(least, -(-(count - start) // parts)))
        runs.append((start, stop))
        start = stop
    return runs


# the Dask settings that say how a local cluster starts its worker processes, and
# whether a worker samples its own stack for the dashboard's profile
METHOD = "distributed.worker.multiprocessing-method"
PROFILE = "distributed.worker.profile.enabled"
# How often a local cluster's processes look at themselves, where Dask's defaults (every
# 20 ms, 100 ms and 500 ms) serve a dashboard and a watch for memory that a command's
# few minutes of draws or solves do not need: each event loop measures its own delay
# (to warn past 3 s), each worker's memory is read, and each process's CPU and memory
# recorded for the dashboard. A cluster of two workers left idle for 10 s used 0.51 to
# 0.62 s of this process's CPU and 0.43 to 0.48 s of its two workers' so, and 0.09 to
# 0.11 and 0.06 to 0.07 s with these (five pairs in turn): about 0.9 s of CPU each 10 s
# that the draws and solves no longer share their two cores with.
QUIET = {"distributed.admin.tick.interval": "1s",
         "distributed.worker.memory.monitor-interval": "1s",
         "distributed.admin.system-monitor.interval": "2s"}


@contextmanager
def dask_client(workers: int | None = None, scheduler: str | None = None,
                processes: bool = True) -> Iterator[Any]:
    """A ``dask.distributed.Client``: with no `scheduler` on a local cluster of
    `workers` (default: one a core; processes, or threads with `processes` False),
    started here and closed after; with one (``tcp://host:8786``) on its cluster."""
    try:
        import dask
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise InputError("--workers", "Dask is not installed: pip install "
                         "'rigidimpact[dask]'") from None
    cluster = None
    if scheduler is None:
        # Dask starts its workers with MALLOC_TRIM_THRESHOLD_ set, which turns off
        # glibc's adaptive mmap threshold: every large NumPy temporary (a chunk of 10^6
        # draws is 8 MB) is then mapped afresh and its pages zeroed by the system. A
        # chunk of the barbell's Monte Carlo took 0.043 to 0.049 s on such a worker and
        # 0.030 to 0.036 s without it, as in one process.
        settings: dict[str, Any] = {"distributed.nanny.pre-spawn-environ."
                                    "MALLOC_TRIM_THRESHOLD_": None}
        forked = processes and _fork_here(dask)
        if forked:
            settings[METHOD] = "fork"
        if _users(dask, PROFILE) is None:
            # Dask's statistical profiler samples each worker's stack every 10 ms for a
            # dashboard that is not started here: on the compliant cradle it took 0.3 s
            # of a worker's CPU over 8 s of solves, beside them, with nobody to read it
            settings[PROFILE] = False
        settings.update({k: v for k, v in QUIET.items() if _users(dask, k) is None})
        with dask.config.set(settings), warnings.catch_warnings():
            if forked:
                # Python 3.12 and later warn at any fork of a process with threads
                # (Dask's event loop runs in one); the fork is chosen here, knowingly
                warnings.filterwarnings("ignore", r"This process .* is multi-threaded",
                                        DeprecationWarning)
            # no dashboard; the scheduler's own HTTP endpoint (health, metrics) on a free
            # port of this machine only, not on 8787 of every interface, where a second
            # run at the same time would collide
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1,
                                   processes=processes, dashboard_address=None,
                                   scheduler_kwargs={"dashboard_address": "127.0.0.1:0"})
        client = Client(cluster)
    else:
        _reachable(scheduler)
        try:
            client = Client(scheduler, timeout=10)
        except MemoryError:  # a length read from the first bytes of what answered
            raise InputError("--scheduler", f"no Dask scheduler at {scheduler}: what "
                             "answers there does not speak Dask's protocol") from None
        except (OSError, ValueError, TypeError) as exc:  # ValueError: not an address
            reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            raise InputError("--scheduler", f"no Dask scheduler at {scheduler}: "
                             f"{reason}") from None
    try:
        yield client
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
            _stop_resource_tracker()


def gathered(client: Any, futures: list[Any],
             progress: Callable[[int, int], None] | None = None) -> tuple[list[Any], int]:
    """The results of `futures`, in their order, and how many of `client`'s workers
    computed them; `progress(done, total)` is told as each task ends.

    The progress is followed here, by the client's own callbacks as each future ends,
    not by Dask's progress bar: that bar (besides writing on the standard output) asks
    the scheduler for a coroutine that sends it the state every 100 ms and learns that
    the bar has stopped listening only at its next send, so a cluster closed within
    those 100 ms cancels it asleep, and the scheduler logged the ``CancelledError``
    with its traceback after the answer (``derive --workers 2`` at every run here).

    Examples
    --------
    >>> told = []
    >>> with dask_client(1, processes=False) as client:
    ...     gathered(client, [client.submit(pow, 2, k) for k in range(3)],
    ...              lambda done, total: told.append(done))
    ([1, 2, 4], 1)
    >>> told
    [0, 1, 2, 3]
    """
    from dask.distributed import as_completed

    if progress is not None:
        progress(0, len(futures))
        for done, _ in enumerate(as_completed(futures), 1):
            progress(done, len(futures))
    results = client.gather(futures)
    # each result is held by the worker that computed it until it is released
    holders = client.who_has(futures)
    return results, len({worker for held in holders.values() for worker in held})


def _fork_here(dask: Any) -> bool:
    """Whether local workers are forked from this process rather than spawned afresh
    (Dask's default): on Linux, unless the user's own Dask configuration (its files or
    a ``DASK_DISTRIBUTED__WORKER__MULTIPROCESSING_METHOD`` variable) names a method.
    A forked worker starts with what this process has imported (NumPy, SciPy, SymPy,
    the package): two workers were up in 0.2 to 0.5 s against 1.1 to 1.3 s spawned, and
    closed in 0.03 s against 0.3 s, and the compliant cradle's 1,000 solves on two
    workers took 22 to 25 s forked against 28 s spawned (40 to 42 s in one process), a
    spawned worker importing SciPy and the package before its first solve. Elsewhere
    Dask's default stands: macOS does not fork safely a process that has threads, and
    Windows cannot fork."""
    return sys.platform == "linux" and _users(dask, METHOD) is None


def _users(dask: Any, key: str) -> Any:
    """What the user's own Dask configuration (its files, its ``DASK_*`` variables)
    says of `key`, or None where it says nothing (Dask's defaults left aside)."""
    return dask.config.get(key, default=None, config=dask.config.collect(dask.config.paths))


def _reachable(scheduler: str) -> None:
    """Say at once that nothing listens at a ``tcp://host:port`` `scheduler` (the
    connection refused), where Dask's client would try again for its whole timeout
    (10 s), and after 10 s that it does not answer (not 10 s more in the client); other
    addresses, and hosts that cannot be reached at all, are left to the client."""
    host, colon, port = scheduler.removeprefix("tcp://").rpartition(":")
    if not scheduler.startswith("tcp://") or not colon or not port.isdigit():
        return
    if not 1 <= int(port) <= 65535:
        raise InputError("--scheduler", f"no Dask scheduler at {scheduler}: a port lies "
                         "between 1 and 65535")
    try:
        socket.create_connection((host.strip("[]"), int(port)), timeout=10).close()
    except ConnectionRefusedError:
        raise InputError("--scheduler", f"no Dask scheduler at {scheduler}: the "
                         "connection was refused") from None
    except TimeoutError:  # said here: the client would wait its own 10 s again
        raise InputError("--scheduler", f"no Dask scheduler at {scheduler}: no answer "
                         "within 10 s") from None
    except OSError:  # no such host, no route: the client says so in its own words
        return


def _stop_resource_tracker() -> None:
    """Wait here for the process that multiprocessing started beside the workers (its
    resource tracker), so nothing the command started outlives it: left alone it exits
    only after the command has, an orphan until the system reaps it."""
    from multiprocessing import resource_tracker

    stop = getattr(resource_tracker._resource_tracker, "_stop", None)
    if stop is not None:
        stop()
