"""Scores: recall and GMCF before and after review, sweeps, checkpoint screening, preregistration."""
