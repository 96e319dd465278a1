"""Parameter groups shared by several algorithms, as mixins (``DemParametersMixin``, …).

Kept out of ``processing/algorithms``: the provider loads every module there as one algorithm.
"""
