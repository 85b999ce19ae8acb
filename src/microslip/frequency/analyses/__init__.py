"""What users run on a structure: forced responses (:mod:`.response`), their stability
(:mod:`.stability`), nonlinear modes and the responses synthesised from them
(:mod:`.nonlinear_modes`, :mod:`.synthesis`), time integration (:mod:`.transient`), a contact's
cycle (:mod:`.contact_cycle`), damper design curves (:mod:`.design`) and a mistuned disk's blade
peaks (:mod:`.blade_peaks`)."""
