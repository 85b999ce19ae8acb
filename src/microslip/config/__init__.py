"""microslip.config."""
