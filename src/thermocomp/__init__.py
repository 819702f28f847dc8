"""thermocomp: thermal test campaigns of machine tools -> compensation models a CNC can run."""

__version__ = "0.1.0"

# the layer folders, lowest first: a module imports only its own layer and those below
__layers__ = ('base', 'core', 'apps', 'shell')
