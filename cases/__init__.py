"""Scenes (TOML <-> dataclasses), runs, sweeps, HDF5 I/O, plots and the command line."""
