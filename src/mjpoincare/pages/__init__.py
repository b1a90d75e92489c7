"""Pages: the commands that write generated pages (docs/results/) from runs and measurements, stamped: the results
pages, the gate's margins, baseline and power pages, the backends' and engines' findings.

May import: the gate, the commands, the registry, :mod:`mjpoincare.core` and :mod:`mjpoincare.analysis`; never a face.
"""
