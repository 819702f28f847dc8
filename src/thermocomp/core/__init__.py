"""The modelling core: data and its contract, models, selection, scoring, figures.

Imports only :mod:`thermocomp.base`; a notebook or a CNC uses it without the shell."""
