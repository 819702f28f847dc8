"""thermocomp: thermal test campaigns of machine tools -> compensation models a CNC can run."""

__version__ = "0.1.0"
