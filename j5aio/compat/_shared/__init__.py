"""What sbot's and sr-robot3's APIs have in common, written once for both.

The two peers grew from one code base and still share pieces of it: the console
logging, some exceptions, the markers' shapes. Each package keeps its own names (in its
own modules, so that a team's program and the peers' API surfaces find them where the
peer has them); the behaviour behind them is here.
"""

from __future__ import annotations

__all__: list[str] = []
