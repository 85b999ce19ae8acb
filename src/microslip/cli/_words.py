"""The library's messages in a configuration's words: an API argument named as the TOML key that sets it."""

from __future__ import annotations

import re

#: an API argument in a message -> the configuration's key: the under-resolved AFT's advice, the point limit of an
#: incomplete curve, a mode that ends at a fold
CONFIG_WORDS = ((re.compile(r"\bsamples=(\d+)"), r"[sweep] samples = \1"),
                (re.compile(r"\bStepControl\.max_points \(or ds_max\)"), "[continuation] max_points"),
                (re.compile(r"\bfolds='(\w+)'"), r'[modes] folds = "\1"'))


def in_config_words(text: str) -> str:
    """``text`` with each API argument of :data:`CONFIG_WORDS` replaced by its configuration key."""
    for pattern, words in CONFIG_WORDS:
        text = pattern.sub(words, text)
    return text
