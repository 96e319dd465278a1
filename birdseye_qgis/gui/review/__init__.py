"""The review dock (``dock.ReviewDock``) and its parts: table model, widgets, background jobs, map context."""
