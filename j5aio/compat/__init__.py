"""The competitions' own APIs as thin layers on j5aio: :mod:`j5aio.compat.sbot`."""
