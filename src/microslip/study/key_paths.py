"""Configuration keys named by their path (``"damper.mass"``, ``"contact.sphere.preload"``) and set in a copy.

A path is the tables' names and the key, joined by dots. An array of tables
(``[[contact]]``, ``[[damper]]``, ``[[damper.interface]]``) is followed by the
``name`` of one of its tables or by its number (1 for the first, as the
configuration's messages count them); the number may be left out when the
array holds one table (``"damper.mass"``). Top-level keys (``"title"``) have
no table.
"""

from __future__ import annotations

import copy

from ..common._checks import close_spelling
from ..config import EXCITATION_ACCEPTS, EXCITATION_EXAMPLES, KEYS, ConfigError, harmonic_key

#: tables that are arrays of tables, and the name their items' paths start with
_ARRAYS = {"contact": "[[contact]]", "damper": "[[damper]]", "interface": "[[damper.interface]]"}
#: plain tables: the table name in a path and its name in :data:`~microslip.config.frf.KEYS`
_TABLES = {name: f"[{name}]" for name in ("structure", "cyclic", "sweep", "continuation", "output", "modes", "design")}
#: a table whose keys are not listed in KEYS (harmonics)
_EXCITATION = "excitation"


def set_key(data: dict, path: str, value, *, where: str) -> dict:
    """A deep copy of the configuration ``data`` with the key at ``path`` set to ``value``.

    Parameters
    ----------
    data : dict
        A configuration's tables (:func:`~microslip.config.frf.read_toml`).
    path : str
        The key's path, e.g. ``"contact.sphere.preload"``.
    value
        Its new value, as it would be written in the file (numbers, strings
        with units, lists).
    where : str
        Who names the path, for messages (e.g. ``"study.toml: [vary]"``).

    Raises
    ------
    ConfigError
        The path names no key the configuration accepts, or a table it does
        not have; the message names the path and what exists.
    """
    out = copy.deepcopy(data)
    set_key_in_place(out, path, value, where=where)
    return out


def set_key_in_place(data: dict, path: str, value, *, where: str) -> None:
    """:func:`set_key` without the copy: ``data`` is changed."""
    parts = _split(path, where)
    table, rest = _locate(data, parts, path, where)
    key = rest[0]
    if len(rest) != 1:
        raise ConfigError(f"{where}: {path!r} goes past the key {key!r} (a key's path ends with the key)")
    table[key] = value
    if path in _SAME:  # one value given in two places: the one set replaces the other
        other, other_key = _SAME[path]
        if isinstance(data.get(other), dict):
            data[other].pop(other_key, None)


#: keys that may be written in either of two tables (the configuration refuses both)
_SAME = {"sweep.engine_order": ("cyclic", "engine_order"), "cyclic.engine_order": ("sweep", "engine_order")}


def _split(path, where: str) -> list[str]:
    if not isinstance(path, str) or not path.strip():
        raise ConfigError(f"{where}: a parameter must be a key path such as \"damper.mass\", got {path!r}")
    parts = path.split(".")
    if any(not p.strip() for p in parts):
        raise ConfigError(f"{where}: {path!r} has an empty part (key paths join names with single dots)")
    return parts


def _locate(data: dict, parts: list[str], path: str, where: str):
    """The table the path's key lives in, and the remaining parts (the key first)."""
    head = parts[0]
    if len(parts) == 1:
        if head not in ("title",):
            raise ConfigError(f"{where}: {path!r} is not a key of the configuration's top level (only title is; "
                              f"other keys are named with their table, e.g. \"sweep.harmonics\")")
        return data, parts
    if head == _EXCITATION:
        table = data.setdefault(_EXCITATION, {})
        if not isinstance(table, dict):
            raise ConfigError(f"{where}: {path!r}: [excitation] is not a table in the base configuration")
        _excitation_key(parts[1], path, where)
        return table, parts[1:]
    if head in _TABLES:
        table = data.setdefault(head, {})
        if not isinstance(table, dict):
            raise ConfigError(f"{where}: {path!r}: [{head}] is not a table in the base configuration")
        _accepted(parts[1], _TABLES[head], path, where)
        return table, parts[1:]
    if head in ("contact", "damper"):
        item, rest = _item(data, head, _ARRAYS[head], parts[1:], path, where)
        if head == "damper" and rest and rest[0] == "interface":
            item, rest = _item(item, "interface", _ARRAYS["interface"], rest[1:], path, where)
            _accepted(rest[0], _ARRAYS["interface"], path, where)
            return item, rest
        if not rest:
            raise ConfigError(f"{where}: {path!r} names a table, not a key (add the key, e.g. \"{path}.mu\")")
        _accepted(rest[0], _ARRAYS[head], path, where)
        return item, rest
    known = ["title", "excitation", *_TABLES, *_ARRAYS]
    raise ConfigError(f"{where}: {path!r} starts with {head!r}, which is no table of the configuration"
                      f"{close_spelling(head, known)} (tables: "
                      f"{', '.join(k for k in known if k not in ('title', 'interface'))})")


def _item(parent: dict, name: str, label: str, rest: list[str], path: str, where: str):
    """The table of the array ``parent[name]`` that ``rest[0]`` names (a name or a number from 1)."""
    items = parent.get(name)
    if not isinstance(items, list) or not items:
        raise ConfigError(f"{where}: {path!r} names a {label} table; the base configuration has none")
    if not rest:
        raise ConfigError(f"{where}: {path!r} names the {label} tables, not a key")
    selector = rest[0]
    names = [str(t.get("name")) for t in items if isinstance(t, dict) and "name" in t]
    for t in items:
        if isinstance(t, dict) and t.get("name") == selector:
            return t, rest[1:]
    if selector.isdigit():
        k = int(selector)
        if not 1 <= k <= len(items):
            raise ConfigError(f"{where}: {path!r} names {label} {k}; the base configuration has {len(items)} "
                              f"(numbered from 1)")
        return items[k - 1], rest[1:]
    if len(items) == 1 and selector in KEYS[label]:
        return items[0], rest  # the only table: its number may be left out
    hint = f" (named: {', '.join(names)})" if names else ""
    raise ConfigError(f"{where}: {path!r}: no {label} table named {selector!r}{close_spelling(selector, names)} in the "
                      f"base configuration{hint}; name it by its name or its number from 1, e.g. "
                      f"\"{name}.1.{rest[-1] if len(rest) > 1 else 'key'}\"")


def _accepted(key: str, label: str, path: str, where: str) -> None:
    accepted = KEYS[label]
    if key not in accepted:
        raise ConfigError(f"{where}: {path!r}: {label} has no key {key!r}{close_spelling(key, accepted)} (it accepts "
                          f"{', '.join(accepted)})")


def _excitation_key(key: str, path: str, where: str) -> None:
    name = key[6:] if key.startswith("phase_") else key
    if key == "scale" or harmonic_key(name) is not None and key != "phase_static":
        return
    raise ConfigError(f"{where}: {path!r}: [excitation] has no key {key!r}{close_spelling(key, EXCITATION_EXAMPLES)} "
                      f"(it accepts {EXCITATION_ACCEPTS})")
