"""The surveillance demo: robots patrolling a topological map through aRMOR commands.

:mod:`.world` prepares the map and the robots, :mod:`.policy` decides where a
robot goes next, :mod:`.patrol` runs the steps and prints the trace, and
:mod:`.mapview` draws the reasoned map.
"""

from .patrol import DemoResult, Move, run_demo
from .policy import Decision, decide

__all__ = ["run_demo", "DemoResult", "Move", "Decision", "decide"]
