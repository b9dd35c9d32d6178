"""Hardware backends for Student Robotics boards."""
