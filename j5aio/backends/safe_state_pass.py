"""The safe-state pass, under the name the backends first knew it by.

It is :mod:`j5aio.safety.safe_state_pass`: the orderly safe path of :mod:`j5aio.safety`
runs it, and a lost backend asks it for one more try
(:func:`~j5aio.safety.safe_state_pass.claim_attempt`). Its names are importable from
here too.
"""

from __future__ import annotations

from j5aio.safety.safe_state_pass import claim_attempt, making_safe, safe_state_pass

__all__ = ["claim_attempt", "making_safe", "safe_state_pass"]
