"""The core's choices a config names (``eval.mode``, ``data.reference``): plain names, so that
the config schema reads them without loading pandas (``--help keys``, ``--cfg job``)."""

MODES = ("simulation", "one_step")   # eval.mode: free run, or one step ahead on y_measured
REFERENCES = ("first_sample", "none")   # data.reference: T_/E_ from a campaign's first sample, or as read
