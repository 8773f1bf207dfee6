import os

# Many tiny matrix operations thrash a threaded BLAS: pin it to one thread (as pycba does).
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
