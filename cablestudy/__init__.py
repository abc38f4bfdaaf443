"""cablestudy: configuration-driven batch studies of marine cable mechanics."""

__version__ = "0.1.0"
