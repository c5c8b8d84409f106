"""Shared fixtures: the Makris damper and its geometry / fluid numbers (Makris et al. 1996, section 3)."""

import math

import pytest

import erdesign

# Makris et al. (1996), section 3: L = 2.15 in, d = 0.563 in, h = 0.0315 in, Dp = 1.315 in, dr = 0.443 in.
MAKRIS = dict(L=0.0546, d=0.0143, h=0.0008, Dp=0.0334, dr=0.01125)
MAKRIS_AP = math.pi / 4 * (MAKRIS["Dp"] ** 2 - MAKRIS["dr"] ** 2)


@pytest.fixture
def makris():
    """The damper of examples/makris.toml."""
    return erdesign.load_example("makris")
