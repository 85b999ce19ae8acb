"""microslip.frequency.equations."""
