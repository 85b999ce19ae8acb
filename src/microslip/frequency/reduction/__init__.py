"""microslip.frequency.reduction."""
