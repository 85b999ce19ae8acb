"""microslip.frequency.numerics."""
