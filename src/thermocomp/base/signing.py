"""Signed pickles: the project loads only pickles it wrote itself.

Unpickling runs code, so a ``model.pkl`` from elsewhere (``model_path=evil.pkl``,
an artifact from an unauthenticated tracking server) must never reach
:func:`pickle.loads`.  Every pickle the project writes gets a digest file next
to it, ``<name>.sig``: HMAC-SHA256 of the pickle's bytes under the project key.
Loading reads the bytes once, checks the digest against them and only then
unpickles; the object is type-checked afterwards.

The key is the environment variable ``THERMOCOMP_SIGNING_KEY`` if set (a team
sets the same value on every machine that trains, promotes or serves), else a
random key created on first use in ``$XDG_CONFIG_HOME/thermocomp/signing.key``
(default ``~/.config/thermocomp/signing.key``), readable by its owner only
(0600).  Losing the key file only means models must be retrained or re-signed
(:func:`sign` on a file you trust).

Pure core: no Hydra, no MLflow.
"""

from __future__ import annotations

import hashlib
import hmac
import os
import pickle
import secrets
from pathlib import Path

from .errors import ContractError
from .files import atomic_write_bytes, atomic_write_text

KEY_ENV = "THERMOCOMP_SIGNING_KEY"
SUFFIX = ".sig"
SCHEME = "hmac-sha256"
MAX_SIG_BYTES = 1024     # a signature is 77 bytes ("hmac-sha256 <64 hex>\n")


class SignatureError(ContractError):
    """A pickle without a valid signature of this project (exit status 2, nothing unpickled)."""


def key_path() -> Path:
    """Where the project key lives when ``THERMOCOMP_SIGNING_KEY`` is not set."""
    base = os.environ.get("XDG_CONFIG_HOME") or Path.home() / ".config"
    return Path(base) / "thermocomp" / "signing.key"


def _key() -> bytes:
    env = os.environ.get(KEY_ENV)
    if env:
        return env.encode("utf-8")
    path = key_path()
    if not path.is_file():
        _create_key(path)
    key = path.read_bytes().strip()
    if len(key) < 32:
        raise ContractError("the signing key is empty or too short; delete it to create a new one "
                            f"or set {KEY_ENV}", file=path)
    return key


def _create_key(path: Path) -> None:
    """A fresh random key, 0600; two processes creating it at once agree on one (link is atomic)."""
    path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{secrets.token_hex(4)}")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(secrets.token_hex(32) + "\n")
        try:
            os.link(tmp, path)          # fails if another process won the race: keep theirs
        except FileExistsError:
            pass
    finally:
        tmp.unlink(missing_ok=True)


def digest(data: bytes) -> str:
    """HMAC-SHA256 of ``data`` under the project key (hex)."""
    return hmac.new(_key(), data, hashlib.sha256).hexdigest()


def sig_path(path: str | os.PathLike) -> Path:
    """``model.pkl`` -> ``model.pkl.sig``."""
    path = Path(path)
    return path.with_name(path.name + SUFFIX)


def _sig_text(data: bytes) -> str:
    return f"{SCHEME} {digest(data)}\n"


def sign(path: str | os.PathLike) -> Path:
    """Write the signature file of an existing file (only for a file you trust); returns it."""
    return atomic_write_text(sig_path(path), _sig_text(Path(path).read_bytes()))


def dump(obj, path: str | os.PathLike) -> Path:
    """Pickle ``obj`` to ``path`` atomically and write its signature next to it; returns ``path``."""
    data = pickle.dumps(obj)
    atomic_write_text(sig_path(path), _sig_text(data))
    return atomic_write_bytes(path, data)


def verified_bytes(path: str | os.PathLike, sig: str | os.PathLike | None = None) -> bytes:
    """The bytes of ``path`` once their signature (``sig``, default ``<path>.sig``) is checked.

    Raises
    ------
    SignatureError
        No signature file ("not signed by this project") or a digest that does
        not match these bytes under this key ("signature mismatch").
    """
    path = Path(path)
    sig = Path(sig) if sig is not None else sig_path(path)
    scheme, _, expected = _signature(sig, path).strip().partition(" ")
    if not path.is_file():      # a device (/dev/zero) would be read until memory runs out
        raise SignatureError("is not a regular file; refusing to read it", file=path)
    data = path.read_bytes()
    if scheme != SCHEME or not hmac.compare_digest(expected, digest(data)):
        raise SignatureError(f"signature mismatch ({sig.name}): the file was changed or signed "
                             f"with another key ({KEY_ENV} or {key_path()}); refusing to "
                             "unpickle it", file=path)
    return data


def _signature(sig: Path, path: Path) -> str:
    """The text of signature file ``sig``, read bounded: a ``.sig`` that is ``/dev/zero`` was
    read until memory ran out (MemoryError, exit 1)."""
    try:
        if not sig.is_file():        # a device or a pipe is no signature: never read from it
            raise OSError
        with sig.open("rb") as f:
            raw = f.read(MAX_SIG_BYTES + 1)
        if len(raw) > MAX_SIG_BYTES:
            raise SignatureError(f"{sig.name} is larger than a signature ({MAX_SIG_BYTES} bytes at "
                                 "most); refusing to unpickle it", file=path)
        return raw.decode("ascii")
    except (OSError, UnicodeDecodeError):
        raise SignatureError(f"not signed by this project (no readable {sig.name} next to it); "
                             "refusing to unpickle it", file=path) from None


def load(path: str | os.PathLike, expected: type | tuple[type, ...],
         sig: str | os.PathLike | None = None):
    """Unpickle ``path`` after checking its signature, then check the object's type.

    Parameters
    ----------
    path : path-like
        The pickle.
    expected : type or tuple of types
        What the object must be an instance of.
    sig : path-like, optional
        The signature file (default ``<path>.sig``).
    """
    obj = pickle.loads(verified_bytes(path, sig))
    if not isinstance(obj, expected):
        names = " or ".join(t.__name__ for t in (expected if isinstance(expected, tuple) else (expected,)))
        raise ContractError(f"holds a {type(obj).__name__}, not a {names}", file=path)
    return obj
