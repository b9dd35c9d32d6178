"""The simulated and hardware environments' lazily made names."""

from __future__ import annotations

import pytest

import j5aio.backends.hardware.env as hardware_env
import j5aio.simulator.environment as sim_env
from j5aio.board_kinds import BoardKind
from j5aio.boards.sr.v4 import MotorBoard


def test_the_exports_resolve_to_where_they_live() -> None:
    from j5aio.simulator import discovery, sim_backends

    assert sim_env.kit_discovery_options is discovery.kit_discovery_options
    assert sim_env.SRV4MotorBoardSimulatedBackend is sim_backends.SRV4MotorBoardSimulatedBackend
    assert set(sim_env.__all__) <= set(dir(sim_env))


def test_every_simulated_backend_is_listed_in_registration_order() -> None:
    backends = sim_env.SIMULATED_BACKENDS
    assert backends == tuple(sim_env.SIMULATED_ENVIRONMENT.backends)
    assert sim_env.SRV4MotorBoardSimulatedBackend in backends
    assert tuple(hardware_env.HARDWARE_ENVIRONMENT.backends) == hardware_env.HARDWARE_BACKENDS


@pytest.mark.parametrize("module", [sim_env, hardware_env])
def test_an_unknown_name_is_an_attribute_error(module: object) -> None:
    with pytest.raises(AttributeError, match="has no attribute 'NO_SUCH_NAME'"):
        _ = module.NO_SUCH_NAME  # type: ignore[attr-defined]


def test_a_kind_without_simulators_or_hardware_has_no_simulated_backend() -> None:
    bare = BoardKind("test-bare", MotorBoard, "no simulator")
    assert sim_env.simulated_backend(bare) is None
    no_sim = BoardKind(
        "test-no-sim", MotorBoard, "hardware only",
        hardware="j5aio.backends.hardware.sr.v4.motor_board:SRV4MotorBoardHardwareBackend",
    )
    assert sim_env.simulated_backend(no_sim) is None
