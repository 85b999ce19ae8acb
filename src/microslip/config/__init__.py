"""Configuration files: the ``frf`` TOML format read into checked objects.

A configuration names a structure (matrices or finite-element files), its
contacts, dampers and cyclic symmetry, the excitation, the frequency sweep, a
nonlinear mode (``[modes]``), a damper design (``[design]``) and a Campbell diagram
(``[speed]``, ``[campbell]``); the format is
described in :mod:`microslip.config.frf`. The command line (``microslip frf``,
``modes``, ``design``) and design studies (:mod:`microslip.study`) read
configurations through the functions here.
"""

from .frf import (EXCITATION_ACCEPTS, EXCITATION_EXAMPLES, KEYS, CampbellTable, ConfigError, ConfigFiles, FrfConfig,
                  ModesTable, SpeedTable, checked, config_from_data, harmonic_key, load_config, read_toml,
                  refuse_unknown)

__all__ = ["EXCITATION_ACCEPTS", "EXCITATION_EXAMPLES", "KEYS", "CampbellTable", "ConfigError", "ConfigFiles",
           "FrfConfig", "ModesTable", "SpeedTable", "checked", "config_from_data", "harmonic_key", "load_config",
           "read_toml", "refuse_unknown"]
