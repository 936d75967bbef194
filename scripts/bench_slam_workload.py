#!/usr/bin/env python3
"""The Soar-SLAM run's matching workload, side by side with the official 9.6 kernel.

A SLAM-on run of `rusoar slam` spends most of its time re-deriving, every decision, each
remembered wall's relation to the robot and its distance objects, because the rules of
rules/CheckRobotPosition.soar test the robot's ^X ^Y ^Th, which change every step. The
official kernel cannot load the thesis's rules (Soar 8 spellings) nor call our exec
functions, so this script builds an agent with the same rule shapes (the same conditions as
slam*elaborate*wall*relation*with*robot, slam*elaborate*wall*distance*from*robot and
slam*elaborate*robot*position*difference, RHS math in place of exec) over N walls, and a
`tick` operator that moves the robot and changes the sonar ranges every decision, as the
input-link does in the robot loop. `run D` is timed after `source` in both kernels (ours
in-process by examples/time_run.rs). Prints decisions per second and the ratio rusoar /
official (above 1: rusoar is faster). One run, the median of REPEAT timings; these machines
are noisy.

usage: python3 scripts/bench_slam_workload.py [--repeat R] [--decisions D] [N ...]
       (default N: 30 60 120 walls; D 2000)
"""
import argparse
import os
import tempfile

from bench_common import official, ours

RULES = """\
sp {slamload*propose*init
   (state <s> ^superstate nil -^robot)
-->
   (<s> ^operator <o> +)
   (<o> ^name init)}

sp {slamload*apply*init
   (state <s> ^operator.name init)
-->
   (<s> ^robot <r> ^wallData <wd> ^sonar-map <sm> ^sonar-max-range 5000)
   (<r> ^step 0 ^X 1000 ^Y 2000 ^Th 0
        ^sonar <s0> <s1> <s2> <s3> <s4> <s5> <s6> <s7>)
   (<s0> ^index 0 ^range 1200) (<s1> ^index 1 ^range 1700)
   (<s2> ^index 2 ^range 900) (<s3> ^index 3 ^range 2500)
   (<s4> ^index 4 ^range 3100) (<s5> ^index 5 ^range 400)
   (<s6> ^index 6 ^range 2200) (<s7> ^index 7 ^range 800)
   (<sm> ^sonar <m0> <m1> <m2> <m3> <m4> <m5> <m6> <m7>)
   (<m0> ^relation 0 ^index 0 ^angle 10) (<m1> ^relation 0 ^index 1 ^angle -10)
   (<m2> ^relation 1 ^index 2 ^angle 90) (<m3> ^relation 1 ^index 3 ^angle 90)
   (<m4> ^relation 2 ^index 4 ^angle -90) (<m5> ^relation 2 ^index 5 ^angle -90)
   (<m6> ^relation 3 ^index 6 ^angle 170) (<m7> ^relation 3 ^index 7 ^angle -170)
{walls}}

sp {slamload*propose*tick
   (state <s> ^superstate nil ^robot.step <n>)
-->
   (<s> ^operator <o> + =)
   (<o> ^name tick ^step <n>)}

sp {slamload*apply*tick*pose
   (state <s> ^operator <o> ^robot <r>)
   (<o> ^name tick ^step <n>)
   (<r> ^step <n> ^X <x> ^Y <y> ^Th <th>)
-->
   (<r> ^step <n> - (+ <n> 1)
        ^X <x> - (mod (+ <x> 30) 8000)
        ^Y <y> - (mod (+ <y> 7) 6000)
        ^Th <th> - (mod (+ <th> 1) 360))}

sp {slamload*apply*tick*sonar
   (state <s> ^operator <o> ^robot.sonar <so>)
   (<o> ^name tick)
   (<so> ^index <i> ^range <r>)
-->
   (<so> ^range <r> - (mod (+ <r> 37 <i>) 5000))}

sp {slamload*elaborate*wall*relation*with*robot
   (state <s> ^wallData.Wall <w>
              ^robot (^X <rx> ^Y <ry> ^Th <rth>))
   (<w> ^Start (^X <sx> ^Y <sy>)
        ^End (^X <ex> ^Y <ey>)
        ^k <k>)
-->
   (<w> ^relation (mod (+ (div <rth> 60) <k>) 5))}

sp {slamload*elaborate*wall*distance*from*robot
   (state <s> ^sonar-map.sonar <m>
              ^wallData.Wall <w>
              ^robot (^X <rx> ^Y <ry> ^Th <rth>))
   (<m> ^relation <rel> ^index <i>)
   (<w> ^relation <rel>
        ^Start (^X <sx> ^Y <sy>)
        ^End (^X <ex> ^Y <ey>))
-->
   (<w> ^distance <d>)
   (<d> ^index <i>
        ^range (+ (abs (- <sx> <rx>)) (abs (- <ey> <ry>)) <i>))}

sp {slamload*elaborate*robot*position*difference
   (state <s> ^sonar-max-range <max>
              ^sonar-map.sonar <m>
              ^wallData.Wall <w>
              ^robot.sonar <so>)
   (<m> ^relation {<rel> << 0 1 2 >>} ^index <i> ^angle <a>)
   (<w> ^relation <rel>
        ^distance <d>)
   (<d> ^index <i>
        ^range {<dist1> > 0})
   (<so> ^index <i>
         ^range {<dist2> <> <dist1> < <max>})
-->
   (<s> ^position-difference <pd>)
   (<pd> ^Wall <w>
         ^index <i>
         ^angle <a>
         ^diff (- <dist1> <dist2>))}
"""


def write_agent(walls, path):
    lines = []
    for i in range(walls):
        sx, sy = (i * 137) % 8000, (i * 211) % 6000
        ex, ey = (sx + 900) % 8000, (sy + 400) % 6000
        lines.append(f"   (<wd> ^Wall <w{i}>)\n"
                     f"   (<w{i}> ^k {i % 5} ^Start <a{i}> ^End <b{i}>)\n"
                     f"   (<a{i}> ^X {sx} ^Y {sy}) (<b{i}> ^X {ex} ^Y {ey})\n")
    with open(path, "w") as f:
        f.write(RULES.replace("{walls}", "".join(lines)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--decisions", type=int, default=2000)
    ap.add_argument("walls", nargs="*", type=int)
    opts = ap.parse_args()
    sizes = opts.walls or [30, 60, 120]
    print("| walls | decisions | firings (ours / official) | rusoar dec/s | official dec/s "
          "| ratio |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            path = os.path.join(tmp, f"slam-workload-{n}.soar")
            write_agent(n, path)
            rt, rd, rf = ours(path, opts.decisions, opts.repeat)
            ot, _, of = official(path, opts.decisions, opts.repeat)
            ours_rate, off_rate = rd / rt, opts.decisions / ot
            print(f"| {n} | {rd} | {rf:,} / {of:,} | {ours_rate:,.0f} | {off_rate:,.0f} | "
                  f"{ours_rate / off_rate:.2f} |", flush=True)


if __name__ == "__main__":
    main()
