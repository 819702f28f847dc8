"""The configuration: its rules and the checks every stage runs before any work."""
