"""Test-suite settings: every compiled kernel checks its arguments against its signature (rollcontact.bem.compiled),
so that a call with another dtype, dimension or layout fails here rather than reading memory wrongly in a run."""
import os

os.environ.setdefault("ROLLCONTACT_KERNEL_CHECKS", "1")
