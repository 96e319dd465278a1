"""One Processing algorithm per module; :mod:`..provider` finds every :class:`BirdsEyeAlgorithm`."""
