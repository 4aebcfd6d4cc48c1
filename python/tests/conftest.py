"""Shared fixtures: the repository's plant files and a scratch directory."""

import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def plants_dir() -> pathlib.Path:
    """data/plants/ of the repository (the README's plant files)."""
    return ROOT / "data" / "plants"
