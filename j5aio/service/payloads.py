"""Checking what arrives from the broker before anything believes it.

A payload is at most :data:`MAX_PAYLOAD_BYTES`, UTF-8, and a JSON object; anything else is
a :class:`PayloadError` whose :attr:`~PayloadError.kind` names the fault (for logging each
kind once) and whose message says what was wrong and what is allowed.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Final

__all__ = [
    "MAX_PAYLOAD_BYTES",
    "PayloadError",
    "decode_object",
    "optional_field",
    "require_field",
]

#: The largest payload read, in bytes. astoria's largest status message is under 1 KiB.
MAX_PAYLOAD_BYTES: Final = 64 * 1024


class PayloadError(ValueError):
    """A message from the broker is not what its topic promises.

    :param kind: ``"oversized"``, ``"not JSON"`` or ``"wrong type"``.
    :param message: what was wrong and what is allowed.
    """

    def __init__(self, kind: str, message: str) -> None:
        super().__init__(message)
        #: Which kind of fault this is.
        self.kind = kind


def decode_object(payload: bytes | bytearray | str, topic: str) -> Mapping[str, object]:
    """The JSON object in ``payload``.

    :raises PayloadError: it is too large, not UTF-8 JSON, or not a JSON object.
    """
    if len(payload) > MAX_PAYLOAD_BYTES:
        raise PayloadError(
            "oversized",
            f"{topic}: a message of {len(payload)} bytes was ignored "
            f"(at most {MAX_PAYLOAD_BYTES} are read)",
        )
    try:
        data = json.loads(payload)
    except (UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise PayloadError("not JSON", f"{topic}: a message that is not JSON was ignored ({exc})")\
            from None
    if not isinstance(data, dict):
        raise PayloadError(
            "wrong type",
            f"{topic}: a message that is a JSON {type(data).__name__}, not an object, "
            "was ignored",
        )
    return data


def require_field(
    data: Mapping[str, object], name: str, kind: type | tuple[type, ...], topic: str,
) -> object:
    """``data[name]``, which must be there and of ``kind`` (``bool`` is not an ``int``).

    :raises PayloadError: it is missing or of another type.
    """
    if name not in data:
        raise PayloadError("wrong type", f"{topic}: a message without {name!r} was ignored")
    return optional_field(data, name, kind, topic)


def optional_field(
    data: Mapping[str, object], name: str, kind: type | tuple[type, ...], topic: str,
) -> object:
    """``data.get(name)``: ``None`` if missing or null, else it must be of ``kind``.

    :raises PayloadError: it is there and of another type.
    """
    value = data.get(name)
    if value is None:
        return None
    kinds = kind if isinstance(kind, tuple) else (kind,)
    if not isinstance(value, kinds) or (isinstance(value, bool) and bool not in kinds):
        names = " or ".join(k.__name__ for k in kinds)
        raise PayloadError(
            "wrong type",
            f"{topic}: a message whose {name!r} is {value!r} was ignored (it must be {names})",
        )
    return value
