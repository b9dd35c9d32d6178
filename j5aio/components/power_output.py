"""Power outputs: a switchable supply on a power board, with a current meter."""

from __future__ import annotations

from abc import abstractmethod
from collections.abc import Iterator, Mapping
from typing import Generic, TypeVar

from j5aio.components._checks import check_bool
from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["PowerOutput", "PowerOutputGroup", "PowerOutputInterface"]


class PowerOutputInterface(Interface):
    """The coroutines a backend implements to drive power outputs."""

    @abstractmethod
    async def get_power_output_enabled(self, identifier: int) -> bool:
        """Return whether output ``identifier`` is switched on."""
        raise NotImplementedError

    @abstractmethod
    async def set_power_output_enabled(self, identifier: int, enabled: bool) -> None:
        """Switch output ``identifier`` on or off."""
        raise NotImplementedError

    @abstractmethod
    async def get_power_output_current(self, identifier: int) -> float:
        """Return the current drawn from output ``identifier``, in amps."""
        raise NotImplementedError


class PowerOutput(IdentifiedComponent[PowerOutputInterface]):
    """A power output: a supply that can be switched on and off, with a current meter.

    :param identifier: the number of the output on its board.
    :param backend: the backend that drives the output.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[PowerOutputInterface]:
        """The interface a backend implements for power outputs: :class:`PowerOutputInterface`."""
        return PowerOutputInterface

    async def get_is_enabled(self) -> bool:
        """Return ``True`` if the output is switched on.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_power_output_enabled(self._identifier)

    async def set_is_enabled(self, enabled: bool) -> None:
        """Switch the output on (``True``) or off (``False``).

        :raises TypeError: ``enabled`` is not a bool; ``1`` and ``0`` are refused as well.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        check_bool(enabled, name="power output state", allowed="True (on) or False (off)")
        await self._backend.set_power_output_enabled(self._identifier, enabled)

    async def get_current(self) -> float:
        """Return the current drawn from the output, in amps.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_power_output_current(self._identifier)


K = TypeVar("K")


class PowerOutputGroup(Generic[K]):
    """Several power outputs that can be switched together.

    Look an output up with ``group[key]``; iterating gives the outputs in the order of
    the mapping the group was made from.

    :param outputs: the outputs, each under its key (a name or a number).
    """

    __slots__ = ("_outputs",)

    def __init__(self, outputs: Mapping[K, PowerOutput]) -> None:
        self._outputs = outputs

    async def power_on(self) -> None:
        """Switch on every output in the group, one after another.

        Every output is tried even if one fails, so one broken output does not leave the
        others off.

        :raises CommunicationError: an output's board did not answer properly (when
            several outputs fail, an ``ExceptionGroup`` of their errors).
        """
        await self._switch_all(True)

    async def power_off(self) -> None:
        """Switch off every output in the group, one after another.

        Every output is tried even if one fails, so one broken output does not leave the
        others on.

        :raises CommunicationError: an output's board did not answer properly (when
            several outputs fail, an ``ExceptionGroup`` of their errors).
        """
        await self._switch_all(False)

    async def _switch_all(self, enabled: bool) -> None:
        errors: list[Exception] = []
        for output in self._outputs.values():
            try:
                await output.set_is_enabled(enabled)
            except Exception as error:  # every output must be tried, whatever happens
                errors.append(error)
        if len(errors) == 1:
            raise errors[0]
        if errors:
            state = "on" if enabled else "off"
            raise ExceptionGroup(f"{len(errors)} power outputs failed to switch {state}", errors)

    def __getitem__(self, key: K | int) -> PowerOutput:
        """Return the output under ``key``, or the output whose number is ``key``.

        ``board.outputs[PowerOutputPosition.H0]`` and ``board.outputs[0]`` are the same
        output.

        :raises KeyError: there is no output under ``key``; the message lists the keys.
        """
        if key in self._outputs:
            return self._outputs[key]  # type: ignore[index]
        if isinstance(key, int) and not isinstance(key, bool):
            for output in self._outputs.values():
                if output.identifier == key:
                    return output
        keys = ", ".join(str(getattr(k, "name", k)) for k in self._outputs)
        numbers = ", ".join(str(output.identifier) for output in self._outputs.values())
        raise KeyError(f"no power output {key!r}: use one of {keys}, or a number ({numbers})")

    def __iter__(self) -> Iterator[PowerOutput]:
        """Iterate over the outputs, in order."""
        return iter(self._outputs.values())

    def __len__(self) -> int:
        """Return how many outputs are in the group."""
        return len(self._outputs)

    def __repr__(self) -> str:
        return f"<PowerOutputGroup of {len(self._outputs)} outputs>"
