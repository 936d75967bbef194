"""Soar-SLAM sweeps on Ray: ``rusoar slam``'s runs as Ray tasks, one task per run.

``python -m rusoar.sweep [rusoar slam options...] [--address ADDR]`` plans the runs
``rusoar slam`` with the same options would make (the same seeds, conditions and methods),
carries each one out in a Ray task, and writes what ``rusoar slam`` writes, from the same
code: each run's files as its result comes back, then ``summary.md``, ``report.md``,
``comparison.md`` and the figures. Only the wall-clock figures of the reports differ.

``--world``, ``--noise`` and ``--rules`` take comma-separated lists; the sweep crosses them.
Each combination is one experiment in its own subfolder of ``--out`` (named after the
values that vary, e.g. ``box-room-realistic``), holding the files ``rusoar slam --out SUB``
with those values would write. All the runs of all the combinations go to Ray at once.

Ray is started on this machine (``ray.init()``) unless ``--address`` names a cluster
(``--address auto`` joins the one this machine belongs to). The rule folders must be at the
same path on every machine, and rusoar installed on each; world files are read here.

Ray is an optional dependency: ``pip install "rusoar[ray]"`` (or ``pip install ray``).
"""

import itertools
import os
import sys
from collections import namedtuple

from rusoar._rusoar import (
    SlamAssembly,
    SlamError,
    SlamUsageError,
    slam_main,
    slam_plan,
    slam_run,
)

__all__ = [
    "Experiment",
    "SlamError",
    "SlamUsageError",
    "SweepError",
    "RayUnavailable",
    "experiments",
    "main",
    "plan",
    "run",
    "slam",
    "sweep",
    "write_report",
]

Experiment = namedtuple("Experiment", "args out text status")
Experiment.__doc__ = """One experiment of a sweep: the ``rusoar slam`` arguments it stands
for, its output folder, what ``rusoar slam`` prints at its end, and its exit status (0, or
1 when a run did not complete)."""

# The options whose comma-separated values the sweep crosses, in the order the subfolder
# names list them.
CROSSED = ("--world", "--noise", "--rules")

HELP = """usage: python -m rusoar.sweep [rusoar slam options...] [--address ADDR] [--num-cpus N]

Runs `rusoar slam`'s runs as Ray tasks, one task per run, and writes the same files.

Sweep options:
  --address ADDR   a Ray cluster to use (`auto`: the one this machine belongs to);
                   default: start Ray on this machine
  --num-cpus N     CPUs of the Ray started on this machine (default: all)
  --world A,B,...  --noise X,Y,...  --rules DIR1,DIR2,...
                   cross these: one experiment per combination, each in its own
                   subfolder of --out
  (--jobs is rusoar slam's number of threads: a sweep runs as many tasks at once
  as Ray has CPUs.)

The options of `rusoar slam`:
"""

INSTALL_RAY = (
    "rusoar.sweep runs on Ray, which is not installed: "
    'pip install "rusoar[ray]" (or: pip install ray)'
)


class SweepError(ValueError):
    """Sweep options that cannot be used (an empty list, two values naming one folder)."""


class RayUnavailable(RuntimeError):
    """Ray could not be started here, or the cluster at ``--address`` could not be joined."""


def plan(args):
    """The runs of ``rusoar slam ARGS``: one dict per run, with its ``seed``, condition
    (``slam``: 'on' or 'off'), output folder (``out``) and description (``spec``, bytes)."""
    return slam_plan(list(args))


def run(spec):
    """Carries out one run of ``plan``; returns its result (bytes)."""
    return slam_run(spec)


def write_report(args, results, jobs=1):
    """Writes the files of ``rusoar slam ARGS`` from the results of all its runs (in any
    order); returns an ``Experiment``. ``jobs`` is the number of runs carried out at once
    that the reports state."""
    assembly = SlamAssembly(list(args))
    for result in results:
        assembly.add(result)
    text, status = assembly.finish(jobs)
    return Experiment(list(args), _out_of(args), text, status)


def slam(args):
    """``rusoar slam ARGS`` itself, in this process on its own threads (no Ray): returns its
    exit status; it prints to the process's standard output and error."""
    return slam_main(list(args))


def _option(token, name):
    """The value of ``--name=VALUE``, True for a bare ``--name``, or None."""
    if token == name:
        return True
    if token.startswith(name + "="):
        return token[len(name) + 1:]
    return None


def _split(argv, names):
    """Takes the first occurrence of each option of ``names`` out of ``argv``: returns the
    remaining tokens (with a placeholder index where each taken option stood) and
    ``{name: (place, value)}``. An option without a value is left for ``rusoar slam`` to
    report."""
    rest, found = [], {}
    i = 0
    while i < len(argv):
        token = argv[i]
        for name in names:
            value = _option(token, name)
            if value is None or name in found:
                continue
            if value is True:
                if i + 1 >= len(argv):
                    break
                value = argv[i + 1]
                i += 1
            found[name] = (len(rest), value)
            rest.append(None)
            break
        else:
            rest.append(token)
        i += 1
    return rest, found


def _label(name, value):
    """A value's part of a subfolder name: a world file's stem, a rule folder's name."""
    if name == "--noise":
        return value
    base = os.path.basename(os.path.normpath(value))
    return os.path.splitext(base)[0] if name == "--world" else base


def _out_of(args):
    """The ``--out`` of ``rusoar slam ARGS`` (its default when not given)."""
    _, found = _split(list(args), ("--out",))
    return found["--out"][1] if "--out" in found else "slam-out"


def experiments(args):
    """The ``rusoar slam`` argument lists of a sweep: ``args`` with each combination of the
    comma-separated values of ``--world``, ``--noise`` and ``--rules`` in their place, and
    ``--out`` pointing to the combination's subfolder. Without lists, ``args`` unchanged."""
    args = list(args)
    rest, found = _split(args, CROSSED + ("--out",))
    axes = []
    for name in CROSSED:
        if name not in found:
            continue
        values = found[name][1].split(",")
        if any(not v.strip() for v in values):
            raise SweepError("%s %s: an empty value in the list" % (name, found[name][1]))
        axes.append((name, [v.strip() for v in values]))
    combos = list(itertools.product(*[values for _, values in axes]))
    if len(combos) == 1:
        return [args]
    out = found["--out"][1] if "--out" in found else "slam-out"
    folders = {}
    lists = []
    for combo in combos:
        varying = [
            _label(name, v) for (name, values), v in zip(axes, combo) if len(values) > 1
        ]
        folder = "-".join(varying)
        if folder in folders:
            raise SweepError(
                "two combinations (%s and %s) would share the folder %s"
                % (folders[folder], ", ".join(combo), folder)
            )
        folders[folder] = ", ".join(combo)
        argv = list(rest)
        for (name, _), v in zip(axes, combo):
            argv[found[name][0]] = (name, v)
        sub = os.path.join(out, folder)
        if "--out" in found:
            argv[found["--out"][0]] = ("--out", sub)
        else:
            argv.append(("--out", sub))
        lists.append([t for slot in argv if slot is not None
                      for t in (slot if isinstance(slot, tuple) else (slot,))])
    return lists


def _import_ray():
    try:
        import ray
    except ImportError:
        raise ImportError(INSTALL_RAY) from None
    return ray


def _run_task(spec):
    return slam_run(spec)


def sweep(args=(), address=None, num_cpus=None, progress=True):
    """Runs the sweep of ``rusoar slam ARGS`` (see ``experiments``) on Ray, one task per run;
    returns an ``Experiment`` per combination. Uses the Ray this process is connected to,
    or else starts one (``ray.init(address=address, num_cpus=num_cpus)``) and shuts it down
    at the end. Raises ``SlamUsageError`` for options ``rusoar slam`` does not take,
    ``SweepError`` for lists that cannot be crossed, ``RayUnavailable`` when Ray cannot be
    started or joined, ``SlamError`` for an experiment that could not be written."""
    ray = _import_ray()
    lists = experiments(args)
    # Every combination is planned before Ray starts, so that bad options fail at once.
    for argv in lists:
        slam_plan(argv)
    started = not ray.is_initialized()
    if started:
        try:
            ray.init(address=address, num_cpus=num_cpus, include_dashboard=False,
                     log_to_driver=False)
        except Exception as e:
            # Ray's own exceptions vary with the way it failed (no cluster at the address,
            # a version mismatch, options a cluster does not take); all mean no Ray to use.
            raise RayUnavailable("cannot %s: %s" % (
                "start Ray on this machine" if address is None else "join Ray at " + address,
                e)) from e
    try:
        task = ray.remote(num_cpus=1)(_run_task)
        assemblies = [SlamAssembly(argv) for argv in lists]
        pending = {}
        # Where each run's files go, for the progress lines: the experiment's folder when
        # there are several, and a comparison's method folder (thesis, v2, oracle).
        places = []
        for k, (argv, assembly) in enumerate(zip(lists, assemblies)):
            out = _out_of(argv)
            places.append({})
            for r in assembly.runs():
                pending[task.remote(r["spec"])] = k
                place = os.path.relpath(str(r["out"]), out) if len(lists) == 1 else str(r["out"])
                places[k][r["index"]] = "" if place == "." else place + " "
        total = len(pending)
        jobs = max(1, int(ray.cluster_resources().get("CPU", 1)))
        if progress:
            print("rusoar.sweep: %d experiment(s), %d run(s) as Ray tasks on %d CPU(s)"
                  % (len(assemblies), total, jobs), file=sys.stderr)
        refs = list(pending)
        done = 0
        while refs:
            ready, refs = ray.wait(refs, num_returns=1)
            for ref in ready:
                k = pending.pop(ref)
                try:
                    result = ray.get(ref)
                except ray.exceptions.RayError as e:
                    # A worker that died, or a machine of the cluster lost, after Ray's
                    # retries.
                    raise SlamError("a run's Ray task failed: %s" % e) from e
                info = assemblies[k].add(result)
                done += 1
                if progress:
                    outcome = "" if info["outcome"] == "completed" else " — " + info["outcome"]
                    print("[%*d/%d] %sseed %d SLAM %s: %.2f s wall; final error %.0f mm%s"
                          % (len(str(total)), done, total, places[k][info["index"]],
                             info["seed"], info["slam"], info["wall_time_s"], info["final_mm"],
                             outcome),
                          file=sys.stderr)
        results = []
        for argv, assembly in zip(lists, assemblies):
            text, status = assembly.finish(jobs)
            results.append(Experiment(argv, _out_of(argv), text, status))
        return results
    finally:
        if started:
            ray.shutdown()


def main(argv=None):
    """``python -m rusoar.sweep``: returns the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if "-h" in argv or "--help" in argv:
        try:
            slam_plan(["--help"])
        except SlamUsageError as e:
            print(HELP + e.message.rstrip())
        return 0
    rest, found = _split(argv, ("--address", "--num-cpus"))
    rest = [t for t in rest if t is not None]
    address = found["--address"][1] if "--address" in found else None
    num_cpus = None
    if "--num-cpus" in found:
        try:
            num_cpus = int(found["--num-cpus"][1])
            if num_cpus < 1:
                raise ValueError
        except ValueError:
            print("error: --num-cpus takes a positive whole number, not %r"
                  % found["--num-cpus"][1], file=sys.stderr)
            return 2
    try:
        _import_ray()
    except ImportError as e:
        print("error: %s" % e, file=sys.stderr)
        return 1
    try:
        results = sweep(rest, address=address, num_cpus=num_cpus)
    except SlamUsageError as e:
        print(e.message.rstrip(), file=sys.stderr)
        return e.status
    except SweepError as e:
        print("error: %s" % e, file=sys.stderr)
        return 2
    except (SlamError, RayUnavailable) as e:
        print("error: %s" % e, file=sys.stderr)
        return 1
    for r in results:
        sys.stdout.write(r.text)
    return max(r.status for r in results)


if __name__ == "__main__":
    sys.exit(main())
