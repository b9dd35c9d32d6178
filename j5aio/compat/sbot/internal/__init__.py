"""sbot's internal modules that programs reach: :mod:`j5aio.compat.sbot.internal.exceptions`."""
