"""The choices of the training recipe that ``birdseye:traindetector`` lists, in lists QGIS's process can import.

Standard library only (no numpy, no torch): the dialog lists these names, :mod:`.recipe` builds the networks,
:mod:`.ground_validation` holds out the splits, ``training/train_heatmap.py`` offers both on its command line.
"""

#: The networks; ``small`` is the default and needs no pretrained weights. The others are torchvision
#: encoders whose ImageNet weights come from a file or torchvision's cache (never downloaded).
BACKBONES = ("small", "efficientnet_b0", "efficientnet_b1", "efficientnet_b2", "efficientnet_b3",
             "efficientnet_v2_s", "resnet18", "resnet34", "resnet50")

#: How validation frames are held out (VALIDATION's order): spatial blocks of targets, whole flights (labels
#: folders), or nothing.
SPLITS = ("blocks", "flights", "none")
