"""microslip.frequency.analyses."""
