"""Sweeps: scenes × seeds × simulation sets × formulations × option sets, run on Dask
(docs/SWEEPS.md).

    python3 -m dynslam.sweep SWEEP.toml --out DIR [--scheduler tcp://HOST:PORT] [--workers N]
    python3 -m dynslam.sweep report DIR

Without --scheduler the cells run on a local Dask cluster of one single-threaded worker per core
this process may use. DIR/results.sqlite holds one row per cell and survives anything: running
the same command again runs only the cells not finished. Exit codes: 0 every cell finished, 1
some failed, 2 a bad sweep file or usage, 130 interrupted.
"""
import argparse
import fcntl
import heapq
import itertools
import os
import signal
import sys
import time

from dask.distributed import Client, LocalCluster, as_completed

from . import _sweep_cells, _sweep_report, _sweep_sensitivity, _sweep_spec, _sweep_tools
from ._sweep_results import Results

EXIT_OK, EXIT_FAILED, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130


class Progress:
    """A bar (cells done / total, failures, ETA) on a terminal; a line per cell otherwise."""

    def __init__(self, total, done, stream=sys.stderr):
        self.total, self.done, self.failed = total, done, 0
        self.stream, self.tty = stream, stream.isatty()
        self.started, self.done_at_start = time.monotonic(), done

    def _eta(self):
        finished_here = self.done - self.done_at_start
        if finished_here == 0:
            return "?"
        seconds = (time.monotonic() - self.started) / finished_here * (self.total - self.done)
        return f"{seconds / 60:.1f} min" if seconds >= 60 else f"{seconds:.0f} s"

    def update(self, row):
        self.done += 1
        self.failed += row["status"] != "ok"
        if self.tty:
            filled = int(30 * self.done / max(self.total, 1))
            self.stream.write(f"\r[{'#' * filled}{' ' * (30 - filled)}] {self.done}/{self.total} "
                              f"cells, {self.failed} failed, ETA {self._eta()}   ")
            if self.done == self.total:
                self.stream.write("\n")
        else:
            what = (f"{row.get('steps')} steps, final cost {row.get('final_cost')}"
                    if row["status"] == "ok" else row.get("error") or row.get("termination"))
            simulate = "" if row["simulate"] == "default" else f" ({row['simulate']})"
            self.stream.write(f"cell {self.done}/{self.total}: {row['scene']}{simulate} seed "
                              f"{row['seed']} {row['formulation']} [{row['options']}]: "
                              f"{row['status']}, {what}\n")
        self.stream.flush()


def _failed_row(cell, error):
    return cell.row(status="failed", error=str(error))


def _client(scheduler, workers):
    if scheduler:
        return Client(scheduler), None
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    return Client(cluster), cluster


def _unique_key(*parts):
    return "-".join(str(p) for p in parts) + f"-{time.time_ns()}"


def _simulate(client, sweep, out, cell):
    """The front end of `cell`'s scene, seed and simulation set."""
    return client.submit(_sweep_cells.simulate, os.path.join(out, cell.scene_dir), cell.scene,
                         cell.seed, sweep.frames, sweep.density, sweep.kitti,
                         sweep.simulate[cell.simulate], pure=False,
                         key=_unique_key("simulate", cell.scene, f"s{cell.seed}", cell.simulate))


def _submit_cell(client, sweep, out, frontend, cell):
    """One cell as an independent task: the files `frontend` names are on the shared DIR, so no
    task depends on another (Dask 2022.12's scheduler could stall when a worker holding a
    dependency died)."""
    return client.submit(_sweep_cells.run_cell, frontend, out, cell, sweep.options[cell.options],
                         pure=False, key=_unique_key("cell", cell.scene, f"s{cell.seed}",
                                                     cell.formulation, cell.options))


class LargestFirst:
    """The cells waiting for a worker, the cells of the largest front-end file first (ties in the
    order they were added): the longest solves start first, so the end of a sweep does not leave
    workers idle behind one long cell (docs/SWEEPS.md)."""

    def __init__(self):
        self._heap, self._added = [], itertools.count()

    def add(self, frontend, cells):
        size = os.path.getsize(frontend[0])
        for cell in cells:
            heapq.heappush(self._heap, (-size, next(self._added), frontend, cell))

    def __len__(self):
        return len(self._heap)

    def pop(self):
        """(frontend, cell) of the largest waiting cell."""
        _, _, frontend, cell = heapq.heappop(self._heap)
        return frontend, cell


def _worker_threads(client):
    return max(1, sum(client.nthreads().values()))


def _run_cells(client, sweep, out, cells, results, progress):
    """Every simulation first (one task per scene, seed and simulation set), then the cells,
    largest first and no more at a time than the cluster has worker threads: the order is the
    client's, since Dask sends a task to a worker as soon as it is submitted. Records every
    cell."""
    by_scene = {}
    for cell in cells:
        by_scene.setdefault((cell.scene, cell.seed, cell.simulate), []).append(cell)
    simulations = {_simulate(client, sweep, out, scene_cells[0]): key
                   for key, scene_cells in by_scene.items()}
    waiting, running, simulating = LargestFirst(), {}, len(simulations)
    pending = as_completed(list(simulations))
    for future in pending:
        if future in simulations:
            simulating -= 1
            scene_cells = by_scene[simulations[future]]
            try:
                waiting.add(future.result(), scene_cells)
            except Exception as error:  # the simulate failed (its message) or its worker died
                for cell in scene_cells:
                    _record(results, progress, _failed_row(cell, error))
        else:
            cell = running.pop(future)
            try:
                row = future.result()
            except Exception as error:  # a worker lost more often than Dask allows
                row = _failed_row(cell, error)
            _record(results, progress, row)
        if simulating == 0:
            threads = _worker_threads(client)  # a call to the scheduler: once per event
            while waiting and len(running) < threads:
                frontend, cell = waiting.pop()
                submitted = _submit_cell(client, sweep, out, frontend, cell)
                running[submitted] = cell
                pending.add(submitted)


def _record(results, progress, row):
    results.record(row)
    progress.update(row)


def _lock(out):
    """DIR/sweep.lock, held while a sweep runs in DIR; None when another process holds it."""
    lock = open(os.path.join(out, "sweep.lock"), "a+")
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        lock.close()
        return None
    return lock


def run(sweep, out, scheduler=None, workers=None):
    """Runs the cells of `sweep` not yet finished in `out`; returns an exit code."""
    os.makedirs(out, exist_ok=True)
    lock = _lock(out)  # released when this process ends
    if lock is None:
        print(f"error: {out} is in use by another sweep (its sweep.lock is held)", file=sys.stderr)
        return EXIT_USAGE
    if len(sweep.simulate) > 1:
        _sweep_sensitivity.write_settings(out, sweep.simulate_settings,
                                          _sweep_tools.simulate_defaults(_sweep_tools.find_cli()))
    results = Results(os.path.join(out, "results.sqlite"))
    finished = results.finished()
    cells = [c for c in sweep.cells()
             if c.key not in finished]
    total = len(sweep.cells())
    print(f"sweep {sweep.path}: {total} cells, {total - len(cells)} finished before, "
          f"{len(cells)} to run", file=sys.stderr)
    interrupted = False
    if cells:
        workers = workers or len(os.sched_getaffinity(0))
        client, cluster = _client(scheduler, workers)
        progress = Progress(total, total - len(cells))
        try:
            _run_cells(client, sweep, out, cells, results, progress)
        except KeyboardInterrupt:
            interrupted = True
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    results.write_csv(os.path.join(out, "results.csv"))
    rows = results.rows()
    keys = {c.key for c in sweep.cells()}
    ok = len(results.finished() & keys)  # of this sweep's cells (DIR may hold others)
    results.close()
    report = _sweep_report.write(out, rows)
    print(f"{ok} of {total} cells finished; results: {out}/results.sqlite, results.csv; "
          f"report: {report}", file=sys.stderr)
    if interrupted:
        print("interrupted: run the same command again to finish the rest", file=sys.stderr)
        return EXIT_INTERRUPTED
    return EXIT_OK if ok == total else EXIT_FAILED


def report(out):
    path = os.path.join(out, "results.sqlite")
    if not os.path.isfile(path):
        print(f"error: {path}: no results database", file=sys.stderr)
        return EXIT_USAGE
    results = Results(path)
    rows = results.rows()
    results.write_csv(os.path.join(out, "results.csv"))
    results.close()
    print(_sweep_report.write(out, rows))
    return EXIT_OK


def _raise_interrupt(signum, frame):
    raise KeyboardInterrupt


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["report"]:
        parser = argparse.ArgumentParser(prog="python3 -m dynslam.sweep report",
                                         description="Writes a finished or partial sweep's report.")
        parser.add_argument("dir", metavar="DIR")
        return report(parser.parse_args(argv[1:]).dir)
    parser = argparse.ArgumentParser(prog="python3 -m dynslam.sweep",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("sweep_file", metavar="SWEEP.toml")
    parser.add_argument("--out", required=True, metavar="DIR")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="a running Dask scheduler, e.g. tcp://10.0.0.1:8786 (default: a "
                             "local cluster)")
    parser.add_argument("--workers", type=int, metavar="N",
                        help="local cluster's workers (default: the cores this process may use)")
    parser.add_argument("--kitti", metavar="DIR", help="KITTI Tracking data (default: embedded)")
    args = parser.parse_args(argv)
    if args.workers is not None and args.workers < 1:
        parser.error("--workers must be at least 1")
    try:
        sweep = _sweep_spec.load(args.sweep_file, kitti=args.kitti)
    except (_sweep_spec.SweepFileError, _sweep_tools.ToolNotFound) as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_USAGE
    signal.signal(signal.SIGTERM, _raise_interrupt)
    return run(sweep, os.path.abspath(args.out), args.scheduler, args.workers)


if __name__ == "__main__":
    sys.exit(main())
