"""Boards made by Student Robotics."""
