"""The one error of the export."""


class NotExportable(ValueError):
    """The deployed compensator is not one linear system (a family or a setting the code lacks)."""
