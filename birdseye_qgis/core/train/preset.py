"""Named training presets of ``birdseye:traindetector``: the network, tiles, stages, optimiser, loss and
stopping rule of a training run as one value (:class:`TrainingPreset`).

Standard library only: QGIS's process lists the presets without importing numpy or torch. The recipe
(:func:`.recipe.train_network`) and the job (:func:`.job.run_job`) read every choice from the preset; a
preset field left ``None`` keeps what the job says (its BACKBONE, RESOLUTION_CM, batch).

* ``fast`` — the recipe as it always was: the job's network and resolution, 96 px crops, 20 % of the
  budget with the encoder frozen then every layer, AdamW 3·10⁻³ (a third in stage 2) on a cosine
  schedule, pixel-weighted cross-entropy, the whole budget spent.
* ``method`` — the published method's recipe: an ImageNet-pretrained EfficientNetV2 encoder
  (torchvision's ``efficientnet_v2_s``, the nearest to the method's EfficientNetV2-B3 that torchvision
  offers) under the transposed-convolution decoder; 224 × 224 crops of tiles kept at their frames' own
  ground sample distance (no resampling); stage 1 with the whole encoder frozen, stage 2 with its top
  30 % of blocks unfrozen; AdamW at a constant 10⁻⁵, β 0.9/0.999 (weight decay 0.004, Keras's default);
  plain binary cross-entropy; each
  stage ends after 15 epochs (passes over the training tiles) without a lower validation loss, or at
  its share of the budget, and keeps the weights of its best epoch.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class TrainingPreset:
    """Every training choice a preset fixes. ``None`` in ``backbone``, ``batch``: the job's value."""

    name: str
    title: str
    #: network (:data:`.recipe.BACKBONES`); None: the job's BACKBONE
    backbone: str | None = None
    #: train from random initialisation, saying so, when no ImageNet weights file is found (else: stop)
    random_init_without_weights: bool = False
    #: training crop side (px)
    crop_px: int = 96
    #: tiles kept at their frames' own ground sample distance (no resampling); the model's resolution is
    #: then the median GSD of the training frames, and RESOLUTION_CM is not used
    native_resolution: bool = False
    batch: int | None = None
    #: share of the budget (time or steps) for stage 1, the encoder frozen
    frozen_fraction: float = 0.2
    #: share of the encoder's blocks (the last ones) trained in stage 2
    unfrozen_fraction: float = 1.0
    #: frozen encoder blocks keep their batch-norm statistics (Keras's frozen layers); else they follow the data
    freeze_batchnorm: bool = False
    optimizer: str = "AdamW"
    lr: float = 3e-3
    #: stage 2's learning rate / stage 1's
    finetune_lr_factor: float = 1.0 / 3.0
    betas: tuple = (0.9, 0.999)
    weight_decay: float = 1e-4
    #: ``cosine`` (decaying to 10⁻⁵ within each stage) or ``constant``
    schedule: str = "cosine"
    #: each pixel's cross-entropy weighted 1 + positive_weight·label (0: plain binary cross-entropy)
    positive_weight: float = 10.0
    #: epochs without a lower validation loss that end a stage (None: the stage runs its whole budget)
    patience_epochs: int | None = None
    #: a stage ended by early stopping returns to the weights of its best epoch
    restore_best: bool = False
    #: held-out tiles the validation loss is taken on (None: all)
    validation_tiles: int | None = 32

    def loss_name(self) -> str:
        return ("binary cross-entropy" if not self.positive_weight
                else f"binary cross-entropy, pixels weighted 1 + {self.positive_weight:g}·label")

    def settings(self) -> dict:
        """The preset as JSON-able settings (the training JSON and the model card)."""
        out = asdict(self)
        out["betas"] = list(self.betas)
        out["loss"] = self.loss_name()
        return out


FAST = TrainingPreset(name="fast", title="Fast (default)")

METHOD = TrainingPreset(
    name="method", title="Method (EfficientNetV2, two stages, AdamW)",
    backbone="efficientnet_v2_s", random_init_without_weights=True, crop_px=224, native_resolution=True,
    frozen_fraction=0.5, unfrozen_fraction=0.3, freeze_batchnorm=True, optimizer="AdamW", lr=1e-5,
    finetune_lr_factor=1.0, betas=(0.9, 0.999), weight_decay=0.004, schedule="constant", positive_weight=0.0,
    patience_epochs=15, restore_best=True, validation_tiles=None)

#: The presets in the order Train detector lists them (its PRESET parameter's index).
PRESETS = (FAST, METHOD)
#: What the method names its encoder, beside what the ``method`` preset trains.
METHOD_ENCODER = "EfficientNetV2-B3"


def preset(name: str | None) -> TrainingPreset:
    """The preset called ``name`` (None or empty: ``fast``, what jobs written before presets ran)."""
    for p in PRESETS:
        if p.name == (name or "fast"):
            return p
    raise ValueError(f"unknown training preset '{name}'; one of {', '.join(p.name for p in PRESETS)}")
