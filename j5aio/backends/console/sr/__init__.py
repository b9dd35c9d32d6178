"""Console backends of the Student Robotics boards."""
