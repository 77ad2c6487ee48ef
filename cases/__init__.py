"""What a user brings and gets back, in the order of a study (imports `rollcontact.solver` and `rollcontact.bem`):

    scene/    a scene: TOML file <-> validated dataclasses, key by key, with units and ranges
    run/      one run of a scene: discretised onto a grid and a load path, stepped by the BEM solver or the 1-D MDR
              model, restarted from a stored step
    results/  the result of a run (RunResult), its HDF5 file and where output files go
    sweep/    parameter sweeps and shakedown-limit searches over many runs, on local processes or Dask
    plots/    figures of a run, of two runs side by side and of a sweep folder
    cli/      the `rollcontact` command, a thin layer over `rollcontact.cases.api`
    api       the Python API that `import rollcontact` exposes

Units: mm, N, MPa, degrees.
"""
