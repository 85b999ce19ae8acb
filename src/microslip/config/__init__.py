"""Configuration files: the ``frf`` TOML format read into checked objects.

A configuration names a structure (matrices or finite-element files), its
contacts, dampers and cyclic symmetry, the excitation, the frequency sweep, a
nonlinear mode (``[modes]``), a damper design (``[design]``) and a Campbell diagram
(``[speed]``, ``[campbell]``). Every table and key
is declared once in :mod:`microslip.config.schema`, which the reader checks files
against and :func:`reference_markdown` renders as the reference (``microslip
config-reference``), the study files' tables included. The command line (``microslip frf``,
``modes``, ``design``) and design studies (:mod:`microslip.study`) read
configurations through the functions here.
"""

from .frf import (EXCITATION_ACCEPTS, EXCITATION_EXAMPLES, KEYS, CampbellTable, ConfigError, ConfigFiles, FrfConfig,
                  ModesTable, PrestressTable, SpeedTable, apply_prestress, checked, config_from_data, harmonic_key,
                  load_config, read_toml, refuse_unknown)
from .schema import reference_markdown

# the rest imported above serves the command line and the study files (microslip.study), not users
__all__ = ["CampbellTable", "ConfigError", "FrfConfig", "ModesTable", "PrestressTable", "SpeedTable",
           "config_from_data", "load_config", "read_toml", "reference_markdown"]
