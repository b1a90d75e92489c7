"""A planted kernel dependence, for tests/test_gate_environments.py: ``python plant_kernel_dependence.py CHECK
SHIFT margins ...`` runs ``mjpoincare margins ...`` with CHECK's error raised by SHIFT whenever an OpenBLAS kernel is
forced (``OPENBLAS_CORETYPE`` set), as a value that depends on the kernel would be."""

from __future__ import annotations

import dataclasses
import os
import sys

from mjpoincare.cli import main
from mjpoincare.gate import forms as gate


def planted(check: str, shift: float):
    """``gate.run_case`` with ``check``'s error moved by ``shift`` under a forced kernel."""
    run_case = gate.run_case

    def run(case, seed=0, **extra):
        result = run_case(case, seed, **extra)
        if not os.environ.get("OPENBLAS_CORETYPE"):
            return result
        checks = [dataclasses.replace(c, error=c.error + shift) if c.name == check else c for c in result.checks]
        return dataclasses.replace(result, checks=checks)

    return run


if __name__ == "__main__":
    gate.run_case = planted(sys.argv[1], float(sys.argv[2]))
    sys.exit(main(sys.argv[3:]))
