"""Geometry: rotations, geodesy, the camera, poses, projection and ground models (level plane, DEM)."""
