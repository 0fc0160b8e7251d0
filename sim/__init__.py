"""Physics-based polarized data synthesis with Mitsuba 3, and the camera sensor model."""
