"""Figures (matplotlib, Agg) and the data behind them."""
