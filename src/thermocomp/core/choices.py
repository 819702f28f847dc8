"""The core's choices a config names (``eval.mode``, ``data.reference``): plain names, so that
the config schema reads them without loading pandas (``--help keys``, ``--cfg job``)."""

MODES = ("simulation", "one_step")   # eval.mode: free run, or one step ahead on y_measured
# data.reference: T_/E_ from a campaign's first sample, or as read, or from its start level (the
# mean over its first START_SPAN_S seconds, :func:`thermocomp.core.frame.start_rows`)
REFERENCES = ("first_sample", "none", "start_level")
START_SPAN_S = 900.0   # data.reference=start_level: the span whose mean is a campaign's start level
