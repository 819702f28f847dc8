"""The foundation: errors, atomic files, JSON, parameter rules, signed pickles, logging, the project root.

No numerics, no Hydra; every other layer may import it."""
