"""Analytic results of the papers, one module per system, plus exact hybrid references."""
