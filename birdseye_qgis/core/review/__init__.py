"""Review: review units, verdict actions, input digests and image chips for the review dock."""
