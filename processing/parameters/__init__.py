"""Parameter groups shared by several algorithms, as mixins (``DemParametersMixin``, …), and the layer
parameters that know the kind of layer they take (``layer_parameters``).

Kept out of ``processing/algorithms``: the provider loads every module there as one algorithm.
"""
