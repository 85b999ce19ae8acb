"""microslip.frequency.structures."""
