"""The result of a run and its files: the HDF5 layout (`hdf5`) and where output goes (`outputs`). Units: mm, N,
MPa."""
