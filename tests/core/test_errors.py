from __future__ import annotations

import pytest

from j5aio import errors


def test_every_communication_error_is_caught_by_the_base() -> None:
    for cls in (
        errors.BoardDisconnectionError,
        errors.CommunicationTimeoutError,
        errors.USBCommunicationError,
        errors.DeviceMissingSerialNumberError,
        errors.UnexpectedReplyError,
    ):
        assert issubclass(cls, errors.CommunicationError)
        assert issubclass(cls, errors.J5AIOError)


def test_lock_error_is_an_os_error() -> None:
    assert issubclass(errors.UnableToObtainLock, OSError)


def test_usb_error_keeps_the_pyusb_error_and_its_errno() -> None:
    cause = OSError(32, "Pipe error")
    err = errors.USBCommunicationError("power board: stalled", cause)
    assert err.usb_error is cause
    assert err.errno == 32
    assert errors.USBCommunicationError("no cause").errno is None


def test_unsupported_firmware_names_found_and_supported() -> None:
    err = errors.UnsupportedFirmwareError("SR v4 Motor Board", "4", ["3"])
    assert isinstance(err, errors.CommunicationError)
    assert err.found == "4"
    assert err.supported == ("3",)
    assert "'4'" in str(err) and "3" in str(err)
    with pytest.raises(errors.CommunicationError, match="SR v4 Motor Board"):
        raise err
