"""Scoring a fitted compensator and the figures read from the scores."""
