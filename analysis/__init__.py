"""Pure analysis layer (numpy/scipy only): sections, return-map fits, theory, checks."""
