"""Training labels: every geotag in every frame that sees it, written as a training set."""
