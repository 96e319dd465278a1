"""Flight planning: waypoints over geotags, the route, missions, and the mission files drones fly."""
