"""The Soar-SLAM sweep on a local Ray with 2 CPUs: its files must be the files `rusoar slam`
writes for the same runs (rusoar.sweep.slam is `rusoar slam` itself, in this process). The
files of a comparison of methods hold no wall-clock time and must be equal byte for byte;
the reports of a single experiment state wall times, which are left out of the comparison
(the wall-time column of runs.csv, the tables' wall-time columns, and the lines giving wall
time), and every other byte must be equal."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from rusoar import sweep as sw

# The rules of this source tree: the installed package may have been built elsewhere.
RULES = str(Path(__file__).resolve().parents[2] / "rules")


@pytest.fixture(scope="module")
def ray():
    try:
        import ray
    except ImportError:
        # CI installs the `ray` extra: there, a missing Ray is a broken install step.
        if os.environ.get("CI"):
            pytest.fail('Ray is not installed: CI installs "./python[ray]"')
        pytest.skip('Ray is not installed (pip install "./python[ray]")')
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield ray
    ray.shutdown()


def files(root):
    return sorted(str(p.relative_to(root)) for p in Path(root).rglob("*") if p.is_file())


def without_wall_time(name, text):
    """`text` of file `name` without its wall-clock figures."""
    if name.endswith("runs.csv"):
        rows = [line.split(",") for line in text.splitlines()]
        column = rows[0].index("wall_time_s")
        return "\n".join(",".join(r[:column] + r[column + 1:]) for r in rows)
    kept = []
    masked = False
    for line in text.splitlines():
        if line.startswith("|"):
            cells = line.split("|")
            if "wall time" in cells[-2].lower():
                masked = True
            elif masked and not set(cells[-2]) <= set("-"):
                line = "|".join(cells[:-2] + [" … ", ""])
        else:
            masked = False
            if re.search(r"wall time|The whole experiment:", line, re.IGNORECASE):
                continue
        kept.append(line)
    return "\n".join(kept)


def assert_same_files(a, b, wall_clock=()):
    assert files(a) == files(b)
    for name in files(a):
        x, y = (Path(root, name).read_bytes() for root in (a, b))
        if name in wall_clock:
            x, y = (without_wall_time(name, t.decode()) for t in (x, y))
        assert x == y, "%s differs" % name


def test_a_comparison_equals_rusoar_slams(ray, tmp_path):
    args = ["--seeds", "2", "--duration", "120", "--method", "dr,thesis,v2,ekf",
            "--rules", RULES, "--io-log"]
    assert sw.slam(args + ["--out", str(tmp_path / "threads")]) == 0
    [exp] = sw.sweep(args + ["--out", str(tmp_path / "ray")], progress=False)
    assert exp.status == 0 and "rules v2" in exp.text
    assert_same_files(tmp_path / "threads", tmp_path / "ray")
    names = files(tmp_path / "ray")
    assert "comparison.md" in names and "thesis/io-on-2.log" in names
    assert "thesis/ekf.md" in names and "v2/steps-on-1.csv" in names


def test_an_experiment_equals_rusoar_slams_but_for_wall_time(ray, tmp_path, monkeypatch):
    # Both write to `out` in a folder of their own, as report.md quotes --out.
    args = ["--seeds", "2", "--duration", "30", "--slam", "both", "--rules", RULES,
            "--out", "out"]
    (tmp_path / "threads").mkdir()
    (tmp_path / "ray").mkdir()
    monkeypatch.chdir(tmp_path / "threads")
    assert sw.slam(args) == 0
    monkeypatch.chdir(tmp_path / "ray")
    [exp] = sw.sweep(args, progress=False)
    assert exp.status == 0 and "position error" in exp.text
    a, b = tmp_path / "threads" / "out", tmp_path / "ray" / "out"
    reports = ("runs.csv", "summary.md", "report.md")
    assert_same_files(a, b, wall_clock=reports)
    # What is left out is only the wall time: the rest of the reports is there.
    summary = without_wall_time("summary.md", (b / "summary.md").read_text())
    assert "Paired comparison" in summary and "at 30 s" in summary
    assert "Wall time" in (b / "summary.md").read_text()


def test_a_sweep_crosses_worlds_and_noise(ray, tmp_path):
    args = ["--seeds", "1", "--duration", "8", "--method", "dr,v2", "--rules", RULES,
            "--world", "empty-room,box-room", "--noise", "ideal,realistic",
            "--out", str(tmp_path / "ray")]
    results = sw.sweep(args, progress=False)
    outs = sorted(os.path.basename(r.out) for r in results)
    assert outs == ["box-room-ideal", "box-room-realistic", "empty-room-ideal",
                    "empty-room-realistic"]
    for r in results:
        assert r.status == 0
        reference = str(tmp_path / "threads" / os.path.basename(r.out))
        argv = [reference if t == r.out else t for t in r.args]
        assert sw.slam(argv) == 0
        assert_same_files(reference, r.out)
    text = (tmp_path / "ray" / "box-room-realistic" / "comparison.md").read_text()
    assert "`box-room` (realistic sonar)" in text


def test_the_crossed_argument_lists():
    lists = sw.experiments(["--seeds", "2", "--world", "a.toml,empty-room",
                            "--rules=r1,x/r2", "--out", "o"])
    assert lists == [
        ["--seeds", "2", "--world", "a.toml", "--rules", "r1", "--out", "o/a-r1"],
        ["--seeds", "2", "--world", "a.toml", "--rules", "x/r2", "--out", "o/a-r2"],
        ["--seeds", "2", "--world", "empty-room", "--rules", "r1", "--out", "o/empty-room-r1"],
        ["--seeds", "2", "--world", "empty-room", "--rules", "x/r2",
         "--out", "o/empty-room-r2"],
    ]
    # One value each: the arguments as given, so the reports quote the same command.
    assert sw.experiments(["--world=box-room", "--seeds", "3"]) == [
        ["--world=box-room", "--seeds", "3"]]
    with pytest.raises(sw.SweepError, match="share the folder"):
        sw.experiments(["--rules", "a/v2,b/v2"])
    with pytest.raises(sw.SweepError, match="empty value"):
        sw.experiments(["--noise", "ideal,"])


def test_bad_options_are_rusoar_slams_errors(tmp_path):
    with pytest.raises(sw.SlamUsageError) as e:
        sw.plan(["--slam", "maybe"])
    assert e.value.status == 2 and "maybe" in e.value.message
    with pytest.raises(sw.SlamUsageError) as e:
        sw.plan(["--world", str(tmp_path / "nowhere.toml")])
    assert "nowhere.toml" in e.value.message
    with pytest.raises(ValueError, match="not a run description"):
        sw.run(b"\xff\x00")
    with pytest.raises(sw.SlamError, match="not a run of this experiment"):
        runs = sw.plan(["--seeds", "1", "--duration", "1", "--slam", "on", "--rules", RULES])
        result = sw.run(runs[0]["spec"])
        sw.write_report(["--seeds", "1", "--first-seed", "5", "--duration", "1", "--slam",
                         "on", "--rules", RULES, "--out", str(tmp_path / "x")], [result])


def test_the_command_line(tmp_path):
    cmd = [sys.executable, "-m", "rusoar.sweep"]
    p = subprocess.run(cmd + ["--help"], capture_output=True, text=True)
    assert p.returncode == 0 and "--address" in p.stdout and "--first-seed" in p.stdout
    p = subprocess.run(cmd + ["--seeds", "0"], capture_output=True, text=True)
    try:
        import ray  # noqa: F401
    except ImportError:
        assert p.returncode == 1 and "pip install" in p.stderr
    else:
        assert p.returncode == 2 and "--seeds" in p.stderr


def test_one_run_in_this_process(tmp_path):
    """plan, run and write_report without Ray equal `rusoar slam` too."""
    args = ["--seeds", "1", "--duration", "5", "--method", "dr,v2", "--rules", RULES]
    runs = sw.plan(args)
    assert [(r["seed"], r["slam"]) for r in runs] == [(1, "off"), (1, "on")]
    results = [sw.run(r["spec"]) for r in reversed(runs)]
    exp = sw.write_report(args + ["--out", str(tmp_path / "b")], results)
    assert exp.status == 0
    assert sw.slam(args + ["--out", str(tmp_path / "a")]) == 0
    assert_same_files(tmp_path / "a", tmp_path / "b")
