"""Scenes: a TOML file <-> a validated `Scene` (`scene`), the keys with their defaults, ranges and units (`keys`),
and the limits of a new run and its default resolution (`limits`). Units: mm, N, MPa, degrees."""
from rollcontact.cases.scene.keys import key_unit
from rollcontact.cases.scene.scene import Scene, default_scene, other_spellings, shipped_scene_path

__all__ = ["Scene", "default_scene", "key_unit", "other_spellings", "shipped_scene_path"]
