"""The base of every conformance suite, for writing the suite of an interface of your own.

A new kind of component comes with a new interface, and a new interface deserves a suite:
the checks every backend implementing it must pass, whatever its board. j5aio's own
suites (:mod:`j5aio.testing.conformance.distance_sensor` is a short one) are written with
nothing but the names of this module:

1. A **subject**: a dataclass (``@dataclass(kw_only=True)``) that subclasses
   :class:`~j5aio.testing.conformance.Subject`, types ``backend`` as your interface,
   and adds one field per *hook*, each typed ``Callable[..., Awaitable[...]] | None =
   None``. A hook is how the suite feeds the board an input (``place_object``,
   ``set_reading``) or observes what it did (``observe``).
   :meth:`~j5aio.testing.conformance.Subject.missing_hooks` finds the hooks by the word
   ``Callable`` in the field's type, so write it there (a plain ``Any`` hook is not
   reported when it is left out). The fields ``backend``, ``identifiers``,
   ``invalid_identifiers``, ``traffic`` and ``cleanup`` are the base's own.
2. A **suite**: a class that subclasses ``InterfaceConformance[YourSubject]`` and whose
   tests are coroutines ``async def test_...(self, subject: YourSubject) -> None``. Do
   not name the suite ``Test...``: the backend author subclasses it in a ``Test...`` class
   and implements :meth:`~j5aio.testing.conformance.InterfaceConformance.make_backend`.
3. In each test: ``hook = require(subject.hook, "hook")`` for a hook the test cannot do
   without (the test skips, naming it, when it is not given); ``with self.bounded():``
   around the calls to the backend, so that a hang fails the test instead of stopping the
   run; ``await self.assert_refused(subject, backend.method)`` to check that every
   identifier the board lacks is refused, with nothing sent to the board (a ``lambda``
   that fills in the other arguments is named: ``(subject, call, "what")``).
4. Class attributes (``ClassVar``) for what a backend author may tune: tolerances, the
   values the tests use. Say in the suite's docstring what it checks; its tests are the
   proof, so test the suite itself against deliberately wrong backends.

A skip for a missing hook carries ``HOOK_SKIP_MARK`` in its reason; the pytest plugin
lists those skips at the end of the run, so a green run cannot hide a check that never ran.
"""

from ._base import HOOK_SKIP_MARK, InterfaceConformance, Subject, SubjectT, require

__all__ = ["HOOK_SKIP_MARK", "InterfaceConformance", "Subject", "SubjectT", "require"]
