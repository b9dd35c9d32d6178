"""Turning core objects into their sync wrappers, and back: what generated wrappers use.

This module is public: the modules that ``python -m j5aio sync-gen`` writes for a
third-party kit import only from here (and from :mod:`j5aio.sync` for the wrappers of
j5aio's own classes). A generated module registers one wrapper class per core class with
:func:`register`; :func:`wrap` then finds the wrapper of a core object (the same wrapper
every time, so ``board.motors[0] is board.motors[0]``) and wraps the items of mappings,
sequences, sets and iterators of core objects lazily. :func:`unwrap` does the reverse for
arguments, and turns a wrapper *class* back into its core class, so that the sync facade
accepts its own board classes wherever the core accepts the core ones. :func:`call` runs a
coroutine of the core on the facade's event-loop thread and blocks until it is done.

None of this is needed to *use* the facade; it is the contract between the generator and
its output, kept stable for generated modules of other packages.
"""

from __future__ import annotations

import importlib
import sys
import weakref
from collections import deque
from collections.abc import Collection, Iterable, Iterator, Mapping, Sequence, Set
from typing import TYPE_CHECKING, Any, Final, TypeVar

from j5aio.numbered import NumberedComponents, Pins
from j5aio.sync._runtime import call

__all__ = [
    "RECENT_WRAPPERS",
    "SyncWrapper",
    "WrappedMapping",
    "WrappedSequence",
    "adopt",
    "adopt_into",
    "call",
    "core_class_of",
    "register",
    "register_later",
    "register_modules_later",
    "registered",
    "unwrap",
    "wrap",
    "wrap_kept",
]

K = TypeVar("K")
V = TypeVar("V")

#: core class -> wrapper class (subclasses of a registered class are added on first use).
_WRAPPER_CLASSES: dict[type, type[SyncWrapper] | None] = {}
#: wrapper class -> core class, for the registered wrapper classes only.
_CORE_CLASSES: dict[type, type] = {}
#: wrapper class -> (module, class name) of a core class registered by name, whose module
#: has not been imported yet (see :func:`register_later`).
_PENDING: dict[type, tuple[str, str]] = {}
#: (module, name) of a core class -> the module defining its wrapper, not imported yet
#: (see :func:`register_modules_later`).
_WRAPPER_MODULES: dict[tuple[str, str], str] = {}
#: id(core object) -> its wrapper. The wrapper keeps its core object (and so the id) alive,
#: and the entry goes when the wrapper does, so an id is never looked up for a new object.
_WRAPPERS: weakref.WeakValueDictionary[int, SyncWrapper] = weakref.WeakValueDictionary()

_LEAVES = (str, bytes, bytearray, int, float, type(None))

#: How many wrappers made by :func:`wrap` are kept alive even when the program holds none.
RECENT_WRAPPERS: Final = 256
#: The wrappers last made by :func:`wrap`, oldest first: ``robot.motor_boards[0]`` read
#: again finds the same wrapper (and quickly) without the table above ever growing
#: without bound when a program makes many short-lived core objects.
_RECENT: deque[SyncWrapper] = deque(maxlen=RECENT_WRAPPERS)


class SyncWrapper:
    """The base class of every generated sync wrapper: it holds one core object.

    It also keeps, once made, the sync faces of the core object's fixed collections
    (``board.pins``, ``board.motors``: see :func:`wrap_kept`).
    """

    __slots__ = ("__weakref__", "_core", "_kept")

    _core: Any
    _kept: dict[str, tuple[Any, Any]]

    @classmethod
    def _from_core(cls, core: Any) -> Any:
        wrapper = object.__new__(cls)
        wrapper._core = core
        return wrapper

    if not TYPE_CHECKING:  # hidden from type checkers, which must still refuse a misspelling

        def __setattr__(self, name: str, value: Any) -> None:
            try:
                object.__setattr__(self, name, value)
            except AttributeError:
                if name.startswith("_") or hasattr(type(self), name):
                    raise  # a read-only property, say: Python's own message says so
                raise AttributeError(_no_such_attribute(self, name)) from None

    def __str__(self) -> str:
        return str(self._core)

    def __repr__(self) -> str:
        return f"<sync {self._core!r}>"


#: (Bound to the class itself, defined above: a bound named by a string is compiled.)
W = TypeVar("W", bound=SyncWrapper)


def _no_such_attribute(wrapper: SyncWrapper, name: str) -> str:
    """Say that ``wrapper`` has no attribute ``name`` to set, and which one was meant."""
    message = f"{type(wrapper).__name__!r} object has no attribute {name!r} to set"
    public = [n for n in dir(type(wrapper)) if not n.startswith("_")]
    import difflib  # (here: only a mistyped name needs it)

    close = difflib.get_close_matches(name, public, n=1)
    return f"{message}. Did you mean: {close[0]!r}?" if close else message


def register(core_class: type, wrapper_class: type[SyncWrapper]) -> None:
    """Use ``wrapper_class`` for instances of ``core_class`` (and its unregistered subclasses).

    Registering forgets what was found earlier for unregistered subclasses, so that a
    wrapper module imported late (a third-party kit's) is used for its own classes.
    """
    explicit = set(_CORE_CLASSES.values())
    for cls in [c for c in _WRAPPER_CLASSES if c not in explicit]:
        del _WRAPPER_CLASSES[cls]
    _WRAPPER_CLASSES[core_class] = wrapper_class
    _CORE_CLASSES[wrapper_class] = core_class


def register_later(module: str, name: str, wrapper_class: type[SyncWrapper]) -> None:
    """Use ``wrapper_class`` for the core class ``name`` of ``module``, without importing it.

    The class is registered (as by :func:`register`) once its module has been imported:
    until then no object of it can exist, so no wrapper of one is asked for. j5aio's own
    facade registers every class this way, so that importing it imports only the core
    modules a program uses (the boards of its kit, not every kind's).
    Asking for the core class of ``wrapper_class`` (:func:`core_class_of`, or
    :func:`unwrap` of the class) imports the module (that of its wrapped bases too).
    """
    _PENDING[wrapper_class] = (module, name)


def register_modules_later(modules: Mapping[str, Iterable[tuple[str, str]]]) -> None:
    """Say which module wraps each core class, to be imported when it is first needed.

    :param modules: the module of wrappers -> the ``(module, name)`` of each core class it
        wraps (registering them itself, by :func:`register` or :func:`register_later`).

    j5aio's own facade is one module per family of classes: the first object of a core
    class that :func:`wrap` is given imports the module of its wrapper (and those of its
    wrapped bases), so a program imports only the wrappers of what it uses.
    :func:`registered` imports them all.
    """
    for module, classes in modules.items():
        for where in classes:
            _WRAPPER_MODULES[where] = module


def _import_wrapper_modules(cls: type) -> bool:
    """Import the modules of :func:`register_modules_later` that wrap ``cls`` or its bases.

    :returns: whether one was imported.
    """
    modules = [
        module
        for klass in cls.__mro__
        if (module := _WRAPPER_MODULES.get((klass.__module__, klass.__qualname__)))
        and module not in sys.modules
    ]
    for module in modules:
        importlib.import_module(module)
    return bool(modules)


def _register_pending(*, importing: bool = False, only: Collection[type] | None = None) -> None:
    """Register the classes of :func:`register_later` whose modules are imported.

    :param importing: import the modules of the others first.
    :param only: the wrapper classes to look at (all pending ones if ``None``).
    """
    pending = list(_PENDING.items())
    if only is not None:
        pending = [(wrapper, where) for wrapper, where in pending if wrapper in only]
    for wrapper_class, (module, name) in pending:
        loaded = importlib.import_module(module) if importing else sys.modules.get(module)
        # (a module still being imported may not have defined the class yet)
        core_class = getattr(loaded, name, None)
        if importing and not isinstance(core_class, type):
            raise TypeError(
                f"{module}.{name}, registered for {wrapper_class.__name__}, is not a class"
            )
        if isinstance(core_class, type) and _PENDING.pop(wrapper_class, None) is not None:
            register(core_class, wrapper_class)


def registered() -> dict[type, type[SyncWrapper]]:
    """Return every registered core class with its wrapper class (a copy).

    The classes registered with :func:`register_later` are among them: their modules are
    imported.
    """
    for module in sorted(set(_WRAPPER_MODULES.values())):
        importlib.import_module(module)
    _register_pending(importing=True)
    return {
        core: wrapper
        for wrapper, core in _CORE_CLASSES.items()
        if _WRAPPER_CLASSES.get(core) is wrapper
    }


def core_class_of(cls: type) -> type | None:
    """Return the core class that wrapper class ``cls`` (or its nearest wrapped base) wraps."""
    if _PENDING and any(klass in _PENDING for klass in cls.__mro__):
        _register_pending(importing=True, only=cls.__mro__)  # (its own modules alone)
    for klass in cls.__mro__:
        core = _CORE_CLASSES.get(klass)
        if core is not None:
            return core
    return None


def adopt(cls: type[W], core: Any) -> W:
    """Return a new ``cls`` wrapping ``core``, remembered as ``core``'s wrapper."""
    wrapper: W = cls._from_core(core)
    _WRAPPERS[id(core)] = wrapper
    return wrapper


def adopt_into(wrapper: SyncWrapper, core: Any) -> None:
    """Make ``wrapper`` (being constructed) the wrapper of the new core object ``core``."""
    wrapper._core = core
    _WRAPPERS[id(core)] = wrapper


def _wrapper_class_of(cls: type) -> type[SyncWrapper] | None:
    try:
        return _WRAPPER_CLASSES[cls]
    except KeyError:
        pass
    # (the module of its wrapper, not imported yet, perhaps; then a class registered by
    # name whose module is imported now)
    if (_WRAPPER_MODULES and _import_wrapper_modules(cls)) or _PENDING:
        _register_pending()
        if cls in _WRAPPER_CLASSES:
            return _WRAPPER_CLASSES[cls]
    found: type[SyncWrapper] | None = None
    for base in cls.__mro__[1:]:
        found = _WRAPPER_CLASSES.get(base)
        if found is not None:
            break
    _WRAPPER_CLASSES[cls] = found
    return found


def _keep_recent(wrapper: SyncWrapper) -> None:
    """Keep ``wrapper`` alive until :data:`RECENT_WRAPPERS` newer ones have been made."""
    _RECENT.append(wrapper)


def wrap(obj: Any) -> Any:
    """Return the sync face of ``obj``: its wrapper, a wrapping view, or ``obj`` itself."""
    if isinstance(obj, _LEAVES):
        return obj
    wrapper = _WRAPPERS.get(id(obj))
    if wrapper is not None:
        return wrapper
    wrapper_class = _wrapper_class_of(type(obj))
    if wrapper_class is not None:
        wrapper = _WRAPPERS.setdefault(id(obj), wrapper_class._from_core(obj))
        _keep_recent(wrapper)
        return wrapper
    if isinstance(obj, type):
        return obj
    if isinstance(obj, list):
        return [wrap(item) for item in obj]
    if isinstance(obj, NumberedComponents):
        return obj.replaced(wrap(item) for item in obj)
    if isinstance(obj, Pins):
        return obj.replaced({number: wrap(pin) for number, pin in obj.items()})
    if isinstance(obj, tuple):
        return tuple(wrap(item) for item in obj)
    if isinstance(obj, Mapping):
        return WrappedMapping(obj)
    if isinstance(obj, Sequence):
        return WrappedSequence(obj)
    if isinstance(obj, set):
        return {wrap(item) for item in obj}
    if isinstance(obj, Set):
        return frozenset(wrap(item) for item in obj)
    if isinstance(obj, Iterator):
        return (wrap(item) for item in obj)
    return obj


#: The collections whose sync face may be kept: they cannot change once made.
_FIXED_COLLECTIONS = (NumberedComponents, Pins, tuple)


def wrap_kept(owner: SyncWrapper, name: str, value: Any) -> Any:
    """Return :func:`wrap` of ``value``, attribute ``name`` of ``owner``'s core object.

    The sync face of a collection that cannot change (a tuple, ``board.motors``,
    ``board.pins``), and the wrapper of a single core object, are kept by ``owner`` for
    as long as the core object gives that same value, so ``board.pins[3]`` costs no more
    than a lookup and ``board.pins is board.pins``. Anything else is wrapped afresh: a
    list, say, may change.
    """
    try:
        kept = owner._kept
    except AttributeError:
        kept = {}
        object.__setattr__(owner, "_kept", kept)
    entry = kept.get(name)
    if entry is not None and entry[0] is value:
        return entry[1]
    wrapped = wrap(value)
    if isinstance(wrapped, SyncWrapper) or (
        isinstance(value, _FIXED_COLLECTIONS) and _holds_only_fixed_faces(wrapped)
    ):
        kept[name] = (value, wrapped)
    return wrapped


def _holds_only_fixed_faces(wrapped: Any) -> bool:
    """Whether every item of a wrapped collection is a wrapper or an immutable leaf."""
    items = wrapped.values() if isinstance(wrapped, Pins) else wrapped
    return all(isinstance(item, (SyncWrapper, *_LEAVES)) for item in items)


def unwrap(obj: Any) -> Any:
    """Return the core object behind a wrapper (or a container of them); others unchanged.

    A wrapper class (such as ``j5aio.sync.MotorBoard``) gives the core class it wraps.
    """
    if isinstance(obj, type):
        if issubclass(obj, SyncWrapper):
            core = core_class_of(obj)
            return obj if core is None else core
        return obj
    if isinstance(obj, SyncWrapper):
        return obj._core
    if isinstance(obj, WrappedMapping | WrappedSequence):
        return obj._core
    if isinstance(obj, list):
        return [unwrap(item) for item in obj]
    if isinstance(obj, tuple):
        return tuple(unwrap(item) for item in obj)
    if isinstance(obj, dict):
        return {key: unwrap(value) for key, value in obj.items()}
    return obj


class WrappedMapping(Mapping[K, V]):
    """A read-only view of a core mapping whose values are shown as sync wrappers."""

    __slots__ = ("_core",)

    def __init__(self, core: Mapping[K, Any]) -> None:
        self._core = core

    def __getitem__(self, key: K) -> V:
        return wrap(self._core[key])  # type: ignore[no-any-return]

    def __iter__(self) -> Iterator[K]:
        return iter(self._core)

    def __len__(self) -> int:
        return len(self._core)

    def __repr__(self) -> str:
        return f"<sync {self._core!r}>"


class WrappedSequence(Sequence[V]):
    """A read-only view of a core sequence whose items are shown as sync wrappers."""

    __slots__ = ("_core",)

    def __init__(self, core: Sequence[Any]) -> None:
        self._core = core

    def __getitem__(self, index: Any) -> Any:
        if isinstance(index, slice):
            return [wrap(item) for item in self._core[index]]
        return wrap(self._core[index])

    def __iter__(self) -> Iterator[V]:
        return (wrap(item) for item in self._core)

    def __len__(self) -> int:
        return len(self._core)

    def __repr__(self) -> str:
        return f"<sync {self._core!r}>"
