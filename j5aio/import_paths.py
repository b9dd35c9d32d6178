"""Classes named by import path, ``"package.module:ClassName"``: checked, then imported on use.

Board kinds (:mod:`j5aio.board_kinds`) name their backends and simulators this way, so that
registering a kind imports none of them; this module is the one place such a path is
checked and resolved.
"""

from __future__ import annotations

import importlib

__all__ = ["check_import_path", "import_class"]


def check_import_path(path: object, what: str) -> str:
    """Return ``path`` if it has the form ``"package.module:ClassName"``.

    It imports nothing.

    :param path: the path to check.
    :param what: what the path names, for the error message (``"the hardware backend of
        board kind 'x'"``).
    :raises ValueError: ``path`` is not a string of that form.
    """
    if isinstance(path, str):
        module, _, name = path.partition(":")
        if module and all(part.isidentifier() for part in module.split(".")) and (
            name.isidentifier()
        ):
            return path
    raise ValueError(f"{what} must be named 'package.module:ClassName', not {path!r}")


def import_class(path: str, what: str) -> type:
    """Import the module of ``path`` (``"package.module:ClassName"``) and return the class.

    :param path: the class's import path.
    :param what: what the path names, for error messages.
    :raises ValueError: ``path`` is not of that form.
    :raises ImportError: the module cannot be imported.
    :raises AttributeError: the module has no such name.
    :raises TypeError: the name is not a class.
    """
    module_name, _, name = check_import_path(path, what).partition(":")
    module = importlib.import_module(module_name)
    found = getattr(module, name)
    if not isinstance(found, type):
        raise TypeError(f"{what}: {path} is not a class")
    return found
