"""Platform design: the sensor bound, its Monte Carlo check, the terrain-slope study and reports."""
