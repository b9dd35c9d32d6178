"""j5aio: an asyncio-native robotics API for school robotics competitions."""

__version__ = "0.1.0"
