# j5's quick start, step 1 ("your first robot"), with only the import changed.
from j5aio.sync import BaseRobot


class MyRobot(BaseRobot):
    """A robot with no boards yet."""


r = MyRobot()
