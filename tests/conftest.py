import os

# Many tiny matrix operations thrash a threaded BLAS: pin it to one thread (as pycba does).
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from pathlib import Path  # noqa: E402

# shared/ lies beside the repository (CI clones main with shared/ next to it).
SHARED = Path(__file__).resolve().parents[2] / "shared"
if not SHARED.is_dir():
    SHARED = Path("/work/shared")
