"""Training heatmap detectors: the recipe (PyTorch, imported only inside functions), the training job
that ``birdseye:traindetector`` runs in a separate Python process, and the line protocol between the
two (docs/design.md §6, "Train detector").

Nothing here imports torch at module level: QGIS's own Python imports :mod:`.protocol` to start and
follow the child process, never the recipe's functions.
"""
