"""The networks the training recipe offers, in one list that QGIS's process can import.

Standard library only (no numpy, no torch): ``birdseye:traindetector`` lists these names in its
dialog, :mod:`.recipe` builds them, ``training/train_heatmap.py`` offers them on its command line.
"""

#: The networks; ``small`` is the default and needs no pretrained weights. The others are torchvision
#: encoders whose ImageNet weights come from a file or torchvision's cache (never downloaded).
BACKBONES = ("small", "efficientnet_b0", "efficientnet_b1", "efficientnet_b2", "efficientnet_b3",
             "efficientnet_v2_s", "resnet18", "resnet34", "resnet50")
