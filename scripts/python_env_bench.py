#!/usr/bin/env python3
"""Speed of a Python-driven environment loop, rusoar.sml against the official soar_sml.

Each decision the environment updates 20 input WMEs, runs one decision (RunSelf(1)) and
reads the one output command the agent writes, marking it complete. Both modules run the
same script; the figure is wall-clock seconds per module and their ratio.

    python3 scripts/python_env_bench.py [--decisions 10000]

Needs `pip install ./python soar-sml==9.6.5` in the interpreter that runs it.
"""

import argparse
import importlib
import time

RULES = r"""
sp {propose*act (state <s> ^superstate nil ^io.input-link.tick <t>) -->
    (<s> ^operator <o> + =) (<o> ^name act ^tick <t>)}
sp {apply*act (state <s> ^operator <o> ^io.output-link <ol>) (<o> ^name act ^tick <t>) -->
    (<ol> ^act <a>) (<a> ^tick <t>)}
sp {apply*act*clean (state <s> ^operator.name act ^io.output-link <ol>)
    (<ol> ^act <a>) (<a> ^status complete) --> (<ol> ^act <a> -)}
"""


def run(module_name, decisions):
    sml = importlib.import_module(module_name)
    kernel = sml.Kernel.CreateKernelInNewThread()
    agent = kernel.CreateAgent("bench")
    agent.ExecuteCommandLine(RULES)
    agent.ExecuteCommandLine("watch 0")
    il = agent.GetInputLink()
    tick = il.CreateIntWME("tick", 0)
    sensors = il.CreateIdWME("sensors")
    readings = [sensors.CreateFloatWME("r%d" % i, 0.0) for i in range(19)]
    commands = 0
    start = time.perf_counter()
    for d in range(decisions):
        agent.Update(tick, d)
        for i, r in enumerate(readings):
            agent.Update(r, (d * 7 + i) % 100 / 10.0)
        agent.RunSelf(1)
        for c in range(agent.GetNumberCommands()):
            cmd = agent.GetCommand(c)
            if cmd.GetParameterValue("status") is None:
                cmd.GetParameterValue("tick")
                cmd.AddStatusComplete()
                commands += 1
    elapsed = time.perf_counter() - start
    kernel.Shutdown()
    return elapsed, commands


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--decisions", type=int, default=10000)
    args = parser.parse_args()
    results = {}
    for name in ("soar_sml", "rusoar.sml"):
        elapsed, commands = run(name, args.decisions)
        results[name] = elapsed
        print("%-11s %8.3f s  %7.1f us/decision  %d commands read"
              % (name, elapsed, elapsed / args.decisions * 1e6, commands))
    print("soar_sml / rusoar.sml: %.2f" % (results["soar_sml"] / results["rusoar.sml"]))


if __name__ == "__main__":
    main()
