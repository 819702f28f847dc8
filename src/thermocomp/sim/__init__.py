"""Digital twin of machine tools in thermal test campaigns.

:mod:`~thermocomp.sim.network` holds the equations; scenarios such as
:class:`~thermocomp.sim.yearround.YearRoundSpindle` assemble a machine
(:mod:`~thermocomp.sim.vmc`) and a test calendar into a dataset in the
contract of ``shared/spec/DATA_FORMAT.md`` plus a ground-truth dict.
"""

from thermocomp.sim.yearround import YearRoundSpindle

__all__ = ["YearRoundSpindle"]
