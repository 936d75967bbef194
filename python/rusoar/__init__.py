"""rusoar: the Soar cognitive architecture (Soar 9.6's semantics), in Rust, for Python.

Two ways in, over the same kernel:

- ``import rusoar.sml as sml``: a drop-in for the official kernel's ``soar_sml`` module.
- ``rusoar.Agent``: a Pythonic agent, with snake_case methods, a context manager,
  iteration over an identifier's children, and ``SoarError`` exceptions (with ``file``,
  ``line`` and ``column`` for a rule that does not parse) instead of status strings.

>>> import rusoar
>>> with rusoar.Agent("hello") as agent:
...     _ = agent.execute("sp {hi (state <s> ^superstate nil) --> (write |hi|) (halt)}")
...     agent.run(5).stop
'Halted'
"""

from collections import namedtuple

from rusoar._rusoar import (
    FloatElement,
    Identifier,
    IntElement,
    Kernel,
    SoarError,
    StringElement,
    WMElement,
)

__all__ = ["Agent", "RunResult", "SoarError", "Kernel", "Identifier", "WMElement"]

RunResult = namedtuple("RunResult", "decisions firings stop")
RunResult.__doc__ = """What a run did: decisions made, rules fired, and why it stopped
('LimitReached', 'Halted', 'Interrupted', 'GoalDepthExceeded')."""


class Agent:
    """One Soar agent, on a kernel of its own unless one is given."""

    def __init__(self, name="soar", kernel=None):
        self._owns_kernel = kernel is None
        self.kernel = Kernel.CreateKernelInNewThread() if kernel is None else kernel
        self.sml = self.kernel.CreateAgent(name)

    # -- the context manager: the agent's kernel shuts down at the end of the block --
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def close(self):
        """Destroys the agent (and shuts its kernel down if the agent made it)."""
        if self._owns_kernel:
            self.kernel.Shutdown()
        else:
            self.kernel.DestroyAgent(self.sml)

    @property
    def name(self):
        return self.sml.GetAgentName()

    # -- commands --
    def execute(self, commands):
        """Runs Soar commands; returns what they printed, or raises SoarError."""
        return self.sml.execute(commands)

    def source(self, path):
        """Sources a file of Soar commands; raises SoarError with the file, line, column."""
        return self.sml.execute("source {%s}" % path)

    # -- running --
    def run(self, decisions=1):
        """Runs `decisions` decision cycles; returns a RunResult."""
        return RunResult(*self.sml.run_decisions(decisions))

    def stop(self):
        """Stops a run (from a callback, or from another thread)."""
        self.sml.StopSelf()

    def init_soar(self):
        self.sml.InitSoar()

    # -- the input and output links --
    @property
    def input_link(self):
        return self.sml.GetInputLink()

    @property
    def output_link(self):
        return self.sml.GetOutputLink()

    def add(self, parent, attr, value=None):
        """Adds (parent ^attr value): an int, float, str, an Identifier (shared), or None
        for a new identifier. Returns the WME."""
        if value is None:
            return parent.CreateIdWME(attr)
        if isinstance(value, bool):
            raise TypeError("Soar has no booleans: use an int or a string")
        if isinstance(value, int):
            return parent.CreateIntWME(attr, value)
        if isinstance(value, float):
            return parent.CreateFloatWME(attr, value)
        if isinstance(value, str):
            return parent.CreateStringWME(attr, value)
        if isinstance(value, Identifier):
            return parent.CreateSharedIdWME(attr, value)
        raise TypeError("a WME's value is an int, float, str or Identifier, not %s"
                        % type(value).__name__)

    def update(self, wme, value):
        self.sml.Update(wme, value)

    def remove(self, wme):
        if not self.sml.DestroyWME(wme):
            raise SoarError("only WMEs the program made can be removed")

    def commands(self):
        """The commands on the output-link (Identifiers: name, parameters, status)."""
        return [self.sml.GetCommand(i) for i in range(self.sml.GetNumberCommands())]

    # -- events --
    def on_print(self, handler):
        """Calls handler(text) with what the agent prints; returns an id for off_print."""
        return self.sml.RegisterForPrintEvent(47, lambda _e, _d, _a, text: handler(text))

    def off_print(self, handler_id):
        return self.sml.UnregisterForPrintEvent(handler_id)

    def on_output(self, command, handler):
        """Calls handler(command) for each new output command named `command`."""
        return self.sml.AddOutputHandler(command, lambda _d, _a, _n, wme: handler(wme))

    def __repr__(self):
        return "<rusoar.Agent %r>" % self.name
