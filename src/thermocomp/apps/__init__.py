"""Applications on the core: deployment, monitoring, diagnosis, volumetric errors, simulation, fleets.

Import :mod:`thermocomp.core` and :mod:`thermocomp.base`, never the shell."""
