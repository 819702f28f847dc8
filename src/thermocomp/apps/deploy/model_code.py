"""MLflow *model from code* entry point of the deployed compensator (see :mod:`.pyfunc`)."""

from mlflow.models import set_model

from thermocomp.apps.deploy.pyfunc import CompensatorModel

set_model(CompensatorModel())
