"""Client scripts in the styles real SML programs use, run on the official kernel and on
rusoar; what each returns, prints and reports through its callbacks must agree."""

import pytest

# An agent that counts: it reads ^x from the input-link and answers with a `move` command
# carrying x + 1; the environment then marks the command complete.
COUNTER = r"""
sp {propose*move (state <s> ^superstate nil ^io.input-link.x <x>) -->
    (<s> ^operator <o> + =) (<o> ^name move ^x <x>)}
sp {apply*move (state <s> ^operator <o> ^io.output-link <ol>) (<o> ^name move ^x <x>) -->
    (<ol> ^move <m>) (<m> ^value (+ <x> 1) ^label |step| ^ratio 0.5)}
sp {apply*move*done (state <s> ^operator <o> ^io.output-link <ol>) (<o> ^name move)
    (<ol> ^move <m>) (<m> ^status complete) --> (<ol> ^move <m> -)}
"""

BLOCKS = r"""
sp {propose*init (state <s> ^superstate nil -^counter) --> (<s> ^operator <o> +) (<o> ^name init)}
sp {apply*init (state <s> ^operator.name init) --> (<s> ^counter 0)}
sp {propose*count (state <s> ^counter <c> < 5) --> (<s> ^operator <o> +) (<o> ^name count ^at <c>)}
sp {apply*count (state <s> ^operator <o> ^counter <c>) (<o> ^name count ^at <c>) -->
    (<s> ^counter <c> -) (<s> ^counter (+ <c> 1)) (write |count | <c> (crlf))}
sp {done (state <s> ^counter 5) --> (write |done| (crlf)) (halt)}
"""


def new_agent(sml, kernel, name="agent", rules=None):
    agent = kernel.CreateAgent(name)
    if rules:
        agent.ExecuteCommandLine(rules)
        assert agent.GetLastCommandLineResult()
    return agent


def command_view(cmd):
    """What a client reads of a command: name, value, parameters (sorted)."""
    params = sorted(
        (cmd.GetChild(i).GetAttribute(), cmd.GetChild(i).GetValueType(),
         cmd.GetChild(i).GetValueAsString())
        for i in range(cmd.GetNumberChildren())
    )
    return (cmd.GetCommandName(), cmd.GetValueAsString(), params)


def same(both, script):
    official, ours = both(script)
    assert ours == official
    return ours


# ---- commands and their results ----

def test_execute_command_line_results(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        for cmd in ["sp {a (state <s> ^superstate nil) --> (<s> ^x 1)}", "print s1",
                    "run 1", "print --depth 2 s1", "watch 0", "run 2", "init-soar", "print s1"]:
            log.append((cmd, agent.ExecuteCommandLine(cmd), agent.GetLastCommandLineResult()))
    same(both, script)


def test_failed_command_reports_false(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        agent.ExecuteCommandLine("sp {bad (state <s> --> }")
        log.append(agent.GetLastCommandLineResult())
        agent.ExecuteCommandLine("print s1")
        log.append(agent.GetLastCommandLineResult())
        log.append(agent.LoadProductions("/nonexistent/agent.soar"))
    same(both, script)


def test_kernel_execute_command_line_names_agent(both):
    def script(sml, kernel, log):
        new_agent(sml, kernel, "first")
        new_agent(sml, kernel, "second", "sp {a (state <s> ^superstate nil) --> (<s> ^y 2)}")
        log.append(kernel.ExecuteCommandLine("print s1", "first"))
        kernel.ExecuteCommandLine("run 1", "second")
        log.append(kernel.ExecuteCommandLine("print s1", "second"))
    same(both, script)


def test_load_productions_from_file(both, tmp_path):
    path = tmp_path / "blocks.soar"
    path.write_text(BLOCKS)

    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        log.append(agent.LoadProductions(str(path)))
        log.append(agent.ExecuteCommandLine("print --name init"))
        log.append(agent.RunSelf(20))
        log.append(agent.GetRunState())
    same(both, script)


# ---- runs ----

def test_run_self_reports(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        for n in (1, 2, 3, 10):
            log.append(agent.RunSelf(n))
        log.append(agent.GetRunState())
    same(both, script)


def test_run_self_forever_halts(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        log.append(agent.RunSelfForever())
        log.append(agent.GetRunState() == sml.sml_RUNSTATE_HALTED)
        log.append(agent.InitSoar())
        log.append(agent.RunSelf(3))
    same(both, script)


def test_run_phases(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        agent.ExecuteCommandLine("watch 0")
        for _ in range(4):
            agent.RunSelf(1, sml.sml_PHASE)
        log.append(agent.ExecuteCommandLine("print s1"))
    same(both, script)


def test_init_soar_keeps_input(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        il = agent.GetInputLink()
        il.CreateIntWME("x", 4)
        agent.RunSelf(2)
        agent.InitSoar()
        agent.RunSelf(2)
        log.append(agent.ExecuteCommandLine("print --depth 3 i2"))
    same(both, script)


# ---- the input-link ----

def test_input_link_tree(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        il = agent.GetInputLink()
        log.append((il.GetValueAsString(), il.GetAttribute(), il.GetValueType(), il.IsIdentifier()))
        pose = agent.CreateIdWME(il, "pose")
        agent.CreateIntWME(pose, "x", 3)
        agent.CreateFloatWME(pose, "heading", 1.5)
        il.CreateStringWME("name", "walker")
        agent.CreateSharedIdWME(il, "again", pose)
        agent.RunSelf(1)
        log.append(agent.ExecuteCommandLine("print --depth 3 i2"))
        log.append(il.GetNumberChildren())
        log.append([(il.GetChild(i).GetAttribute(), il.GetChild(i).GetValueType())
                    for i in range(il.GetNumberChildren())])
        log.append(il.GetChild(99))
    same(both, script)


def test_update_each_cycle(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        x = agent.GetInputLink().CreateIntWME("x", 0)
        for i in range(6):
            agent.Update(x, i * 10)
            agent.RunSelf(1)
            log.append((x.GetValue(), agent.GetNumberCommands()))
        log.append(agent.ExecuteCommandLine("print --depth 4 i1"))
    same(both, script)


def test_update_types(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        il = agent.GetInputLink()
        i, f, s = il.CreateIntWME("i", 1), il.CreateFloatWME("f", 0.25), il.CreateStringWME("s", "a")
        agent.RunSelf(1)
        agent.Update(i, 2)
        agent.Update(f, 2.75)
        agent.Update(s, "b c")
        agent.RunSelf(1)
        log.append([w.GetValueAsString() for w in (i, f, s)])
        log.append([type(w.GetValue()).__name__ for w in (i, f, s)])
        log.append(agent.ExecuteCommandLine("print i2"))
    same(both, script)


def test_destroy_wme(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        il = agent.GetInputLink()
        block = il.CreateIdWME("block")
        block.CreateStringWME("color", "red")
        keep = il.CreateIntWME("keep", 1)
        agent.RunSelf(1)
        log.append(agent.DestroyWME(block))
        agent.RunSelf(1)
        log.append(agent.ExecuteCommandLine("print --depth 2 i2"))
        log.append(il.GetNumberChildren())
        log.append(keep.GetValue())
    same(both, script)


def test_find_by_attribute(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        il = agent.GetInputLink()
        for v in (1, 2, 3):
            il.CreateIntWME("n", v)
        il.CreateStringWME("s", "x")
        log.append([il.FindByAttribute("n", k).GetValueAsString() for k in range(3)])
        log.append(il.FindByAttribute("n", 3))
        log.append(il.FindByAttribute("zz", 0))
        log.append(il.FindByAttribute("s", 0).GetValueAsString())
    same(both, script)


def test_conversions(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        il = agent.GetInputLink()
        elems = [il.CreateIntWME("i", 1), il.CreateFloatWME("f", 2.5), il.CreateStringWME("s", "t"),
                 il.CreateIdWME("o")]
        for w in elems:
            log.append((w.GetValueType(), w.IsIdentifier(),
                        w.ConvertToIdentifier() is not None, w.ConvertToIntElement() is not None,
                        w.ConvertToFloatElement() is not None, w.ConvertToStringElement() is not None))
    same(both, script)


def test_float_values_as_strings(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        il = agent.GetInputLink()
        for v in (2.0, 0.5, -3.25, 1e-7, 123456789.125, 1.0 / 3):
            log.append(il.CreateFloatWME("f", v).GetValueAsString())
    same(both, script)


def test_commit_without_auto_commit(both):
    def script(sml, kernel, log):
        kernel.SetAutoCommit(False)
        agent = new_agent(sml, kernel)
        il = agent.GetInputLink()
        log.append(agent.IsCommitRequired())
        il.CreateIntWME("x", 1)
        log.append(agent.IsCommitRequired())
        log.append(agent.Commit())
        log.append(agent.IsCommitRequired())
        agent.RunSelf(1)
        log.append(agent.ExecuteCommandLine("print i2"))
    same(both, script)


# ---- the output-link ----

def test_output_commands_with_status(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        x = agent.GetInputLink().CreateIntWME("x", 1)
        for step in range(5):
            agent.RunSelf(1)
            for i in range(agent.GetNumberCommands()):
                cmd = agent.GetCommand(i)
                log.append((step, command_view(cmd), cmd.GetParameterValue("value"),
                            cmd.GetParameterValue("status")))
                if cmd.GetParameterValue("status") is None:
                    cmd.AddStatusComplete()
                    agent.Update(x, int(cmd.GetParameterValue("value")))
            agent.ClearOutputLinkChanges()
        log.append(agent.ExecuteCommandLine("print --depth 4 i1"))
    same(both, script)


def test_output_handler(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        x = agent.GetInputLink().CreateIntWME("x", 1)

        def on_move(data, ag, name, wme):
            cmd = wme.ConvertToIdentifier()
            log.append((data, ag.GetAgentName(), name, cmd.GetParameterValue("value"),
                        cmd.GetParameterValue("label"), cmd.GetParameterValue("ratio")))
            cmd.AddStatusComplete()
            agent.Update(x, int(cmd.GetParameterValue("value")))

        agent.AddOutputHandler("move", on_move, "data")
        agent.RunSelf(8)
        log.append(x.GetValue())
    same(both, script)


def test_output_handler_removed(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        agent.GetInputLink().CreateIntWME("x", 1)
        hid = agent.AddOutputHandler("move", lambda *a: log.append("called"), None)
        log.append(agent.RemoveOutputHandler(hid))
        agent.RunSelf(3)
    same(both, script)


def test_add_status_error(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        agent.GetInputLink().CreateIntWME("x", 7)
        agent.RunSelf(2)
        cmd = agent.GetCommand(0)
        cmd.AddStatusError()
        agent.RunSelf(1)
        log.append(agent.ExecuteCommandLine("print --depth 4 i3"))
    same(both, script)


# ---- events ----

def test_run_events_order(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        names = {getattr(sml, n): n for n in dir(sml) if n.startswith("smlEVENT_")}
        for e in (sml.smlEVENT_BEFORE_INPUT_PHASE, sml.smlEVENT_AFTER_OUTPUT_PHASE,
                  sml.smlEVENT_AFTER_DECISION_CYCLE, sml.smlEVENT_BEFORE_DECIDE_PHASE,
                  sml.smlEVENT_AFTER_DECIDE_PHASE):
            agent.RegisterForRunEvent(e, lambda ev, data, ag, phase: log.append(
                (names[ev], data, ag.GetAgentName(), phase)), "d")
        agent.RunSelf(3)
    same(both, script)


def test_run_event_driven_environment(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        x = agent.GetInputLink().CreateIntWME("x", 0)
        state = {"x": 0}

        def after_output(ev, data, ag, phase):
            for i in range(ag.GetNumberCommands()):
                cmd = ag.GetCommand(i)
                if cmd.GetParameterValue("status") is None:
                    state["x"] = int(cmd.GetParameterValue("value"))
                    cmd.AddStatusComplete()
            ag.Update(x, state["x"])
            log.append(state["x"])

        agent.RegisterForRunEvent(sml.smlEVENT_AFTER_OUTPUT_PHASE, after_output, None)
        agent.RunSelf(10)
    same(both, script)


def test_unregister_run_event(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        rid = agent.RegisterForRunEvent(sml.smlEVENT_AFTER_DECISION_CYCLE,
                                        lambda *a: log.append("dc"), None)
        agent.RunSelf(2)
        log.append(agent.UnregisterForRunEvent(rid))
        agent.RunSelf(2)
    same(both, script)


def test_print_event_text(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        printed = []
        agent.RegisterForPrintEvent(sml.smlEVENT_PRINT,
                                    lambda ev, data, ag, msg: printed.append(msg), None)
        agent.RunSelf(20)
        log.append("".join(printed))
    same(both, script)


def test_print_event_watch_levels(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        printed = []
        agent.RegisterForPrintEvent(sml.smlEVENT_PRINT,
                                    lambda ev, data, ag, msg: printed.append(msg), None)
        agent.ExecuteCommandLine("watch 2")
        agent.RunSelf(3)
        log.append("".join(printed))
    same(both, script)


def test_production_events(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        agent.RegisterForProductionEvent(
            sml.smlEVENT_AFTER_PRODUCTION_FIRED,
            lambda ev, data, ag, name, inst: log.append(("fired", data, name)), 5)
        # (Stops before the rule that halts: the official kernel reports no firing event
        # for it, rusoar does.)
        agent.RunSelf(5)
    same(both, script)


def test_rhs_function(both):
    def script(sml, kernel, log):
        def join(ev, data, ag, name, args):
            log.append((ev, data, ag.GetAgentName(), name, args))
            return "got-" + args

        kernel.AddRhsFunction("join", join, "ud")
        agent = new_agent(sml, kernel, rules="sp {a (state <s> ^superstate nil) --> "
                          "(<s> ^r (exec join 1 |x| 2.5))}")
        agent.RunSelf(1)
        log.append(agent.ExecuteCommandLine("print s1"))
    same(both, script)


def test_rhs_function_in_write(both):
    def script(sml, kernel, log):
        kernel.AddRhsFunction("twice", lambda ev, d, ag, n, a: a + a, None)
        agent = new_agent(sml, kernel, rules="sp {a (state <s> ^superstate nil) --> "
                          "(write (exec twice ab) (crlf))}")
        printed = []
        agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, lambda *a: printed.append(a[3]), None)
        agent.RunSelf(1)
        log.append("".join(printed))
    same(both, script)


def test_agent_events(both):
    def script(sml, kernel, log):
        for e in (sml.smlEVENT_AFTER_AGENT_CREATED, sml.smlEVENT_BEFORE_AGENT_DESTROYED,
                  sml.smlEVENT_BEFORE_AGENT_REINITIALIZED, sml.smlEVENT_AFTER_AGENT_REINITIALIZED):
            kernel.RegisterForAgentEvent(e, lambda ev, data, ag: log.append(
                (ev, data, ag.GetAgentName())), "k")
        agent = new_agent(sml, kernel, "a1")
        agent.InitSoar()
        kernel.DestroyAgent(agent)
    same(both, script)


def test_client_message(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel)
        kernel.RegisterForClientMessageEvent(
            "env", lambda ev, data, ag, client, msg: "echo:" + msg, None)
        log.append(kernel.SendClientMessage(agent, "env", "hello"))
    same(both, script)


def test_system_events_around_runs(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        for e in (sml.smlEVENT_SYSTEM_START, sml.smlEVENT_SYSTEM_STOP):
            kernel.RegisterForSystemEvent(e, lambda ev, data, k: log.append((ev, data)), "s")
        agent.RunSelf(2)
    same(both, script)


# ---- several agents ----

def test_multiple_agents(both):
    def script(sml, kernel, log):
        a = new_agent(sml, kernel, "a", BLOCKS)
        b = new_agent(sml, kernel, "b", COUNTER)
        b.GetInputLink().CreateIntWME("x", 5)
        log.append(kernel.GetNumberAgents())
        log.append([kernel.GetAgentByIndex(i).GetAgentName() for i in range(2)])
        log.append(kernel.GetAgent("b").GetAgentName())
        log.append(kernel.GetAgent("nobody"))
        a.RunSelf(3)
        b.RunSelf(3)
        log.append(a.ExecuteCommandLine("print s1"))
        log.append(b.ExecuteCommandLine("print --depth 3 i3"))
        log.append(kernel.DestroyAgent(a))
        log.append(kernel.GetNumberAgents())
    same(both, script)


def test_run_all_agents_state(both):
    def script(sml, kernel, log):
        a = new_agent(sml, kernel, "a", BLOCKS)
        b = new_agent(sml, kernel, "b", BLOCKS)
        kernel.RunAllAgentsForever()
        log.append((a.GetRunState(), b.GetRunState()))
        log.append(a.ExecuteCommandLine("print s1") == b.ExecuteCommandLine("print s1"))
    same(both, script)


# ---- the constants ----

CONSTANTS = ["smlEVENT_BEFORE_INPUT_PHASE", "smlEVENT_AFTER_OUTPUT_PHASE", "smlEVENT_PRINT",
             "smlEVENT_AFTER_PRODUCTION_FIRED", "smlEVENT_AFTER_AGENT_CREATED",
             "smlEVENT_SYSTEM_START", "smlEVENT_AFTER_ALL_OUTPUT_PHASES", "sml_RUNSTATE_HALTED",
             "sml_DECIDE", "sml_PHASE", "sml_INPUT_PHASE", "sml_OUTPUT_PHASE"]


@pytest.mark.parametrize("name", CONSTANTS)
def test_constants(sml, name):
    import soar_sml
    assert getattr(sml, name) == getattr(soar_sml, name)


# ---- more environment styles ----

def test_update_event_environment(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        x = agent.GetInputLink().CreateIntWME("x", 0)

        def on_update(ev, data, k, flags):
            log.append(("update", ev, data, flags, agent.GetNumberCommands()))
            for i in range(agent.GetNumberCommands()):
                cmd = agent.GetCommand(i)
                if cmd.GetParameterValue("status") is None:
                    cmd.AddStatusComplete()
                    agent.Update(x, int(cmd.GetParameterValue("value")))

        kernel.RegisterForUpdateEvent(sml.smlEVENT_AFTER_ALL_OUTPUT_PHASES, on_update, "u")
        kernel.RegisterForUpdateEvent(sml.smlEVENT_AFTER_ALL_GENERATED_OUTPUT, on_update, "g")
        log.append(agent.RunSelf(6))
        log.append(x.GetValue())
    same(both, script)


def test_run_loop_with_init_soar(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        x = agent.GetInputLink().CreateIntWME("x", 0)
        for episode in range(2):
            for _ in range(4):
                agent.RunSelf(1)
                log.append(agent.Commands())
                for cmd in [agent.GetCommand(i) for i in range(agent.GetNumberCommands())]:
                    if cmd.GetParameterValue("status") is None:
                        cmd.AddStatusComplete()
                        agent.Update(x, int(cmd.GetParameterValue("value")))
            log.append((episode, x.GetValue(), agent.ExecuteCommandLine("print --depth 3 i3")))
            agent.InitSoar()
            agent.Update(x, 0)
    same(both, script)


def test_current_thread_kernel(both):
    def script(sml, kernel, log):
        other = sml.Kernel.CreateKernelInCurrentThread()
        try:
            agent = other.CreateAgent("here")
            agent.ExecuteCommandLine(BLOCKS)
            log.append(agent.RunSelf(3))
            log.append(agent.ExecuteCommandLine("print s1"))
        finally:
            other.Shutdown()
    same(both, script)


def test_print_during_command_line_run(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=BLOCKS)
        printed = []
        agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, lambda *a: printed.append(a[3]), None)
        log.append(agent.ExecuteCommandLine("run 3"))
        log.append("".join(printed))
    same(both, script)


def test_run_til_output(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules=COUNTER)
        agent.ExecuteCommandLine("watch 0")
        agent.GetInputLink().CreateIntWME("x", 2)
        agent.RunSelfTilOutput()
        log.append([agent.GetCommand(i).GetParameterValue("value")
                    for i in range(agent.GetNumberCommands())])
    same(both, script)


def test_blink_if_no_change_off(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules="sp {see (state <s> ^superstate nil "
                          "^io.input-link.x <x>) --> (write |see | <x> (crlf))}")
        printed = []
        agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, lambda *a: printed.append(a[3]), None)
        agent.ExecuteCommandLine("watch 0")
        agent.SetBlinkIfNoChange(False)
        x = agent.GetInputLink().CreateIntWME("x", 1)
        for v in (1, 1, 2, 2):
            agent.Update(x, v)
            agent.RunSelf(1)
        log.append("".join(printed))
    same(both, script)


def test_blink_if_no_change_default(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules="sp {see (state <s> ^superstate nil "
                          "^io.input-link.x <x>) --> (write |see | <x> (crlf))}")
        printed = []
        agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, lambda *a: printed.append(a[3]), None)
        agent.ExecuteCommandLine("watch 0")
        x = agent.GetInputLink().CreateIntWME("x", 1)
        for v in (1, 1, 2):
            agent.Update(x, v)
            agent.RunSelf(1)
        log.append("".join(printed))
    same(both, script)


def test_two_agents_output_handlers(both):
    def script(sml, kernel, log):
        agents = [new_agent(sml, kernel, n, COUNTER) for n in ("left", "right")]
        for i, agent in enumerate(agents):
            x = agent.GetInputLink().CreateIntWME("x", 10 * i)

            def handler(data, ag, name, wme, x=x):
                cmd = wme.ConvertToIdentifier()
                log.append((data, ag.GetAgentName(), cmd.GetParameterValue("value")))
                cmd.AddStatusComplete()
                ag.Update(x, int(cmd.GetParameterValue("value")))

            agent.AddOutputHandler("move", handler, i)
        for _ in range(4):
            for agent in agents:
                agent.RunSelf(1)
    same(both, script)


def test_input_link_object_removed_and_rebuilt(both):
    def script(sml, kernel, log):
        agent = new_agent(sml, kernel, rules="sp {see (state <s> ^superstate nil "
                          "^io.input-link.obj.name <n>) --> (write |obj | <n> (crlf))}")
        printed = []
        agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, lambda *a: printed.append(a[3]), None)
        agent.ExecuteCommandLine("watch 0")
        il = agent.GetInputLink()
        for name in ("box", "ball", "cone"):
            obj = il.CreateIdWME("obj")
            obj.CreateStringWME("name", name)
            agent.RunSelf(1)
            agent.DestroyWME(obj)
            agent.RunSelf(1)
        log.append("".join(printed))
        log.append(agent.ExecuteCommandLine("print i2"))
    same(both, script)
