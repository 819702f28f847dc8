"""The command around the core and the applications: CLI, stages, tracking, sweeps.

The only layer that knows Hydra's config and MLflow's runs."""
