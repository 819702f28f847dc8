"""``hydra/sweeper=optuna``: a Hydra sweeper on a current Optuna (the ``[scale]`` extra)."""
