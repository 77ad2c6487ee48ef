"""Many runs: sweep plans over scene keys (`plan`), their execution and resumption (`runner`) on local processes or
Dask (`workers`), the summary tables (`table`) and the shakedown-limit search (`limit_search`)."""
