"""Signed pickles: nothing the project did not write itself is ever unpickled.

Every pickle the project writes (``model.pkl``, ``denoiser.pkl``, the pyfunc
``compensator.pkl``) has an HMAC-SHA256 ``.sig`` next to it; loading checks it
on the bytes before :func:`pickle.loads`, then checks the type.  A hostile
pickle (``__reduce__`` that writes a marker file) must never run.
"""

from __future__ import annotations

import pickle
import stat

import pytest

from test_deploy import campaigns, write_small_dataset
from thermocomp.base import signing
from thermocomp.base.errors import ContractError
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR
from thermocomp.shell.cli import main


def evil_pickle(path, marker) -> bytes:
    """Write to ``path`` a pickle that, once unpickled, creates ``marker``."""
    class _Payload:
        def __reduce__(self):
            return (exec, (f"open({str(marker)!r}, 'w').write('pwned')",))

    data = pickle.dumps(_Payload())
    path.write_bytes(data)
    return data


@pytest.fixture
def key(monkeypatch):
    monkeypatch.setenv(signing.KEY_ENV, "k" * 40)


@pytest.fixture(scope="session")
def fitted():
    camps = campaigns(0)
    return Compensator(MLR()).fit({c: camps[c] for c in list(camps)[:4]})


def test_round_trip_and_signature_file(tmp_path, key, fitted):
    path = signing.dump(fitted, tmp_path / "model.pkl")
    sig = (tmp_path / "model.pkl.sig").read_text()
    assert sig.startswith("hmac-sha256 ") and len(sig.split()[1]) == 64
    back = signing.load(path, Compensator)
    assert isinstance(back, Compensator) and back.inputs_ == fitted.inputs_


def test_tampered_unsigned_or_foreign_pickles_are_refused_before_unpickling(tmp_path, key,
                                                                             monkeypatch):
    marker = tmp_path / "marker"
    evil = tmp_path / "evil.pkl"
    evil_pickle(evil, marker)
    with pytest.raises(signing.SignatureError, match="not signed by this project"):
        signing.load(evil, Compensator)
    (tmp_path / "evil.pkl.sig").write_text("hmac-sha256 " + "0" * 64 + "\n")    # forged
    with pytest.raises(signing.SignatureError, match="signature mismatch"):
        signing.load(evil, Compensator)
    signing.sign(evil)                                      # signed here, but with another key:
    monkeypatch.setenv(signing.KEY_ENV, "another key of at least 32 chars!!")
    with pytest.raises(signing.SignatureError, match="signature mismatch"):
        signing.load(evil, Compensator)
    assert not marker.exists()

    good = signing.dump({"a": 1}, tmp_path / "good.pkl")
    good.write_bytes(good.read_bytes() + b"\x00")          # one byte appended
    with pytest.raises(signing.SignatureError, match="signature mismatch"):
        signing.load(good, dict)


def test_the_type_is_checked_after_the_signature(tmp_path, key):
    path = signing.dump({"not": "a model"}, tmp_path / "model.pkl")
    with pytest.raises(ContractError, match="holds a dict, not a Compensator"):
        signing.load(path, Compensator)


def test_key_file_is_created_once_owner_only(tmp_path, monkeypatch):
    monkeypatch.delenv(signing.KEY_ENV, raising=False)
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "cfg"))
    path = signing.dump([1, 2], tmp_path / "x.pkl")
    key = tmp_path / "cfg" / "thermocomp" / "signing.key"
    assert signing.key_path() == key and key.is_file()
    assert stat.S_IMODE(key.stat().st_mode) == 0o600
    first = key.read_bytes()
    assert signing.load(path, list) == [1, 2] and key.read_bytes() == first    # reused, not replaced
    key.write_text("f" * 64 + "\n")                                            # a new key:
    with pytest.raises(signing.SignatureError, match="signature mismatch"):   # old files refused
        signing.load(path, list)


def test_cli_never_executes_a_foreign_model_pickle(tmp_path, key):
    data = write_small_dataset(tmp_path / "small")
    marker = tmp_path / "marker"
    evil = tmp_path / "evil.pkl"
    evil_pickle(evil, marker)
    common = [f"data.path={data}", "track=false", f"out={tmp_path / 'o'}"]
    assert main(["replay", *common, f"replay.model={evil}"]) == 2
    (tmp_path / "evil.pkl.sig").write_text("hmac-sha256 " + "ab" * 32 + "\n")
    assert main(["replay", *common, f"replay.model={evil}"]) == 2
    assert not marker.exists() and not (tmp_path / "o" / "replay.json").exists()


def test_cli_messages_name_the_file_and_the_reason(tmp_path, key, capsys, fitted):
    data = write_small_dataset(tmp_path / "small")
    evil = tmp_path / "evil.pkl"
    evil_pickle(evil, tmp_path / "marker")
    assert main(["replay", f"data.path={data}", "track=false", f"replay.model={evil}"]) == 2
    errors = [ln for ln in capsys.readouterr().err.splitlines() if "error" in ln]
    assert len(errors) == 1 and str(evil) in errors[0] and "not signed by this project" in errors[0]
    # a model the project wrote loads and replays
    path = signing.dump(fitted, tmp_path / "model.pkl")
    assert main(["replay", f"data.path={data}", "track=false", f"replay.model={path}",
                 f"out={tmp_path / 'ok'}"]) == 0


def test_pyfunc_artifact_is_signed_and_checked(tmp_path, key, fitted):
    import mlflow

    from thermocomp.apps.deploy import StreamingCompensator
    from thermocomp.apps.deploy.pyfunc import save_compensator

    camps = campaigns(0)
    streaming = StreamingCompensator.from_training(fitted, {c: camps[c] for c in list(camps)[:4]})
    folder = save_compensator(streaming, tmp_path / "pyfunc")
    art = folder / "artifacts"
    assert {p.name for p in art.iterdir()} >= {"compensator.pkl", "compensator.pkl.sig"}
    assert mlflow.pyfunc.load_model(str(folder)).predict(camps["K05"]).shape[0] == len(camps["K05"])
    marker = tmp_path / "marker"
    evil_pickle(art / "compensator.pkl", marker)
    with pytest.raises(Exception, match="signature mismatch"):
        mlflow.pyfunc.load_model(str(folder))
    assert not marker.exists()
