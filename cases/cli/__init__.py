"""The `rollcontact` command (`main`): run, limits, sweep, limit-search, plot, compare. A thin layer over
`rollcontact.cases.api`."""
