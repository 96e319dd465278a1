"""Start training from a BirdsEye ONNX model of the recipe's network (the bundled model ships as ONNX only).

PyTorch's exporter keeps the names of the parameters it leaves alone (``inner.<name>``, ``inner`` being
the sigmoid wrapper of :func:`.recipe.export_onnx`) and folds each convolution followed by a batch norm
into one convolution with a bias (``W' = W·γ/σ``, ``b' = β − μ·γ/σ``, σ the running standard deviation):
those come back as the convolution ``W'`` and a batch norm that adds ``b'`` (γ 1, β b', mean 0,
variance 1 − ε). The network then computes exactly what the ONNX model computes (checked against
onnxruntime on a random image), but only while those batch norms use their running statistics:
γ and σ cannot be told apart any more, so batch statistics would change the function. Their statistics
therefore stay frozen through training (:class:`FrozenStatsBatchNorm2d`; their γ and β still learn),
the usual practice when fine-tuning a detector from a few images. A checkpoint of such a network names
those batch norms (:func:`frozen_batch_norms`), and a run that starts from it freezes them again
(:func:`freeze_batch_norm_stats`).
"""
from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from ..errors import InputError

# Largest difference (probability) allowed between the rebuilt network and the ONNX model.
ONNX_MATCH_TOLERANCE = 1e-4
_WRAPPER_PREFIX = "inner."


def is_onnx(path) -> bool:
    return Path(path).suffix.lower() == ".onnx"


@functools.lru_cache(maxsize=None)
def frozen_stats_batch_norm():
    """The class, built on first use so that this module imports without torch (one class per process, so
    ``isinstance`` tells its modules)."""
    from torch import nn

    class FrozenStatsBatchNorm2d(nn.BatchNorm2d):
        """A batch norm that always normalises with its running statistics (its affine γ, β still train)."""

        def train(self, mode: bool = True):
            return super().train(False)

    return FrozenStatsBatchNorm2d


def load_onnx_init(net, path) -> list[str]:
    """Load the weights of the BirdsEye ONNX model at ``path`` into ``net`` (the network it was exported
    from); returns the names of the batch norms whose statistics are now frozen. Refuses a model whose
    graph does not fit ``net``, or whose rebuilt outputs differ from the ONNX model's."""
    import onnx
    import torch
    from onnx import numpy_helper

    try:
        model = onnx.load(str(path))
    except Exception as exc:  # noqa: BLE001 - any unreadable file is the user's to fix
        raise InputError(f"is not an ONNX model ({exc})", source=str(path), field="INIT") from exc
    weights = {t.name: numpy_helper.to_array(t) for t in model.graph.initializer}
    state = net.state_dict()
    loaded = {}
    for name in state:
        if _WRAPPER_PREFIX + name in weights:
            loaded[name] = torch.from_numpy(np.array(weights[_WRAPPER_PREFIX + name]))
    folded_onnx = [(node.input[1], node.input[2] if len(node.input) > 2 else None)
                   for node in model.graph.node
                   if node.op_type == "Conv" and not node.input[1].startswith(_WRAPPER_PREFIX)]
    folded_torch = _convolutions_in_call_order(net, missing=lambda conv_name: conv_name + ".weight" not in loaded)
    if len(folded_onnx) != len(folded_torch):
        raise InputError(f"has {len(folded_onnx)} folded convolutions where the network has {len(folded_torch)}: "
                         "it was not exported from this network (train with the backbone it was trained with)",
                         source=str(path), field="INIT")
    modules = dict(net.named_modules())
    frozen = []
    for (w_name, b_name), conv_name in zip(folded_onnx, folded_torch):
        conv = modules[conv_name]
        w = weights[w_name]
        if tuple(w.shape) != tuple(conv.weight.shape) or b_name is None:
            raise InputError(f"convolution {w_name} has shape {tuple(w.shape)} where {conv_name} has "
                             f"{tuple(conv.weight.shape)}: it was not exported from this network",
                             source=str(path), field="INIT")
        bn_name = _following_batch_norm(conv_name, modules)
        bn = modules[bn_name]
        loaded[conv_name + ".weight"] = torch.from_numpy(np.array(w))
        loaded[bn_name + ".weight"] = torch.ones_like(bn.weight)
        loaded[bn_name + ".bias"] = torch.from_numpy(np.array(weights[b_name]))
        loaded[bn_name + ".running_mean"] = torch.zeros_like(bn.running_mean)
        loaded[bn_name + ".running_var"] = torch.full_like(bn.running_var, 1.0 - bn.eps)
        frozen.append(bn_name)
    missing = [n for n in state if n not in loaded and not n.endswith("num_batches_tracked")]
    if missing:
        raise InputError(f"holds no weights for {', '.join(missing[:3])}{'…' if len(missing) > 3 else ''}: it was "
                         "not exported from this network", source=str(path), field="INIT")
    net.load_state_dict({**state, **loaded})
    freeze_batch_norm_stats(net, frozen)
    _check_against_onnx(net, model, path)
    return frozen


def freeze_batch_norm_stats(net, names, source=None) -> None:
    """Replace the batch norms of ``net`` named in ``names`` by :class:`FrozenStatsBatchNorm2d` holding the same
    state (weights, bias, running statistics); refuses a name that is not a batch norm of ``net``."""
    from torch import nn

    frozen_class = frozen_stats_batch_norm()
    modules = dict(net.named_modules())
    for bn_name in names:
        bn = modules.get(bn_name)
        if not isinstance(bn, nn.BatchNorm2d):
            raise InputError(f"names {bn_name} as a batch norm with frozen statistics, which the network does not "
                             "have: it was not trained with this network", source=source, field="INIT")
        if isinstance(bn, frozen_class):
            continue
        parent_name, _, child = bn_name.rpartition(".")
        replacement = frozen_class(bn.num_features, eps=bn.eps, momentum=bn.momentum)
        replacement.load_state_dict(bn.state_dict())
        setattr(modules[parent_name] if parent_name else net, child, replacement)


def frozen_batch_norms(net) -> list[str]:
    """Names of the batch norms of ``net`` whose statistics are frozen (:class:`FrozenStatsBatchNorm2d`)."""
    frozen_class = frozen_stats_batch_norm()
    return [name for name, module in net.named_modules() if isinstance(module, frozen_class)]


def _convolutions_in_call_order(net, missing) -> list[str]:
    """Names of the Conv2d modules of ``net`` that ``missing(name)`` selects, in the order a forward pass
    calls them (the order of the ONNX graph's nodes)."""
    import torch
    from torch import nn

    names = {module: name for name, module in net.named_modules()}
    order, hooks = [], []
    for module, name in names.items():
        if isinstance(module, nn.Conv2d) and missing(name):
            hooks.append(module.register_forward_hook(lambda m, _i, _o: order.append(names[m])))
    was_training = net.training
    net.eval()
    try:
        with torch.no_grad():
            net(torch.zeros(1, 3, 64, 64))
    finally:
        for hook in hooks:
            hook.remove()
        net.train(was_training)
    return order


def _following_batch_norm(conv_name: str, modules: dict) -> str:
    """The batch norm after a convolution in its Sequential (``….0`` → ``….1``)."""
    from torch import nn

    parent, _, index = conv_name.rpartition(".")
    candidate = f"{parent}.{int(index) + 1}" if index.isdigit() else None
    if candidate is None or not isinstance(modules.get(candidate), nn.BatchNorm2d):
        raise InputError(f"the network's convolution {conv_name} has no batch norm after it to carry the folded "
                         "bias", field="INIT")
    return candidate


def _check_against_onnx(net, model, path) -> None:
    import onnxruntime as ort
    import torch

    session = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    # A fixed input size (export_onnx fixes it at the tile size) accepts nothing else; a dynamic one any.
    h, w = (d if isinstance(d, int) and d > 0 else 64 for d in session.get_inputs()[0].shape[2:])
    x = np.random.default_rng(0).normal(0.0, 1.0, (1, 3, h, w)).astype(np.float32)
    expected = session.run(None, {session.get_inputs()[0].name: x})[0]
    was_training = net.training
    net.eval()
    with torch.no_grad():
        got = torch.sigmoid(net(torch.from_numpy(x))).numpy()
    net.train(was_training)
    worst = float(np.max(np.abs(got - expected)))
    if worst > ONNX_MATCH_TOLERANCE:
        raise InputError(f"rebuilt from its ONNX graph, the network differs from the model by {worst:.2g} (more than "
                         f"{ONNX_MATCH_TOLERANCE:g}): it was not exported from this network", source=str(path),
                         field="INIT")
