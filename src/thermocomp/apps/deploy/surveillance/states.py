"""The states a monitored sensor and the field take, and the rules' constants."""

OK, WARNING, ALARM, EXCLUDED = 0, 1, 2, 3
SPREAD_FACTOR = 3.0   # bands never within this × a sensor's training spread (from_training)
MAX_BACKOFF = 10      # a sensor excluded again waits at most window × 2**MAX_BACKOFF to return
READMIT = 0.5   # hysteresis: back in when within this share of the warning band for a window
THAW = 2        # readings in a row off the value it held that bring one out for a freeze back
# a reading whose noise spans its resolution: training's median |second difference| at least
# this many of its smallest step (mon97: its constant run past blind_run is a freeze alone)
DITHER = 2.0
STATES = ("ok", "warning", "alarm", "excluded")
COMMON_MIN = 3        # jumping sensors, at least, that a common step (a logger's fault) needs
COMMON_SPREAD = 2.0   # ... each within this factor of their median step (about the same size)
NEW_STATE, TRAINED = "new thermal state", "trained"   # the field's states (events, sensor None)
EXCHANGED = "exchanged"   # (wires100) an event's "to": two sensors' wires read exchanged from here
# an excursion out of band hovers (a regime) unless its error's share of its rise grew past this
# factor of the share it had EXCURSION_TAU_S seconds ago (excursion.py; mon73)
EXCURSION_TAU_S, EXCURSION_GROWTH = 1800.0, 1.5
# (mon105c) readings of each sensor kept for the rate of one that freezes: its held value is read
# instead of its stand-in while that rate's drift stays within the stand-in's spread (monitor.py)
TREND_ROWS = 128
