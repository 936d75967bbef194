#!/usr/bin/env python3
"""evo's ATE and RPE on the trajectories `rusoar slam --method ...` writes, beside our own error.

Usage: python3 scripts/slam_evo.py OUT [--markdown FILE]

OUT is the output folder of a comparison run (`rusoar slam --method dr,thesis,v2,ekf,oracle
--out OUT`): its method folders hold `true-<tag>-<seed>.tum` and `believed-<tag>-<seed>.tum`
(TUM format: t x y z qx qy qz qw, metres). Installs evo (`pip install evo`) when it is missing.

For each method and seed, with the trajectories associated by time stamp:
- our own RMSE: sqrt(mean ||p_true - p_believed||^2) over all steps, no alignment (the
  believed pose starts at the true one, so the two share a frame);
- evo's APE (absolute trajectory error, Sturm et al., IROS 2012) on the translation, without
  alignment, RMSE: it must equal ours;
- evo's RPE on the translation and the rotation over delta = 1 m of travel, RMSE: the drift
  over short stretches, which no absolute figure shows.
Medians over seeds are written to OUT/evo.md (or --markdown FILE) and printed.
"""

import argparse
import math
import statistics
import subprocess
import sys
from pathlib import Path

EVO = "evo==1.38.1"

# (method folder, file tag, method label), in the comparison's order.
SOURCES = [
    ("thesis", "off", "dead reckoning"),
    ("dr", "off", "dead reckoning"),
    ("thesis", "on", "thesis rules"),
    ("v2", "on", "rules v2"),
    ("thesis", "ekf", "EKF"),
    ("dr", "ekf", "EKF"),
    ("oracle", "on", "oracle (true map)"),
]


def import_evo():
    """evo's modules, installing evo first when it is missing."""
    try:
        from evo.core import metrics, sync
        from evo.tools import file_interface
    except ImportError:
        subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", EVO], check=True)
        from evo.core import metrics, sync
        from evo.tools import file_interface
    return metrics, sync, file_interface


def seeds_of(folder, tag):
    """The seeds with both trajectories in `folder`, in numeric order."""
    seeds = []
    for p in folder.glob(f"true-{tag}-*.tum"):
        seed = p.stem.rsplit("-", 1)[-1]
        if seed.isdigit() and (folder / f"believed-{tag}-{seed}.tum").is_file():
            seeds.append(int(seed))
    return sorted(seeds)


def figures(evo, folder, tag, seed):
    """(our RMSE, APE RMSE, RPE translation RMSE, RPE rotation RMSE) in m, m, m, degrees."""
    metrics, sync, file_interface = evo
    gt = file_interface.read_tum_trajectory_file(str(folder / f"true-{tag}-{seed}.tum"))
    est = file_interface.read_tum_trajectory_file(str(folder / f"believed-{tag}-{seed}.tum"))
    gt, est = sync.associate_trajectories(gt, est)
    d = gt.positions_xyz - est.positions_xyz
    ours = math.sqrt(sum(float(x * x + y * y + z * z) for x, y, z in d) / len(d))
    ape = metrics.APE(metrics.PoseRelation.translation_part)
    ape.process_data((gt, est))
    out = [ours, ape.get_statistic(metrics.StatisticsType.rmse)]
    for relation in (metrics.PoseRelation.translation_part, metrics.PoseRelation.rotation_angle_deg):
        rpe = metrics.RPE(relation, delta=1.0, delta_unit=metrics.Unit.meters, all_pairs=False)
        rpe.process_data((gt, est))
        out.append(rpe.get_statistic(metrics.StatisticsType.rmse))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", type=Path, help="output folder of rusoar slam --method ...")
    ap.add_argument("--markdown", type=Path, help="where to write the table (default OUT/evo.md)")
    args = ap.parse_args()
    if not args.out.is_dir():
        sys.exit(f"error: {args.out} is not a folder")
    evo = import_evo()
    rows = []
    done = set()
    for sub, tag, label in SOURCES:
        folder = args.out / sub
        if label in done or not folder.is_dir():
            continue
        seeds = seeds_of(folder, tag)
        if not seeds:
            continue
        done.add(label)
        per_seed = [figures(evo, folder, tag, s) for s in seeds]
        medians = [statistics.median(col) for col in zip(*per_seed)]
        gap = max(abs(p[0] - p[1]) for p in per_seed)
        rows.append((label, len(seeds), medians, gap))
    if not rows:
        sys.exit(f"error: no true-*/believed-* TUM pairs under {args.out}/<method>/")
    text = [
        "# evo's ATE and RPE beside our own error",
        "",
        f"Computed by `python3 scripts/slam_evo.py` with {EVO} on the TUM trajectories of "
        "`rusoar slam --method ...`. Medians over seeds of each seed's RMSE. ATE: evo's APE "
        "on the translation, no alignment (the believed pose starts at the true one), which "
        "must equal our own RMSE; RPE: over 1 m of travel.",
        "",
        "| method | seeds | our RMSE, m | evo ATE RMSE, m | largest per-seed gap, m "
        "| evo RPE translation (1 m), m | evo RPE rotation (1 m), ° |",
        "|---|---|---|---|---|---|---|",
    ]
    for label, n, m, gap in rows:
        text.append(
            f"| {label} | {n} | {m[0]:.3f} | {m[1]:.3f} | {gap:.1e} | {m[2]:.3f} | {m[3]:.2f} |"
        )
    body = "\n".join(text) + "\n"
    target = args.markdown or args.out / "evo.md"
    target.write_text(body)
    print(body, end="")


if __name__ == "__main__":
    main()
