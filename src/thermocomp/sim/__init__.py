"""Digital twin of machine tools in thermal test campaigns.

:mod:`~thermocomp.sim.network` holds the equations; a scenario
(:class:`~thermocomp.sim.scenario.Scenario`) assembles a machine and a test
calendar into a dataset in the contract of ``shared/spec/DATA_FORMAT.md`` plus
a ground-truth dict, with undeclared effects (:mod:`~thermocomp.sim.effects`)
planted on demand.  Scenarios (``conf/sim/<name>.yaml``):

* :class:`~thermocomp.sim.yearround.YearRoundSpindle` -- ``yearround_spindle``
* :class:`~thermocomp.sim.large_mill.LargeMillWeek` -- ``large_mill_week``
* :class:`~thermocomp.sim.swiss_lathe.SwissLatheDoor` -- ``swiss_lathe_door``
* :class:`~thermocomp.sim.column.ColumnMovingSource` -- ``column_moving_source``
* :class:`~thermocomp.sim.long_record.LongRecord` -- ``long_record``
"""

from thermocomp.sim.column import ColumnMovingSource
from thermocomp.sim.effects import EFFECTS
from thermocomp.sim.large_mill import LargeMillWeek
from thermocomp.sim.long_record import LongRecord
from thermocomp.sim.swiss_lathe import SwissLatheDoor
from thermocomp.sim.yearround import YearRoundSpindle

SCENARIOS = {cls.name: cls for cls in (YearRoundSpindle, LargeMillWeek, SwissLatheDoor, ColumnMovingSource,
                                       LongRecord)}

__all__ = ["EFFECTS", "SCENARIOS", "ColumnMovingSource", "LargeMillWeek", "LongRecord", "SwissLatheDoor",
           "YearRoundSpindle"]
