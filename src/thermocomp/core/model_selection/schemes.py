"""The names of the cross-validation schemes (``cv_scheme``): no scikit-learn, so the config
schema reads them without importing the splitters."""

CV_SCHEMES = ("auto", "campaigns", "forward")
