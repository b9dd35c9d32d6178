"""What the simulated boards draw from the power board's 12 V outputs, and what it costs.

The figures are a plain model, chosen to be of the right size for the Student Robotics
kit (the kit's motors, a 3-cell LiPo battery), not measured on any one robot:

- each motor draws :data:`MOTOR_FULL_POWER_CURRENT` times the fraction of full power it
  is driven at (nothing while it coasts or brakes), unless the simulator is told what a
  motor draws (a stalled motor, say: ``set_motor_current``);
- each servo that is being sent pulses draws :data:`SERVO_HOLDING_CURRENT` (an unloaded
  servo holding its place);
- the boards' own electronics draw nothing worth counting
  (:data:`MOTOR_BOARD_IDLE_CURRENT` and :data:`SERVO_BOARD_IDLE_CURRENT` are 0), so a
  kit whose motors are still and whose servos are off reads the battery's idle voltage;
- the battery behaves as a source of its idle voltage behind
  :data:`BATTERY_INTERNAL_RESISTANCE`: under a load of ``I`` amps it reads
  ``idle - I x BATTERY_INTERNAL_RESISTANCE`` volts.

The power board's limits are the real board's
(:doc:`/internals/kit-wiring-and-service`): 20 A on H0 and H1,
10 A on L0 to L3, 2 A on the 5 V rail and 30 A for the whole board.
"""

from __future__ import annotations

from typing import ClassVar, Final

__all__ = [
    "BATTERY_INTERNAL_RESISTANCE",
    "BOARD_CURRENT_LIMIT",
    "MOTOR_BOARD_IDLE_CURRENT",
    "MOTOR_FULL_POWER_CURRENT",
    "OUTPUT_CURRENT_LIMITS",
    "SERVO_BOARD_IDLE_CURRENT",
    "SERVO_HOLDING_CURRENT",
    "PowerBoardLoads",
]

#: Amps a motor driven at full power draws.
MOTOR_FULL_POWER_CURRENT: Final = 2.5
#: Amps a powered motor board draws with its motors still.
MOTOR_BOARD_IDLE_CURRENT: Final = 0.0
#: Amps a servo draws while the board sends it pulses.
SERVO_HOLDING_CURRENT: Final = 0.02
#: Amps a powered servo board draws with no servo pulsing.
SERVO_BOARD_IDLE_CURRENT: Final = 0.0
#: Ohms between the battery's idle voltage and the power board (cells and wiring).
BATTERY_INTERNAL_RESISTANCE: Final = 0.05
#: The over-current limit of each power board output, in amps (H0, H1, L0, L1, L2, L3, 5 V).
OUTPUT_CURRENT_LIMITS: Final = (20.0, 20.0, 10.0, 10.0, 10.0, 10.0, 2.0)
#: The whole power board's over-current limit, in amps.
BOARD_CURRENT_LIMIT: Final = 30.0


class PowerBoardLoads:
    """A simulated power board's battery and load model (a mixin of firmware 3's and 4's).

    What the boards fed by each output draw (a kit's wiring sets it) loads the battery
    while that output is on, and the battery's voltage sags under it behind
    :data:`BATTERY_INTERNAL_RESISTANCE`. The board keeps its outputs' states in
    ``_outputs``, and calls ``_start_loads`` when it is made.
    """

    #: Number of the board's outputs.
    OUTPUT_COUNT: ClassVar[int]
    _outputs: list[bool]

    def _start_loads(self, battery_voltage: float) -> None:
        """Start with a battery of ``battery_voltage`` volts and nothing drawn from it."""
        self._battery_mv = 0
        self._battery_ma = 0
        self.battery_voltage = battery_voltage
        self._supplied_ma = [0] * self.OUTPUT_COUNT

    @property
    def battery_voltage(self) -> float:
        """The battery's idle voltage, in volts (stored in mV)."""
        return self._battery_mv / 1000

    @battery_voltage.setter
    def battery_voltage(self, volts: float) -> None:
        if volts < 0:
            raise ValueError("battery voltage cannot be negative")
        self._battery_mv = round(volts * 1000)

    @property
    def battery_current(self) -> float:
        """The battery current besides the outputs' loads, in amps (stored in mA).

        It is negative while the battery charges; the outputs' loads add to it in what
        the board reports.
        """
        return self._battery_ma / 1000

    @battery_current.setter
    def battery_current(self, amps: float) -> None:
        self._battery_ma = round(amps * 1000)

    def set_supplied_current(self, output: int, amps: float) -> None:
        """Set what the boards fed by ``output`` draw through it (a kit's wiring does).

        While the output is on, it adds to the output's current and the battery's, and
        pulls the battery voltage down (:data:`BATTERY_INTERNAL_RESISTANCE`).

        :raises IndexError: the board has no output ``output``.
        """
        self._check_output(output)
        self._supplied_ma[output] = round(amps * 1000)

    def _supplied_now_ma(self, output: int) -> int:
        """The mA the boards fed by ``output`` draw through it now (none while it is off)."""
        return self._supplied_ma[output] if self._outputs[output] else 0

    @property
    def load_current(self) -> float:
        """The amps the boards fed by the outputs that are on draw, in all."""
        return sum(map(self._supplied_now_ma, range(self.OUTPUT_COUNT))) / 1000

    @property
    def loaded_voltage(self) -> float:
        """The battery voltage under the outputs' load, in volts (what the board reads)."""
        return max(0.0, self.battery_voltage - self.load_current * BATTERY_INTERNAL_RESISTANCE)

    def _check_output(self, output: int) -> None:
        if not 0 <= output < self.OUTPUT_COUNT:
            raise IndexError(f"output {output} does not exist (0-{self.OUTPUT_COUNT - 1})")
