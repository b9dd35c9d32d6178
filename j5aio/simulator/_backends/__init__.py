"""The simulated backends, one module per board generation (or per hardware module).

Each class is documented, and imported, as :mod:`j5aio.simulator.sim_backends`'s or
:mod:`j5aio.simulator.sim_backends_2023`'s; it lives here so that finding one board's
boards imports that board's hardware backend only, and none of the others of its era.
"""
