"""Denoising of input sensors: offline EMD (remove the first IMFs) and its causal twin.

Pure core: arrays and DataFrames in, arrays and DataFrames out.
"""

from .campaigns import denoise_campaigns, fit_denoiser
from .denoiser import EMDDenoiser
from .emd import decompose, leading_imfs, remove_imfs

__all__ = ["EMDDenoiser", "decompose", "denoise_campaigns", "fit_denoiser", "leading_imfs",
           "remove_imfs"]
