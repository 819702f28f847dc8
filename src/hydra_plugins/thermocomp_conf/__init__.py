"""The project's ``conf/`` read by Hydra with each file's YAML parsed once per text."""
