"""Digital twin of machine tools in thermal test campaigns.

:mod:`~thermocomp.apps.sim.network` holds the equations; a scenario
(:class:`~thermocomp.apps.sim.scenario.Scenario`) assembles a machine and a test
calendar into a dataset in the contract of ``shared/spec/DATA_FORMAT.md`` plus
a ground-truth dict, with undeclared effects (:mod:`~thermocomp.apps.sim.effects`)
planted on demand.  Scenarios (``conf/sim/<name>.yaml``):

* :class:`~thermocomp.apps.sim.yearround.YearRoundSpindle` -- ``yearround_spindle``
* :class:`~thermocomp.apps.sim.large_mill.LargeMillWeek` -- ``large_mill_week``
* :class:`~thermocomp.apps.sim.swiss_lathe.SwissLatheDoor` -- ``swiss_lathe_door``
* :class:`~thermocomp.apps.sim.column.ColumnMovingSource` -- ``column_moving_source``
* :class:`~thermocomp.apps.sim.long_record.LongRecord` -- ``long_record``
* :class:`~thermocomp.apps.sim.climate_room.ClimateRoom` -- ``climate_room``
"""

from thermocomp.apps.sim.climate_room import ClimateRoom
from thermocomp.apps.sim.column import ColumnMovingSource
from thermocomp.apps.sim.effects import EFFECTS
from thermocomp.apps.sim.large_mill import LargeMillWeek
from thermocomp.apps.sim.long_record import LongRecord
from thermocomp.apps.sim.swiss_lathe import SwissLatheDoor
from thermocomp.apps.sim.yearround import YearRoundSpindle

SCENARIOS = {cls.name: cls for cls in (YearRoundSpindle, LargeMillWeek, SwissLatheDoor, ColumnMovingSource,
                                       LongRecord, ClimateRoom)}

__all__ = ["EFFECTS", "SCENARIOS", "ClimateRoom", "ColumnMovingSource", "LargeMillWeek", "LongRecord",
           "SwissLatheDoor", "YearRoundSpindle"]
