"""A drop-in for the official kernel's `soar_sml` module: `import rusoar.sml as sml`.

The classes, method names, argument orders, callback arguments and constants are those of
`soar_sml` 9.6.5; the kernel behind them is rusoar's.
"""

from rusoar._rusoar import (  # noqa: F401  (re-exported)
    Agent,
    FloatElement,
    Identifier,
    IntElement,
    Kernel,
    SoarError,
    StringElement,
    WMElement,
)
from rusoar._constants import *  # noqa: F401,F403  (the smlEVENT_* and sml_* constants)
