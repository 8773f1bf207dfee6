"""Whether openseespy can be imported, and one sentence saying what to install when it cannot.

openseespy does not raise ImportError when its shared libraries are missing: on Linux without the
system packages libblas3 and liblapack3 its import raises ``RuntimeError("Failed to import
openseespy on Linux.")``. Everything in femoat that needs OpenSees (the twins, ``femoat
opensees``, the test suite's cross-checks) goes through :func:`import_opensees`, so whatever the
import raises becomes the same ImportError with the same advice.
"""

INSTALL_HINT = (
    "openseespy is needed for the OpenSees cross-checks: pip install femoat[verify]; on Linux "
    "openseespy also needs the system packages libblas3 and liblapack3 "
    "(Debian/Ubuntu: apt-get install libblas3 liblapack3)"
)


def import_opensees():
    """Return the ``openseespy.opensees`` module.

    Raises
    ------
    ImportError
        Whatever the import raised (ImportError, RuntimeError, OSError, ...), with
        :data:`INSTALL_HINT` and the original error in the message.
    """
    try:
        import openseespy.opensees as ops
    except Exception as exc:  # noqa: BLE001 - RuntimeError when libblas3/liblapack3 are missing
        raise ImportError(f"{INSTALL_HINT}. (The import raised {type(exc).__name__}: {exc})") \
            from exc
    return ops
