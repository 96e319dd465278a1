"""Field data: rover geotags, flight logs, DJI image metadata and the frame-layer contract."""
