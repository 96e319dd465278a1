"""Detection: ONNX heatmap models, their metadata, and clustering detections on the ground."""
